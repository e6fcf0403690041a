"""Where the example scripts find the ASM ParaView plugin (ASM.so), and the
checks they share on their command lines.

The plugin, in this order: the explicit path (--plugin), else $ASM_PLUGIN,
else ASM.so (or ASM/ASM.so) in a directory of $PV_PLUGIN_PATH, else the build
tree next to this repository (build/lib/paraview-*/plugins/ASM/ASM.so). A
path given but missing is an error, not a reason to look elsewhere."""
import argparse
import glob
import os
import sys

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def find_plugin(explicit=None):
    for source, path in (("--plugin", explicit), ("$ASM_PLUGIN", os.environ.get("ASM_PLUGIN"))):
        if path:
            if not os.path.isfile(path):
                sys.exit("ASM plugin not found: %s %s is not a file" % (source, path))
            return os.path.abspath(path)
    for directory in filter(None, os.environ.get("PV_PLUGIN_PATH", "").split(os.pathsep)):
        for candidate in (os.path.join(directory, "ASM.so"), os.path.join(directory, "ASM", "ASM.so")):
            if os.path.isfile(candidate):
                return os.path.abspath(candidate)
    found = sorted(glob.glob(os.path.join(REPO, "build", "lib", "paraview-*", "plugins", "ASM", "ASM.so")))
    if not found:
        sys.exit("ASM plugin not found: build first (bash scripts/build.sh), or pass --plugin or set ASM_PLUGIN")
    return found[-1]


def require_file(path, what="input"):
    """Exit with a message unless path is a readable file (before any pipeline runs: under MPI, a
    reader's error on one process would leave the others waiting in a collective)."""
    if not os.path.isfile(path):
        sys.exit("%s %s: no such file" % (what, path))
    if not os.access(path, os.R_OK):
        sys.exit("%s %s: not readable" % (what, path))


def require_writable(path, create=False):
    """Exit with a message unless path's directory exists (is made, with `create`, as ParaView's
    writers make it) and is writable."""
    directory = os.path.dirname(os.path.abspath(path))
    if create:
        try:
            os.makedirs(directory, exist_ok=True)
        except OSError as error:
            sys.exit("output %s: cannot make directory %s (%s)" % (path, directory, error.strerror))
    if not os.path.isdir(directory):
        sys.exit("output %s: directory %s does not exist" % (path, directory))
    if not os.access(directory, os.W_OK):
        sys.exit("output %s: directory %s is not writable" % (path, directory))


def fraction_arg(text):
    """argparse type: a fraction of the input points in (0, 1]."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError("not a number: %r" % text)
    if not 0.0 < value <= 1.0:  # (also rejects nan)
        raise argparse.ArgumentTypeError("must be in (0, 1], got %r" % text)
    return value


def int_at_least(minimum):
    """argparse type: an integer >= minimum."""
    def parse(text):
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError("not an integer: %r" % text)
        if value < minimum:
            raise argparse.ArgumentTypeError("must be at least %d, got %r" % (minimum, text))
        return value
    return parse


positive_int_arg = int_at_least(1)
