// SPDX-License-Identifier: BSD-3-Clause
#include "Metrics.h"

#include "CellFrame.h"
#include "CellSize.h"
#include "GroupBy.h"
#include "Neighbors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
DistanceSummary Summarize(const std::vector<double>& d)
{
  DistanceSummary s;
  s.Count = static_cast<Index>(d.size());
  if (d.empty())
  {
    return s;
  }
  double sum = 0.0, sumSquares = 0.0;
  for (double v : d)
  {
    sum += v;
    sumSquares += v * v;
    s.Max = std::max(s.Max, v);
  }
  s.Mean = sum / static_cast<double>(d.size());
  s.RMS = std::sqrt(sumSquares / static_cast<double>(d.size()));
  return s;
}

std::vector<Eigen::Vector3d> CloudKeyPoints(const double* xyz, IdView ids,
  const GridSpec& spec, const KeyPointRule& rule, const Execution& execution)
{
  const CellGrid grid = BuildCellGrid(xyz, ids, spec, execution);
  const Index cells = grid.NumberOfCells();
  std::vector<std::vector<Eigen::Vector3d>> perCell(static_cast<std::size_t>(cells));
  execution.Run(0, cells, [&](Index b, Index e) {
    LocalPoints q;
    for (Index c = b; c < e; ++c)
    {
      const IdView points = grid.CellIds(c);
      const CellFrame frame = ComputeCellFrame(xyz, points);
      const KeyClusters kc = FindCellKeyClusters(xyz, points, frame, rule, q);
      for (Index k = 0; k < kc.Key.Size(); ++k)
      {
        perCell[c].push_back(frame.Centroid + frame.Axes * Centroid(q, kc.Key.Begin(k), kc.Key.End(k)));
      }
    }
  });
  std::vector<Eigen::Vector3d> keys;
  for (const auto& cell : perCell)
  {
    keys.insert(keys.end(), cell.begin(), cell.end());
  }
  return keys;
}

namespace
{
// The positions in `ids` grouped by a coarse grid over their bounding box
// (cells numbered in Morton order), about 64 points per cell: queries made
// in this order walk a k-d tree of a nearby cloud through a small working
// set, whatever the order of the points. Stable: deterministic.
std::vector<Index> SpatialOrder(
  const double* xyz, IdView ids, const Execution& execution)
{
  const Index n = static_cast<Index>(ids.size());
  const Bounds bounds = ComputeBounds(xyz, ids, execution);
  int bits = 0; // per axis
  while (bits < 5 && (Index(64) << (3 * (bits + 1))) <= n)
  {
    ++bits;
  }
  double scale[3];
  for (int a = 0; a < 3; ++a)
  {
    const double extent = bounds.Max[a] - bounds.Min[a];
    scale[a] = extent > 0.0 ? static_cast<double>(1 << bits) / extent : 0.0;
    scale[a] = std::isfinite(scale[a]) ? scale[a] : 0.0;
  }
  const double top = static_cast<double>((1 << bits) - 1);
  auto cellOf = [&](Index i) {
    const double* p = xyz + 3 * ids[i];
    Index key = 0;
    int c[3];
    for (int a = 0; a < 3; ++a)
    {
      c[a] = static_cast<int>(std::min(top, std::max(0.0, (p[a] - bounds.Min[a]) * scale[a])));
    }
    for (int b = bits - 1; b >= 0; --b)
    {
      for (int a = 0; a < 3; ++a)
      {
        key = 2 * key + ((c[a] >> b) & 1);
      }
    }
    return key;
  };
  std::vector<Index> start, order;
  GroupBy(n, Index(1) << (3 * bits), cellOf, [](Index i) { return i; }, start, order, execution);
  return order;
}
} // namespace

void SurfaceDistances(const double* xyz, IdView ids, const double* surfaceXyz,
  const Neighbors& surface, int k, std::vector<double>* plane, std::vector<double>* nearest,
  const Execution& execution)
{
  const double infinity = std::numeric_limits<double>::infinity();
  for (std::vector<double>* d : { plane, nearest })
  {
    if (d)
    {
      d->assign(ids.size(), infinity);
    }
  }
  if (ids.empty())
  {
    return;
  }
  const std::vector<Index> order = SpatialOrder(xyz, ids, execution);
  // Only the nearest point when no plane is asked for.
  k = plane ? std::max(1, k) : 1;
  execution.Run(0, static_cast<Index>(ids.size()), [&](Index b, Index e) {
    std::vector<Index> near;
    std::vector<double> sq;
    for (Index j = b; j < e; ++j)
    {
      const Index i = order[j];
      const double* p = xyz + 3 * ids[i];
      surface.KNearest(p, k, near, sq);
      if (near.empty())
      {
        continue;
      }
      if (nearest)
      {
        (*nearest)[i] = std::sqrt(sq[0]);
      }
      if (!plane)
      {
        continue;
      }
      if (near.size() < 3)
      {
        (*plane)[i] = std::sqrt(sq[0]);
        continue;
      }
      const CellFrame fit = ComputeCellFrame(surfaceXyz, near);
      (*plane)[i] = std::abs(fit.Normal().dot(Eigen::Vector3d(p[0], p[1], p[2]) - fit.Centroid));
    }
  });
}

std::vector<double> NearestDistances(
  const double* xyz, IdView ids, const Neighbors& target, const Execution& execution)
{
  std::vector<double> d;
  SurfaceDistances(xyz, ids, nullptr, target, 1, nullptr, &d, execution);
  return d;
}

std::vector<double> PointToPlaneDistances(const double* xyz, IdView ids,
  const double* surfaceXyz, const Neighbors& surface, int k, const Execution& execution)
{
  std::vector<double> d;
  SurfaceDistances(xyz, ids, surfaceXyz, surface, k, &d, nullptr, execution);
  return d;
}

namespace
{
std::vector<double> Flatten(const std::vector<Eigen::Vector3d>& points, std::vector<Index>& ids)
{
  std::vector<double> flat;
  flat.reserve(3 * points.size());
  ids.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    flat.insert(flat.end(), { points[i][0], points[i][1], points[i][2] });
    ids[i] = static_cast<Index>(i);
  }
  return flat;
}

Bounds Union(const Bounds& a, const Bounds& b)
{
  if (!a.Valid || !b.Valid)
  {
    return a.Valid ? a : b;
  }
  Bounds u = a;
  for (int k = 0; k < 3; ++k)
  {
    u.Min[k] = std::min(a.Min[k], b.Min[k]);
    u.Max[k] = std::max(a.Max[k], b.Max[k]);
  }
  return u;
}
} // namespace

Comparison CompareClouds(const double* xyz, IdView ids,
  const Neighbors& originalTree, const double* sxyz, const std::vector<Index>& sids,
  const ComparisonOptions& options, const Execution& execution)
{
  Comparison result;
  if (ids.empty() || sids.empty())
  {
    return result;
  }
  const Bounds original = ComputeBounds(xyz, ids, execution);
  const Bounds both = Union(original, ComputeBounds(sxyz, sids, execution));
  result.Diagonal = original.Diagonal();

  // One grid for both clouds, sized as the simplifier sizes it: from the
  // original points and the simplified count.
  double cellSize = options.CellSize;
  if (!(cellSize > 0.0) || !std::isfinite(cellSize))
  {
    cellSize = AutomaticCellSize(xyz, ids, both,
      static_cast<double>(sids.size()) / std::max(1.0, options.SamplesPerCell), execution);
  }
  const GridSpec spec = GridSpec::Make(both, cellSize);
  result.CellSize = spec.CellSize;
  if (execution.Report(0.1))
  {
    result.Aborted = true;
    return result;
  }

  // Key point error (Eq. 1-3): each original key point against the nearest
  // key point of the simplified cloud (its nearest point when it has none).
  KeyPointRule rule = options.Rule;
  rule.ErrorTolerance = 0.0;
  rule.Snap = false;
  const auto originalKeys = CloudKeyPoints(xyz, ids, spec, rule, execution);
  const auto simplifiedKeys = CloudKeyPoints(sxyz, sids, spec, rule, execution);
  result.OriginalKeyPoints = static_cast<Index>(originalKeys.size());
  result.SimplifiedKeyPoints = static_cast<Index>(simplifiedKeys.size());
  if (execution.Report(0.4))
  {
    result.Aborted = true;
    return result;
  }
  std::vector<Index> keyIds, simplifiedKeyIds;
  const std::vector<double> keyXyz = Flatten(originalKeys, keyIds);
  const std::vector<double> simplifiedKeyXyz = Flatten(simplifiedKeys, simplifiedKeyIds);
  const Neighbors simplifiedTree(sxyz, sids, execution);
  const Neighbors simplifiedKeyTree(simplifiedKeyXyz.data(), simplifiedKeyIds, execution);
  std::vector<double> keyErrors = NearestDistances(keyXyz.data(), keyIds,
    simplifiedKeys.empty() ? simplifiedTree : simplifiedKeyTree, execution);
  if (options.Measure == KeyPointDistance::Squared)
  {
    for (double& e : keyErrors)
    {
      e *= e;
    }
  }
  const DistanceSummary keySummary = Summarize(keyErrors);
  result.AKPE = keySummary.Mean;
  result.MKPE = keySummary.Max;
  if (execution.Report(0.5))
  {
    result.Aborted = true;
    return result;
  }

  // Nearest-neighbour distances both ways (the Hausdorff distance), and
  // point-to-plane: original points to the simplified surface, and each
  // simplified point's distance to the original surface; each direction in
  // one pass of k-nearest queries.
  std::vector<double> plane, nearest;
  SurfaceDistances(xyz, ids, sxyz, simplifiedTree, options.PlaneNeighbors, &plane, &nearest, execution);
  result.PointToPlane = Summarize(plane);
  result.OriginalToSimplified = Summarize(nearest);
  if (execution.Report(0.8))
  {
    result.Aborted = true;
    return result;
  }
  SurfaceDistances(sxyz, sids, xyz, originalTree, options.PlaneNeighbors, &result.SimplifiedError,
    &nearest, execution);
  result.SimplifiedToOriginal = Summarize(nearest);
  result.Hausdorff = std::max(result.OriginalToSimplified.Max, result.SimplifiedToOriginal.Max);
  execution.Report(1.0);
  return result;
}
} // namespace asmcore
