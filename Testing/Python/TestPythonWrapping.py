"""Test of the Python wrapping: vtkASMSimplify used directly, no plugin.

Environment (set by CTest, see CMakeLists.txt):
  PYTHONPATH    must contain the directory holding the asmvtk package
  ASM_DATA_DIR  Testing/Data
"""
import os

from asmvtk import vtkASMSimplify
from vtkmodules.vtkIOPLY import vtkPLYReader  # ParaView's VTK under pvpython

here = os.path.dirname(os.path.abspath(__file__))
data_dir = os.environ.get("ASM_DATA_DIR", os.path.join(here, "..", "Data"))

reader = vtkPLYReader()
reader.SetFileName(os.path.join(data_dir, "bunny.ply"))

asm = vtkASMSimplify()
asm.SetInputConnection(reader.GetOutputPort())
# Every parameter is reachable from Python.
asm.SetTargetMode(vtkASMSimplify.OUTPUT_FRACTION)
asm.SetOutputFraction(0.05)
asm.SetNumberOfOutputPoints(1000)
asm.SetCellSize(0.0)
asm.SetSamplesPerCell(8.0)
asm.SetAlpha(0.125)
asm.SetErrorTolerance(0.0)
asm.SetRelativeErrorTolerance(False)
asm.SetWeightMode(vtkASMSimplify.UNIFORM_WEIGHT)
asm.SetCurvatureWeight(1.0)
asm.SetRandomSeed(1)
asm.SetSnapToInputPoints(False)
asm.SetOutputPointsPrecision(2)
assert asm.GetOutputFraction() == 0.05
print(asm.GetClassName(), "from", vtkASMSimplify.__module__)

asm.Update()
n_in = reader.GetOutput().GetNumberOfPoints()
assert n_in == 35947, n_in
expected = round(0.05 * n_in)  # 1797
n_out = asm.GetOutput().GetNumberOfPoints()
print("N = %d, N_s = %d (expected %d)" % (n_in, n_out, expected))
assert n_out == expected, "got %d points, expected %d" % (n_out, expected)
print("TestPythonWrapping: OK")
