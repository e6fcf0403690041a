"""MPI test, run under `mpiexec -n K pvbatch --mpi --symmetric` (every
process runs this script): the bunny split over the K processes in an
interleaved way (every grid cell is split; each process holds its points in
reverse order), simplified to exactly N_s points with the wrapped
vtkASMSimplify (started by mpiexec, so K = 1 takes the distributed path
too, without AlwaysDistribute), then
measured by vtkKeyPointError. Every process must report the same global
figures (MKPE, AKPE, counts, cell size). Process 0 gathers the output and writes
sorted coordinates, arrays and figures to the .npz file given as argument;
CheckMPIOutputs.py compares the files of K = 1, 2, 3, 4 (with 3 and 4
processes the grid is cut across two axes: boxes of cells, not slabs).

Second argument: the mode, "paper" (N_s = 1800) or "feature" (the default
FEATURE_PRESERVING mode, N_s = 8000 with FeatureSamplesPerCell 1, a grid of
52 cells along the bunny, so that each process's halo of 6 cell rings does
not cover the whole bunny; every refinement at its default:
FillHoles, whose rankings and removal costs a distributed run gathers over
all processes, the final Lloyd iterations, whose weights it normalises over
all processes, and BoundSnappedHoles, which it takes over all processes).
"lattice-paper" and "lattice-feature": the same two modes (N_s = 2000) on
gridded data instead of the bunny, whose points tie exactly everywhere: a
150 x 150 lattice over [-3, 3]^2 with a stepped height z = 0.1 floor(x + y),
every point twice, the copies of every other point with different labels
(an integer array, "Label", taken from each sample's representative: 5,
the copy whose values come first), the others with the same label and
different strings (which then decide: a distributed run reads them from
the processes holding the copies), the representatives' indices compared
too ("Source", from that string array); each cell is processed in its canonical order
(asmcore::CanonicalOrder), so the serial path, which reads the points in
input order, and the distributed runs, which receive them in another, agree.
Optional third argument "serial": pvbatch started without mpiexec (one
process, AlwaysDistribute off), so the serial path runs; its output must
match the distributed runs.

Environment: ASM_DATA_DIR (Testing/Data), PYTHONPATH with the asmvtk package.
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import (vtkBitArray, vtkDoubleArray, vtkPoints, vtkStringArray,
                                      vtkVariant, vtkVariantArray)
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkParallelCore import vtkMultiProcessController

from asmvtk import vtkASMSimplify, vtkKeyPointError

MODE = sys.argv[2] if len(sys.argv) > 2 else "paper"
LATTICE = MODE.startswith("lattice-")
NS = 2000 if LATTICE else 1800 if MODE == "paper" else 8000
SERIAL = len(sys.argv) > 3 and sys.argv[3] == "serial"
controller = vtkMultiProcessController.GetGlobalController()
rank, size = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
data_dir = os.environ.get("ASM_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "Data"))

if LATTICE:
    u = np.linspace(-3.0, 3.0, 150)
    gx, gy = np.meshgrid(u, u, indexing="ij")
    grid = np.column_stack([gx.ravel(), gy.ravel(), 0.1 * np.floor(gx.ravel() + gy.ravel())])
    xyz = np.concatenate([grid, grid])
else:
    reader = vtkPLYReader()
    reader.SetFileName(os.path.join(data_dir, "bunny.ply"))
    reader.Update()
    xyz = vtk_to_numpy(reader.GetOutput().GetPoints().GetData()).astype(np.float64)
# Interleaved split by a hash of the point index, reversed order.
index = np.arange(len(xyz), dtype=np.uint64)
owner = ((index * np.uint64(2654435761)) % np.uint64(2 ** 32)) % np.uint64(size)


def points_of(process):
    """The indices (into xyz) of the points process `process` holds, in its order."""
    return np.nonzero(owner == process)[0][::-1]


mine = points_of(rank)
points = vtkPoints()
points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz[mine]), deep=1))
piece = vtkPolyData()
piece.SetPoints(points)
# A point array that must be averaged over the same clusters whatever K.
value = numpy_to_vtk(np.ascontiguousarray(xyz[mine, 0] * 10.0 + xyz[mine, 1]), deep=1)
value.SetName("Value")
piece.GetPointData().AddArray(value)
if LATTICE:
    # The lattice's two copies of every odd point carry different labels (an
    # integer array: a sample takes its representative's): the copy whose
    # label comes first, 5 (by value, not by id or by the values' bytes), in
    # every run, whatever the order the copies come in. The copies of an even
    # point both have 5: their strings decide.
    copy_index = np.arange(len(xyz))
    labels = np.where((copy_index < len(grid)) & (copy_index % 2 == 1), 256, 5).astype(np.int32)
    label = numpy_to_vtk(np.ascontiguousarray(labels[mine]), deep=1)
    label.SetName("Label")
    piece.GetPointData().AddArray(label)
# A string array (it does not travel with the points: a distributed run reads
# it at the samples' representatives after the run): each point's index in
# xyz, which every sample must carry for its representative (and, on the
# lattice, the copy whose label comes first: the string comes after the
# label, so the label decides, on the serial path too; where the labels tie,
# the copy whose string comes first, in every run).
# A variant and a bit array travel the same way.
names = vtkStringArray()
names.SetName("Point name")
variants = vtkVariantArray()
variants.SetName("Point variant")
bits = vtkBitArray()
bits.SetName("Point bit")


def variant_of(g):
    return vtkVariant(int(g)) if g % 2 else vtkVariant("v%d" % g)


for g in mine:
    names.InsertNextValue("point %d" % g)
    variants.InsertNextValue(variant_of(g))
    bits.InsertNextValue(int(g % 3 == 0))
for array in (names, variants, bits):
    piece.GetPointData().AddArray(array)

asm = vtkASMSimplify()
asm.SetInputData(piece)
asm.SetTargetModeToNumberOfOutputPoints()
asm.SetNumberOfOutputPoints(NS)
assert not asm.GetAlwaysDistribute()
if SERIAL:
    assert size == 1, "the serial run is a one-process run"
    assert not any(os.environ.get(v) for v in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE")), \
        "the serial run is started without mpiexec"
if MODE in ("paper", "lattice-paper"):
    asm.SetMode(vtkASMSimplify.PAPER)
elif LATTICE:
    assert asm.GetMode() == vtkASMSimplify.FEATURE_PRESERVING and asm.GetFillHoles()
    asm.SetFeatureSamplesPerCell(1.0)
else:
    assert asm.GetMode() == vtkASMSimplify.FEATURE_PRESERVING and asm.GetFillHoles()
    asm.SetFeatureSamplesPerCell(1.0)
    assert asm.GetFinalLloydIterations() > 0 and asm.GetLloydVariationWeight() > 0
    assert asm.GetCoveringRounds() == 0  # (off by default; CoveringRoundsOverSlabs tests it)
if os.environ.get("VTK_SMP_BACKEND_IN_USE") == "STDThread":
    # The threaded runs: threads whatever the size of a process's share.
    from vtkmodules.vtkCommonCore import vtkSMPTools
    assert vtkSMPTools.GetBackend() == "STDThread", vtkSMPTools.GetBackend()
    asm.SetMinimumPointsForThreads(0)
asm.Update()
out = asm.GetOutput()
# The distributed path (every run under mpiexec, K = 1 included) says which
# process each sample's representative comes from; the serial path does not.
assert (out.GetPointData().GetArray("vtkOriginalProcessIds") is not None) == (not SERIAL), \
    "a run under mpiexec is distributed, a run without it is not"

# Each sample's string is its representative's (vtkOriginalPointIds on the
# process vtkOriginalProcessIds names; on the serial path, this process).
out_names = out.GetPointData().GetAbstractArray("Point name")
assert out_names is not None and out_names.GetNumberOfValues() == out.GetNumberOfPoints()
representative = vtk_to_numpy(out.GetPointData().GetArray("vtkOriginalPointIds"))
source_process = (np.zeros(len(representative), dtype=int) if SERIAL
                  else vtk_to_numpy(out.GetPointData().GetArray("vtkOriginalProcessIds")))
sources = np.array([points_of(r)[i] for r, i in zip(source_process, representative)], dtype=np.int64)
carried = np.array([int(out_names.GetValue(i).split()[1]) for i in range(out.GetNumberOfPoints())],
                   dtype=np.int64)
assert np.array_equal(carried, sources), np.count_nonzero(carried != sources)
out_variants = out.GetPointData().GetAbstractArray("Point variant")
out_bits = out.GetPointData().GetAbstractArray("Point bit")
assert out_variants is not None and out_bits is not None
for i, g in enumerate(sources):
    v = out_variants.GetValue(i)
    assert v.GetType() == variant_of(g).GetType() and v.ToString() == variant_of(g).ToString(), (i, g)
    assert out_bits.GetValue(i) == int(g % 3 == 0), (i, g)

kpe = vtkKeyPointError()
kpe.SetInputData(0, piece)
kpe.SetInputConnection(1, asm.GetOutputPort())
kpe.Update()
measured = kpe.GetOutput()

# Gather every process's output on process 0.
def gather(name_arrays):
    local = np.column_stack(name_arrays) if len(name_arrays[0]) else np.zeros((0, len(name_arrays)))
    send = numpy_to_vtk(np.ascontiguousarray(local.ravel(), dtype=np.float64), deep=1)
    received = vtkDoubleArray()
    controller.AllGatherV(send, received)
    allv = vtk_to_numpy(received)
    return allv.reshape(-1, len(name_arrays))


n = out.GetNumberOfPoints()
pd = out.GetPointData()
mpd = measured.GetPointData()
columns = [vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64).reshape(n, 3)[:, c] for c in range(3)]
for name in ("Value", "MeanCurvature", "KeyPoint", "ClusterSize"):
    columns.append(vtk_to_numpy(pd.GetArray(name)).astype(np.float64) if n else np.zeros(0))
columns.append(vtk_to_numpy(mpd.GetArray("Error")).astype(np.float64) if n else np.zeros(0))
if LATTICE:
    columns.append(vtk_to_numpy(pd.GetArray("Label")).astype(np.float64) if n else np.zeros(0))
    # Which input point each sample stands for: the same in every run.
    columns.append(carried.astype(np.float64))
table = gather(columns)
fd = out.GetFieldData()
mfd = measured.GetFieldData()
figures = {name: fd.GetArray(name).GetValue(0) for name in ("AKPE", "MKPE", "NumberOfKeyPoints", "CellSize")}
for name in ("AKPE", "MKPE", "HausdorffDistance", "MeanDistanceOriginalToSimplified",
             "MeanDistanceSimplifiedToOriginal", "PointToPlaneMean", "NumberOfOriginalKeyPoints",
             "NumberOfSimplifiedKeyPoints", "NumberOfOriginalPoints", "NumberOfSimplifiedPoints"):
    figures["KPE." + name] = mfd.GetArray(name).GetValue(0)
# The figures table (output 1): one row over the processes, process 0's (the
# other processes: the same columns, no row).
figure_table = kpe.GetOutputDataObject(1)
table_rows = vtkDoubleArray()
controller.AllGatherV(numpy_to_vtk(np.array([figure_table.GetNumberOfRows()], dtype=np.float64),
                                   deep=1), table_rows)
assert vtk_to_numpy(table_rows).tolist() == [1] + [0] * (size - 1), vtk_to_numpy(table_rows)
assert figure_table.GetNumberOfColumns() == 22, figure_table.GetNumberOfColumns()
if rank == 0:
    assert figure_table.GetColumnByName("AKPE").GetValue(0) == mfd.GetArray("AKPE").GetValue(0)
# Every process reports the same global figures: each is reduced over the
# processes (MKPE the largest error, AKPE the mean over every key point, the
# counts summed), not taken of this process's share.
every = vtkDoubleArray()
mine_figures = numpy_to_vtk(np.array(list(figures.values()), dtype=np.float64), deep=1)
controller.AllGatherV(mine_figures, every)
every = vtk_to_numpy(every).reshape(size, len(figures))
spread = np.abs(every - every[0]).max(0) / np.maximum(1.0, np.abs(every[0]))
assert np.all(spread <= 1e-12), dict(zip(figures, every.T.tolist()))
# The path taken: the distributed one names the process of each sample's
# representative point.
assert (pd.GetArray("vtkOriginalProcessIds") is None) == SERIAL
local_keys = int(np.sum(vtk_to_numpy(pd.GetArray("KeyPoint")))) if n else 0
all_keys = vtkDoubleArray()
controller.AllGatherV(numpy_to_vtk(np.array([local_keys], dtype=np.float64), deep=1), all_keys)
if rank == 0:
    # Global figures: exactly N_s points over the processes, the key point
    # count of the whole output, the error measured on the whole cloud.
    assert len(table) == NS, len(table)
    assert figures["NumberOfKeyPoints"] == vtk_to_numpy(all_keys).sum() > 0, figures
    assert figures["KPE.NumberOfSimplifiedPoints"] == NS, figures
    assert figures["KPE.NumberOfOriginalPoints"] == len(xyz), figures
    assert 0 < figures["KPE.AKPE"] <= figures["KPE.MKPE"], figures
    if LATTICE:
        assert np.all(table[:, 8] == 5), np.unique(table[:, 8], return_counts=True)
    if MODE == "feature":
        # InputPointSamples: every output point is an input point, exactly,
        # except the few that BoundSnappedHoles moved towards their cluster's
        # centre (the bound of the whole cloud, over all processes).
        inputs = set(map(tuple, xyz))
        moved = sum(tuple(p) not in inputs for p in table[:, :3])
        print("output points moved off their input point by the snapped-hole bound:", moved)
        assert 0 < moved < NS // 10, moved

    order = np.lexsort(table[:, 2::-1].T)
    np.savez(sys.argv[1], table=table[order], names=list(figures), values=list(figures.values()),
             ns=NS, mode=MODE, serial=SERIAL)
    print("%s, K = %d%s: %d output points, figures %s"
          % (MODE, size, " (serial path)" if SERIAL else "", len(table), figures))
