"""MPI test of the plugin, run under `mpiexec -n K pvbatch --mpi` (the
script runs on process 0; ParaView runs the pipeline on every process): the
bunny read on process 0, spread over the K processes by ParaView's
RedistributeDataSet (a spatial split, unlike TestMPISimplify.py's
interleaved one), simplified by the ASMSimplify proxy to exactly N_s = 1800
points (Always Distribute on) and measured by the KeyPointError proxy, whose
figures table has one row (process 0's; before 2026-11-28, one per process). The
fetched output goes to the .npz file given as argument, in the format of
TestMPISimplify.py, so CheckMPIOutputs.py compares it with the other runs.

Environment: ASM_PLUGIN (plugin library), ASM_DATA_DIR (Testing/Data).
"""
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy

plugin = os.environ["ASM_PLUGIN"]
LoadPlugin(plugin, ns=globals())
data_dir = os.environ["ASM_DATA_DIR"]
MODE = sys.argv[2] if len(sys.argv) > 2 else "paper"  # as TestMPISimplify.py
NS = 1800 if MODE == "paper" else 8000

reader = PLYReader(FileNames=[os.path.join(data_dir, "bunny.ply")])
value = Calculator(Input=reader, ResultArrayName="Value", Function="coordsX*10+coordsY",
                   ResultArrayType="Double")
# RedistributeDataSet moves cells: give every point a vertex cell first
# (MaskPoints keeping all; ConvertToPointCloud of ParaView 5.11 crashes on
# the empty pieces of processes 1..K-1).
cloud = MaskPoints(Input=value, OnRatio=1, MaximumNumberofPoints=10 ** 9, GenerateVertices=1,
                   SingleVertexPerCell=1)
spread = RedistributeDataSet(Input=cloud)
asm = ASMSimplify(Input=spread, TargetMode="Number Of Output Points",  # noqa: F405
                  NumberOfOutputPoints=NS, AlwaysDistribute=1)
if MODE == "paper":
    asm.Mode = "Paper"
else:
    asm.FeatureSamplesPerCell = 1.0  # the default mode, FillHoles on (gathered over the processes)
kpe = KeyPointError(Original=spread, Simplified=asm)  # noqa: F405
kpe.UpdatePipeline()

processes = servermanager.ActiveConnection.GetNumberOfDataPartitions()
# Every process holds part of the input and of the output.
info = spread.GetDataInformation()
assert info.GetNumberOfPoints() == 35947, info.GetNumberOfPoints()

out = servermanager.Fetch(asm)
measured = servermanager.Fetch(kpe, idx=0)
n = out.GetNumberOfPoints()
assert measured.GetNumberOfPoints() == n
pd, mpd = out.GetPointData(), measured.GetPointData()
xyz = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)
columns = [xyz[:, 0], xyz[:, 1], xyz[:, 2]]
for name in ("Value", "MeanCurvature", "KeyPoint", "ClusterSize"):
    columns.append(vtk_to_numpy(pd.GetArray(name)).astype(np.float64))
# The fetched pieces keep their order: the Error of point i is at i.
columns.append(vtk_to_numpy(mpd.GetArray("Error")).astype(np.float64))
table = np.column_stack(columns)
fd, mfd = out.GetFieldData(), measured.GetFieldData()
figures = {name: fd.GetArray(name).GetValue(0) for name in ("AKPE", "MKPE", "NumberOfKeyPoints", "CellSize")}
for name in ("AKPE", "MKPE", "HausdorffDistance", "MeanDistanceOriginalToSimplified",
             "MeanDistanceSimplifiedToOriginal", "PointToPlaneMean", "NumberOfOriginalKeyPoints",
             "NumberOfSimplifiedKeyPoints", "NumberOfOriginalPoints", "NumberOfSimplifiedPoints"):
    figures["KPE." + name] = mfd.GetArray(name).GetValue(0)
# The figures table: one row in ParaView (the processes' tables gathered),
# with the field data's figures: process 0 alone fills it.
assert kpe.GetDataInformation(1).GetNumberOfRows() == 1, kpe.GetDataInformation(1).GetNumberOfRows()
fetched = servermanager.Fetch(kpe, idx=1)
assert fetched.GetNumberOfRows() == 1, fetched.GetNumberOfRows()
for name in figures:
    if name.startswith("KPE."):
        assert fetched.GetColumnByName(name[4:]).GetValue(0) == figures[name], name
order = np.lexsort(table[:, 2::-1].T)
assert n == NS and figures["KPE.NumberOfSimplifiedPoints"] == NS, (n, figures)
np.savez(sys.argv[1], table=table[order], names=list(figures), values=list(figures.values()),
         ns=NS, mode=MODE)
print("plugin, %s mode, %d processes: %d output points, figures %s" % (MODE, processes, n, figures))
