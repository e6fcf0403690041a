// SPDX-License-Identifier: BSD-3-Clause
/**
 * Key points (paper §3.2 steps v-vi and §3.5): the alpha partition of a
 * cell's points along v2, the separate clusters of the top and bottom bands
 * in the (v0, v1) plane, the clustering of the middle band, and the
 * adaptation of alpha to an error tolerance on MKPE (Eq. 5).
 *
 * Everything here works on a cell's points in its PCA frame: q[i] holds the
 * coordinates (u0, u1, u2) of the cell's i-th point along (v0, v1, v2).
 */
#ifndef asm_core_KeyPoints_h
#define asm_core_KeyPoints_h

#include "CellFrame.h"
#include "Common.h"

#include <Eigen/Core>

#include <cfloat>

namespace asmcore
{
using LocalPoints = std::vector<Eigen::Vector3d>;

/// A list of clusters, each a list of indices into a LocalPoints.
struct VTKASMFILTERS_EXPORT Clusters
{
  std::vector<Index> Members;
  std::vector<Index> Offsets = { 0 }; ///< cluster k is Members[Offsets[k], Offsets[k+1])

  Index Size() const { return static_cast<Index>(this->Offsets.size()) - 1; }
  Index CountOf(Index k) const { return this->Offsets[k + 1] - this->Offsets[k]; }
  const Index* Begin(Index k) const { return this->Members.data() + this->Offsets[k]; }
  const Index* End(Index k) const { return this->Members.data() + this->Offsets[k + 1]; }
  void Clear()
  {
    this->Members.clear();
    this->Offsets.assign(1, 0);
  }
  template <typename It>
  void Add(It first, It last)
  {
    this->Members.insert(this->Members.end(), first, last);
    this->Offsets.push_back(static_cast<Index>(this->Members.size()));
  }
};

/// Centroid of q[members[i]].
VTKASMFILTERS_EXPORT Eigen::Vector3d Centroid(
  const LocalPoints& q, const Index* first, const Index* last);

/// The member nearest `target` (ties: the lower index).
VTKASMFILTERS_EXPORT Index NearestMember(
  const LocalPoints& q, const Index* first, const Index* last, const Eigen::Vector3d& target);

/// Where a cluster is represented: its centroid, or the member nearest the
/// centroid when `snap` is set.
VTKASMFILTERS_EXPORT Eigen::Vector3d Representative(
  const LocalPoints& q, const Index* first, const Index* last, bool snap);

/// Separate clusters of `subset` in the (u0, u1) plane: the connected
/// components of the graph linking points closer than `linkDistance` in that
/// plane (single linkage). Clusters are ordered by their first member in
/// `subset`. linkDistance <= 0 puts every point in one cluster.
VTKASMFILTERS_EXPORT Clusters LinkInPlane(
  const LocalPoints& q, const std::vector<Index>& subset, double linkDistance);

/// Split `subset` (reordered in place) into exactly k >= 1 non-empty,
/// spatially coherent clusters in the (u0, u1) plane by recursive median
/// splits along the axis of larger extent, appended to `out`. Requires
/// k <= subset.size().
VTKASMFILTERS_EXPORT void SplitInPlane(
  const LocalPoints& q, Index* first, Index* last, Index k, Clusters& out);

/// Parameters of the key point search in one cell.
struct VTKASMFILTERS_EXPORT KeyPointOptions
{
  double Alpha = 0.125;        ///< partition threshold, fraction of the v2 extent, [0, 1/2]
  double ErrorTolerance = 0.0; ///< bound on each key point's error (length); <= 0: off
  double LinkDistance = 0.0;   ///< single-linkage distance for key clusters (length)
  double FlatTolerance = 0.0;  ///< a v2 extent <= this is a flat cell: no key points
  bool Snap = false;           ///< key points are snapped to input points
};

/// The key clusters of one cell.
struct VTKASMFILTERS_EXPORT KeyClusters
{
  Clusters Key;               ///< top-band clusters first, then bottom-band clusters
  Index NumberOfTop = 0;      ///< how many of Key are top-band clusters
  std::vector<Index> Extreme; ///< per key cluster: its extreme point along v2
  std::vector<Index> Middle;  ///< the middle band
  double Alpha = 0.0;         ///< alpha used (after adaptation)
  double MaxError = 0.0;      ///< max over key clusters of |representative - extreme|
  int Iterations = 0;         ///< partitions computed (1 without adaptation)
  bool Flat = false;          ///< the cell had no extent along v2
};

/// Typical spacing-based link distance: `factor` times the mean point spacing
/// of n points spread over the (u0, u1) extent of q.
VTKASMFILTERS_EXPORT double PlaneLinkDistance(const LocalPoints& q, double factor);

/// Partition q with alpha, cluster the top and bottom bands, and, when
/// ErrorTolerance > 0, shrink alpha (alpha <- alpha * eps / MKPE_c, the
/// translation-invariant Eq. 5) until every key cluster's representative is
/// within the tolerance of its extreme point. MKPE_c is taken over every key
/// cluster (the paper's global max and min included), so the bound holds for
/// each key point. Each step shrinks alpha by at least 10 %, and the last of
/// at most 100 passes uses alpha = 0, where a band holds only the points at
/// the extreme itself: the bound is met unless several points tie there.
VTKASMFILTERS_EXPORT KeyClusters FindKeyClusters(const LocalPoints& q, const KeyPointOptions& options);
/// The key point rule shared by every filter that looks for key points (the
/// simplifier and the key point error), so both see the same key points.
struct VTKASMFILTERS_EXPORT KeyPointRule
{
  double Alpha = 0.125;                   ///< partition threshold, fraction of the v2 extent
  double ErrorTolerance = 0.0;            ///< bound on each key point's error (length); <= 0: off
  double LinkFactor = 2.0;                ///< key-cluster link distance, in mean point spacings
  double CoordinateEpsilon = DBL_EPSILON; ///< relative precision of the input coordinates
  bool Snap = false;                      ///< key points are snapped to input points
};

/// The key clusters of one grid cell holding the points xyz[points[i]],
/// i < points.size(), whose PCA frame is `frame`. Fills `q` with the points in the frame
/// (q[i] for points[i]). A cell whose extent along v2 is within rounding of
/// its coordinates (CoordinateEpsilon) is flat.
VTKASMFILTERS_EXPORT KeyClusters FindCellKeyClusters(Coordinates xyz, IdView points,
  const CellFrame& frame, const KeyPointRule& rule, LocalPoints& q);
} // namespace asmcore

#endif
