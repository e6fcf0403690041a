"""Scaling of vtkASMSimplify in MPI runs: a large synthetic cloud generated in
parallel (each process makes its share, seeded by process id), simplified to
1 % with 1, 2, ... processes. Not a test; figures for docs/parallel.md ("Scaling").

  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \\
    mpiexec --oversubscribe -n 2 pvbatch --mpi --symmetric Examples/Python/mpi_scaling.py \\
      --points 50000000 [--fraction 0.01] [--always-distribute] [--mode paper] [--no-fill-holes] \\
      [--no-covering] [--final-lloyd-iterations N]

--symmetric is needed: every process runs this script and makes its share of
the cloud (without it, only process 0 would, and the run would hang in the
filter's collectives). PYTHONPATH must hold the build tree's asmvtk package
(build/lib/python3/dist-packages).
Prints, on process 0: processes, points, output points, wall time of the
filter (max over processes), each process's CPU time in the filter (what
a loaded machine cannot inflate) and peak resident memory (of the whole
process: the generated cloud included).
The cloud: points on a wavy sphere-like surface (r = 1 + 0.1 sin(5u) sin(4v))
with 0.2 % noise, so the cells hold curved patches, as scans do.
"""
import argparse
import os
import resource
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkParallelCore import vtkMultiProcessController

from asmvtk import vtkASMSimplify

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from asm_plugin import fraction_arg, positive_int_arg  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--points", type=positive_int_arg, default=50_000_000)
parser.add_argument("--fraction", type=fraction_arg, default=0.01)
parser.add_argument("--always-distribute", action="store_true")
parser.add_argument("--no-curvature", action="store_true")
parser.add_argument("--mode", choices=("feature", "paper"), default="feature")
# FillHoles off (the faster setting; distributed runs gather its rankings)
parser.add_argument("--no-fill-holes", action="store_true")
parser.add_argument("--final-lloyd-iterations", type=int, choices=range(0, 9), metavar="0..8")  # (default: the filter's)
parser.add_argument("--no-covering", action="store_true")  # CoveringRounds 0, as distributed runs do
args = parser.parse_args()

controller = vtkMultiProcessController.GetGlobalController()
rank, size = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()

# This process's share of the cloud, from its own seeded generator.
count = args.points // size + (1 if rank < args.points % size else 0)
rng = np.random.default_rng(12345 + rank)
xyz = np.empty((count, 3))
chunk = 5_000_000
for start in range(0, count, chunk):
    n = min(chunk, count - start)
    u = rng.uniform(0.0, 2.0 * np.pi, n)
    v = np.arccos(rng.uniform(-1.0, 1.0, n))
    r = 1.0 + 0.1 * np.sin(5.0 * u) * np.sin(4.0 * v) + rng.normal(0.0, 0.002, n)
    xyz[start:start + n, 0] = r * np.sin(v) * np.cos(u)
    xyz[start:start + n, 1] = r * np.sin(v) * np.sin(u)
    xyz[start:start + n, 2] = r * np.cos(v)
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz, deep=0))
cloud = vtkPolyData()
cloud.SetPoints(points)

asm = vtkASMSimplify()
asm.SetInputData(cloud)
asm.SetOutputFraction(args.fraction)
asm.SetAlwaysDistribute(args.always_distribute)
asm.SetGenerateCurvature(not args.no_curvature)
asm.SetMode(vtkASMSimplify.PAPER if args.mode == "paper" else vtkASMSimplify.FEATURE_PRESERVING)
asm.SetFillHoles(not args.no_fill_holes)
if args.final_lloyd_iterations is not None:
    asm.SetFinalLloydIterations(args.final_lloyd_iterations)
if args.no_covering:
    asm.SetCoveringRounds(0)
controller.Barrier()
start, cpu_start = time.perf_counter(), time.process_time()
asm.Update()
elapsed, cpu = time.perf_counter() - start, time.process_time() - cpu_start

out = asm.GetOutput().GetNumberOfPoints()
peak_mib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
send = np.array([elapsed, out, peak_mib, cpu])
gathered = np.zeros(4 * size)
controller.AllGather(send, gathered, 4)
if rank == 0:
    g = gathered.reshape(size, 4)
    print("%s  processes %d  points %d  output %d  wall %.2f s  CPU s per process %s  peak MiB per process %s"
          % (args.mode, size, args.points, int(g[:, 1].sum()), g[:, 0].max(),
             " ".join("%.1f" % c for c in g[:, 3]), " ".join("%.0f" % m for m in g[:, 2])))
