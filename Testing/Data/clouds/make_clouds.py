"""Regenerates the small text and PCD clouds in this directory from the PLY
scans next to it (run with pvpython, from the repository root):

    pvpython Testing/Data/clouds/make_clouds.py

kitten.xyz        every 2nd kitten point: "x y z nx ny nz", a '#' comment header
fandisk.csv       every 2nd fandisk point: a "X,Y,Z" header line, comma separated
kitten-ascii.pcd  every 2nd kitten point: PCD DATA ascii, fields x y z normal_x normal_y normal_z
laurana-binary.pcd every 5th laurana point: PCD DATA binary, fields x y z rgb (packed float)
"""
import os
import struct

from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)


def read(name):
    reader = vtkPLYReader()
    reader.SetFileName(os.path.join(DATA, name))
    reader.Update()
    out = reader.GetOutput()
    return out, vtk_to_numpy(out.GetPoints().GetData())


def pcd_header(fields, sizes, types, n, data):
    return ("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS %s\nSIZE %s\nTYPE %s\n"
            "COUNT %s\nWIDTH %d\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS %d\nDATA %s\n" % (
                " ".join(fields), " ".join(map(str, sizes)), " ".join(types),
                " ".join("1" for _ in fields), n, n, data))


kitten, kp = read("kitten.ply")
kn = vtk_to_numpy(kitten.GetPointData().GetNormals())
rows = [(*kp[i], *kn[i]) for i in range(0, len(kp), 2)]
with open(os.path.join(HERE, "kitten.xyz"), "w") as f:
    f.write("# kitten (every 2nd point of Testing/Data/kitten.ply)\n# x y z nx ny nz\n")
    for r in rows:
        f.write("%.6g %.6g %.6g %.4f %.4f %.4f\n" % r)
with open(os.path.join(HERE, "kitten-ascii.pcd"), "w") as f:
    f.write(pcd_header(["x", "y", "z", "normal_x", "normal_y", "normal_z"], [4] * 6, ["F"] * 6,
                       len(rows), "ascii"))
    for r in rows:
        f.write("%.6g %.6g %.6g %.4f %.4f %.4f\n" % r)

_, fp = read("fandisk.ply")
with open(os.path.join(HERE, "fandisk.csv"), "w") as f:
    f.write("X,Y,Z\n")
    for p in fp[::2]:
        f.write("%.6g,%.6g,%.6g\n" % tuple(p))

laurana, lp = read("laurana.ply")
colours = laurana.GetPointData().GetArray("RGB")
lc = vtk_to_numpy(colours) if colours is not None else None
picked = range(0, len(lp), 5)
with open(os.path.join(HERE, "laurana-binary.pcd"), "wb") as f:
    f.write(pcd_header(["x", "y", "z", "rgb"], [4] * 4, ["F"] * 4, len(picked), "binary").encode())
    for i in picked:
        r, g, b = (int(c) for c in lc[i][:3]) if lc is not None else (0, 0, 0)
        packed = struct.unpack("<f", struct.pack("<I", (r << 16) | (g << 8) | b))[0]
        f.write(struct.pack("<ffff", *lp[i], packed))
print("wrote", len(rows), len(fp[::2]), len(picked), "points")
