"""Shared set-up of the pvbatch MPI tests that run a fixed number of
processes on the first points of the bunny, and the gather they use.

Environment: ASM_DATA_DIR (Testing/Data).
"""
import os

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkParallelCore import vtkMultiProcessController


def controller_and_bunny(processes, count):
    """The global controller, this process's rank, the number of processes
    (which must be `processes`) and the bunny's first `count` points (doubles),
    read on every process."""
    controller = vtkMultiProcessController.GetGlobalController()
    rank, size = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    assert size == processes, size
    here = os.path.dirname(os.path.abspath(__file__))
    data_dir = os.environ.get("ASM_DATA_DIR", os.path.join(here, "..", "Data"))
    reader = vtkPLYReader()
    reader.SetFileName(os.path.join(data_dir, "bunny.ply"))
    reader.Update()
    xyz = vtk_to_numpy(reader.GetOutput().GetPoints().GetData()).astype(np.float64)[:count]
    return controller, rank, size, xyz


def gathered(controller, values):
    """Every process's `values` (numbers), in process order, on every process."""
    received = vtkDoubleArray()
    controller.AllGatherV(numpy_to_vtk(np.asarray(values, dtype=np.float64), deep=1), received)
    return vtk_to_numpy(received)


def simplified(controller, data, mode, count, warnings=None, serial=False):
    """vtkASMSimplify of `data` to `count` points in `mode` on every process:
    the filter, its output here and every process's output count, in process
    order (their sum must be `count`). Warning events go to `warnings` (a
    list) when given. `serial`: each process runs the serial path on its
    own `data` (no controller)."""
    from asmvtk import vtkASMSimplify

    asm = vtkASMSimplify()
    if serial:
        asm.SetController(None)
    if warnings is not None:
        asm.AddObserver("WarningEvent", lambda caller, event: warnings.append(event))
    asm.SetInputData(data)
    asm.SetMode(mode)
    asm.SetTargetModeToNumberOfOutputPoints()
    asm.SetNumberOfOutputPoints(count)
    asm.Update()
    out = asm.GetOutput()
    return asm, out, gathered(controller, [out.GetNumberOfPoints()])
