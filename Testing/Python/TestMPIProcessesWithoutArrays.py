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

vtkKeyPointError on each of these runs, its original the same input (no
vtkPoints on the processes without points, or leaves without points, whose
merged cloud has none: until 2026-11-28 a SIGSEGV in RequestData on
original->GetPoints()): the figures of a serial run on the whole clouds, the
same on every process. With the simplified cloud's normals one tuple long
(whose buffer still holds normals pointing the other way), it warns and
signs the curvature as without normals (it used to read the normals past
the array's end in distributed runs). And a nearly flat patch of double
points (a relief of 1e-8 on coordinates about 1.5: flat at float precision,
not at double precision), both clouds held by one process: every process
takes the coordinates' precision of the whole cloud (double, as
vtkASMSimplify does), so the original and simplified key points are a
serial run's, more than none; a process without points used to take float.
In each of these runs, the figures table (output 1) has one row over the
processes, process 0's, with the field data's figures, and every process's
table has the same 22 columns (until 2026-11-28 each process output a row,
so ParaView showed one per process).

Two wavy sheets split along x over the processes, without normals: each
simplified point's curvature is a serial run's, signed away from the whole
original cloud's centroid (until 2026-11-28 each process signed the points it
measured away from the centroid of its own part: a third of the signs
differed).

Environment: ASM_DATA_DIR (Testing/Data), PYTHONPATH with the asmvtk package.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_DOUBLE, VTK_UNSIGNED_CHAR, vtkPoints, vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet, vtkPolyData

from asm_mpi_setup import controller_and_bunny, gathered, simplified
from asmvtk import vtkASMSimplify, vtkKeyPointError

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
    asm, out, counts = simplified(controller, data, mode, NS)
    local = out.GetNumberOfPoints()
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
    return data, asm, every


def polydata_of(points):
    cloud = vtkPolyData()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=1))
    cloud.SetPoints(vtk_points)
    return cloud


def measure(original, simplified, controller=controller, warnings=None):
    kpe = vtkKeyPointError()
    if controller is None:
        kpe.SetController(None)
    if warnings is not None:
        kpe.AddObserver("WarningEvent", lambda caller, event: warnings.append(event))
    kpe.SetInputData(0, original)
    kpe.SetInputData(1, simplified)
    kpe.Update()
    return kpe


def figures_of(kpe, names):
    fd = kpe.GetOutput().GetFieldData()
    return np.array([fd.GetArray(name).GetValue(0) for name in names])


def check_same_figures(kpe, serial, what):
    """kpe's figures (field data) are serial's, the same on every process."""
    table = serial.GetOutputDataObject(1)
    names = [table.GetColumnName(c) for c in range(table.GetNumberOfColumns())]
    assert len(names) == 22 and table.GetNumberOfRows() == 1, (what, names)
    expected = figures_of(serial, names)
    mine = figures_of(kpe, names)
    every = gathered(controller, mine).reshape(size, len(names))
    spread = np.abs(every - every[0]).max(0) / np.maximum(1.0, np.abs(every[0]))
    assert np.all(spread <= 1e-12), (what, dict(zip(names, every.T.tolist())))
    worst = np.abs(mine - expected) / np.maximum(1.0, np.abs(expected))
    assert np.all(worst <= 1e-9), (what, dict(zip(names, zip(mine, expected))))
    # The table: one row over the processes, process 0's; the same columns
    # on every process.
    table = kpe.GetOutputDataObject(1)
    rows = gathered(controller, [table.GetNumberOfRows()])
    assert rows.tolist() == [1] + [0] * (size - 1), (what, rows)
    assert [table.GetColumnName(c) for c in range(table.GetNumberOfColumns())] == names, what
    if rank == 0:
        row = np.array([table.GetValue(0, c).ToDouble() for c in range(len(names))])
        assert np.array_equal(row, mine), what
    return dict(zip(names, mine))


def check_key_point_error(holder, composite, mode, data, asm, every):
    what = (holder, composite, mode, rank)
    kpe = measure(data, asm.GetOutput())
    local = asm.GetOutput().GetNumberOfPoints()
    out = kpe.GetOutput()
    assert out.GetNumberOfPoints() == local, what
    assert out.GetPointData().GetArray("Error").GetNumberOfTuples() == local, what
    serial = measure(cloud_of(np.arange(len(xyz))), polydata_of(every), controller=None)
    figures = check_same_figures(kpe, serial, what)
    assert figures["NumberOfOriginalPoints"] == len(xyz), (what, figures)
    assert figures["NumberOfSimplifiedPoints"] == NS, (what, figures)
    assert figures["NumberOfOriginalKeyPoints"] > 0, (what, figures)

    # Normals one tuple long: not read past their end (their buffer still
    # holds the output's normals reversed), the curvature signed as without
    # normals, and a warning where they are short.
    normals = asm.GetOutput().GetPointData().GetNormals()
    assert normals is not None and normals.GetNumberOfTuples() == local, what
    short, bare = vtkPolyData(), vtkPolyData()
    short.ShallowCopy(asm.GetOutput())
    bare.ShallowCopy(asm.GetOutput())
    reversed_normals = numpy_to_vtk(-vtk_to_numpy(normals).reshape(local, 3), deep=1)
    reversed_normals.SetName("Normals")
    if local > 1:
        first = reversed_normals.GetTuple3(0)
        reversed_normals.Reset()  # (keeps the buffer: the other tuples are still there)
        reversed_normals.InsertNextTuple3(*first)
        assert reversed_normals.GetNumberOfTuples() == 1
    short.GetPointData().SetNormals(reversed_normals)
    bare.GetPointData().RemoveArray("Normals")
    assert bare.GetPointData().GetNormals() is None
    warnings = []
    with_short = measure(data, short, warnings=warnings)
    without = measure(data, bare)
    assert len(warnings) == (1 if local > 1 else 0), (what, warnings)
    # Without normals, each point's curvature is the serial run's: signed
    # away from the whole original cloud's centroid (not from that of the
    # part a process measures it on).
    offset = int(gathered(controller, [local])[:rank].sum())
    for name in ("MeanCurvature", "NeighborhoodSurfaceVariation"):
        a = vtk_to_numpy(with_short.GetOutput().GetPointData().GetArray(name))
        b = vtk_to_numpy(without.GetOutput().GetPointData().GetArray(name))
        assert np.array_equal(a, b), (what, name)
        expected = vtk_to_numpy(serial.GetOutput().GetPointData().GetArray(name))
        expected = expected[offset:offset + local]
        differ = np.flatnonzero(~np.isclose(b, expected, rtol=1e-9, atol=1e-12))
        assert differ.size == 0, (what, name, differ.size, b[differ[:3]], expected[differ[:3]])
    if rank == 0:
        print("  key point error: %s" % {k: figures[k] for k in ("AKPE", "MKPE",
                                                                "NumberOfOriginalKeyPoints")})


def check_precision(holder):
    """A nearly flat patch: key points at double precision only."""
    u = np.linspace(1.0, 2.0, 60)
    gx, gy = np.meshgrid(u, u, indexing="ij")
    gx, gy = gx.ravel(), gy.ravel()
    patch = np.column_stack([gx, gy, 1.5 + 1e-8 * np.sin(9.0 * gx) * np.cos(7.0 * gy)])
    every_seventh = patch[::7]
    original = polydata_of(patch) if rank == holder else vtkPolyData()
    simplified = polydata_of(every_seventh) if rank == holder else vtkPolyData()
    kpe = measure(original, simplified)
    serial = measure(polydata_of(patch), polydata_of(every_seventh), controller=None)
    figures = check_same_figures(kpe, serial, ("patch", holder, rank))
    assert figures["NumberOfOriginalKeyPoints"] > 0, figures
    assert figures["NumberOfSimplifiedKeyPoints"] > 0, figures
    if rank == 0:
        print("patch on process %d: key points %d original, %d simplified"
              % (holder, figures["NumberOfOriginalKeyPoints"],
                 figures["NumberOfSimplifiedKeyPoints"]))


def check_curvature_sign():
    """Two wavy sheets, split along x over the processes, without normals:
    each simplified point's curvature is the serial run's, signed away from
    the whole original cloud's centroid (a process used to sign the points it
    measures away from the centroid of its own part, which near a sheet's
    far end lies on the other side of the sheet's normal)."""
    u, v = np.meshgrid(np.linspace(0.0, 4.0, 160), np.linspace(0.0, 1.0, 40), indexing="ij")
    u, v = u.ravel(), v.ravel()
    wave = 0.2 * np.sin(3.0 * u)
    sheets = np.vstack([np.column_stack([u, v, wave]), np.column_stack([u, v, 1.0 + wave])])
    reduced = sheets[::7]
    mine = lambda p: p[np.floor(p[:, 0] * size / 4.0001).astype(int) == rank]
    kpe = measure(polydata_of(mine(sheets)), polydata_of(mine(reduced)))
    local = kpe.GetOutput().GetNumberOfPoints()
    offset = int(gathered(controller, [local])[:rank].sum())
    every = gathered(controller, mine(reduced).ravel()).reshape(-1, 3)
    serial = measure(polydata_of(sheets), polydata_of(every), controller=None)
    got = vtk_to_numpy(kpe.GetOutput().GetPointData().GetArray("MeanCurvature"))
    expected = vtk_to_numpy(serial.GetOutput().GetPointData().GetArray("MeanCurvature"))
    expected = expected[offset:offset + local]
    differ = np.flatnonzero(~np.isclose(got, expected, rtol=1e-9, atol=1e-12))
    assert differ.size == 0, (rank, differ.size, local, got[differ[:3]], expected[differ[:3]])


check_curvature_sign()
for holder in (0, size - 1):
    for composite in (False, True):
        for mode in (vtkASMSimplify.PAPER, vtkASMSimplify.FEATURE_PRESERVING):
            check_key_point_error(holder, composite, mode,
                                  *check_simplify(holder, composite, mode))
    check_precision(holder)
