"""Check a rendered PNG (run with pvpython or any Python with VTK and numpy):

    check_image.py IMAGE [--baseline BASELINE.png] [--tolerance 4.0]

Not blank: at least 1 % of the pixels differ from the background (the most
common colour) and the image holds at least 16 distinct colours. With
--baseline: same size, and the mean absolute difference over all pixels and
channels (0-255 scale) is at most --tolerance. Exit status 0 when all hold;
prints the figures either way. Used by the CTest tests gui.ParaViewSmoke and
gui.PaperFigures. Grey images (with or without alpha) are compared as RGB;
alpha is ignored.
"""
import argparse
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader


def read_png(path):
    reader = vtkPNGReader()
    if not reader.CanReadFile(path):
        sys.exit("check_image: cannot read PNG %s" % path)
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    scalars = vtk_to_numpy(image.GetPointData().GetScalars())
    pixels = scalars.reshape(height, width, -1).astype(np.int16)
    if pixels.shape[2] <= 2:  # grey (+ alpha): the grey value in all three channels
        return np.repeat(pixels[:, :, :1], 3, axis=2)
    return pixels[:, :, :3]


def not_blank(pixels):
    flat = pixels.reshape(-1, 3)
    colours, counts = np.unique(flat, axis=0, return_counts=True)
    background = colours[np.argmax(counts)]
    foreground = np.any(flat != background, axis=1).mean()
    print("size %dx%d, background %s, foreground %.2f %%, %d colours" % (
        pixels.shape[1], pixels.shape[0], background.tolist(), 100 * foreground, len(colours)))
    return foreground >= 0.01 and len(colours) >= 16


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("image")
    parser.add_argument("--baseline")
    parser.add_argument("--tolerance", type=float, default=4.0,
                        help="largest mean absolute pixel difference to the baseline (0-255)")
    args = parser.parse_args()

    pixels = read_png(args.image)
    ok = not_blank(pixels)
    if not ok:
        print("check_image: %s looks blank" % args.image)
    if args.baseline:
        baseline = read_png(args.baseline)
        if baseline.shape != pixels.shape:
            print("check_image: size %s differs from the baseline's %s" % (pixels.shape, baseline.shape))
            ok = False
        else:
            diff = np.abs(pixels - baseline)
            mean = diff.mean()
            changed = np.any(diff > 32, axis=2).mean()
            print("baseline %s: mean absolute difference %.3f (tolerance %.3f), %.2f %% pixels off by > 32" % (
                args.baseline, mean, args.tolerance, 100 * changed))
            if mean > args.tolerance:
                print("check_image: %s differs from the baseline" % args.image)
                ok = False
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
