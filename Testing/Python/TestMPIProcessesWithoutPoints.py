"""MPI test, run under `mpiexec -n 3 pvbatch --mpi --symmetric`: a cloud of 12
points (the bunny's first ones), all on process 0, then all on process 2,
simplified to N_s = 4 in both modes. The grid has too few non-empty cells
for three processes' boxes, so some processes own no point and receive none:
they must still take part in every collective of the run (the feature mode's
final Lloyd iterations sum a mean over the processes, and its hole filling
gathers rankings and removal costs as many times as its data asks: a process
without points serves those collectives with nothing until every process is
done), so the run ends (no hang: the test's timeout) with exactly N_s points
over the processes, none of them on a process without points, and with the
holder's numeric and string arrays on every output (before 2026-11-27 a
process without points voted every array out). The feature mode runs twice:
as by default (N_s = 4 makes no hole-filling move), and with Hole Fill
Fraction 0.5 (two moves a round). With the points on process 2, process 0
(which apportions the global budget) and process 1 have none: the budget is
N_s of the whole cloud, and the arrays are those of the first process that
has points. Last, the cloud scaled out of range (coordinates of 1e160) on
process 0 alone: an error with an empty output on every process, no hang.

Environment: ASM_DATA_DIR (Testing/Data), PYTHONPATH with the asmvtk package.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints, vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkPolyData

from asm_mpi_setup import controller_and_bunny, gathered
from asmvtk import vtkASMSimplify

NS = 4
controller, rank, size, xyz = controller_and_bunny(3, 12)


def run(holder):
    """The whole cloud on process `holder`, the others without points."""
    mine = xyz if rank == holder else xyz[:0]
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(mine), deep=1))
    piece = vtkPolyData()
    piece.SetPoints(points)
    # A string array on the holder alone (the others have no points): read at
    # the samples' representatives after the run, in two more exchanges, which
    # the processes without points serve too; every output has the array.
    names = vtkStringArray()
    names.SetName("Point name")
    for i in range(len(mine)):
        names.InsertNextValue("point %d" % i)
    piece.GetPointData().AddArray(names)
    # And a numeric array, which travels with the points (a process without
    # points has no arrays: it must not vote an array of the others out).
    value = numpy_to_vtk(np.ascontiguousarray(mine[:, 0]), deep=1)
    value.SetName("Value")
    piece.GetPointData().AddArray(value)

    for mode, fraction in ((vtkASMSimplify.FEATURE_PRESERVING, None),
                           (vtkASMSimplify.FEATURE_PRESERVING, 0.5), (vtkASMSimplify.PAPER, None)):
        asm = vtkASMSimplify()
        asm.SetInputData(piece)
        asm.SetMode(mode)
        if fraction is not None:
            asm.SetHoleFillFraction(fraction)
        asm.SetTargetModeToNumberOfOutputPoints()
        asm.SetNumberOfOutputPoints(NS)
        if mode == vtkASMSimplify.FEATURE_PRESERVING:
            assert asm.GetFinalLloydIterations() > 0 and asm.GetLloydVariationWeight() > 0
        asm.Update()
        local = asm.GetOutput().GetNumberOfPoints()
        counts = gathered(controller, [local])
        assert counts.sum() == NS, (mode, counts)
        assert (counts == 0).any(), ("some process must be left without points", mode, counts)
        out_names = asm.GetOutput().GetPointData().GetAbstractArray("Point name")
        assert out_names is not None and out_names.GetNumberOfValues() == local, (mode, rank)
        out_value = asm.GetOutput().GetPointData().GetArray("Value")
        assert out_value is not None and out_value.GetNumberOfTuples() == local, (mode, rank)
        if local:
            ids = vtk_to_numpy(asm.GetOutput().GetPointData().GetArray("vtkOriginalPointIds"))
            assert [out_names.GetValue(i) for i in range(local)] == ["point %d" % i for i in ids]
        if rank == 0:
            print("points on process %d, mode %d: output points per process %s"
                  % (holder, mode, counts.astype(int).tolist()))


def out_of_range():
    """The cloud scaled by 1e160 (beyond asmcore::CoordinateRange), on process
    0 alone: every process learns the largest coordinate and stops with an
    error and an empty output; none is left waiting in a collective (the
    test's timeout), in both filters."""
    from vtkmodules.vtkCommonCore import vtkCommand
    from asmvtk import vtkKeyPointError
    mine = xyz * 1e160 if rank == 0 else xyz[:0]
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(mine), deep=1))
    piece = vtkPolyData()
    piece.SetPoints(points)
    errors = []

    def count(caller, event):
        errors.append(event)

    for mode in (vtkASMSimplify.FEATURE_PRESERVING, vtkASMSimplify.PAPER):
        asm = vtkASMSimplify()
        asm.AddObserver(vtkCommand.ErrorEvent, count)
        asm.SetInputData(piece)
        asm.SetMode(mode)
        asm.SetTargetModeToNumberOfOutputPoints()
        asm.SetNumberOfOutputPoints(NS)
        asm.Update()
        assert asm.GetOutput().GetNumberOfPoints() == 0, (mode, rank)
    error = vtkKeyPointError()
    error.AddObserver(vtkCommand.ErrorEvent, count)
    error.SetInputData(0, piece)
    error.SetInputData(1, piece)
    error.Update()
    assert error.GetOutput().GetNumberOfPoints() == 0, rank
    assert len(errors) == 3, (rank, errors)
    if rank == 0:
        print("coordinates of 1e160: an error on every process, empty outputs")


run(0)
run(size - 1)
out_of_range()
