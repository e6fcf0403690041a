// SPDX-License-Identifier: BSD-3-Clause
/**
 * Bounded hole filling for the feature-preserving mode: move the samples
 * whose removal costs least into the largest gaps of the sampling.
 *
 * The largest hole of a sampling is the input point farthest from every
 * sample. A gap is such a point (one per gap: gap points closer to each other
 * than their own gap distance count once). Removing a free sample s leaves
 * its cluster to the other samples: its cost is the largest distance from a
 * member of s to the nearest other sample. The cheapest samples move to the
 * largest gaps while the cost is below the gap, each move blocking the
 * samples that took over the moved one's members.
 *
 * The ranking is global (all samples and points of the cloud). A distributed
 * run takes part through a HoleFillScope: each process ranks the samples and
 * points of its own cells and computes its candidates' removal costs, the
 * rankings and costs are gathered, and every process makes the same moves
 * (those of a one-process run) and applies them to the cells it holds.
 */
#ifndef asm_core_HoleFilling_h
#define asm_core_HoleFilling_h

#include "Assignment.h"

#include <functional>

namespace asmcore
{
/// A distributed run's part in FillHoles (default: a serial run, every cell
/// this run's own and nothing to gather).
struct VTKASMFILTERS_EXPORT HoleFillScope
{
  /// Per cell of the grid: 1 for the cells this process ranks (its output
  /// cells), 0 for halo cells. Empty: every cell.
  std::vector<char> Owned;
  /// Collective: replaces `values` by every process's `values`, concatenated
  /// in process order. Empty: one process.
  std::function<void(std::vector<double>& values)> Gather;
  /// The number of samples of the whole cloud (the candidates are at most
  /// 8 per move and at most all of them); -1: this run's.
  Index TotalSamples = -1;
};

/// Moves at most `maxMoves` free samples of `samples` to gap points, given
/// the current assignment (AssignToSamples). A moved sample changes owner
/// cell and the set is regrouped by owner: order[new slot] = old slot (-1
/// for a sample that arrived from a cell this run does not hold: a position,
/// not fixed), and moved[new slot] is 1 for a sample moved to a gap, 0 for
/// the others (which keep their cell and position). A sample that moved to a
/// cell this run does not hold leaves the set. Returns the number of moves
/// (of the whole cloud). The removal costs are computed ahead in parallel
/// batches of candidates, `firstBatch` first, doubling up to 1024 (1: one at
/// a time, each at its turn, as a serial scan); the result does not depend
/// on it, nor on how a scope splits the cells.
VTKASMFILTERS_EXPORT Index FillHoles(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const PointArray<SampleId>& assign, Index maxMoves,
  SampleSet& samples, std::vector<Index>& order, std::vector<char>& moved,
  const Execution& execution, Index firstBatch = 32, const HoleFillScope& scope = {});
} // namespace asmcore

#endif
