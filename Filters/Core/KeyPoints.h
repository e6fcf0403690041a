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
#include "PlaneClusters.h"

#include <cfloat>

namespace asmcore
{
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

/// Partition q with alpha, cluster the top and bottom bands, and, when
/// ErrorTolerance > 0, shrink alpha (alpha <- alpha * eps / MKPE_c, the
/// translation-invariant Eq. 5) until every key cluster's representative is
/// within the tolerance of its extreme point. MKPE_c is taken over every key
/// cluster (the paper's global max and min included), so the bound holds for
/// each key point. Each step shrinks alpha by at least 10 %, and the last of
/// at most 100 passes uses alpha = 0, where a band holds only the points at
/// the extreme itself: the bound is met unless several points tie there.
VTKASMFILTERS_EXPORT KeyClusters FindKeyClusters(
  const LocalPoints& q, const KeyPointOptions& options);
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
/// (q[i] for points[i]). A cell whose extent along v2 is within the rounding
/// of its coordinates (CoordinateEpsilon) and of its PCA is flat.
VTKASMFILTERS_EXPORT KeyClusters FindCellKeyClusters(
  Coordinates xyz, IdView points, const CellFrame& frame, const KeyPointRule& rule, LocalPoints& q);
} // namespace asmcore

#endif
