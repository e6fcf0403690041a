"""Smoke test of the ASM plugin in the real Qt ParaView GUI (run by
gui-smoke.sh under Xvfb as `paraview --script=GuiSmoke.py --exit`, with the
plugin loaded at start-up by --plugins=ASM; ParaView 5.11 from Debian plays
no Python --test-script, and --script errors do not change its exit status,
so the result goes to a file):

reads Testing/Data/bunny.ply, applies ASM Simplify (5 %) and Key Point Error
(original vs simplified) in the GUI's session, shows both in the GUI's render
view next to the input, checks the display defaults the plugin's XML asks for
(points, coloured by MeanCurvature) and saves a screenshot.

Environment: ASM_DATA_DIR (Testing/Data), ASM_GUI_SCREENSHOT (the PNG to
write), ASM_GUI_RESULT (a text file: one line per check, then "GuiSmoke: OK"
or the error).
"""
import os
import traceback

import paraview.simple as simple
from paraview.simple import *  # noqa: F401,F403

data_dir = os.environ["ASM_DATA_DIR"]
screenshot = os.environ["ASM_GUI_SCREENSHOT"]
result = open(os.environ["ASM_GUI_RESULT"], "w")
failures = []


def check(condition, message):
    result.write(("ok   " if condition else "FAIL ") + message + "\n")
    result.flush()
    if not condition:
        failures.append(message)


def main():
    # The plugin was loaded at start-up (--plugins=ASM), before this script.
    check(hasattr(simple, "ASMSimplify") and hasattr(simple, "KeyPointError"),
          "the plugin's filters are in paraview.simple")
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [800, 600]
    reader = PLYReader(registrationName="bunny.ply", FileNames=[os.path.join(data_dir, "bunny.ply")])
    reader_display = Show(reader, view)
    # A raw scan has points but no vertex cells, which the Points representation
    # needs; Point Gaussian draws the points themselves.
    reader_display.SetRepresentationType("Point Gaussian")
    reader_display.GaussianRadius = 0.0006
    reader_display.ShaderPreset = "Plain circle"
    reader_display.AmbientColor = reader_display.DiffuseColor = [0.75, 0.75, 0.75]

    asm = simple.ASMSimplify(registrationName="ASMSimplify1", Input=reader, OutputFraction=0.05)  # noqa: F405
    asm_display = Show(asm, view)
    asm.UpdatePipeline()
    check(asm.GetDataInformation().GetNumberOfPoints() == 1797, "ASM Simplify gives 1797 points")
    check(asm_display.Representation == "Points", "ASM Simplify shows as Points (got %s)" % asm_display.Representation)
    check(list(asm_display.ColorArrayName) == ["POINTS", "MeanCurvature"],
          "ASM Simplify is coloured by MeanCurvature (got %s)" % list(asm_display.ColorArrayName))
    asm_display.PointSize = 4
    asm_display.Position = [0.2, 0, 0]  # beside the input

    kpe = simple.KeyPointError(registrationName="KeyPointError1", Original=reader, Simplified=asm)  # noqa: F405
    kpe_display = Show(OutputPort(kpe, 0), view)
    kpe.UpdatePipeline()
    check(kpe_display.Representation == "Points", "Key Point Error shows as Points")
    kpe_display.PointSize = 4
    kpe_display.Position = [0.4, 0, 0]
    ColorBy(kpe_display, ("POINTS", "Error"))
    check(reader_display.Visibility == 1, "the input stays visible")

    view.ResetCamera()
    Render(view)
    SaveScreenshot(screenshot, view, ImageResolution=[800, 600])
    check(os.path.isfile(screenshot), "screenshot written: " + screenshot)


try:
    main()
    result.write("GuiSmoke: %s\n" % ("OK" if not failures else "%d check(s) failed" % len(failures)))
except Exception:  # noqa: BLE001 - report anything, the GUI would swallow it
    result.write("GuiSmoke: error\n" + traceback.format_exc())
result.close()
