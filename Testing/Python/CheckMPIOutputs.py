"""Compares the outputs of TestMPISimplify.py for K = 1, 2, 3 processes
(files given as arguments): exactly N_s points each, the same sorted points
and array values, the same figures, up to a relative tolerance of 1e-9 (of
the bounding-box diagonal for positions; floating-point summation order is
the only difference between runs).

One exception: ClusterSize. Points of cells that Eq. 4 gives no sample join
their nearest sample, and across a process border that can be a different
neighbouring sample than in a single-process run (the sample itself, its
position and its averaged arrays, which come from its own points, do not
change). So ClusterSize is checked in total (every input point counted
once) and on at least 90 % of the samples exactly."""
import sys

import numpy as np

NS = 1800
TOL = 1e-9
runs = [np.load(f) for f in sys.argv[1:]]
base = runs[0]
assert len(base["table"]) == NS, len(base["table"])
xyz = base["table"][:, :3]
diagonal = np.linalg.norm(xyz.max(0) - xyz.min(0))
columns = ["x", "y", "z", "Value", "MeanCurvature", "KeyPoint", "ClusterSize", "Error"]
for k, run in enumerate(runs[1:], start=2):
    table = run["table"]
    assert len(table) == NS, "run %d: %d points" % (k, len(table))
    for c, name in enumerate(columns):
        a, b = base["table"][:, c], table[:, c]
        if name == "ClusterSize":
            assert a.sum() == b.sum(), "run %d: ClusterSize total %d != %d" % (k, b.sum(), a.sum())
            same = np.mean(a == b)
            assert same >= 0.9, "run %d: ClusterSize equal on %.1f %% of samples" % (k, 100 * same)
            continue
        scale = diagonal if c < 3 else max(1.0, np.abs(a).max())
        worst = np.nanmax(np.abs(a - b)) / scale
        assert worst <= TOL, "run %d: %s differs by %.3g (relative)" % (k, name, worst)
    for name, v0, v in zip(base["names"], base["values"], run["values"]):
        assert abs(v - v0) <= TOL * max(1.0, abs(v0)), "run %d: %s %r != %r" % (k, name, v, v0)
print("CheckMPIOutputs: %d runs agree (%d points, tolerance %g)" % (len(runs), NS, TOL))
