"""Time vtkASMSimplify on PLY scans and print one line per scan (pvpython).

    PYTHONPATH=build/lib/python3/dist-packages pvpython Examples/Python/time_scans.py \
        [--fraction 0.05] [--runs 5] [--threads 0] [--no-curvature] [--mode paper] \
        scan.ply [scan.ply ...]

Prints N, N_s, the median wall time of --runs executions of the filter alone
(reading excluded), AKPE, MKPE, the number of key points and the cell size.
--threads > 0 uses vtkSMPTools' STDThread backend with that many threads;
0 keeps the default backend (Sequential on Debian's ParaView). --mode picks
the filter's Mode: "feature" (FEATURE_PRESERVING, the default) or "paper".
A scan that is missing, holds no points or gives an empty output is reported
on stderr and skipped; the exit status is then 1.
"""
import argparse
import os
import statistics
import sys
import time

from asmvtk import vtkASMSimplify
from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkIOPLY import vtkPLYReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from asm_plugin import fraction_arg, int_at_least, positive_int_arg  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scans", nargs="+")
    parser.add_argument("--fraction", type=fraction_arg, default=0.05)
    parser.add_argument("--runs", type=positive_int_arg, default=5)
    parser.add_argument("--threads", type=int_at_least(0), default=0)
    parser.add_argument("--no-curvature", action="store_true", help="GenerateCurvature off")
    parser.add_argument("--mode", choices=("feature", "paper"), default="feature")
    args = parser.parse_args()
    if args.threads > 0:
        vtkSMPTools.SetBackend("STDThread")
        vtkSMPTools.Initialize(args.threads)
    print("backend %s, %d thread(s), mode %s" % (
        vtkSMPTools.GetBackend(), vtkSMPTools.GetEstimatedNumberOfThreads(), args.mode))
    print("%-18s %9s %7s %9s %10s %10s %6s %9s" % ("scan", "N", "N_s", "time (s)", "AKPE", "MKPE", "keys", "cell"))
    failed = False
    for path in args.scans:
        if not os.path.isfile(path):
            print("%s: no such file" % path, file=sys.stderr)
            failed = True
            continue
        reader = vtkPLYReader()
        reader.SetFileName(path)
        reader.Update()
        if reader.GetOutput().GetNumberOfPoints() == 0:
            print("%s: no points read" % path, file=sys.stderr)
            failed = True
            continue
        asm = vtkASMSimplify()
        asm.SetInputData(reader.GetOutput())
        asm.SetOutputFraction(args.fraction)
        asm.SetGenerateCurvature(not args.no_curvature)
        asm.SetMode(vtkASMSimplify.PAPER if args.mode == "paper" else vtkASMSimplify.FEATURE_PRESERVING)
        times = []
        for _ in range(args.runs):
            asm.Modified()
            start = time.perf_counter()
            asm.Update()
            times.append(time.perf_counter() - start)
        out = asm.GetOutput()
        if out.GetNumberOfPoints() == 0:
            print("%s: empty output (N_s rounds to 0?)" % path, file=sys.stderr)
            failed = True
            continue
        fd = out.GetFieldData()
        value = lambda name: fd.GetArray(name).GetValue(0)
        print("%-18s %9d %7d %9.4f %10.3g %10.3g %6d %9.4g" % (
            os.path.basename(path), reader.GetOutput().GetNumberOfPoints(), out.GetNumberOfPoints(),
            statistics.median(times), value("AKPE"), value("MKPE"), value("NumberOfKeyPoints"),
            value("CellSize")))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
