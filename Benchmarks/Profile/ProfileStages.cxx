// SPDX-License-Identifier: BSD-3-Clause
// asm_profile --stages and --floor: the core's stages one by one, and what
// grouping the points by cell alone costs (see asm_profile.cxx).
#include "Profile.h"

#include "Core/Budget.h"
#include "Core/CellFrame.h"
#include "Core/CellSize.h"
#include "Core/Curvature.h"
#include "Core/Grid.h"
#include "Core/KeyPoints.h"
#include "Core/Neighbors.h"
#include "Core/Simplify.h"
#include "vtkASMFilterUtilities.h"
#include "vtkASMSimplify.h"

#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

namespace asmprofile
{
namespace
{
// The curvature's parts at the given positions, as vtkASMSimplify computes
// it (the input's floats in place), one thread, best of 3: the tree over the
// input, the k nearest alone, and the whole estimate.
void TimeCurvature(
  vtkPolyData* input, const std::vector<double>& positions, const std::vector<double>& normals)
{
  using namespace asmcore;
  const InputCoordinates cloud(input, false, true);
  const Coordinates xyz = cloud.Xyz;
  const IdView ids = cloud.Ids;
  const Index nq = static_cast<Index>(positions.size() / 3);
  double build = 1e9, knn = 1e9, all = 1e9;
  Neighbors tree;
  for (int r = 0; r < 3; ++r)
  {
    const double t0 = Cpu();
    tree.Build(xyz, ids);
    build = std::min(build, Cpu() - t0);
  }
  std::vector<Index> found;
  std::vector<double> d2;
  double check = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    const double t0 = Cpu();
    for (Index q = 0; q < nq; ++q)
    {
      tree.KNearest(positions.data() + 3 * q, DefaultCurvatureNeighbors, found, d2);
      check += d2.back();
    }
    knn = std::min(knn, Cpu() - t0);
  }
  // The neighbours' coordinates: from the tree's copies (what the curvature
  // reads since round 23), or gathered from the cloud (before).
  std::vector<double> local;
  double fromTree = 1e9, fromCloud = 1e9;
  for (int r = 0; r < 3; ++r)
  {
    double t0 = Cpu();
    for (Index q = 0; q < nq; ++q)
    {
      tree.KNearest(positions.data() + 3 * q, DefaultCurvatureNeighbors, found, d2, local);
      check += local[5];
    }
    fromTree = std::min(fromTree, Cpu() - t0);
    t0 = Cpu();
    for (Index q = 0; q < nq; ++q)
    {
      tree.KNearest(positions.data() + 3 * q, DefaultCurvatureNeighbors, found, d2);
      local.resize(3 * found.size());
      for (std::size_t j = 0; j < found.size(); ++j)
      {
        xyz.Get(found[j], local.data() + 3 * j);
      }
      check += local[5];
    }
    fromCloud = std::min(fromCloud, Cpu() - t0);
  }
  std::printf("    %d nearest with their coordinates, best of 3: from the tree %.1f ms, "
              "gathered from the cloud %.1f ms\n",
    DefaultCurvatureNeighbors, 1e3 * fromTree, 1e3 * fromCloud);
  for (int r = 0; r < 3; ++r)
  {
    const double t0 = Cpu();
    const auto estimates = EstimateCurvature(
      xyz, ids, tree, positions.data(), nq, normals.data(), DefaultCurvatureNeighbors, {});
    all = std::min(all, Cpu() - t0);
    check += estimates.empty() ? 0.0 : estimates[0].SurfaceVariation;
  }
  std::printf("    curvature at %lld positions, best of 3: tree %.1f ms, %d nearest %.1f ms "
              "(%.2f us each), estimates with their queries %.1f ms (check %g)\n",
    (long long)nq, 1e3 * build, DefaultCurvatureNeighbors, 1e3 * knn,
    1e6 * knn / std::max<Index>(nq, 1), 1e3 * all, check);
}

} // namespace

// The core's stages one by one, one thread (mirrors asmcore::Simplify).
void TimeStages(vtkPolyData* input, double fraction, int mode)
{
  using namespace asmcore;
  double t0 = Cpu();
  const InputCoordinates cloud(input);
  const double* xyz = cloud.Xyz.Doubles;
  const IdView ids = cloud.Ids;
  double t1 = Cpu();
  double t2 = Cpu();
  const Index target = static_cast<Index>(std::llround(fraction * ids.size()));
  const Bounds bounds = ComputeBounds(xyz, ids);
  double t3 = Cpu();
  const double cellSize = AutomaticCellSize(xyz, ids, bounds, target / 8.0);
  double t4 = Cpu();
  const double search = t4 - t3; // before the extra counts below
  double best = 1e9;
  for (int r = 0; r < 7; ++r)
  {
    const double c0 = Cpu();
    CountOccupiedCells(xyz, ids, GridSpec::Make(bounds, cellSize));
    best = std::min(best, Cpu() - c0);
  }
  std::printf("    (one occupancy count, best of 7: %.1f ms)\n", 1e3 * best);
  t4 = Cpu();
  const CellGrid grid = BuildCellGrid(xyz, ids, GridSpec::Make(bounds, cellSize));
  double t5 = Cpu();
  const Index cells = grid.NumberOfCells();
  std::vector<CellFrame> frames(cells);
  for (Index c = 0; c < cells; ++c)
    frames[c] = ComputeCellFrame(xyz, grid.CellIds(c));
  double t6 = Cpu();
  std::vector<double> share(cells);
  std::vector<Index> capacity(cells);
  for (Index c = 0; c < cells; ++c)
  {
    capacity[c] = grid.CellSizeOf(c);
    share[c] = double(capacity[c]);
  }
  const std::vector<Index> budget = ApportionBudget(share, capacity, target);
  double t7 = Cpu();
  KeyPointRule rule;
  rule.CoordinateEpsilon = 1.2e-7;
  LocalPoints q;
  Index keys = 0;
  for (Index c = 0; c < cells; ++c)
  {
    KeyClusters kc = FindCellKeyClusters(xyz, grid.CellIds(c), frames[c], rule, q);
    keys += kc.Key.Size();
  }
  double t8 = Cpu();
  std::printf("  stages (1 thread, %lld points, %lld cells, %lld key clusters):\n",
    (long long)ids.size(), (long long)cells, (long long)keys);
  std::printf("    coordinates + finite ids %6.1f ms\n", 1e3 * (t1 - t0));
  std::printf("    finite ids             %8.1f ms\n", 1e3 * (t2 - t1));
  std::printf("    bounds                 %8.1f ms\n", 1e3 * (t3 - t2));
  std::printf("    automatic cell size    %8.1f ms\n", 1e3 * search);
  std::printf("    grid (hash + sort)     %8.1f ms\n", 1e3 * (t5 - t4));
  std::printf("    PCA per cell           %8.1f ms\n", 1e3 * (t6 - t5));
  std::printf("    budgets                %8.1f ms\n", 1e3 * (t7 - t6));
  std::printf("    key clusters (local frame, partition, link) %8.1f ms\n", 1e3 * (t8 - t7));
  std::printf("    (sampling, assembly, output arrays: the rest of the end-to-end time)\n");
  // Share of asmcore::Simplify's CPU time spent inside Execution loops (what
  // a second thread can share): an Amdahl bound robust to a loaded machine.
  std::vector<double> positions, normals;
  {
    double inside = 0.0;
    asmcore::Execution counting;
    counting.For = [&inside](Index b, Index e, const std::function<void(Index, Index)>& body) {
      const double c0 = Cpu();
      body(b, e);
      inside += Cpu() - c0;
    };
    SimplifyParameters parameters;
    parameters.NumberOfSamples = target;
    parameters.CoordinateEpsilon = 1.2e-7;
    if (mode == vtkASMSimplify::PAPER)
    {
      parameters.Mode = asmcore::SimplifyMode::Paper;
    }
    const double c0 = Cpu();
    const SimplifyResult result = Simplify(xyz, ids, nullptr, parameters, counting);
    const double total = Cpu() - c0;
    std::printf(
      "    asmcore::Simplify %.1f ms, %.1f %% of it in parallel loops: 2-thread bound %.2fx\n",
      1e3 * total, 100.0 * inside / total, 1.0 / ((total - inside) / total + 0.5 * inside / total));
    for (const Sample& s : result.Samples)
    {
      positions.insert(positions.end(), s.Position, s.Position + 3);
      normals.insert(normals.end(), s.Normal, s.Normal + 3);
    }
  }
  TimeCurvature(input, positions, normals);
}

// The floor of a grid simplifier with a target count, on this input (its
// own coordinates, floats in place, one thread, best of 3): the bounds, one
// occupancy count (the least a search for the cell size can do), the grid
// (hash + counting sort) and one pass over every cell's points (a centroid
// per cell) -- what the grouping alone costs, before any of ASM's per-cell
// steps.
void TimeFloor(vtkPolyData* input, double fraction)
{
  using namespace asmcore;
  const InputCoordinates cloud(input, true, true);
  const Coordinates xyz = cloud.Xyz;
  const IdView ids = cloud.Ids;
  const auto n = static_cast<double>(ids.size());
  const double cellSize = AutomaticCellSize(xyz, ids, ComputeBounds(xyz, ids), fraction * n / 8.0);
  double best[5] = { 1e9, 1e9, 1e9, 1e9, 1e9 };
  double sum = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    const double t0 = Cpu();
    const Bounds bounds = ComputeBounds(xyz, ids);
    const double t1 = Cpu();
    const GridSpec spec = GridSpec::Make(bounds, cellSize);
    sum += static_cast<double>(CountOccupiedCells(xyz, ids, spec));
    const double t2 = Cpu();
    const CellGrid grid = BuildCellGrid(xyz, ids, spec);
    const double t3 = Cpu();
    for (Index c = 0; c < grid.NumberOfCells(); ++c)
    {
      double centroid[3] = { 0, 0, 0 };
      for (Index id : grid.CellIds(c))
      {
        double p[3];
        xyz.Get(id, p);
        for (int a = 0; a < 3; ++a)
          centroid[a] += p[a];
      }
      sum += centroid[0] + centroid[1] + centroid[2];
    }
    const double t4 = Cpu();
    const double part[5] = { t1 - t0, t2 - t1, t3 - t2, t4 - t3, t4 - t0 };
    for (int k = 0; k < 5; ++k)
      best[k] = std::min(best[k], part[k]);
  }
  const double ns = 1e9 / n;
  volatile double sink = sum; // (the centroids are computed, not optimised away)
  (void)sink;
  std::printf("  floor (1 thread, best of 3, ns per point): bounds %.1f, one occupancy count %.1f, "
              "grid %.1f, a pass over the cells %.1f; in all %.1f ns = %.1f M pt/s\n",
    ns * best[0], ns * best[1], ns * best[2], ns * best[3], ns * best[4], n / best[4] / 1e6);
}
} // namespace asmprofile
