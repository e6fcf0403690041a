"""MPI test, run under `mpiexec -n 3 pvbatch --mpi --symmetric`: the first
3000 points of the bunny, every third one on each process, whose processes
disagree on some point arrays. A distributed run passes on only the arrays
that every process holding points has, with the same type and components
(vtkASMDistributedRedistribute.cxx): "Value" (doubles) and "Point name"
(strings) are on every process and reach every output; "Partial" is missing
on process 1, and "Shape" has 2 components on processes 0 and 2 but 3 on
process 1, so neither is on any output, and every process warns that it is
not passed on. "Value" is the active scalars, and stays so on the output.
Both modes, N_s = 300 over the processes.

Environment: ASM_DATA_DIR (Testing/Data), PYTHONPATH with the asmvtk package.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints, vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkPolyData

from asm_mpi_setup import controller_and_bunny, gathered, simplified
from asmvtk import vtkASMSimplify

NS = 300
controller, rank, size, xyz = controller_and_bunny(3, 3000)
ids = np.arange(rank, len(xyz), size)
mine = xyz[ids]

points = vtkPoints()
points.SetData(numpy_to_vtk(np.ascontiguousarray(mine), deep=1))
piece = vtkPolyData()
piece.SetPoints(points)
pd = piece.GetPointData()


def add(name, values):
    array = numpy_to_vtk(np.ascontiguousarray(values), deep=1)
    array.SetName(name)
    pd.AddArray(array)


add("Value", ids.astype(np.float64))
pd.SetActiveScalars("Value")
if rank != 1:
    add("Partial", mine[:, 0].astype(np.float32))
add("Shape", np.tile(mine[:, :1], (1, 2 if rank != 1 else 3)))
names = vtkStringArray()
names.SetName("Point name")
for g in ids:
    names.InsertNextValue("point %d" % g)
pd.AddArray(names)

for mode in (vtkASMSimplify.PAPER, vtkASMSimplify.FEATURE_PRESERVING):
    warnings = []
    asm, out, counts = simplified(controller, piece, mode, NS, warnings)
    local = out.GetNumberOfPoints()
    assert counts.sum() == NS, (mode, counts)
    opd = out.GetPointData()
    for name in ("Partial", "Shape"):
        assert opd.GetAbstractArray(name) is None, (mode, rank, name)
    # Two warnings: one for each array that is not passed on.
    assert len(warnings) == 2, (mode, rank, warnings)
    value = opd.GetArray("Value")
    out_names = opd.GetAbstractArray("Point name")
    assert value is not None and value.GetNumberOfTuples() == local, (mode, rank)
    # The active scalars stay active (the arrays are put back in the input's
    # order after the strings are fetched, with their attribute roles).
    assert opd.GetScalars() is value, (mode, rank, opd.GetScalars())
    assert out_names is not None and out_names.GetNumberOfValues() == local, (mode, rank)
    # Each sample's name is its representative's.
    representative = vtk_to_numpy(opd.GetArray("vtkOriginalPointIds"))
    process = vtk_to_numpy(opd.GetArray("vtkOriginalProcessIds"))
    expected = ["point %d" % (size * i + p) for i, p in zip(representative, process)]
    assert [out_names.GetValue(i) for i in range(local)] == expected, (mode, rank)
    if rank == 0:
        print("mode %d: %d output points over the processes, warnings %d"
              % (mode, NS, len(warnings)))
