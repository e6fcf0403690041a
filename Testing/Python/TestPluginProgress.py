"""pvpython test: progress and Cancel of ASM Simplify on a 1 M-point cloud,
through ParaView's server manager (what the GUI's progress bar listens to).

1. The filter's vtkAlgorithm progress events reach ParaView's progress handler
   (vtkPVProgressHandler, the source of the progress bar) as several distinct
   values, labelled with the filter, each one the filter reported, up to
   its last quarter. (The handler drops a report that comes less than 10 ms
   after the previous one, its smallest interval, so the filter's last
   reports, 0.9 to 1.0 within the run's last milliseconds on a fast machine,
   may not reach it.)
2. Setting AbortExecute from a progress observer (what Cancel does) stops the
   run at the next report: the output is empty and no report follows.
3. The next update after an abort runs normally (Cancel does not leave the
   filter stuck).

Set-up (plugin and data paths): asm_test_setup.py.
"""
import math

import numpy as np
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.util.numpy_support import numpy_to_vtk

from asm_test_setup import load_asm_plugin

load_asm_plugin("TestPluginProgress", globals())

# A 1 M-point noisy torus (deterministic).
N = 1000000
rng = np.random.default_rng(7)
u, v = rng.uniform(0, 2 * math.pi, (2, N))
R, r = 1.0, 0.35
xyz = np.column_stack(((R + r * np.cos(v)) * np.cos(u), (R + r * np.cos(v)) * np.sin(u), r * np.sin(v)))
xyz += rng.normal(0, 0.002, xyz.shape)
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz.astype(np.float32), deep=True))
cloud = vtkPolyData()
cloud.SetPoints(points)

producer = PVTrivialProducer()  # noqa: F405
producer.GetClientSideObject().SetOutput(cloud)
asm = ASMSimplify(Input=producer, OutputFraction=0.01)  # noqa: F405

# 1. Progress reaches ParaView's progress handler.
handler = servermanager.ActiveConnection.Session.GetProgressHandler()
handler.SetProgressInterval(0.0)  # as often as it can (it clamps to 0.01 s)
reports = []
own = []  # the filter's own reports, as the handler turns them into percents
own_tag = asm.GetClientSideObject().AddObserver(
    vtkCommand.ProgressEvent, lambda obj, event: own.append(int(obj.GetProgress() * 100.0)))


def on_handler_progress(obj, event):
    reports.append((obj.GetLastProgressText(), obj.GetLastProgress()))


tag = handler.AddObserver(vtkCommand.ProgressEvent, on_handler_progress)
asm.UpdatePipeline()
handler.RemoveObserver(tag)
asm.GetClientSideObject().RemoveObserver(own_tag)
n_out = asm.GetDataInformation().GetNumberOfPoints()
assert n_out == 10000, n_out
ours = [value for text, value in reports if text and "ASM" in text]
print("progress handler reports:", len(reports), "of ASM:", len(ours), "values:", sorted(set(ours)))
assert len(set(ours)) >= 5, "too few distinct progress values reached ParaView: %r" % reports
assert set(ours) <= set(own), "reports the filter did not make: %r (filter: %r)" % (ours, own)
assert max(ours) >= 75, ours

# 2. Cancel: AbortExecute set from a progress observer at 25 %.
algorithm = asm.GetClientSideObject()
seen = []


def on_progress(obj, event):
    seen.append(obj.GetProgress())
    if obj.GetProgress() >= 0.25 and not obj.GetAbortExecute():
        seen.append("abort")
        obj.SetAbortExecute(1)


tag = algorithm.AddObserver(vtkCommand.ProgressEvent, on_progress)
asm.RandomSeed = 2  # re-execute
asm.UpdatePipeline()
algorithm.RemoveObserver(tag)
after = seen[seen.index("abort") + 1:]
print("progress values up to the abort:", seen[:seen.index("abort")], "after:", after)
assert asm.GetDataInformation().GetNumberOfPoints() == 0, "an aborted run must give an empty output"
# At most one more report of the filter's own, plus the pipeline's closing 1.0.
working = [value for value in after if value != 1.0]
assert all(value < 0.5 for value in working), "the run went on after the abort: %r" % after
assert len(working) <= 1, "the run went on after the abort: %r" % after

# 3. The next run works again.
asm.RandomSeed = 3
asm.UpdatePipeline()
n_out = asm.GetDataInformation().GetNumberOfPoints()
assert n_out == 10000, "after an abort, the next run gave %d points" % n_out
print("TestPluginProgress: progress, abort and re-run OK")
