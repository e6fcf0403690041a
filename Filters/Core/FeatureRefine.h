// SPDX-License-Identifier: BSD-3-Clause
/**
 * Step 5 of the feature-preserving mode (FeatureSimplify.h): the samples
 * placed cell by cell are refined across cell borders. CrossCellIterations
 * Lloyd steps; the bounded hole filling (FillHoles, HoleFilling.h), each
 * round followed by one Lloyd step; with input-point samples, the covering
 * rounds (Covering.h); FinalLloydIterations Lloyd steps, weighted by the
 * clusters' surface variation with LloydVariationWeight. After every step
 * that moves samples, a distributed run exchanges its halo cells' samples
 * (SimplifyParameters::ShareSamples).
 */
#ifndef asm_core_FeatureRefine_h
#define asm_core_FeatureRefine_h

#include "FeatureOutput.h"
#include "FeatureSimplify.h"
#include "Lloyd.h"

#include <algorithm>
#include <vector>

namespace asmcore
{
/// The cross-cell Lloyd iterations the parameters ask for, clamped.
inline int CrossIterations(const SimplifyParameters& p)
{
  return std::max(0, std::min(MaxCrossCellIterations, p.CrossCellIterations));
}

/// Refine `samples` (with their `info`, regrouped when the hole filling moves
/// samples between cells; their number may change in a distributed run)
/// over the points P in the cells of `grid` (slot order). `assign` holds, on
/// return, the assignment of the last step (possibly stale by its Lloyd
/// move: the caller assigns again). False when the run was aborted
/// (execution.Report), progress reported from 0.6 to 0.8.
VTKASMFILTERS_EXPORT bool RefineAcrossCells(Coordinates P, const CellGrid& grid,
  const CellNeighborTable& neighbors, const SimplifyParameters& parameters,
  const Execution& execution, SampleSet& samples, std::vector<feature::SampleInfo>& info,
  PointArray<SampleId>& assign);
} // namespace asmcore

#endif
