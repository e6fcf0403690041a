// SPDX-License-Identifier: BSD-3-Clause
/**
 * Key points of the feature-preserving mode (see ASM-spec.md, "What the
 * literal reading measures, and what fixes it").
 *
 * Candidates, per cell: the extreme point of each top- and bottom-band
 * cluster along +-v2 (paper §3.2, bands and clusters as in KeyPoints.h), and,
 * when InPlaneExtremes is on, the cell's extreme points along +-v0 and +-v1
 * (spike tips, corners, scan borders, which the paper discards).
 *
 * Validation (the paper's Lemma 2 applied across cell borders): a candidate
 * extreme p along direction d is kept only when no input point within
 * `radius` of p, in its own cell or a neighbouring one, lies farther along d
 * (d.x > d.p), and that stands out from them: its prominence (d.p minus the
 * mean of d.x over those points) exceeds MinimumProminence, which drops
 * scanner noise and the tangent points of smooth curved patches (prominence
 * about curvature * radius^2 / 4). Where the grid cuts a smooth surface, the highest point of a
 * cell lies on a cell face and the next cell holds higher points: such
 * candidates are dropped. The radius is at most one cell edge, so the test
 * reads one ring of cells.
 */
#ifndef asm_core_FeatureKeyPoints_h
#define asm_core_FeatureKeyPoints_h

#include "CellFrame.h"
#include "CellNeighbors.h"
#include "KeyPoints.h"

namespace asmcore
{
/// One key point of a cell.
struct VTKASMFILTERS_EXPORT FeatureKey
{
  Index Point = -1;                 ///< the extreme input point (global id)
  double Position[3] = { 0, 0, 0 }; ///< where the key sample goes
  double Prominence = 0.0; ///< d.p - mean of d.x over the points within the radius (length)
  double Error = 0.0;      ///< |Position - extreme point|
};

/// Options of the key point search of the feature-preserving mode.
struct VTKASMFILTERS_EXPORT FeatureKeyOptions
{
  KeyPointRule Rule;                 ///< bands, link distance and Eq. 5 for the +-v2 candidates
  bool Validate = true;              ///< Lemma 2 across cell borders
  double Radius = 0.0;               ///< Lemma 2 radius (length, clamped to one cell edge)
  double MinimumProminence = 0.0;    ///< a validated key stands out by more than this (length)
  bool InPlaneExtremes = true;       ///< +-v0 and +-v1 extremes are candidates too
  bool ExtremeRepresentative = true; ///< a key sample is its extreme point, not the band centroid
  /// Cells of fewer than 3 points (no frame): a point that is the extreme
  /// away from the centroid of its neighbours within Radius is a key (with
  /// Validate and InPlaneExtremes)
  bool SparseCells = true;
};

/// The key points of cell c, ordered by decreasing prominence (ties: point
/// id). `q` is scratch space (the cell's points in its PCA frame).
VTKASMFILTERS_EXPORT std::vector<FeatureKey> FindFeatureKeys(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const CellFrame& frame, Index c,
  const FeatureKeyOptions& options, LocalPoints& q);

/// A tip alone in a cell too sparse for a frame: whether input point `id` of
/// cell c is the extreme (IsLocalExtreme) along the direction away from the
/// centroid of the other points within `radius` (at least two of them).
VTKASMFILTERS_EXPORT bool IsSparseCellTip(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, Index c, Index id, double radius, double& prominence);

/// Lemma 2 across cell borders: whether input point `id` of cell c is the
/// extreme along the unit vector d among all points within `radius` (at most
/// one cell edge); on success `prominence` is d.p minus the mean of d.x over
/// those points.
VTKASMFILTERS_EXPORT bool IsLocalExtreme(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, Index c, Index id, const double d[3], double radius,
  double& prominence);
} // namespace asmcore

#endif
