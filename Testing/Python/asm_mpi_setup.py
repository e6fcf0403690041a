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
