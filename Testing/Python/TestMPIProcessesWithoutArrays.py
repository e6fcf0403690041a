"""MPI test, run under `mpiexec -n 3 pvbatch --mpi --symmetric`: a cloud held
by one process, as a reader that loads a whole file on process 0 gives it in
ParaView (a PLY file with colours), while the other processes have a bare
vtkPolyData: no vtkPoints object and none of the holder's point arrays. The
cloud is the bunny's first 3000 points (doubles) with a numeric array
("Value"), 3-component unsigned char colours ("RGB", the active scalars) and a
string array ("Point name"), held by process 0, then by process 2; given as
one vtkPolyData, then as a vtkMultiBlockDataSet of two leaves (the other
processes: two bare leaves, so that their merged cloud has no vtkPoints and
lacks the arrays vtkOriginalBlockIds and vtkOriginalPointIds that the
holder's merged cloud gets, as with ParaView's Group Datasets of two readers).

vtkASMSimplify, in both modes, N_s = 300: the processes without points own
cells (the boxes are balanced by point count) and receive points with their
arrays, whose layout they take from the agreement alone (until 2026-11-28
they read it from the array of that name in their own input, a null pointer:
SIGSEGV in asmvtk::Redistribute). Exactly N_s points over the processes, the
same points as a serial run on the whole cloud; every process's output has
the holder's arrays with their types, the colours still the active scalars,
and each sample's colour and name are its representative's.

Environment: ASM_DATA_DIR (Testing/Data), PYTHONPATH with the asmvtk package.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_DOUBLE, VTK_UNSIGNED_CHAR, vtkPoints, vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet, vtkPolyData

from asm_mpi_setup import controller_and_bunny, gathered
from asmvtk import vtkASMSimplify

NS = 300
controller, rank, size, xyz = controller_and_bunny(3, 3000)
diagonal = np.linalg.norm(xyz.max(0) - xyz.min(0))
HALF = len(xyz) // 2


def colour_of(g):
    """The colours of the points g (indices into xyz)."""
    g = np.asarray(g, dtype=np.int64)
    return np.column_stack([g % 256, (7 * g) % 256, (13 * g) % 251]).astype(np.uint8)


def cloud_of(ids):
    """A vtkPolyData of the points xyz[ids] with the holder's three arrays."""
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz[ids]), deep=1))
    cloud = vtkPolyData()
    cloud.SetPoints(points)
    pd = cloud.GetPointData()
    value = numpy_to_vtk(np.ascontiguousarray(xyz[ids, 0] * 10.0 + xyz[ids, 1]), deep=1)
    value.SetName("Value")
    pd.AddArray(value)
    rgb = numpy_to_vtk(colour_of(ids), deep=1, array_type=VTK_UNSIGNED_CHAR)
    rgb.SetName("RGB")
    pd.SetScalars(rgb)
    names = vtkStringArray()
    names.SetName("Point name")
    for g in ids:
        names.InsertNextValue("point %d" % g)
    pd.AddArray(names)
    return cloud


def input_of(holder, composite):
    """This process's input: the whole cloud on `holder`, bare elsewhere."""
    if not composite:
        return cloud_of(np.arange(len(xyz))) if rank == holder else vtkPolyData()
    blocks = vtkMultiBlockDataSet()
    for b, ids in enumerate((np.arange(HALF), np.arange(HALF, len(xyz)))):
        blocks.SetBlock(b, cloud_of(ids) if rank == holder else vtkPolyData())
    return blocks


def sorted_points(points):
    return points[np.lexsort(points.T[::-1])]


def check_simplify(holder, composite, mode):
    data = input_of(holder, composite)
    asm = vtkASMSimplify()
    asm.SetInputData(data)
    asm.SetMode(mode)
    asm.SetTargetModeToNumberOfOutputPoints()
    asm.SetNumberOfOutputPoints(NS)
    asm.Update()
    out = asm.GetOutput()
    local = out.GetNumberOfPoints()
    counts = gathered(controller, [local])
    assert counts.sum() == NS, (holder, composite, mode, counts)
    # The processes without input points own cells and output samples.
    assert np.count_nonzero(counts) > 1, (holder, composite, mode, counts)
    what = (holder, composite, mode, rank)

    # The holder's arrays, with their types, on every output.
    opd = out.GetPointData()
    value, rgb = opd.GetArray("Value"), opd.GetArray("RGB")
    names = opd.GetAbstractArray("Point name")
    assert value is not None and value.GetDataType() == VTK_DOUBLE, what
    assert value.GetNumberOfTuples() == local, what
    assert rgb is not None and rgb.GetDataType() == VTK_UNSIGNED_CHAR, what
    assert rgb.GetNumberOfComponents() == 3 and rgb.GetNumberOfTuples() == local, what
    assert opd.GetScalars() is rgb, (what, opd.GetScalars())
    assert names is not None and names.GetNumberOfValues() == local, what
    process = vtk_to_numpy(opd.GetArray("vtkOriginalProcessIds"))
    assert np.all(process == holder), what
    # Each sample's colour and name are its representative's (an integer
    # array, and a string array read at the representative after the run).
    represented = vtk_to_numpy(opd.GetArray("vtkOriginalPointIds")).astype(np.int64)
    if composite:
        blocks = opd.GetArray("vtkOriginalBlockIds")
        assert blocks is not None and blocks.GetNumberOfTuples() == local, what
        flat = vtk_to_numpy(blocks)
        assert np.all((flat == 1) | (flat == 2)), (what, np.unique(flat))
        represented = represented + np.where(flat == 2, HALF, 0)
    if local:
        assert np.array_equal(vtk_to_numpy(rgb).reshape(local, 3), colour_of(represented)), what
        assert [names.GetValue(i) for i in range(local)] == \
            ["point %d" % g for g in represented], what

    # The points of a serial run on the whole cloud.
    mine = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64).reshape(local, 3)
    every = gathered(controller, mine.ravel()).reshape(-1, 3)
    serial = vtkASMSimplify()
    serial.SetController(None)
    serial.SetInputData(cloud_of(np.arange(len(xyz))))
    serial.SetMode(mode)
    serial.SetTargetModeToNumberOfOutputPoints()
    serial.SetNumberOfOutputPoints(NS)
    serial.Update()
    assert serial.GetOutput().GetPointData().GetArray("vtkOriginalProcessIds") is None
    expected = vtk_to_numpy(serial.GetOutput().GetPoints().GetData()).astype(np.float64)
    worst = np.abs(sorted_points(every) - sorted_points(expected)).max() / diagonal
    assert worst <= 1e-9, (what, worst)
    if rank == 0:
        print("cloud on process %d (%s), mode %d: output points per process %s"
              % (holder, "two leaves" if composite else "one polydata", mode,
                 counts.astype(int).tolist()))


for holder in (0, size - 1):
    for composite in (False, True):
        for mode in (vtkASMSimplify.PAPER, vtkASMSimplify.FEATURE_PRESERVING):
            check_simplify(holder, composite, mode)
