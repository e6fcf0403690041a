"""MPI test, run under `mpiexec -n 2 pvbatch --mpi` (the script runs on
process 0; ParaView runs the pipeline on both): a triangle mesh split over
the processes, as the README's "Split meshes" describes.

ParaView's Sphere source makes one piece per process and Redistribute
DataSet moves cells, so the points the pieces share are on both processes,
unflagged: both filters count them twice (the premise of the README's
advice, checked here so that the advice is revisited if ParaView changes).
Ghost Cells Generator (Build If Required off) flags those copies as
duplicate ghosts; ASM Simplify and Key Point Error then skip them and give
the serial run's points and figures, computed here on process 0 alone by
the VTK classes (no controller: the serial path).

Environment: ASM_PLUGIN (plugin library).
"""
import os

import numpy as np
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkCleanPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource

LoadPlugin(os.environ["ASM_PLUGIN"], ns=globals())
from asmvtk import vtkASMSimplify, vtkKeyPointError  # noqa: E402

NS = 500
RESOLUTION = 120
assert servermanager.ActiveConnection.GetNumberOfDataPartitions() == 2

# The serial reference: the whole mesh on this process, no controller.
source = vtkSphereSource()
source.SetThetaResolution(RESOLUTION)
source.SetPhiResolution(RESOLUTION)
clean = vtkCleanPolyData()
clean.SetInputConnection(source.GetOutputPort())
serial = vtkASMSimplify()
serial.SetController(None)
serial.SetInputConnection(clean.GetOutputPort())
serial.SetTargetModeToNumberOfOutputPoints()
serial.SetNumberOfOutputPoints(NS)
serial.SetOutputPointsPrecision(1)  # double: the split's points are widened to double
serial_error = vtkKeyPointError()
serial_error.SetController(None)
serial_error.SetInputConnection(0, clean.GetOutputPort())
serial_error.SetInputConnection(1, serial.GetOutputPort())
serial_error.Update()
points = clean.GetOutput().GetNumberOfPoints()


def sorted_points(data):
    xyz = vtk_to_numpy(data.GetPoints().GetData()).astype(np.float64)
    return xyz[np.lexsort(xyz.T[::-1])]


def figure(data, name):
    return data.GetFieldData().GetArray(name).GetValue(0)


expected = sorted_points(serial.GetOutput())
expected_akpe = figure(serial_error.GetOutput(), "AKPE")
assert expected.shape == (NS, 3), expected.shape

mesh = Clean(Input=Sphere(ThetaResolution=RESOLUTION, PhiResolution=RESOLUTION))  # noqa: F405
split = RedistributeDataSet(Input=mesh)  # noqa: F405
for ghosts in (False, True):
    source = GhostCellsGenerator(Input=split, BuildIfRequired=0) if ghosts else split  # noqa: F405
    asm = ASMSimplify(Input=source, TargetMode="Number Of Output Points",  # noqa: F405
                      NumberOfOutputPoints=NS, OutputPointsPrecision="Double")
    kpe = KeyPointError(Original=source, Simplified=asm)  # noqa: F405
    kpe.UpdatePipeline()
    out = servermanager.Fetch(asm)
    measured = servermanager.Fetch(kpe, idx=0)
    counted = figure(measured, "NumberOfOriginalPoints")
    clusters = vtk_to_numpy(out.GetPointData().GetArray("ClusterSize")).sum()
    print("ghosts %s: %d points counted (serial %d), ClusterSize sum %d, AKPE %.9g (serial %.9g)"
          % (ghosts, counted, points, clusters, figure(measured, "AKPE"), expected_akpe))
    assert out.GetNumberOfPoints() == NS, out.GetNumberOfPoints()
    if not ghosts:
        # The shared points counted once per process that holds them.
        assert counted > points and clusters == counted, (counted, clusters, points)
        continue
    assert counted == points and clusters == points, (counted, clusters, points)
    got = sorted_points(out)
    assert np.abs(got - expected).max() <= 1e-6, np.abs(got - expected).max()
    assert abs(figure(measured, "AKPE") - expected_akpe) <= 1e-9, (figure(measured, "AKPE"), expected_akpe)
print("TestMPISplitMesh: OK")
