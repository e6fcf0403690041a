// SPDX-License-Identifier: BSD-3-Clause
#include "FeatureKeyPoints.h"

#include <algorithm>
#include <cmath>

namespace asmcore
{
namespace
{
// For each octant of a direction d (bit a set: d[a] > 0), the 27 entries of
// a cell's ring in the order Lemma 2's test visits them: the 7 neighbours of
// that octant (faces, then edges, then the corner), the other 19 in table
// order, the cell itself (entry 13) last.
struct NeighbourOrders
{
  int Order[8][27];
  NeighbourOrders()
  {
    for (int octant = 0; octant < 8; ++octant)
    {
      int m = 0;
      bool taken[27] = {};
      for (int moved = 1; moved <= 3; ++moved)
      {
        for (int k = 0; k < 27; ++k)
        {
          const int o[3] = { k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1 };
          int count = 0;
          bool inside = true;
          for (int a = 0; a < 3; ++a)
          {
            count += o[a] != 0;
            inside = inside && (o[a] == 0 || (o[a] > 0) == (((octant >> a) & 1) != 0));
          }
          if (inside && count == moved)
          {
            this->Order[octant][m++] = k;
            taken[k] = true;
          }
        }
      }
      for (int k = 0; k < 27; ++k)
      {
        if (!taken[k] && k != 13)
        {
          this->Order[octant][m++] = k;
        }
      }
      this->Order[octant][m] = 13;
    }
  }
};

const int* NeighbourOrder(const double d[3])
{
  static const NeighbourOrders orders;
  return orders.Order[(d[0] > 0.0) | ((d[1] > 0.0) << 1) | ((d[2] > 0.0) << 2)];
}
} // namespace

bool IsLocalExtreme(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  Index c, Index id, const double d[3], double radius, double& prominence)
{
  double p[3];
  xyz.Get(id, p);
  const double r = std::min(radius, grid.Spec.CellSize);
  const double r2 = r * r;
  const double height = d[0] * p[0] + d[1] * p[1] + d[2] * p[2];
  double sum = 0.0;
  Index count = 0;
  const CellRef* ring = neighbors.Of(c);
  // The neighbours first, those ahead along d before the others, the own
  // cell (where the candidate is the extreme already) last: grid-cut
  // candidates fall quickly.
  const int* visit = NeighbourOrder(d);
  for (int step = 0; step < 27; ++step)
  {
    const int k = visit[step];
    const Index n = ring[k];
    if (n < 0 || (k != 13 && SquaredDistanceToCell(grid.Spec, grid.CellKey[n], p) > r2))
    {
      continue;
    }
    const Index end = grid.CellStart[n + 1];
    for (Index slot = grid.CellStart[n]; slot < end; ++slot)
    {
      double x[3];
      xyz.Get(grid.PointAt(slot), x);
      const double dx = x[0] - p[0], dy = x[1] - p[1], dz = x[2] - p[2];
      if (dx * dx + dy * dy + dz * dz > r2)
      {
        continue;
      }
      const double h = d[0] * x[0] + d[1] * x[1] + d[2] * x[2];
      if (h > height)
      {
        return false;
      }
      sum += h;
      ++count;
    }
  }
  prominence = count > 0 ? height - sum / static_cast<double>(count) : 0.0;
  return true;
}

bool IsSparseCellTip(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  Index c, Index id, double radius, double& prominence)
{
  // The direction away from the centroid of the other points within the radius.
  double p[3];
  xyz.Get(id, p);
  const double r = std::min(radius, grid.Spec.CellSize);
  double mean[3] = { 0.0, 0.0, 0.0 };
  Index count = 0;
  for (int k = 0; k < 27; ++k)
  {
    const Index nb = neighbors.Of(c)[k];
    if (nb < 0 || (k != 13 && SquaredDistanceToCell(grid.Spec, grid.CellKey[nb], p) > r * r))
    {
      continue;
    }
    for (Index slot = grid.CellStart[nb]; slot < grid.CellStart[nb + 1]; ++slot)
    {
      double x[3];
      xyz.Get(grid.PointAt(slot), x);
      const double dx = x[0] - p[0], dy = x[1] - p[1], dz = x[2] - p[2];
      if (grid.PointAt(slot) != id && dx * dx + dy * dy + dz * dz <= r * r)
      {
        mean[0] += dx;
        mean[1] += dy;
        mean[2] += dz;
        ++count;
      }
    }
  }
  const double length = std::sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]);
  if (count < 2 || !(length > 0.0))
  {
    return false; // alone or with one neighbour: no direction to stand out along
  }
  const double d[3] = { -mean[0] / length, -mean[1] / length, -mean[2] / length };
  return IsLocalExtreme(xyz, grid, neighbors, c, id, d, radius, prominence);
}

std::vector<FeatureKey> FindFeatureKeys(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const CellFrame& frame, Index c,
  const FeatureKeyOptions& options, LocalPoints& q)
{
  std::vector<FeatureKey> keys;
  const IdView points = grid.CellIds(c);
  const Index n = grid.CellSizeOf(c);
  if (n < 3)
  {
    // Too few points for a frame: coverage gives the cell a sample; with
    // SparseCells (and the in-plane extremes, tips), a point that stands out
    // from its neighbourhood (a spike tip alone in its cell) is a key point.
    if (options.SparseCells && options.Validate && options.InPlaneExtremes)
    {
      for (Index i = 0; i < n; ++i)
      {
        FeatureKey key;
        if (IsSparseCellTip(xyz, grid, neighbors, c, points[i], options.Radius, key.Prominence) &&
          key.Prominence > options.MinimumProminence)
        {
          key.Point = points[i];
          xyz.Get(points[i], key.Position);
          keys.push_back(key);
        }
      }
      std::sort(keys.begin(), keys.end(), [](const FeatureKey& a, const FeatureKey& b) {
        return a.Prominence > b.Prominence || (a.Prominence == b.Prominence && a.Point < b.Point);
      });
    }
    return keys;
  }
  const KeyClusters kc = FindCellKeyClusters(xyz, points, frame, options.Rule, q);
  if (kc.Flat)
  {
    return keys;
  }
  auto consider = [&](Index local, const Eigen::Vector3d& direction,
                    const Eigen::Vector3d* centroid) {
    const Index id = points[local];
    for (const FeatureKey& k : keys)
    {
      if (k.Point == id)
      {
        return;
      }
    }
    FeatureKey key;
    key.Point = id;
    const double d[3] = { direction[0], direction[1], direction[2] };
    if (options.Validate)
    {
      if (!IsLocalExtreme(xyz, grid, neighbors, c, id, d, options.Radius, key.Prominence) ||
        !(key.Prominence > options.MinimumProminence))
      {
        return;
      }
    }
    else
    {
      key.Prominence = direction.dot(frame.Axes * q[local]);
    }
    if (centroid && !options.ExtremeRepresentative)
    {
      const Eigen::Vector3d world = frame.Centroid + frame.Axes * (*centroid);
      for (int a = 0; a < 3; ++a)
      {
        key.Position[a] = world[a];
      }
      key.Error = (*centroid - q[local]).norm();
    }
    else
    {
      xyz.Get(id, key.Position);
    }
    keys.push_back(key);
  };
  // +-v2: the extreme point of every band cluster.
  for (Index k = 0; k < kc.Key.Size(); ++k)
  {
    const Eigen::Vector3d dir = (k < kc.NumberOfTop ? 1.0 : -1.0) * frame.Axes.col(2);
    const Eigen::Vector3d local = options.Rule.Snap
      ? Representative(q, kc.Key.Begin(k), kc.Key.End(k), true)
      : Centroid(q, kc.Key.Begin(k), kc.Key.End(k));
    consider(kc.Extreme[k], dir, &local);
  }
  // +-v0, +-v1 (tips, scan borders) and the eight diagonals +-v0 +-v1 +-v2
  // (corners, whatever their orientation in the frame): the cell's extreme
  // point along each.
  if (options.InPlaneExtremes)
  {
    static const double directions[12][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 },
      { 1, 1, 1 }, { 1, 1, -1 }, { 1, -1, 1 }, { 1, -1, -1 }, { -1, 1, 1 }, { -1, 1, -1 },
      { -1, -1, 1 }, { -1, -1, -1 } };
    for (const auto& dir : directions)
    {
      const Eigen::Vector3d local = Eigen::Vector3d(dir[0], dir[1], dir[2]).normalized();
      Index best = 0;
      double bestH = local.dot(q[0]);
      for (Index i = 1; i < n; ++i)
      {
        const double h = local.dot(q[i]);
        if (h > bestH)
        {
          bestH = h;
          best = i;
        }
      }
      consider(best, frame.Axes * local, nullptr);
    }
  }
  std::sort(keys.begin(), keys.end(), [](const FeatureKey& a, const FeatureKey& b) {
    return a.Prominence > b.Prominence || (a.Prominence == b.Prominence && a.Point < b.Point);
  });
  return keys;
}
} // namespace asmcore
