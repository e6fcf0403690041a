"""Compares the outputs of TestMPISimplify.py (and TestMPIPlugin.py) for
K = 1, 2, 3, 4 processes (files given as arguments), mode by mode (each file
names its mode and N_s; the first file of a mode is the reference): exactly
N_s points each, the same sorted points and array values, the same figures,
up to a relative tolerance of 1e-9 (of the bounding-box diagonal for
positions; floating-point summation order is the only difference between
runs). The one-process runs of the serial path (AlwaysDistribute off) must
agree with the distributed runs too: a cell's result does not depend on the
order of its points.

The lattice modes (gridded data, exact ties everywhere, every point twice
with two labels) compare the same way, their labels and the input point
each sample stands for exactly too: Key Point Error's planes are fitted to the 8 nearest simplified points,
chosen among equidistant ones by position, not by the order the simplified
points were gathered in.

One exception: ClusterSize in the paper mode (and lattice-paper). Points of cells that Eq. 4
gives no sample join their nearest sample, and across a process border that
can be a different neighbouring sample than in a single-process run (the
sample itself, its position and its averaged arrays, which come from its own
points, do not change). So ClusterSize is checked in total (every input
point counted once) and on at least 90 % of the samples exactly. In the
feature-preserving mode every cell has a sample and the halo covers the
clusters: ClusterSize must agree exactly."""
import sys

import numpy as np

TOL = 1e-9
columns = ["x", "y", "z", "Value", "MeanCurvature", "KeyPoint", "ClusterSize", "Error"]
files = sys.argv[1:]
runs = [np.load(f) for f in files]
modes = {}
for f, run in zip(files, runs):
    mode = str(run["mode"]) if "mode" in run.files else "paper"
    modes.setdefault(mode, []).append((f, run))
assert modes, "no runs"
for mode, group in sorted(modes.items()):
    base_file, base = group[0]
    ns = int(base["ns"]) if "ns" in base.files else 1800
    assert len(base["table"]) == ns, "%s: %d points" % (base_file, len(base["table"]))
    xyz = base["table"][:, :3]
    diagonal = np.linalg.norm(xyz.max(0) - xyz.min(0))
    # (The lattice runs add the representatives' labels and input indices.)
    names = columns + ["Label", "Source"][:base["table"].shape[1] - len(columns)]
    for f, run in group[1:]:
        table = run["table"]
        assert len(table) == ns, "%s: %d points, not %d" % (f, len(table), ns)
        assert table.shape[1] == len(names), "%s: %d columns, not %d" % (f, table.shape[1], len(names))
        for c, name in enumerate(names):
            a, b = base["table"][:, c], table[:, c]
            if name == "ClusterSize":
                assert a.sum() == b.sum(), "%s: ClusterSize total %d != %d" % (f, b.sum(), a.sum())
                same = np.mean(a == b)
                least = 0.9 if mode.endswith("paper") else 1.0
                assert same >= least, "%s: ClusterSize equal on %.1f %% of samples" % (f, 100 * same)
                continue
            scale = diagonal if c < 3 else max(1.0, np.abs(a).max())
            worst = np.nanmax(np.abs(a - b)) / scale
            assert worst <= TOL, "%s: %s differs by %.3g (relative)" % (f, name, worst)
        for name, v0, v in zip(base["names"], base["values"], run["values"]):
            assert abs(v - v0) <= TOL * max(1.0, abs(v0)), "%s: %s %r != %r" % (f, name, v, v0)
    print("CheckMPIOutputs: %s mode, %d runs agree (%d points, tolerance %g)"
          % (mode, len(group), ns, TOL))
if "feature" in modes and "paper" in modes:
    # The modes differ (the feature mode did run, not the paper mode).
    a, b = modes["paper"][0][1]["table"], modes["feature"][0][1]["table"]
    assert len(a) != len(b) or not np.allclose(a[:, :3], b[:, :3])
