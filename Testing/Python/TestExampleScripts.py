"""The example scripts (Examples/Python) on good and bad command lines, each run
as a user runs it, in a scratch directory: a bad input, fraction, count or
output stops the script with a message and a non-zero exit status, and
writes nothing; relative paths are read against the current directory; a
run under mpiexec with a missing file ends instead of hanging.

Environment (set by CTest, see CMakeLists.txt):
  ASM_PVPYTHON, ASM_PVBATCH  ParaView's interpreters
  ASM_MPIEXEC                mpiexec (optional: the MPI cases are skipped without it)
  ASM_PLUGIN, ASM_DATA_DIR   the plugin and Testing/Data
  PYTHONPATH                 holds the asmvtk package (time_scans.py, paper_table2.py)
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

from vtkmodules.vtkImagingCore import vtkImageCast
from vtkmodules.vtkImagingSources import vtkImageMandelbrotSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOPLY import vtkPLYReader

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "..", "Examples", "Python")
DATA = os.path.abspath(os.environ.get("ASM_DATA_DIR", os.path.join(HERE, "..", "Data")))
PVPYTHON = os.environ["ASM_PVPYTHON"]
PVBATCH = os.environ["ASM_PVBATCH"]
MPIEXEC = os.environ.get("ASM_MPIEXEC")
KITTEN = os.path.join(DATA, "kitten.ply")  # 5210 points
failures = []


def clean(env):
    """env without the MPI singleton's variables that pvpython (this interpreter) set: a child
    mpiexec or pvbatch that inherits them takes itself for a process of this job and fails."""
    keep = ("OMPI_ALLOW_RUN_AS_ROOT", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM")
    return {key: value for key, value in env.items()
            if key in keep or not key.startswith(("OMPI_", "PMIX_", "ORTE_", "OPAL_"))}


def run(command, cwd, env=None, timeout=120):
    try:
        done = subprocess.run(command, cwd=cwd, env=clean(env or os.environ), timeout=timeout,
                              capture_output=True, text=True)
    except subprocess.TimeoutExpired:
        return None, "", "timed out after %d s" % timeout
    return done.returncode, done.stdout, done.stderr


def check(name, command, cwd, status, output=None, absent=(), env=None):
    """Run; status is the expected exit status ("nonzero": any but 0); output a regular expression
    (or a list of them) expected in stdout + stderr; absent: files (relative to cwd) that must not exist afterwards."""
    code, out, err = run(command, cwd, env)
    problems = []
    if code is None:
        problems.append("did not end (hang?)")
    elif status == "nonzero" and code == 0 or status != "nonzero" and code != status:
        problems.append("exit status %r, expected %r" % (code, status))
    for expected in ([output] if isinstance(output, str) else output or []):
        if not re.search(expected, out + err):
            problems.append("output lacks %r" % expected)
    problems += ["wrote %s" % f for f in absent if os.path.exists(os.path.join(cwd, f))]
    if problems:
        failures.append(name)
        print("FAIL %s: %s\n  command: %s\n  stdout: %s\n  stderr: %s" % (
            name, "; ".join(problems), " ".join(command), out[-2000:], err[-2000:]))
    else:
        print("ok   %s" % name)
    return out


def points_in(path):
    reader = vtkPLYReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput().GetNumberOfPoints()


scratch = tempfile.mkdtemp(prefix="asm-examples-")
inputs, work = os.path.join(scratch, "in"), os.path.join(scratch, "work")
os.makedirs(inputs)
os.makedirs(work)
shutil.copy(KITTEN, inputs)
with open(os.path.join(inputs, "notes.ply"), "w") as text:
    text.write("not a PLY file\n")

# --- simplify_bunny.py (the README's main job) ------------------------------------------------
bunny = [PVPYTHON, os.path.join(EXAMPLES, "simplify_bunny.py")]
check("simplify_bunny: relative paths against the current directory", bunny + ["../in/kitten.ply"], work, 0,
      r"N         : 5210\s+mode      : Feature Preserving\s+N_s       : 261\s")
written = os.path.join(work, "asm-output.ply")
if not os.path.isfile(written) or points_in(written) != 261:
    failures.append("simplify_bunny: asm-output.ply in the current directory with 261 points")
    print("FAIL asm-output.ply not written to %s with 261 points" % work)
if os.path.exists(written):
    os.remove(written)
check("simplify_bunny: missing input", bunny + ["../in/missing.ply", "a.ply"], work, 1, r"no such file", ["a.ply"])
check("simplify_bunny: not a PLY file", bunny + ["../in/notes.ply", "a.ply"], work, 1, r"no points read", ["a.ply"])
check("simplify_bunny: output not .ply", bunny + ["../in/kitten.ply", "a.txt"], work, 2, r"must end in \.ply",
      ["a.txt", "a.txt.ply"])
check("simplify_bunny: output .PLY", bunny + ["../in/kitten.ply", "a.PLY"], work, 2, r"must end in \.ply",
      ["a.PLY", "a.PLY.ply"])
check("simplify_bunny: output directory missing", bunny + ["../in/kitten.ply", "none/a.ply"], work, 1,
      r"does not exist")
for fraction in ("0", "-0.1", "1.5", "nan", "x"):
    check("simplify_bunny: --fraction %s" % fraction, bunny + ["../in/kitten.ply", "a.ply", "--fraction", fraction],
          work, 2, r"--fraction", ["a.ply"])
check("simplify_bunny: empty result", bunny + ["../in/kitten.ply", "a.ply", "--fraction", "1e-5"], work, 1,
      r"produced no points", ["a.ply"])
check("simplify_bunny: --plugin missing", bunny + ["../in/kitten.ply", "a.ply", "--plugin", "none.so"], work, 1,
      r"ASM plugin not found", ["a.ply"])
# The plugin from PV_PLUGIN_PATH alone: the scripts copied out of the repository (no build tree
# next to them to fall back on). pvpython loads the plugins of PV_PLUGIN_PATH itself; the script
# then loads the same file (loading another copy would register the proxies twice).
outside = os.path.join(scratch, "scripts")
shutil.copytree(EXAMPLES, outside)
environment = dict(os.environ, PV_PLUGIN_PATH=os.path.dirname(os.environ["ASM_PLUGIN"]))
del environment["ASM_PLUGIN"]
check("simplify_bunny: plugin from PV_PLUGIN_PATH",
      [PVPYTHON, os.path.join(outside, "simplify_bunny.py"), "../in/kitten.ply", "b.ply", "--fraction", "0.1"],
      work, 0, r"N_s       : 521\s", env=environment)
environment["PV_PLUGIN_PATH"] = scratch
check("simplify_bunny: no plugin anywhere",
      [PVPYTHON, os.path.join(outside, "simplify_bunny.py"), "../in/kitten.ply", "c.ply"], work, 1,
      r"ASM plugin not found", ["c.ply"], env=environment)

# --- time_scans.py and paper_table2.py (the wrapped classes) ----------------------------------
scans = [PVPYTHON, os.path.join(EXAMPLES, "time_scans.py"), "--runs", "1"]
check("time_scans: a missing scan is reported, the others timed", scans + ["../in/missing.ply", "../in/kitten.ply"],
      work, 1, [r"missing\.ply: no such file", r"kitten\.ply +5210 +261 "])
check("time_scans: --runs 0", scans[:2] + ["--runs", "0", "../in/kitten.ply"], work, 2, r"--runs")
check("time_scans: --threads -1", scans + ["--threads", "-1", "../in/kitten.ply"], work, 2, r"--threads")
table = check("paper_table2: a scan also in Testing/Data is one row",
              [PVPYTHON, os.path.join(EXAMPLES, "paper_table2.py"), "--runs", "1", "--with-test-data", KITTEN],
              work, 0, r"kitten +5210 +261 ")
if len(re.findall(r"^kitten ", table, re.M)) != 1:
    failures.append("paper_table2: kitten rows")
    print("FAIL paper_table2: %d kitten rows" % len(re.findall(r"^kitten ", table, re.M)))

# --- paper_figures.py (the checks come before any rendering) and check_image.py --------------
figures = [PVBATCH, os.path.join(EXAMPLES, "paper_figures.py")]
check("paper_figures: missing scan", figures + ["../in/missing.ply", "-o", "f.png"], work, 1, r"no such file",
      ["f.png"])
check("paper_figures: output directory missing", figures + ["../in/kitten.ply", "-o", "none/f.png"], work, 1,
      r"does not exist")
check("paper_figures: --fractions 0", figures + ["../in/kitten.ply", "--fractions", "0.05", "0"], work, 2,
      r"--fractions")
grey = vtkImageMandelbrotSource()
grey.SetWholeExtent(0, 63, 0, 63, 0, 0)
cast = vtkImageCast()
cast.SetInputConnection(grey.GetOutputPort())
cast.SetOutputScalarTypeToUnsignedChar()
png = vtkPNGWriter()
png.SetFileName(os.path.join(work, "grey.png"))
png.SetInputConnection(cast.GetOutputPort())
png.Write()
check("check_image: a grey PNG against itself", [PVPYTHON, os.path.join(EXAMPLES, "check_image.py"), "grey.png",
                                                "--baseline", "grey.png"], work, 0, r"mean absolute difference 0\.000")

# --- mpi_scaling.py: its command line (the run itself is not a test) ------------------------
scaling = [PVPYTHON, os.path.join(EXAMPLES, "mpi_scaling.py")]
check("mpi_scaling: --points 0", scaling + ["--points", "0"], work, 2, r"--points")
check("mpi_scaling: --fraction 0", scaling + ["--fraction", "0"], work, 2, r"--fraction")
check("mpi_scaling: --final-lloyd-iterations 9", scaling + ["--final-lloyd-iterations", "9"], work, 2,
      r"--final-lloyd-iterations")

# --- mpi_simplify_pieces.py under mpiexec: bad input ends the run (no hang) ------------------
if MPIEXEC:
    pieces = [MPIEXEC, "--oversubscribe", "-n", "2", PVBATCH, "--mpi", os.path.join(EXAMPLES, "mpi_simplify_pieces.py")]
    check("pieces: --split of a missing file", pieces + ["--split", "../in/missing.ply", "m.pvtp"], work, "nonzero",
          r"no such file", ["m.pvtp"])
    check("pieces: --split to a .vtp", pieces + ["--split", "../in/kitten.ply", "m.vtp"], work, "nonzero",
          r"\.pvtp or \.pvtu", ["m.vtp"])
    check("pieces: --split", pieces + ["--split", "../in/kitten.ply", "k.pvtp"], work, 0, r"5210 points into 2 pieces")
    check("pieces: --split into a new directory", pieces + ["--split", "../in/kitten.ply", "new/k.pvtp"], work, 0,
          r"5210 points into 2 pieces")
    check("pieces: --points 0", pieces + ["k.pvtp", "s.pvtp", "--points", "0"], work, "nonzero", r"--points",
          ["s.pvtp"])
    check("pieces: empty result", pieces + ["k.pvtp", "s.pvtp", "--fraction", "1e-5"], work, "nonzero",
          r"produced no points", ["s.pvtp"])
    check("pieces: simplify", pieces + ["k.pvtp", "s.pvtp", "--points", "100"], work, 0, r"N 5210  N_s 100 ")
    os.remove(os.path.join(work, "s.pvtp"))
    os.remove(os.path.join(work, "k", "k_1.vtp"))
    check("pieces: a piece missing", pieces + ["k.pvtp", "s.pvtp"], work, "nonzero", r"k_1\.vtp: no such file",
          ["s.pvtp"])

if failures:
    sys.exit("TestExampleScripts: %d failed: %s" % (len(failures), ", ".join(failures)))
shutil.rmtree(scratch)
print("TestExampleScripts: OK")
