"""MPI test, run under `mpiexec -n 3 pvbatch --mpi --symmetric`: small random
clouds (100 points in a cube: nearly every grid cell holds too few points
for a sample of its own, so the automatic cell size takes the outlier-robust
second search, asmcore::SparseCellsDominate) split over the processes by
point index, simplified in both modes. The distributed run must pick the
serial run's cell size exactly and give its points: each cell's points are
summed over the processes before its share is taken, and the shares are
summed in fixed point (before 2026-11-28 the distributed search left the
second search out, and 12 of 360 such runs of a sweep's reproducer, one
process, differed from the serial ones).
vtkKeyPointError's grid too, on slabs with three far outliers.

Environment: PYTHONPATH with the asmvtk package.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints, vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkParallelCore import vtkMultiProcessController

from asm_mpi_setup import gathered, simplified
from asmvtk import vtkASMSimplify, vtkKeyPointError

controller = vtkMultiProcessController.GetGlobalController()
rank, size = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
assert size == 3, size


def cloud(xyz):
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz), deep=1))
    data = vtkPolyData()
    data.SetPoints(points)
    return data


def run(data, mode, count, serial):
    _, out, _ = simplified(controller, data, mode, count, serial=serial)
    cell = out.GetFieldData().GetArray("CellSize").GetValue(0)
    return cell, vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64).reshape(-1, 3)


def all_points(local):
    received = vtkDoubleArray()
    controller.AllGatherV(numpy_to_vtk(np.ascontiguousarray(local.ravel()), deep=1), received)
    return vtk_to_numpy(received).reshape(-1, 3)


def ordered(xyz):
    return xyz[np.lexsort(xyz.T[::-1])]


runs = 0
for seed in range(30):
    xyz = np.random.default_rng(seed).random((100, 3))
    mine = xyz[rank::size]
    for mode in (vtkASMSimplify.FEATURE_PRESERVING, vtkASMSimplify.PAPER):
        for count in (5, 12, 30):
            serial_cell, serial_points = run(cloud(xyz), mode, count, True)
            cell, local = run(cloud(mine), mode, count, False)
            points = all_points(local)
            what = (seed, mode, count)
            assert cell == serial_cell, (what, cell, serial_cell)
            assert len(points) == count, (what, len(points))
            assert np.allclose(ordered(points), ordered(serial_points), rtol=0, atol=1e-12), what
            runs += 1


def figures(original, simplified, serial):
    kpe = vtkKeyPointError()
    if serial:
        kpe.SetController(None)
    kpe.SetInputData(0, original)
    kpe.SetInputData(1, simplified)
    kpe.SetGenerateCurvature(False)
    kpe.Update()
    fd = kpe.GetOutput().GetFieldData()
    return {name: fd.GetArray(name).GetValue(0)
            for name in ("CellSize", "AKPE", "MKPE", "NumberOfOriginalKeyPoints")}


# vtkKeyPointError sizes its grid as the simplifier does: the same search
# (before 2026-11-28 its distributed runs left out the subsample start and
# the sparse-cell search: on a slab with three far outliers, a cell size of
# 31.6 against the serial 0.867). The "simplified" cloud: every 10th point.
for seed in range(10):
    xyz = np.random.default_rng(seed).random((200, 3))
    xyz[:, 2] *= 0.2
    xyz[:3] = [[50, 0, 0], [0, 50, 0], [0, 0, 50]]
    serial = figures(cloud(xyz), cloud(xyz[::10]), True)
    distributed = figures(cloud(xyz[rank::size]), cloud(xyz[::10][rank::size]), False)
    assert distributed["CellSize"] == serial["CellSize"], (seed, distributed, serial)
    for name, value in serial.items():
        assert abs(distributed[name] - value) <= 1e-9 * abs(value), (seed, name, distributed, serial)
    runs += 1

# Exact duplicates with different values (every point twice: ("b", 0), then
# ("a", 1), the string array listed first): a sample stands for the copy
# whose values come first, the numeric arrays compared first in both runs;
# at N_s = N two samples share each position and both stand for it (before
# 2026-11-28 a serial run let the string decide, and at N_s = N a distributed
# run left 7 of 300 samples on the other copy: their group's lead was a halo
# sample, not in the result).
def labelled(xyz, names, labels):
    data = cloud(xyz)
    strings = vtkStringArray()
    strings.SetName("name")
    for value in names:
        strings.InsertNextValue(value)
    data.GetPointData().AddArray(strings)
    numbers = numpy_to_vtk(np.ascontiguousarray(labels, dtype=np.int32), deep=1)
    numbers.SetName("label")
    data.GetPointData().AddArray(numbers)
    return data


def chosen(out, everywhere):
    """(name is "a", label) of every output point, sorted: of this process's
    output, or of every process's (`everywhere`: collective)."""
    n = out.GetNumberOfPoints()
    names = out.GetPointData().GetAbstractArray("name")
    labels = out.GetPointData().GetArray("label")
    local = [float(v) for i in range(n) for v in (names.GetValue(i) == "a", labels.GetValue(i))]
    values = gathered(controller, local) if everywhere else np.array(local)
    return sorted(map(tuple, values.reshape(-1, 2).tolist()))


base = np.random.default_rng(5).random((150, 3))
xyz = np.r_[base, base]
names = ["b"] * 150 + ["a"] * 150
labels = [0] * 150 + [1] * 150
whole = labelled(xyz, names, labels)
mine = labelled(xyz[rank::size], names[rank::size], labels[rank::size])
for mode in (vtkASMSimplify.FEATURE_PRESERVING, vtkASMSimplify.PAPER):
    for count in (30, 300):
        _, serial, _ = simplified(controller, whole, mode, count, serial=True)
        _, distributed, _ = simplified(controller, mine, mode, count)
        expected = chosen(serial, False)  # (each process ran the whole serial run)
        got = chosen(distributed, True)
        assert len(got) == count and got == expected, (mode, count, got[:5], expected[:5])
        assert all(pair == (0.0, 0.0) for pair in got), (mode, count)
        runs += 1
# N_s close to N (a slab of 3000 points, 98 and 99.5 %): a sample whose ring
# has no point to give takes one among those its process outputs. Before
# 2026-11-29 it took the nearest anywhere in the process's grid, halo
# included: one point was then output in two clusters (ClusterSize summed to
# 3001, seed 7) or in none (2999, seed 3, a halo sample that seemed empty
# took it). Every point is in exactly one cluster, every sample in its own
# position (the choice may differ from a one-process run's).
for seed, count in ((3, 2985), (7, 2940), (3, 2940), (7, 2985)):
    xyz = np.random.default_rng(seed).random((3000, 3)) * [1.0, 1.0, 0.02]
    _, out, _ = simplified(controller, cloud(xyz[rank::size]), vtkASMSimplify.FEATURE_PRESERVING,
                           count)
    sizes = gathered(controller, vtk_to_numpy(out.GetPointData().GetArray("ClusterSize")))
    points = all_points(vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64))
    assert len(points) == count and len(np.unique(points, axis=0)) == count, (seed, count)
    assert sizes.sum() == 3000 and sizes.min() >= 1, (seed, count, sizes.sum(), sizes.min())
    runs += 1
if rank == 0:
    print("%d runs: the serial cell size, points, key point error and choice among duplicates,"
          " and whole clusters at N_s close to N, over %d processes" % (runs, size))
