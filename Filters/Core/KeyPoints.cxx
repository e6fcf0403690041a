// SPDX-License-Identifier: BSD-3-Clause
#include "KeyPoints.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace asmcore
{
namespace
{
// Partition into bands and cluster the top and bottom ones.
void PartitionAndCluster(const LocalPoints& q, double alpha, double maxV2, double minV2,
  double linkDistance, KeyClusters& result)
{
  const double range = maxV2 - minV2;
  const double topPlane = maxV2 - alpha * range;
  const double bottomPlane = minV2 + alpha * range;
  std::vector<Index> top, bottom;
  result.Middle.clear();
  for (Index i = 0; i < static_cast<Index>(q.size()); ++i)
  {
    const double v = q[i][2];
    if (v >= topPlane)
    {
      top.push_back(i);
    }
    else if (v <= bottomPlane)
    {
      bottom.push_back(i);
    }
    else
    {
      result.Middle.push_back(i);
    }
  }
  result.Key = LinkInPlane(q, top, linkDistance);
  result.NumberOfTop = result.Key.Size();
  const Clusters low = LinkInPlane(q, bottom, linkDistance);
  for (Index k = 0; k < low.Size(); ++k)
  {
    result.Key.Add(low.Begin(k), low.End(k));
  }
  result.Extreme.assign(static_cast<std::size_t>(result.Key.Size()), -1);
  for (Index k = 0; k < result.Key.Size(); ++k)
  {
    const double sign = k < result.NumberOfTop ? 1.0 : -1.0;
    Index best = -1;
    for (const Index* it = result.Key.Begin(k); it != result.Key.End(k); ++it)
    {
      if (best < 0 || sign * q[*it][2] > sign * q[best][2] ||
        (q[*it][2] == q[best][2] && *it < best))
      {
        best = *it;
      }
    }
    result.Extreme[k] = best;
  }
}

// The v2 extent below which a cell is flat: what rounding alone can give an
// exactly planar cell.
// - The input coordinates: rounding moves a point by at most sqrt(3)/2 ulp
//   <= 0.87 eps |p| along the normal, so the extent stays below 1.75 eps |p|,
//   |p| <= |centroid| + 4 sqrt(lambda0): 2 eps |p| leaves georeferenced float
//   clouds (1 m rounding at 1e7 m) their key points.
// - The PCA (in double): its normal is off by ~eps (lambda0 / lambda0) towards
//   v0 and ~eps (lambda0 / lambda1) towards v1, which tilts points
//   sqrt(lambda0) and sqrt(lambda1) away: an extent of about
//   eps (sqrt(lambda0) + lambda0 / sqrt(lambda1)). Measured on tilted planar
//   lattices and random planar cells (sizes 1e-3..1e4, aspect ratios 1..1000,
//   about the origin, where the first term vanishes): at most 15 times that;
//   64 times leaves a margin. A line-like cell (lambda1 = 0) is flat.
double FlatTolerance(const CellFrame& frame, double coordinateEpsilon)
{
  const double coordinates = 2.0 * coordinateEpsilon *
    (frame.Centroid.cwiseAbs().maxCoeff() + 4.0 * std::sqrt(frame.Lambda[0]));
  if (!(frame.Lambda[1] > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  const double pca = 64.0 * std::numeric_limits<double>::epsilon() *
    (std::sqrt(frame.Lambda[0]) + frame.Lambda[0] / std::sqrt(frame.Lambda[1]));
  return coordinates + pca;
}
} // namespace

KeyClusters FindKeyClusters(const LocalPoints& q, const KeyPointOptions& options)
{
  KeyClusters result;
  result.Alpha = std::min(0.5, std::max(0.0, options.Alpha));
  if (q.empty())
  {
    return result;
  }
  double maxV2 = q[0][2], minV2 = q[0][2];
  for (const auto& p : q)
  {
    maxV2 = std::max(maxV2, p[2]);
    minV2 = std::min(minV2, p[2]);
  }
  if (!(maxV2 - minV2 > options.FlatTolerance))
  {
    // No relief along the normal: no extremes to keep.
    result.Flat = true;
    result.Middle.resize(q.size());
    std::iota(result.Middle.begin(), result.Middle.end(), Index(0));
    return result;
  }
  const int maxIterations = 100;
  for (;;)
  {
    PartitionAndCluster(q, result.Alpha, maxV2, minV2, options.LinkDistance, result);
    ++result.Iterations;
    result.MaxError = 0.0;
    for (Index k = 0; k < result.Key.Size(); ++k)
    {
      const Eigen::Vector3d rep =
        Representative(q, result.Key.Begin(k), result.Key.End(k), options.Snap);
      result.MaxError = std::max(result.MaxError, (rep - q[result.Extreme[k]]).norm());
    }
    if (options.ErrorTolerance <= 0.0 || result.MaxError <= options.ErrorTolerance ||
      result.Alpha <= 0.0 || result.Iterations >= maxIterations)
    {
      break;
    }
    // Eq. 5 in a frame where MAX_v2 = 0: alpha_new = alpha * eps / MKPE_c.
    // At least a 10 % step: a snapped key point's error moves in jumps, and
    // an error just above eps would otherwise shrink alpha too slowly. The
    // last pass uses alpha = 0, where each band is its extreme point alone.
    result.Alpha *= std::min(0.9, options.ErrorTolerance / result.MaxError);
    if (result.Alpha < 1e-12 || result.Iterations + 1 >= maxIterations)
    {
      result.Alpha = 0.0;
    }
  }
  return result;
}

KeyClusters FindCellKeyClusters(
  Coordinates xyz, IdView points, const CellFrame& frame, const KeyPointRule& rule, LocalPoints& q)
{
  const auto n = static_cast<Index>(points.size());
  q.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i)
  {
    double p[3];
    xyz.Get(points[i], p);
    q[i] = frame.ToLocal(p);
  }
  KeyPointOptions options;
  options.Alpha = rule.Alpha;
  options.ErrorTolerance = rule.ErrorTolerance;
  options.LinkDistance = PlaneLinkDistance(q, rule.LinkFactor);
  options.FlatTolerance = FlatTolerance(frame, rule.CoordinateEpsilon);
  options.Snap = rule.Snap;
  return FindKeyClusters(q, options);
}
} // namespace asmcore
