// SPDX-License-Identifier: BSD-3-Clause
/**
 * The nearest-sample assignment of the feature-preserving mode: every point
 * joins the nearest sample owned by its own or a neighbouring cell (Lloyd.h).
 * A full pass (AssignToSamples) after steps that move every sample, an
 * incremental one (UpdateAssignment) after hole filling moved a few.
 *
 * Each cell writes the slots of its own points only, from its ring's samples:
 * the result does not depend on the thread count.
 */
#ifndef asm_core_Assignment_h
#define asm_core_Assignment_h

#include "Lloyd.h"

#include <limits>

namespace asmcore
{
/// For every point (slot i of grid.Order): the nearest sample owned by its
/// cell or a neighbouring one (ties: lower sample index); -1 when none of
/// those cells owns a sample. The squared distance the search compared is
/// AssignedDistance2 (recomputed where it is needed: no array of 8 bytes per
/// point).
/// With `scale` (one factor >= 1 per sample), the distance compared is
/// scale[s] * |p - s|^2 (a multiplicatively weighted Voronoi partition:
/// a sample of larger scale takes a smaller cluster).
VTKASMFILTERS_EXPORT void AssignToSamples(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const SampleSet& samples, PointArray<SampleId>& assign,
  const Execution& execution, const double* scale = nullptr);

/// The squared distance from the point in slot i to its sample (infinity
/// without one), bit for bit the value the assignment compared, as long as
/// that sample has not moved since.
inline double AssignedDistance2(Coordinates xyz, const CellGrid& grid, const SampleSet& samples,
  const PointArray<SampleId>& assign, Index i)
{
  return assign[i] < 0
    ? std::numeric_limits<double>::infinity()
    : SquaredDistance(xyz.At(grid.PointAt(i)).data(), samples.Position.data() + 3 * assign[i]);
}

/// AssignToSamples after a few samples moved (FillHoles): `assign` holds
/// the assignment before, to samples numbered as before (previous[new slot]
/// = old slot, keeping the order of the samples that did not move; -1 for a
/// sample that was not in the set; `previousCount` samples before, -1: as
/// many as now), and `moved` flags the samples (new slots) whose position or
/// owner cell changed (every sample with no old slot). Gives exactly what
/// AssignToSamples gives (the nearest ring sample, ties: the lower index),
/// but only the points whose sample moved or left are searched again; the
/// others only compare with the moved samples of their ring. The points of a cell owning more than
/// LargeCellBudget samples are searched again (with a k-d tree).
VTKASMFILTERS_EXPORT void UpdateAssignment(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const SampleSet& samples, const std::vector<Index>& previous,
  const std::vector<char>& moved, PointArray<SampleId>& assign, const Execution& execution,
  Index previousCount = -1);
} // namespace asmcore

#endif
