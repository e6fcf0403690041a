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

namespace asmcore
{
/// For every point (slot i of grid.Order): the nearest sample owned by its
/// cell or a neighbouring one (ties: lower sample index), and the squared
/// distance. -1 / infinity when none of those cells owns a sample.
VTKASMFILTERS_EXPORT void AssignToSamples(const double* xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const SampleSet& samples, PointArray<SampleId>& assign,
  PointArray<double>& distance2, const Execution& execution);

/// AssignToSamples after a few samples moved (FillHoles): `assign` and
/// `distance2` hold the assignment before, to samples numbered as before
/// (previous[new slot] = old slot, a permutation that keeps the order of the
/// samples that did not move), and `moved` flags the samples (new slots)
/// whose position or owner cell changed. Gives exactly what AssignToSamples
/// gives (the nearest ring sample, ties: the lower index), but only the
/// points whose sample moved are searched again; the others only compare
/// with the moved samples of their ring. The points of a cell owning more
/// than LargeCellBudget samples are searched again (with a k-d tree).
VTKASMFILTERS_EXPORT void UpdateAssignment(const double* xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const SampleSet& samples, const std::vector<Index>& previous,
  const std::vector<char>& moved, PointArray<SampleId>& assign, PointArray<double>& distance2,
  const Execution& execution);
} // namespace asmcore

#endif
