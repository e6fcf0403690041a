"""Simplify a point cloud with the ASM ParaView plugin (run with pvpython).

    pvpython Examples/Python/simplify_bunny.py [input.ply] [output.ply]
             [--fraction 0.05] [--plugin path/to/ASM.so]

Reads a PLY file (default: Testing/Data/bunny.ply), simplifies it to 5 % of its
points with the ASM Simplify filter, writes the result as PLY (default:
asm-output.ply in the current directory) and prints N, N_s, the filter's
run time, the number of key points and the maximum key point error MKPE
(output field data; 0 in the default mode, whose key points are the extreme
input points themselves).

Exits with a message and a non-zero status, writing nothing, when the input
is missing or holds no points, the fraction is not in (0, 1], the output name
does not end in .ply or its directory is not writable (status 2 for a bad
command line, 1 otherwise).

The plugin is looked up in this order: --plugin, $ASM_PLUGIN, $PV_PLUGIN_PATH,
then the build tree (build/lib/paraview-*/plugins/ASM/ASM.so next to this
repository).
"""
import argparse
import os
import sys
import time

from paraview import servermanager
from paraview.simple import LoadPlugin, PLYReader
from vtkmodules.vtkCommonCore import VTK_FLOAT, vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOPLY import vtkPLYWriter

from asm_plugin import REPO, find_plugin, fraction_arg, require_file, require_writable


def write_ply(polydata, path):
    """Write points (+ normals) as binary PLY; vtkPLYWriter takes float normals only."""
    copy = vtkPolyData()
    copy.ShallowCopy(polydata)
    normals = polydata.GetPointData().GetNormals()
    if normals is not None and normals.GetDataType() != VTK_FLOAT:
        float_normals = vtkFloatArray()
        float_normals.DeepCopy(normals)
        float_normals.SetName(normals.GetName())
        copy.GetPointData().SetNormals(float_normals)
    writer = vtkPLYWriter()
    writer.SetFileName(path)
    writer.SetFileTypeToBinary()
    writer.SetInputData(copy)
    if not writer.Write():
        sys.exit("could not write " + path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input", nargs="?", default=os.path.join(REPO, "Testing", "Data", "bunny.ply"),
                        help="input PLY file (default: Testing/Data/bunny.ply)")
    parser.add_argument("output", nargs="?", default="asm-output.ply",
                        help="output PLY file, ending in .ply, lower case (default: asm-output.ply)")
    parser.add_argument("--fraction", type=fraction_arg, default=0.05,
                        help="fraction of the input points to keep, in (0, 1] (default: 0.05)")
    parser.add_argument("--mode", choices=["Feature Preserving", "Paper"], default="Feature Preserving",
                        help="vtkASMSimplify Mode (default: Feature Preserving)")
    parser.add_argument("--plugin", help="path of the ASM plugin library (ASM.so)")
    args = parser.parse_args()
    if not args.output.endswith(".ply"):
        # (vtkPLYWriter appends ".ply" to any other name, ".PLY" included: another file than the one named)
        parser.error("the output file name must end in .ply (lower case): %s" % args.output)
    require_file(args.input)
    require_writable(args.output)

    LoadPlugin(find_plugin(args.plugin), ns=globals())

    reader = PLYReader(FileNames=[os.path.abspath(args.input)])
    reader.UpdatePipeline()
    n_in = reader.GetDataInformation().GetNumberOfPoints()
    if n_in == 0:
        sys.exit("input %s: no points read (not a PLY file with vertices?)" % args.input)

    asm = ASMSimplify(Input=reader, OutputFraction=args.fraction, Mode=args.mode)  # noqa: F821 (from the plugin)
    start = time.perf_counter()
    asm.UpdatePipeline()
    seconds = time.perf_counter() - start

    output = servermanager.Fetch(asm)
    if output is None or output.GetNumberOfPoints() == 0:
        sys.exit("ASM Simplify produced no points from %d input points (see its messages above)" % n_in)
    mkpe_array = output.GetFieldData().GetArray("MKPE")
    mkpe = mkpe_array.GetValue(0) if mkpe_array is not None else float("nan")
    keys_array = output.GetFieldData().GetArray("NumberOfKeyPoints")
    keys = int(keys_array.GetValue(0)) if keys_array is not None else -1

    write_ply(output, os.path.abspath(args.output))

    print("input     : %s" % args.input)
    print("N         : %d" % n_in)
    print("mode      : %s" % args.mode)
    print("N_s       : %d" % output.GetNumberOfPoints())
    print("key points: %d" % keys)
    print("time (s)  : %.3f" % seconds)
    print("MKPE      : %.6g" % mkpe)
    print("output    : %s" % args.output)


if __name__ == "__main__":
    main()
