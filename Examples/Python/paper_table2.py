"""Simplify PLY scans to 5 % with ASM and measure the result, as in Table 2 of Yu & Wong (ICME 2006).

    PYTHONPATH=build/lib/python3/dist-packages pvpython Examples/Python/paper_table2.py \
        [--fraction 0.05] [--runs 5] [--curvature] [--with-test-data] [scan.ply ...]

For each scan (default: every .ply in Testing/Data; with paths given, those
instead, plus Testing/Data's with --with-test-data), runs vtkASMSimplify at
N_s = round(fraction * N) and prints one line: the model, N, N_s, the median
wall time of --runs executions of the filter alone (the scan is read once,
before; the curvature arrays are off unless --curvature, as they are not part
of the simplification), then vtkKeyPointError's figures for the original
against the simplified cloud (from the field data of its port 0): AKPE and MKPE
(Euclidean, paper Eqs. 1-2), the symmetric Hausdorff distance and the mean
point-to-plane distance of the original points to the simplified surface.
Distances are in the scan's units. Works with pvpython, or any Python with
ParaView's (or VTK's) vtkmodules and the asmvtk package on the path.
"""
import argparse
import glob
import os
import statistics
import sys
import time

from asmvtk import vtkASMSimplify, vtkKeyPointError
from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkIOPLY import vtkPLYReader

from asm_plugin import fraction_arg, positive_int_arg

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
TEST_DATA = os.path.join(REPO, "Testing", "Data")

HEADER = "%-14s %9s %7s %9s %10s %10s %10s %10s" % (
    "model", "N", "N_s", "time (s)", "AKPE", "MKPE", "Hausdorff", "P2P mean")
ROW = "%-14s %9d %7d %9.4f %10.4g %10.4g %10.4g %10.4g"


def read_ply(path):
    if not os.path.isfile(path):
        raise RuntimeError("no such file")
    reader = vtkPLYReader()
    reader.SetFileName(path)
    reader.Update()
    cloud = reader.GetOutput()
    if cloud is None or cloud.GetNumberOfPoints() == 0:
        raise RuntimeError("no points read")
    return cloud


def measure(path, fraction, runs, curvature):
    """One table row: (model, N, N_s, median seconds, AKPE, MKPE, Hausdorff, P2P mean)."""
    original = read_ply(path)

    asm = vtkASMSimplify()
    asm.SetInputData(original)
    asm.SetModeToPaper()  # the paper's pipeline, as in its Table 2
    asm.SetTargetModeToOutputFraction()
    asm.SetOutputFraction(fraction)
    asm.SetGenerateCurvature(curvature)
    times = []
    for _ in range(runs):
        asm.Modified()
        start = time.perf_counter()
        asm.Update()
        times.append(time.perf_counter() - start)
    simplified = asm.GetOutput()

    kpe = vtkKeyPointError()
    kpe.SetInputData(0, original)  # the original cloud
    kpe.SetInputData(1, simplified)  # the simplified one
    kpe.SetGenerateCurvature(False)  # not part of the figures
    kpe.Update()
    # The figures as one-value arrays in the field data of port 0, which every
    # process has in an MPI run (the table of port 1 has its row on process 0
    # only).
    figures = kpe.GetOutput().GetFieldData()

    def figure(name):
        array = figures.GetArray(name)
        if array is None or array.GetNumberOfTuples() != 1:
            raise RuntimeError("vtkKeyPointError gave no figure " + name)
        return array.GetValue(0)

    model = os.path.splitext(os.path.basename(path))[0]
    return (model, original.GetNumberOfPoints(), simplified.GetNumberOfPoints(),
            statistics.median(times), figure("AKPE"), figure("MKPE"),
            figure("HausdorffDistance"), figure("PointToPlaneMean"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scans", nargs="*",
                        help="PLY files (default: every .ply in Testing/Data)")
    parser.add_argument("--fraction", type=fraction_arg, default=0.05,
                        help="N_s as a fraction of N (default: 0.05)")
    parser.add_argument("--runs", type=positive_int_arg, default=5,
                        help="timed runs of the filter per scan; the median is printed (default: 5)")
    parser.add_argument("--curvature", action="store_true",
                        help="time the filter with its curvature arrays on (GenerateCurvature)")
    parser.add_argument("--with-test-data", action="store_true",
                        help="also run on every .ply in Testing/Data when scans are given")
    args = parser.parse_args()

    scans = list(args.scans)
    if not scans or args.with_test_data:
        scans += sorted(glob.glob(os.path.join(TEST_DATA, "*.ply")))
    # Each file once, in the order given (a scan named and also in Testing/Data is one row).
    seen = set()
    scans = [path for path in scans
             if os.path.realpath(path) not in seen and not seen.add(os.path.realpath(path))]
    if not scans:
        sys.exit("no PLY files given and none in " + TEST_DATA)

    print("# ASM at N_s = %g %% of N, time = median of %d run(s) of vtkASMSimplify alone%s;"
          % (100.0 * args.fraction, args.runs, " (with curvature)" if args.curvature else ""))
    print("# SMP backend %s, %d thread(s); errors from vtkKeyPointError, in the scan's units"
          % (vtkSMPTools.GetBackend(), vtkSMPTools.GetEstimatedNumberOfThreads()))
    print(HEADER)
    failed = False
    for path in scans:
        try:
            row = measure(path, args.fraction, args.runs, args.curvature)
        except RuntimeError as error:
            print("%s: %s" % (path, error), file=sys.stderr)
            failed = True
            continue
        print(ROW % row)
        sys.stdout.flush()
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
