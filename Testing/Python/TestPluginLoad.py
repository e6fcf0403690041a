"""pvpython test: load the ASM plugin, simplify the Stanford bunny to 5 %.

Set-up (plugin and data paths): asm_test_setup.py.
"""
import os

from paraview import servermanager
from paraview.modules.vtkRemotingServerManager import vtkSMOrderedPropertyIterator
from paraview.simple import *  # noqa: F401,F403

from asm_test_setup import load_asm_plugin

data_dir = load_asm_plugin("TestPluginLoad", globals())

reader = PLYReader(FileNames=[os.path.join(data_dir, "bunny.ply")])
asm = ASMSimplify(Input=reader, OutputFraction=0.05)  # noqa: F405

# Every property of Plugin/ASMSimplify.xml, with its default.
expected_defaults = {
    "Mode": "Feature Preserving",
    "TargetMode": "Output Fraction",
    "OutputFraction": 0.05,
    "NumberOfOutputPoints": 1000,
    "CellSize": 0.0,
    "SamplesPerCell": 8.0,
    "Alpha": 0.125,
    "ErrorTolerance": 0.0,
    "RelativeErrorTolerance": 0,
    "WeightMode": "Uniform",
    "CurvatureWeight": 1.0,
    "RandomSeed": 1,
    "SnapToInputPoints": 0,
    "GenerateCurvature": 1,
    "CurvatureNeighbors": 20,
    "OutputPointsPrecision": "Same as input",
    # Options of the feature-preserving mode.
    "ValidateKeyPoints": 1,
    "KeyPointRadius": 0.7,
    "KeyPointProminence": 0.05,
    "InPlaneKeyPoints": 1,
    "ExtremeKeyPoints": 1,
    "CoverEveryCell": 1,
    "BudgetExponent": 0.5,
    "LloydIterations": 4,
    "CrossCellIterations": 1,
    "InputPointSamples": 1,
    "FillHoles": 1,
    "HoleFillFraction": 0.02,
    "FeatureSamplesPerCell": 4.0,
    "VariationBudget": 1.0,
    "VariationCap": 4.0,
    "ReserveFreeSample": 1,
    "FinalLloydIterations": 2,
    "LloydVariationWeight": 0.75,
    "CoveringRounds": 0,
    "SparseCellKeyPoints": 1,
    "BoundSnappedHoles": 1,
    # Parallel (MPI) runs.
    "AlwaysDistribute": 0,
    "MinimumPointsForThreads": -1,
}
# Nothing in the XML that the test does not know about.
listed = set(asm.ListProperties()) - {"Input"}
assert listed == set(expected_defaults), "untested or missing properties: %r" % (
    listed ^ set(expected_defaults))
for name, value in expected_defaults.items():
    actual = asm.GetPropertyValue(name)
    assert actual == value, "%s: %r != %r" % (name, actual, value)
    doc = asm.GetProperty(name).SMProperty.GetDocumentation()
    assert doc is not None and doc.GetDescription().strip(), name + " has no documentation"
# Ranges and panel visibility of the curvature properties.
neighbors = asm.GetProperty("CurvatureNeighbors").SMProperty
neighbors_range = neighbors.GetDomain("range")
assert (neighbors_range.GetMinimum(0), neighbors_range.GetMaximum(0)) == (6, 1000)
# The everyday parameters on the default panel, everything else under Advanced.
everyday = {"Mode", "TargetMode", "OutputFraction", "NumberOfOutputPoints", "ErrorTolerance"}
for name in listed:
    visibility = asm.GetProperty(name).SMProperty.GetPanelVisibility()
    assert visibility == ("default" if name in everyday else "advanced"), (name, visibility)
# An advanced property reaches the VTK object (the ParaView-only wiring; the
# plugin's class is not wrapped, so its PrintSelf tells).
asm.MinimumPointsForThreads = 0
printed = str(asm.GetClientSideObject())
assert "MinimumPointsForThreads: 0 (" in printed, printed
asm.MinimumPointsForThreads = -1
assert "MinimumPointsForThreads: -1 (automatic" in str(asm.GetClientSideObject())
print("properties, defaults and documentation OK")

# The advanced properties in labelled sections of the panel, each in one, and
# each section's properties next to each other in the panel's order.
sections = {}
proxy = asm.SMProxy
for g in range(proxy.GetNumberOfPropertyGroups()):
    group = proxy.GetPropertyGroup(g)
    sections[group.GetXMLLabel()] = [group.GetPropertyName(i) for i in range(group.GetNumberOfProperties())]
assert list(sections) == ["Grid", "Key Points", "Budget", "Clusters and Holes", "Curvature",
                          "Output and Parallel Runs"], list(sections)
grouped = [name for names in sections.values() for name in names]
assert sorted(grouped) == sorted(listed - everyday | {"ErrorTolerance"}), (
    set(grouped) ^ (listed - everyday | {"ErrorTolerance"}))
assert len(grouped) == len(set(grouped)), "a property in two sections"
xml_order = []  # the panel's order: the XML's
iterator = vtkSMOrderedPropertyIterator()
iterator.SetProxy(proxy)
iterator.Begin()
while not iterator.IsAtEnd():
    xml_order.append(iterator.GetKey())
    iterator.Next()
panel_order = [name for name in xml_order if name in grouped]
assert panel_order == grouped, "sections not contiguous in the panel: %r" % panel_order
assert xml_order[:5] == ["Input", "Mode", "TargetMode", "OutputFraction", "NumberOfOutputPoints"], (
    xml_order[:5])
for name in sections["Clusters and Holes"][:3]:
    assert asm.GetProperty(name).SMProperty.GetDocumentation().GetDescription().strip().startswith(
        "Feature Preserving"), name
print("panel sections OK")

# Menu entry and display hints.
assert asm.SMProxy.GetXMLLabel() == "ASM Simplify", asm.SMProxy.GetXMLLabel()
hints = asm.SMProxy.GetHints()
menu = hints.FindNestedElementByName("ShowInMenu")
assert menu is not None and menu.GetAttribute("category") == "Point Cloud"
visibility = hints.FindNestedElementByName("Visibility")
assert visibility is not None and visibility.GetAttribute("replace_input") == "0"
representation = hints.FindNestedElementByName("RepresentationType")
assert representation is not None and representation.GetAttribute("type") == "Points"
print("label and hints OK")

asm.UpdatePipeline()
out = servermanager.Fetch(asm)

n_in = servermanager.Fetch(reader).GetNumberOfPoints()
assert n_in == 35947, n_in
expected = round(0.05 * n_in)  # 1797
n_out = out.GetNumberOfPoints()
print("N = %d, N_s = %d (expected %d)" % (n_in, n_out, expected))
assert n_out == expected, "got %d points, expected %d" % (n_out, expected)

point_data = out.GetPointData()
for name in ("KeyPoint", "ClusterSize", "SurfaceVariation", "Normals", "vtkOriginalPointIds",
             "MeanCurvature", "NeighborhoodSurfaceVariation"):
    assert point_data.GetArray(name) is not None, "missing point array " + name
    assert point_data.GetArray(name).GetNumberOfTuples() == n_out, name
print("TestPluginLoad: OutputFraction OK")

# GenerateCurvature off drops the curvature arrays.
asm.GenerateCurvature = 0
asm.UpdatePipeline()
point_data = servermanager.Fetch(asm).GetPointData()
for name in ("MeanCurvature", "NeighborhoodSurfaceVariation"):
    assert point_data.GetArray(name) is None, name + " present with GenerateCurvature off"
asm.GenerateCurvature = 1
print("TestPluginLoad: GenerateCurvature OK")

# The other target mode, through the enumeration and the id-type property.
asm.TargetMode = "Number Of Output Points"
asm.NumberOfOutputPoints = 500
asm.UpdatePipeline()
n_out = servermanager.Fetch(asm).GetNumberOfPoints()
assert n_out == 500, "NumberOfOutputPoints=500 gave %d points" % n_out
print("TestPluginLoad: NumberOfOutputPoints OK")

# Scans grouped (Group Datasets: a multiblock) are ONE cloud: one polydata of
# the requested size, with the block and the point of each representative.
kitten = PLYReader(FileNames=[os.path.join(data_dir, "kitten.ply")])
group = GroupDatasets(Input=[reader, kitten])  # noqa: F405
grouped = ASMSimplify(Input=group, TargetMode="Number Of Output Points",  # noqa: F405
                      NumberOfOutputPoints=2000, GenerateCurvature=0)
grouped.UpdatePipeline()
out = servermanager.Fetch(grouped)
assert out.IsA("vtkPolyData"), out.GetClassName()
assert out.GetNumberOfPoints() == 2000, out.GetNumberOfPoints()
blocks = out.GetPointData().GetArray("vtkOriginalBlockIds")
assert blocks is not None and blocks.GetRange() == (1.0, 2.0), blocks and blocks.GetRange()
print("TestPluginLoad: grouped scans OK")
