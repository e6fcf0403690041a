// SPDX-License-Identifier: BSD-3-Clause
/**
 * Clusters of a cell's points in the plane of its first two PCA axes (u0,
 * u1): single linkage for the key clusters of the top and bottom bands
 * (LinkInPlane), recursive median splits for the middle band (SplitInPlane),
 * and a cluster's representative.
 *
 * q[i] holds the coordinates (u0, u1, u2) of a cell's i-th point along (v0,
 * v1, v2) (KeyPoints.h).
 */
#ifndef asm_core_PlaneClusters_h
#define asm_core_PlaneClusters_h

#include "Common.h"

#include <Eigen/Core>

#include <vector>

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
/// components of the graph linking points at most `linkDistance` apart in
/// that plane (single linkage). Clusters are ordered by their first member in
/// `subset`. linkDistance <= 0 puts every point in one cluster.
VTKASMFILTERS_EXPORT Clusters LinkInPlane(
  const LocalPoints& q, const std::vector<Index>& subset, double linkDistance);

/// Split `subset` (reordered in place) into exactly k >= 1 non-empty,
/// spatially coherent clusters in the (u0, u1) plane by recursive median
/// splits along the axis of larger extent (ties by index), appended to
/// `out` left half first. Each cluster lists its members in the order they
/// come in `subset`. Requires k <= subset.size().
VTKASMFILTERS_EXPORT void SplitInPlane(
  const LocalPoints& q, Index* first, Index* last, Index k, Clusters& out);

/// Typical spacing-based link distance: `factor` times the mean point spacing
/// of n points spread over the (u0, u1) extent of q.
VTKASMFILTERS_EXPORT double PlaneLinkDistance(const LocalPoints& q, double factor);
} // namespace asmcore

#endif
