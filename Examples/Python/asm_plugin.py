"""Where the example scripts find the ASM ParaView plugin (ASM.so): the
explicit path (--plugin), else $ASM_PLUGIN, else the build tree next to this
repository (build/lib/paraview-*/plugins/ASM/ASM.so)."""
import glob
import os
import sys

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def find_plugin(explicit=None):
    if explicit:
        return explicit
    if os.environ.get("ASM_PLUGIN"):
        return os.environ["ASM_PLUGIN"]
    found = sorted(glob.glob(os.path.join(REPO, "build", "lib", "paraview-*", "plugins", "ASM", "ASM.so")))
    if not found:
        sys.exit("ASM plugin not found: build first (bash scripts/build.sh) or pass --plugin")
    return found[-1]
