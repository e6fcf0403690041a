// SPDX-License-Identifier: BSD-3-Clause
#include "Metrics.h"

#include "BlockNeighbors.h"
#include "CanonicalOrder.h"
#include "CellFrame.h"
#include "CellSize.h"
#include "Neighbors.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

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

std::vector<Eigen::Vector3d> CloudKeyPoints(const double* xyz, IdView ids, const GridSpec& spec,
  const KeyPointRule& rule, const Execution& execution)
{
  const CellGrid grid = BuildCellGrid(xyz, ids, spec, execution);
  const Index cells = grid.NumberOfCells();
  std::vector<std::vector<Eigen::Vector3d>> perCell(static_cast<std::size_t>(cells));
  execution.Run(0, cells, [&](Index b, Index e) {
    LocalPoints q;
    CanonicalCell local; // (the simplifier's order: the same key points)
    for (Index c = b; c < e; ++c)
    {
      local.Gather(xyz, grid.CellIds(c));
      const IdView points = IdView::Identity(local.Ids.size());
      const CellFrame frame = ComputeCellFrame(local.Xyz.data(), points);
      const KeyClusters kc = FindCellKeyClusters(local.Xyz.data(), points, frame, rule, q);
      for (Index k = 0; k < kc.Key.Size(); ++k)
      {
        perCell[c].push_back(
          frame.Centroid + frame.Axes * Centroid(q, kc.Key.Begin(k), kc.Key.End(k)));
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
// A fitted plane: a point of it and its unit normal; Defined false when the
// points span no plane (see FitPlane).
struct Plane
{
  double Centroid[3];
  double Normal[3];
  bool Defined;
};

// The plane fitted (PCA) to `count` points side by side: through their
// centroid, normal to the eigenvector of their covariance's smallest
// eigenvalue, from Eigen's closed-form 3x3 solver (about half the time of
// the iterative one that ComputeCellFrame uses; the distances agree with
// the latter's to about 1e-12 of the cloud's extent). A covariance that
// overflows: ComputeCellFrame's identity frame (normal z).
//
// Points that span no plane leave the normal arbitrary (the solver's pick
// among equal eigenvalues: a distance along x for points at one position,
// which changed with a rotation of the data): they are not Defined when
// their spread across the largest axis (the square root of the middle
// eigenvalue, a Rayleigh quotient of the computed eigenvector, exact to a
// rounding of the largest one) is within 1e-6 of their spread along it, or
// within the rounding of their coordinates (relative precision `epsilon`:
// a float cloud's line is off its line by its roundings): a line
// (collinear points, or two positions), or one position (exact duplicates:
// a covariance of rank 1 at most, from the centroid's rounding, or 0).
Plane FitPlane(const double* xyz, std::size_t count, double epsilon)
{
  const double n = static_cast<double>(count);
  Plane plane;
  double* c = plane.Centroid;
  c[0] = c[1] = c[2] = 0.0;
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      c[a] += xyz[3 * i + a];
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    c[a] /= n;
  }
  // (The six sums in scalars: a 3x3 matrix summed in place stalls on its
  // partial stores.)
  double xx = 0.0, xy = 0.0, xz = 0.0, yy = 0.0, yz = 0.0, zz = 0.0;
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* x = xyz + 3 * i;
    const double dx = x[0] - c[0], dy = x[1] - c[1], dz = x[2] - c[2];
    xx += dx * dx;
    xy += dx * dy;
    xz += dx * dz;
    yy += dy * dy;
    yz += dy * dz;
    zz += dz * dz;
  }
  Eigen::Matrix3d cov;
  cov << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  cov /= n;
  Eigen::Vector3d normal(0.0, 0.0, 1.0);
  plane.Defined = true;
  if (cov.allFinite())
  {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(cov);
    const Eigen::Matrix3d& v = solver.eigenvectors();
    normal = v.col(0).normalized();
    const double largest = std::max(0.0, v.col(2).dot(cov * v.col(2)));
    const double middle = std::max(0.0, v.col(1).dot(cov * v.col(1)));
    const double magnitude = std::max({ std::abs(c[0]), std::abs(c[1]), std::abs(c[2]) });
    const double along = std::sqrt(largest);
    plane.Defined = std::sqrt(middle) > 1e-6 * along + 2.0 * epsilon * (magnitude + 4.0 * along);
  }
  CopyPoint(normal.data(), plane.Normal);
  return plane;
}

// The planes of one thread's recent neighbour sets. Consecutive queries of
// a block often have the same k nearest (at 5 %, 62 % of an original
// cloud's queries against its ASM simplification; 88 % at 1 %, 30 % at
// 20 %), and a plane depends on the set alone: it is fitted to the points
// in position order, whichever query comes first, so that a kept plane is
// the one a fit would give. Direct-mapped by a hash of the sorted ids;
// sets of more than MaxIds points, or with an id twice, are not kept.
class PlaneFits
{
public:
  /// `epsilon`: the relative precision of the surface's coordinates (FitPlane).
  explicit PlaneFits(double epsilon)
    : Epsilon(epsilon)
  {
  }
  /// The distance from the answer's query to its neighbours' plane; to the
  /// nearest of them when they span no plane (see FitPlane).
  double Distance(const KNearestAnswer& a)
  {
    const std::size_t n = a.Ids.size();
    // (An insertion sort by hand: std::sort shifts its few elements with
    // calls to memmove, which took a tenth of the run.)
    this->Sorted.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const Index id = a.Ids[i];
      std::size_t j = i;
      for (; j > 0 && this->Sorted[j - 1] > id; --j)
      {
        this->Sorted[j] = this->Sorted[j - 1];
      }
      this->Sorted[j] = id;
    }
    std::uint64_t hash = 0;
    for (Index id : this->Sorted)
    {
      hash = (hash ^ static_cast<std::uint64_t>(id)) * 0x9E3779B97F4A7C15ULL;
    }
    Entry& e = this->Table[(hash >> 32) % Slots];
    const bool keep = n <= MaxIds &&
      std::adjacent_find(this->Sorted.begin(), this->Sorted.end()) == this->Sorted.end();
    bool same = keep && e.Count == n;
    for (std::size_t i = 0; i < n && same; ++i)
    {
      same = e.Ids[i] == this->Sorted[i];
    }
    if (!same)
    {
      // The points in position order (ties: id), so that the plane does
      // not depend on the ids (the order a simplified cloud was gathered in).
      this->Order.resize(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        std::size_t j = i;
        for (; j > 0 && Before(a, i, this->Order[j - 1]); --j)
        {
          this->Order[j] = this->Order[j - 1];
        }
        this->Order[j] = i;
      }
      this->Xyz.resize(3 * n);
      for (std::size_t i = 0; i < n; ++i)
      {
        CopyPoint(a.Xyz + 3 * this->Order[i], this->Xyz.data() + 3 * i);
      }
      const Plane fit = FitPlane(this->Xyz.data(), n, this->Epsilon);
      if (!keep)
      {
        return DistanceTo(fit, a);
      }
      e.Count = n;
      for (std::size_t i = 0; i < n; ++i)
      {
        e.Ids[i] = this->Sorted[i];
      }
      e.Fit = fit;
    }
    return DistanceTo(e.Fit, a);
  }

private:
  double Epsilon;
  static constexpr std::size_t MaxIds = 16;
  static constexpr std::size_t Slots = 1024;
  struct Entry
  {
    std::size_t Count = 0; // (0: empty)
    Index Ids[MaxIds];
    Plane Fit;
  };
  // Whether neighbour i of the answer comes before neighbour j.
  static bool Before(const KNearestAnswer& a, std::size_t i, std::size_t j)
  {
    return PositionThenIdBefore(a.Xyz + 3 * i, a.Ids[i], a.Xyz + 3 * j, a.Ids[j]);
  }
  static double DistanceTo(const Plane& plane, const KNearestAnswer& a)
  {
    if (!plane.Defined)
    {
      return std::sqrt(a.SqDist[0]);
    }
    const double* p = a.Point;
    return std::abs(plane.Normal[0] * (p[0] - plane.Centroid[0]) +
      plane.Normal[1] * (p[1] - plane.Centroid[1]) + plane.Normal[2] * (p[2] - plane.Centroid[2]));
  }
  std::vector<Entry> Table = std::vector<Entry>(Slots);
  std::vector<Index> Sorted;
  std::vector<std::size_t> Order;
  std::vector<double> Xyz;
};
} // namespace

void SurfaceDistances(const double* xyz, IdView ids, const Neighbors& surface, int k,
  std::vector<double>* plane, std::vector<double>* nearest, const Execution& execution,
  double surfaceEpsilon)
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
  // Only the nearest point when no plane is asked for.
  k = plane ? std::max(1, k) : 1;
  // (Each range of blocks with planes of its own.)
  auto makeVisit = [&]() -> KNearestVisit {
    return [&, fits = std::make_shared<PlaneFits>(surfaceEpsilon)](const KNearestAnswer& a) {
      if (nearest)
      {
        (*nearest)[a.Query] = std::sqrt(a.SqDist[0]);
      }
      if (plane)
      {
        (*plane)[a.Query] = a.Ids.size() < 3 ? std::sqrt(a.SqDist[0]) : fits->Distance(a);
      }
    };
  };
  ForEachKNearest(xyz, ids, surface, k, makeVisit, execution);
}

std::vector<double> NearestDistances(
  const double* xyz, IdView ids, const Neighbors& target, const Execution& execution)
{
  std::vector<double> d;
  SurfaceDistances(xyz, ids, target, 1, nullptr, &d, execution);
  return d;
}

std::vector<double> PointToPlaneDistances(
  const double* xyz, IdView ids, const Neighbors& surface, int k, const Execution& execution)
{
  std::vector<double> d;
  SurfaceDistances(xyz, ids, surface, k, &d, nullptr, execution);
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

Comparison CompareClouds(const double* xyz, IdView ids, const Neighbors& originalTree,
  const double* sxyz, const std::vector<Index>& sids, const ComparisonOptions& options,
  const Execution& execution)
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
  std::vector<double> keyErrors = NearestDistances(
    keyXyz.data(), keyIds, simplifiedKeys.empty() ? simplifiedTree : simplifiedKeyTree, execution);
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
  SurfaceDistances(xyz, ids, simplifiedTree, options.PlaneNeighbors, &plane, &nearest, execution,
    options.SurfaceEpsilon);
  result.PointToPlane = Summarize(plane);
  result.OriginalToSimplified = Summarize(nearest);
  if (execution.Report(0.8))
  {
    result.Aborted = true;
    return result;
  }
  SurfaceDistances(sxyz, sids, originalTree, options.PlaneNeighbors, &result.SimplifiedError,
    &nearest, execution, options.SurfaceEpsilon);
  result.SimplifiedToOriginal = Summarize(nearest);
  result.Hausdorff = std::max(result.OriginalToSimplified.Max, result.SimplifiedToOriginal.Max);
  execution.Report(1.0);
  return result;
}
} // namespace asmcore
