"""pvpython test: the plugin's XML against the C++ classes it exposes.

1. Every property of ASMSimplify.xml and KeyPointError.xml has the default of
   its C++ member and the range its setter clamps to (no range where the
   setter takes any value; booleans and enumerations included), and every
   setter has a property.
2. Every property that the panel hides (its visibility decorators, evaluated
   as ParaView 5.11's GenericDecorator and CompositeDecorator do) in a state of
   Mode, Weight Mode, Target Mode and Feature Samples Per Cell changes nothing
   in the output there; and the widgets that a mode uses are shown.

Environment (set by CTest, see CMakeLists.txt):
  ASM_PLUGIN    path of the plugin library
  ASM_DATA_DIR  Testing/Data
  PYTHONPATH    the build tree's Python directory holding the asmvtk package
"""
import itertools
import os

from asmvtk import vtkASMSimplify, vtkKeyPointError
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkCommonCore import vtkVariant

from asm_test_setup import load_asm_plugin

data_dir = load_asm_plugin("TestPluginDomains", globals())
reader = PLYReader(FileNames=[os.path.join(data_dir, "fandisk.ply")])  # noqa: F405
asm = ASMSimplify(Input=reader)  # noqa: F405
kpe = KeyPointError(Original=reader, Simplified=asm)  # noqa: F405

# The vtkAlgorithm setters that are not parameters of the filters.
NOT_PARAMETERS = {
    "AbortExecute", "AbortOutput", "ContainerAlgorithm", "Controller", "Debug", "Executive",
    "GlobalWarningDisplay", "Information", "InformationObject", "InputArrayToProcess",
    "InputConnection", "InputData", "InputDataObject", "ObjectName", "Output", "Progress",
    "ProgressObserver", "ProgressScale", "ProgressShift", "ProgressText", "ReferenceCount",
    "ReleaseDataFlag", "SimplifiedConnection", "SimplifiedData", "UsingMemkind"}
INPUTS = {"Input", "Original", "Simplified"}


def domains(prop):
    iterator = prop.NewDomainIterator()
    iterator.Begin()
    while not iterator.IsAtEnd():
        yield iterator.GetDomain()
        iterator.Next()


def xml_range(prop):
    """(kind, minimum, maximum) of the property's domain; None: unbounded."""
    for domain in domains(prop):
        if domain.IsA("vtkSMBooleanDomain"):
            return "bool", 0, 1
        if domain.IsA("vtkSMEnumerationDomain"):
            values = [domain.GetEntryValue(i) for i in range(domain.GetNumberOfEntries())]
            assert values == list(range(min(values), max(values) + 1)), values
            return "enum", min(values), max(values)
        if domain.IsA("vtkSMDoubleRangeDomain") or domain.IsA("vtkSMIntRangeDomain"):
            return ("range",
                    domain.GetMinimum(0) if domain.GetMinimumExists(0) else None,
                    domain.GetMaximum(0) if domain.GetMaximumExists(0) else None)
    return "none", None, None


def cxx_range(cls, name, default):
    """What the setter clamps to, probed with huge values; None: unbounded."""
    if isinstance(default, bool):
        return 0, 1
    big = 2**31 - 1 if isinstance(default, int) else 1e300
    probe = cls()
    getattr(probe, "Set" + name)(-big)
    low = getattr(probe, "Get" + name)()
    getattr(probe, "Set" + name)(big)
    high = getattr(probe, "Get" + name)()
    # (a clamp to VTK_INT_MAX, VTK_ID_MAX or VTK_DOUBLE_MAX is no maximum)
    return (None if low == -big else low), (None if high >= big or high >= 2**31 - 1 else high)


# 1. Defaults and ranges.
for proxy, cls in ((asm, vtkASMSimplify), (kpe, vtkKeyPointError)):
    obj = cls()
    setters = {m[3:] for m in dir(obj) if m.startswith("Set") and hasattr(obj, "Get" + m[3:])}
    setters -= NOT_PARAMETERS
    properties = set(proxy.ListProperties()) - INPUTS
    assert properties == setters, (cls.__name__, "XML only:", properties - setters,
                                   "C++ only:", setters - properties)
    for name in sorted(properties):
        prop = proxy.GetProperty(name).SMProperty
        default = getattr(obj, "Get" + name)()
        assert float(prop.GetElement(0)) == float(default), (name, prop.GetElement(0), default)
        kind, low, high = xml_range(prop)
        assert (low, high) == cxx_range(cls, name, default), (
            cls.__name__, name, kind, (low, high), cxx_range(cls, name, default))
print("defaults and ranges agree with the C++ clamps")


# 2. Visibility decorators.
def decorator_matches(element, proxy):
    """ParaView 5.11's GenericDecorator: the watched property's element as a
    vtkVariant string equals `value` (or one of `values`), `inverse` negates."""
    watched = proxy.GetProperty(element.GetAttribute("property")).SMProperty
    value = watched.GetElement(int(element.GetAttribute("index") or 0))
    values = (element.GetAttribute("value") or element.GetAttribute("values")).split(" ")
    match = vtkVariant(value).ToString() in values
    return not match if element.GetAttribute("inverse") == "1" else match


def evaluate(element, proxy):
    """A decorator or an Expression (and/or) of them; None: no visibility rule."""
    if element.GetName() == "Expression":
        results = [evaluate(element.GetNestedElement(i), proxy)
                   for i in range(element.GetNumberOfNestedElements())]
        results = [r for r in results if r is not None]
        return all(results) if element.GetAttribute("type") == "and" else any(results)
    kind = element.GetAttribute("type")
    if kind == "CompositeDecorator":
        return evaluate(element.GetNestedElement(0), proxy)
    assert kind == "GenericDecorator", kind
    if element.GetAttribute("mode") != "visibility":
        return None
    return decorator_matches(element, proxy)


def shown(proxy, name):
    hints = proxy.GetProperty(name).SMProperty.GetHints()
    results = []
    for i in range(hints.GetNumberOfNestedElements() if hints else 0):
        element = hints.GetNestedElement(i)
        if element.GetName() == "PropertyWidgetDecorator":
            results.append(evaluate(element, proxy))
    return all(r for r in results if r is not None)


def changed_value(proxy, name):
    """Another value of the property, in its domain."""
    prop = proxy.GetProperty(name).SMProperty
    value = prop.GetElement(0)
    kind, low, high = xml_range(prop)
    if kind in ("bool", "enum"):
        return low if value != low else high
    integer = prop.IsA("vtkSMIntVectorProperty") or prop.IsA("vtkSMIdTypeVectorProperty")
    if low is not None and high is not None:
        other = low + 0.37 * (high - low)
        other = round(other) if integer else other
        return other if other != value else high
    return value * 2 + (1 if integer else 0.5)


def set_element(proxy, name, value):
    proxy.GetProperty(name).SMProperty.SetElement(0, value)
    proxy.SMProxy.UpdateVTKObjects()


def points(proxy):
    proxy.UpdatePipeline()
    data = servermanager.Fetch(proxy)
    return [data.GetPoint(i) for i in range(data.GetNumberOfPoints())]


# What each mode reads (vtkASMSimplifySteps.cxx, Core/Simplify.cxx): the
# widgets the panel must show.
expect_shown = {
    "SamplesPerCell": lambda s: s["Mode"] == 1 or s["FeatureSamplesPerCell"] == 0,
    "FeatureSamplesPerCell": lambda s: s["Mode"] == 0,
    "RandomSeed": lambda s: s["Mode"] == 1,
    "CurvatureWeight": lambda s: s["WeightMode"] == 1,
    "VariationBudget": lambda s: s["Mode"] == 0 and s["WeightMode"] == 0,
    "VariationCap": lambda s: s["Mode"] == 0,
    "ValidateKeyPoints": lambda s: s["Mode"] == 0,
    "OutputFraction": lambda s: s["TargetMode"] == 0,
    "NumberOfOutputPoints": lambda s: s["TargetMode"] == 1,
}
names = sorted(set(asm.ListProperties()) - INPUTS)
hidden_runs = 0
for mode, weight, target, feature in itertools.product((0, 1), (0, 1), (0, 1), (4.0, 0.0)):
    state = {"Mode": mode, "WeightMode": weight, "TargetMode": target,
             "FeatureSamplesPerCell": feature}
    for name in names:
        asm.GetProperty(name).SMProperty.ResetToXMLDefaults()
    for name, value in state.items():
        set_element(asm, name, value)
    set_element(asm, "NumberOfOutputPoints", 361)  # (Output Fraction's 5 %)
    set_element(asm, "GenerateCurvature", 0)  # (faster; the points are the same)
    for name, rule in expect_shown.items():
        assert shown(asm, name) == rule(state), (name, state, shown(asm, name))
    reference = points(asm)
    for name in names:
        if name in state or shown(asm, name):
            continue
        before = asm.GetProperty(name).SMProperty.GetElement(0)
        set_element(asm, name, changed_value(asm, name))
        assert points(asm) == reference, "hidden %s changes the output in %r" % (name, state)
        set_element(asm, name, before)
        hidden_runs += 1
print("hidden widgets change nothing (%d runs)" % hidden_runs)
print("TestPluginDomains: OK")
