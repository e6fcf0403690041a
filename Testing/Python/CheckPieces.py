"""Checks the output of Examples/Python/mpi_simplify_pieces.py (the bunny
split into pieces, simplified by K processes that each read their own
pieces and write their share of the output): the .pvtp given as first
argument lists one piece per process (second argument: K), holds exactly
N_s = 1800 points over its pieces, every process's piece holds some, and
they are the points the serial path gives for the bunny (Paper mode,
N_s = 1800, read from the .ply given as third argument), up to the
rounding of the summation order.

    pvpython CheckPieces.py simplified.pvtp K bunny.ply

Environment: PYTHONPATH with the asmvtk package.
"""
import os
import sys
import xml.etree.ElementTree as ElementTree

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from asmvtk import vtkASMSimplify

NS = 1800
path, processes, ply = sys.argv[1], int(sys.argv[2]), sys.argv[3]

pieces = [p.get("Source") for p in ElementTree.parse(path).getroot().iter("Piece")]
assert len(pieces) == processes, (pieces, processes)
tables = []
for piece in pieces:
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(os.path.join(os.path.dirname(path), piece))
    reader.Update()
    out = reader.GetOutput()
    assert out.GetNumberOfPoints() > 0, piece + ": no points"
    assert out.GetPointData().GetArray("vtkOriginalProcessIds") is not None, piece
    tables.append(vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64))
distributed = np.concatenate(tables)
assert len(distributed) == NS, len(distributed)

bunny = vtkPLYReader()
bunny.SetFileName(ply)
serial = vtkASMSimplify()
serial.SetInputConnection(bunny.GetOutputPort())
serial.SetMode(vtkASMSimplify.PAPER)
serial.SetTargetModeToNumberOfOutputPoints()
serial.SetNumberOfOutputPoints(NS)
serial.Update()
expected = vtk_to_numpy(serial.GetOutput().GetPoints().GetData()).astype(np.float64)


def by_position(xyz):
    return xyz[np.lexsort(xyz[:, ::-1].T)]


# The same points; the centroids' last bits differ with the summation order
# (a distributed run sums a cell's points in canonical order), and the
# output points are floats, as the input's.
diagonal = np.linalg.norm(expected.max(axis=0) - expected.min(axis=0))
difference = np.abs(by_position(distributed) - by_position(expected)).max()
assert difference <= 1e-6 * diagonal, difference
print("%s: %d pieces, %d points, the serial path's points (largest difference %g)"
      % (path, len(pieces), len(distributed), difference))
