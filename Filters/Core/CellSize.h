// SPDX-License-Identifier: BSD-3-Clause
/**
 * The automatic cell size (paper §3.5 step 1 leaves it open; ASM-spec.md):
 * the cell edge for which about a target number of grid cells is non-empty,
 * searched in log(cell size) with the measured occupancy, first on a
 * subsample picked by the points' coordinates (so that serial and
 * distributed runs pick the same points), then on all points.
 */
#ifndef asm_core_CellSize_h
#define asm_core_CellSize_h

#include "Grid.h"

#include <functional>

namespace asmcore
{
/// The cell edge for which about `targetCells` cells are non-empty. Searches
/// in log(cell size) with the measured occupancy: first on CellSizeSubsample
/// (about 32 points per target cell), then from there on all points, usually
/// in one or two passes. When sparse cells (far outliers) make up a fifth of the
/// count, searches again counting each cell by its share of a sample.
VTKASMFILTERS_EXPORT double AutomaticCellSize(Coordinates xyz, IdView ids, const Bounds& bounds,
  double targetCells, const Execution& execution = {});

/// BuildCellGrid with the cell size of AutomaticCellSize, searched and built
/// in one go (the grid of the search's last count is reused when it is the
/// answer).
VTKASMFILTERS_EXPORT CellGrid BuildAutomaticCellGrid(Coordinates xyz, IdView ids,
  const Bounds& bounds, double targetCells, const Execution& execution = {});

/// The same search with the occupancy counted by `countOccupied` (e.g. the
/// distinct non-empty cells over all processes of a distributed run),
/// starting from `start` (> 0; e.g. the search on CellSizeSubsample) or from
/// the guess that the points sample a surface (0). The sparse-cell search of
/// the overload above is the caller's (the same search, with counts of
/// EffectiveOccupiedCells).
VTKASMFILTERS_EXPORT double AutomaticCellSize(const Bounds& bounds, double targetCells, bool empty,
  const std::function<double(const GridSpec&)>& countOccupied, double start = 0.0);

/// The outlier-robust occupancy of the search: a non-empty cell with fewer
/// than SparseCellPoints(total points, targetCells) points (less than one
/// sample's worth at 8 samples per target cell: a far outlier, a stray
/// point) counts by its share, SparseCellShare; when such cells make up a
/// fifth of the count (SparseCellsDominate), they would drive the cell size
/// of the whole cloud, and the size is searched again on these counts.
/// The shares are summed in fixed point (ExactMean), so a distributed run,
/// which sums each cell's points over the processes, counts exactly as a
/// serial one.
VTKASMFILTERS_EXPORT double SparseCellPoints(Index points, double targetCells);
VTKASMFILTERS_EXPORT double SparseCellShare(Index points, double minPoints);
VTKASMFILTERS_EXPORT bool SparseCellsDominate(double effective, double raw);
/// The non-empty cells of `spec`, each counted by SparseCellShare.
VTKASMFILTERS_EXPORT double EffectiveOccupiedCells(
  Coordinates xyz, IdView ids, const GridSpec& spec, double minPoints);

/// The points the automatic cell size is first searched on (3 coordinates
/// each): about one in max(4, totalPoints / targetCells / 32), picked by a
/// hash of the point's coordinates, so that the same points are picked
/// whatever the order or the partition of the cloud over processes; empty
/// when totalPoints < 200000 (the search then runs on all points).
VTKASMFILTERS_EXPORT PointArray<double> CellSizeSubsample(Coordinates xyz, IdView ids,
  double totalPoints, double targetCells, const Execution& execution = {});
} // namespace asmcore

#endif
