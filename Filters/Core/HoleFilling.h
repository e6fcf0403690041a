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
 * samples that took over the moved one's members. Global (it ranks all
 * samples and points), so not for distributed runs.
 */
#ifndef asm_core_HoleFilling_h
#define asm_core_HoleFilling_h

#include "Assignment.h"

namespace asmcore
{
/// Moves at most `maxMoves` free samples of `samples` to gap points, given
/// the current assignment (AssignToSamples). A moved sample changes owner
/// cell and the set is regrouped by owner: order[new slot] = old slot, and
/// moved[new slot] is 1 for a sample moved to a gap, 0 for the others (which
/// keep their cell and position). Returns the number of moves. The removal costs are computed ahead in
/// parallel batches of candidates, `firstBatch` first, doubling up to 1024
/// (1: one at a time, each at its turn, as a serial scan); the result does
/// not depend on it.
VTKASMFILTERS_EXPORT Index FillHoles(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const PointArray<SampleId>& assign, Index maxMoves,
  SampleSet& samples,
  std::vector<Index>& order, std::vector<char>& moved, const Execution& execution,
  Index firstBatch = 32);
} // namespace asmcore

#endif
