"""Simplify a cloud stored in pieces, in parallel, without gathering it on one
process: each process reads its own pieces of a partitioned PolyData file
(.pvtp, or .pvtu), ASM Simplify simplifies the whole cloud to exactly N_s points (one
grid, one budget over all processes), and each process writes its share of
the output as a piece of another .pvtp. Run under pvbatch with MPI (the
script runs on process 0, ParaView runs the pipeline on every process):

    mpiexec -n K pvbatch --mpi Examples/Python/mpi_simplify_pieces.py \\
        pieces.pvtp simplified.pvtp [--fraction 0.05 | --points N] [--mode paper]

To make a .pvtp (or .pvtu) from one file (read on process 0, spread over
the K processes by Redistribute DataSet, written as K pieces):

    mpiexec -n K pvbatch --mpi Examples/Python/mpi_simplify_pieces.py \\
        --split cloud.ply pieces.pvtp

A cloud too large for one machine is written in pieces by whatever produced
it (a .pvtp lists .vtp pieces; any number of pieces per process). Every
point array is carried through; the output's vtkOriginalPointIds and
vtkOriginalProcessIds say where each output point's representative was.
Prints N, N_s, the processes, the time of the simplification and the
figures on process 0. The plugin is found as the other examples find it
(--plugin, $ASM_PLUGIN, $PV_PLUGIN_PATH, the build tree).

A missing input or input piece, an output directory that cannot be made,
an input with no points, a --fraction outside (0, 1] or --points below 1,
and an empty result stop it
with a message and a non-zero exit status before anything is written
(mpiexec then stops the other processes, which may print a SIGTERM trace).
"""
import argparse
import os
import sys
import time
import xml.etree.ElementTree as ElementTree

from paraview import servermanager
from paraview.simple import (ExtractSurface, LoadPlugin, MaskPoints, PLYReader, RedistributeDataSet,
                             SaveData, XMLPartitionedPolydataReader, XMLPartitionedUnstructuredGridReader)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from asm_plugin import find_plugin, fraction_arg, positive_int_arg, require_file, require_writable  # noqa: E402

PARTITIONED = (".pvtp", ".pvtu")


def check_pieces(path):
    """Exit unless every piece a .pvtp/.pvtu lists is a file (a missing one would be read as no
    points: a partial result with exit status 0)."""
    try:
        pieces = [piece.get("Source") for piece in ElementTree.parse(path).getroot().iter("Piece")]
    except ElementTree.ParseError as error:
        sys.exit("input %s: not a partitioned VTK XML file (%s)" % (path, error))
    if not pieces or None in pieces:
        sys.exit("input %s: lists no pieces" % path)
    for piece in pieces:
        require_file(os.path.join(os.path.dirname(os.path.abspath(path)), piece), "piece of " + path + ":")


parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("input", help=".pvtp or .pvtu to simplify (or, with --split, the .ply to split)")
parser.add_argument("output", help=".pvtp to write (with --split, .pvtp or .pvtu)")
parser.add_argument("--split", action="store_true", help="split a .ply into K pieces instead")
parser.add_argument("--fraction", type=fraction_arg, default=0.05, help="N_s as a fraction of N (default 0.05)")
parser.add_argument("--points", type=positive_int_arg, help="N_s as a number of points (instead of --fraction)")
parser.add_argument("--mode", choices=("feature", "paper"), default="feature")
parser.add_argument("--plugin", help="path to ASM.so")
args = parser.parse_args()

# Every check comes before the pipeline: an error inside it on process 0 would leave the other
# processes waiting in a collective (a hang); sys.exit here ends the whole run.
require_file(args.input)
require_writable(args.output, create=True)  # (SaveData makes the directories of a .pvtp)
if args.split:
    if not args.output.endswith(PARTITIONED):
        parser.error("with --split the output must be a .pvtp or .pvtu: %s" % args.output)
else:
    if not args.input.endswith(PARTITIONED):
        parser.error("the input must be a .pvtp or .pvtu (make one with --split): %s" % args.input)
    if not args.output.endswith(".pvtp"):
        parser.error("the output must be a .pvtp: %s" % args.output)
    check_pieces(args.input)
    plugin = find_plugin(args.plugin)

processes = servermanager.ActiveConnection.GetNumberOfDataPartitions()

if args.split:
    reader = PLYReader(FileNames=[args.input])
    reader.UpdatePipeline()
    if reader.GetDataInformation().GetNumberOfPoints() == 0:
        sys.exit("input %s: no points read (not a PLY file with vertices?)" % args.input)
    # Redistribute DataSet moves cells: give every point a vertex cell first.
    cloud = MaskPoints(Input=reader, OnRatio=1, MaximumNumberofPoints=2 ** 31 - 1, GenerateVertices=1,
                       SingleVertexPerCell=1)
    spread = RedistributeDataSet(Input=cloud)  # (an unstructured grid: .pvtu)
    if args.output.endswith(".pvtp"):
        spread = ExtractSurface(Input=spread)  # the points and their vertex cells as PolyData
    SaveData(args.output, proxy=spread)
    print("split %s: %d points into %d pieces: %s"
          % (args.input, spread.GetDataInformation().GetNumberOfPoints(), processes, args.output))
else:  # (ending normally: every process reaches pvbatch's own end)
    LoadPlugin(plugin, ns=globals())
    if args.input.endswith(".pvtu"):
        reader = XMLPartitionedUnstructuredGridReader(FileName=[args.input])
    else:
        reader = XMLPartitionedPolydataReader(FileName=[args.input])
    asm = ASMSimplify(Input=reader)  # noqa: F821 (defined by LoadPlugin)
    if args.points is not None:
        asm.TargetMode = "Number Of Output Points"
        asm.NumberOfOutputPoints = args.points
    else:
        asm.OutputFraction = args.fraction
    if args.mode == "paper":
        asm.Mode = "Paper"
    reader.UpdatePipeline()
    n = reader.GetDataInformation().GetNumberOfPoints()
    if n == 0:
        sys.exit("input %s: no points read" % args.input)
    start = time.perf_counter()
    asm.UpdatePipeline()
    elapsed = time.perf_counter() - start
    ns = asm.GetDataInformation().GetNumberOfPoints()
    if ns == 0:
        sys.exit("ASM Simplify produced no points from %d input points (see its messages above); "
                 "nothing written" % n)
    SaveData(args.output, proxy=asm)

    fields = asm.GetFieldDataInformation()
    figures = {name: fields.GetArray(name).GetRange(0)[0] for name in ("NumberOfKeyPoints", "MKPE", "CellSize")}
    print("N %d  N_s %d  processes %d  mode %s  time %.3f s  key points %d  MKPE %g  cell size %g  -> %s"
          % (n, ns, processes, args.mode, elapsed, figures["NumberOfKeyPoints"], figures["MKPE"],
             figures["CellSize"], args.output))
