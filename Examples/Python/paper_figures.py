"""The paper's Figures 4 and 7 (Yu & Wong, ICME 2006) with the ASM plugin, off
screen in pvbatch:

    pvbatch Examples/Python/paper_figures.py [scan.ply] [-o paper_figures.png]
            [--fractions 0.01 0.05 0.2] [--size 1200 800] [--plugin ASM.so]

One column per output size N_s (default 1 %, 5 % and 20 % of the scan's
points; default scan Testing/Data/bunny.ply). Top row: the simplified cloud in
grey with its key points (KeyPoint == 1) drawn larger in red, as the paper's
arrows point out preserved key points. Bottom row: the same cloud coloured by
|MeanCurvature| from green (low) to blue (high), as in the paper, on one
colour range for all columns (5th to 95th percentile of the densest result,
whatever the order of --fractions). A missing or empty scan, a fraction
outside (0, 1], an unwritable output or a failed screenshot stop it with a
message and a non-zero exit status (2 for a bad command line, 1 otherwise).

Needs an OpenGL context: on a machine without a display run it under Xvfb,
e.g. Testing/Gui/run-xvfb.sh pvbatch Examples/Python/paper_figures.py.
The CTest test gui.PaperFigures renders it with Mesa's software
OpenGL and compares it with Testing/Data/Baseline/paper_figures.png.
"""
import argparse
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import (AssignViewToLayout, Calculator, CreateLayout, CreateView, GetColorTransferFunction,
                             LoadPlugin, PLYReader, Render, SaveScreenshot, Show, Text, Threshold)
from vtkmodules.util.numpy_support import vtk_to_numpy

from asm_plugin import REPO, find_plugin, fraction_arg, int_at_least, require_file, require_writable

GREY = [0.55, 0.55, 0.55]
RED = [0.85, 0.1, 0.1]
BACKGROUND = [1.0, 1.0, 1.0]


def new_view(size):
    view = CreateView("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.Background = BACKGROUND
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    return view


def label(view, text):
    title = Text(Text=text)
    display = Show(title, view)
    display.FontSize = 14
    display.Color = [0, 0, 0]
    display.WindowLocation = "Upper Center"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scan", nargs="?", default=os.path.join(REPO, "Testing", "Data", "bunny.ply"))
    parser.add_argument("-o", "--output", default="paper_figures.png")
    parser.add_argument("--fractions", type=fraction_arg, nargs="+", default=[0.01, 0.05, 0.2])
    parser.add_argument("--size", type=int_at_least(16), nargs=2, default=[1200, 800],
                        help="image width and height")
    parser.add_argument("--mode", choices=["Paper", "Feature Preserving"], default="Paper",
                        help="vtkASMSimplify Mode (default: the paper's literal pipeline)")
    parser.add_argument("--plugin", help="path of the ASM plugin library (ASM.so)")
    args = parser.parse_args()
    require_file(args.scan, "scan")
    require_writable(args.output)

    LoadPlugin(find_plugin(args.plugin), ns=globals())
    reader = PLYReader(FileNames=[os.path.abspath(args.scan)])
    reader.UpdatePipeline()
    n_in = reader.GetDataInformation().GetNumberOfPoints()
    if n_in == 0:
        sys.exit("scan %s: no points read (not a PLY file with vertices?)" % args.scan)
    name = os.path.splitext(os.path.basename(args.scan))[0]

    columns = len(args.fractions)
    panel = [args.size[0] // columns, args.size[1] // 2]
    layout = CreateLayout("ASM")
    # Split the layout into 2 rows of `columns` cells (cells numbered as a binary tree).
    layout.SplitVertical(0, 0.5)
    rows = []
    for row_cell in (1, 2):
        cells, cell = [], row_cell
        for c in range(columns - 1):
            layout.SplitHorizontal(cell, 1.0 / (columns - c))
            cells.append(2 * cell + 1)
            cell = 2 * cell + 2
        cells.append(cell)
        rows.append(cells)

    results = []
    for fraction in args.fractions:
        asm = ASMSimplify(Input=reader, OutputFraction=fraction, Mode=args.mode)  # noqa: F821 (from the plugin)
        asm.UpdatePipeline()
        if asm.GetDataInformation().GetNumberOfPoints() == 0:
            sys.exit("ASM Simplify gave no points at %g %% of %d (see its messages above)" % (100 * fraction, n_in))
        magnitude = Calculator(Input=asm, ResultArrayName="AbsMeanCurvature", Function="abs(MeanCurvature)")
        keys = Threshold(Input=asm, Scalars=["POINTS", "KeyPoint"])
        if hasattr(keys, "LowerThreshold"):
            keys.LowerThreshold, keys.UpperThreshold = 0.5, 1.5
        else:
            keys.ThresholdRange = [0.5, 1.5]
        keys.UpdatePipeline()
        magnitude.UpdatePipeline()
        results.append((fraction, asm, magnitude, keys))

    # One colour range for all columns, from the densest result.
    densest = servermanager.Fetch(max(results, key=lambda result: result[0])[1])
    curvature = np.abs(vtk_to_numpy(densest.GetPointData().GetArray("MeanCurvature")))
    low, high = np.percentile(curvature, [5, 95])
    lut = GetColorTransferFunction("AbsMeanCurvature")
    # green (low curvature) -> blue (high curvature), as in the paper
    lut.RGBPoints = [low, 0.1, 0.75, 0.2, (low + high) / 2, 0.1, 0.6, 0.7, high, 0.05, 0.1, 0.85]
    lut.ColorSpace = "RGB"
    lut.AutomaticRescaleRangeMode = "Never"

    camera = None
    for column, (fraction, asm, magnitude, keys) in enumerate(results):
        n_s = asm.GetDataInformation().GetNumberOfPoints()
        n_keys = keys.GetDataInformation().GetNumberOfPoints()
        top, bottom = new_view(panel), new_view(panel)
        AssignViewToLayout(view=top, layout=layout, hint=rows[0][column])
        AssignViewToLayout(view=bottom, layout=layout, hint=rows[1][column])

        # Bigger points for sparser clouds: 5 px at 1 %, 4 at 5 %, 3 at 20 %.
        size = max(2, min(6, round(5 - np.log(fraction / 0.01) / np.log(4))))
        cloud = Show(asm, top)
        cloud.ColorArrayName = ["POINTS", ""]
        cloud.AmbientColor = cloud.DiffuseColor = GREY
        cloud.PointSize = max(1, size - 2)
        highlighted = Show(keys, top)
        highlighted.SetRepresentationType("Points")
        highlighted.ColorArrayName = ["POINTS", ""]
        highlighted.AmbientColor = highlighted.DiffuseColor = RED
        highlighted.PointSize = size
        label(top, "%s  N_s = %g %% = %d points, %d key points (red)" % (name, 100 * fraction, n_s, n_keys))

        coloured = Show(magnitude, bottom)
        coloured.ColorArrayName = ["POINTS", "AbsMeanCurvature"]
        coloured.LookupTable = lut
        coloured.PointSize = size
        label(bottom, "absolute mean curvature: green low, blue high")

        for display in (cloud, highlighted, coloured):  # flat colours, no shading
            display.Ambient, display.Diffuse = 1.0, 0.0
        for view in (top, bottom):
            if camera is None:
                view.ResetCamera()
                camera = view.GetActiveCamera()
                camera.Zoom(1.3)
            else:
                view.CameraPosition = list(camera.GetPosition())
                view.CameraFocalPoint = list(camera.GetFocalPoint())
                view.CameraViewUp = list(camera.GetViewUp())
                view.CameraParallelScale = camera.GetParallelScale()
                view.CameraViewAngle = camera.GetViewAngle()
            Render(view)
        print("N = %d  N_s = %d (%g %%)  key points = %d" % (n_in, n_s, 100 * fraction, n_keys))

    if not SaveScreenshot(os.path.abspath(args.output), layout, ImageResolution=args.size) \
            or not os.path.isfile(args.output):
        sys.exit("could not write " + args.output)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
