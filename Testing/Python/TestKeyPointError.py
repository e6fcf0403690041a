"""pvpython test: the KeyPointError proxy of the ASM plugin on the bunny at 5 %.

Set-up (plugin and data paths): asm_test_setup.py.
"""
import os

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403

from asm_test_setup import load_asm_plugin

data_dir = load_asm_plugin("TestKeyPointError", globals())

reader = PLYReader(FileNames=[os.path.join(data_dir, "bunny.ply")])
asm = ASMSimplify(Input=reader, OutputFraction=0.05)  # noqa: F405
kpe = KeyPointError(Original=reader, Simplified=asm)  # noqa: F405

# Every property of Plugin/KeyPointError.xml, with its default and documentation.
expected_defaults = {
    "Alpha": 0.125,
    "CellSize": 0.0,
    "SamplesPerCell": 8.0,
    "DistanceMeasure": "Euclidean",
    "PlaneNeighbors": 8,
    "GenerateCurvature": 1,
    "CurvatureNeighbors": 20,
    "MinimumPointsForThreads": -1,
}
listed = set(kpe.ListProperties()) - {"Original", "Simplified"}
assert listed == set(expected_defaults), "untested or missing properties: %r" % (
    listed ^ set(expected_defaults))
for name, value in expected_defaults.items():
    actual = kpe.GetPropertyValue(name)
    assert actual == value, "%s: %r != %r" % (name, actual, value)
for name in list(expected_defaults) + ["Original", "Simplified"]:
    doc = kpe.GetProperty(name).SMProperty.GetDocumentation()
    assert doc is not None and doc.GetDescription().strip(), name + " has no documentation"
assert kpe.GetProperty("DistanceMeasure").Available == ["Euclidean", "Squared (Eq. 3)"]

# Two required inputs (ParaView's GUI then asks for both), on ports 0 and 1.
inputs = {}
for name in ("Original", "Simplified"):
    prop = kpe.GetProperty(name).SMProperty
    assert prop.IsA("vtkSMInputProperty"), name
    assert prop.GetHints() is None or prop.GetHints().FindNestedElementByName("Optional") is None
    inputs[name] = prop.GetPortIndex()
assert inputs == {"Original": 0, "Simplified": 1}, inputs

# Label, menu, output ports and display hints.
proxy = kpe.SMProxy
assert proxy.GetXMLLabel() == "Key Point Error", proxy.GetXMLLabel()
assert proxy.GetDocumentation().GetShortHelp() and proxy.GetDocumentation().GetLongHelp()
assert proxy.GetNumberOfOutputPorts() == 2, proxy.GetNumberOfOutputPorts()
assert proxy.GetOutputPortName(0) == "Simplified With Errors", proxy.GetOutputPortName(0)
assert proxy.GetOutputPortName(1) == "Figures", proxy.GetOutputPortName(1)
for port in (0, 1):
    doc = proxy.GetOutputPortDocumentation(port)
    assert doc is not None and doc.GetDescription().strip(), "output port %d has no documentation" % port
hints = proxy.GetHints()
menu = hints.FindNestedElementByName("ShowInMenu")
assert menu is not None and menu.GetAttribute("category") == "Point Cloud"
visibility = hints.FindNestedElementByName("Visibility")
assert visibility is not None and visibility.GetAttribute("replace_input") == "0"
views = [hints.GetNestedElement(i) for i in range(hints.GetNumberOfNestedElements())]
views = [(e.GetAttribute("type"), e.GetAttribute("port")) for e in views if e.GetName() == "View"]
assert views == [("SpreadSheetView", "1")], views
print("properties, documentation, ports and hints OK")

kpe.UpdatePipeline()

# Port 0: the simplified cloud with the per-point errors and curvature.
cloud = servermanager.Fetch(kpe, idx=0)
assert cloud.IsA("vtkPolyData"), cloud.GetClassName()
n_out = cloud.GetNumberOfPoints()
assert n_out == 1797, n_out
assert cloud.GetNumberOfVerts() == n_out, cloud.GetNumberOfVerts()
point_data = cloud.GetPointData()
for name in ("Error", "MeanCurvature", "NeighborhoodSurfaceVariation", "KeyPoint"):
    array = point_data.GetArray(name)
    assert array is not None, "missing point array " + name
    assert array.GetNumberOfTuples() == n_out, name
print("port 0: %d points with Error and MeanCurvature" % n_out)

# Port 1: a one-row table of the figures.
table = servermanager.Fetch(kpe, idx=1)
assert table.IsA("vtkTable"), table.GetClassName()
assert table.GetNumberOfRows() == 1, table.GetNumberOfRows()
figures = {}
for name in ("AKPE", "MKPE", "HausdorffDistance", "PointToPlaneMean"):
    column = table.GetColumnByName(name)
    assert column is not None, "missing column " + name
    figures[name] = column.GetValue(0)
print("port 1:", ", ".join("%s = %.6g" % item for item in figures.items()))
assert figures["MKPE"] >= figures["AKPE"] > 0, figures
assert figures["HausdorffDistance"] > 0 and figures["PointToPlaneMean"] > 0, figures
# The same figures in port 0's field data.
fd = cloud.GetFieldData()
for name, value in figures.items():
    assert fd.GetArray(name) is not None and fd.GetArray(name).GetValue(0) == value, name
print("TestKeyPointError: OK")
