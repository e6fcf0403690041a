// SPDX-License-Identifier: BSD-3-Clause
/**
 * Per-cell budgets (paper Eq. 4): N_c proportional to w_c * n_c, apportioned
 * so that the budgets add up to N_s exactly.
 */
#ifndef asm_core_Budget_h
#define asm_core_Budget_h

#include "Common.h"

namespace asmcore
{
/// Split `total` samples among cells in proportion to `share` (>= 0), never
/// giving a cell more than its `capacity` (its number of points): quotas of
/// cells that would exceed their capacity are fixed at it and the rest is
/// shared again; then each cell gets the floor of its quota and the units
/// left go to the largest remainders (ties: the lower cell index). The result
/// adds up to min(total, sum of capacities) exactly. Cells with a zero share
/// only receive samples once every other cell is full.
VTKASMFILTERS_EXPORT std::vector<Index> ApportionBudget(
  const std::vector<double>& share, const std::vector<Index>& capacity, Index total);

/// Budgets of the feature-preserving mode. `share` is w_c * n_c^gamma. With
/// `cover` on and total >= the number of non-empty cells, every cell first
/// gets one sample and the rest is apportioned by share (capacity n_c - 1);
/// with total < cells, the `total` cells of largest share get one each (ties:
/// lower index). With `cover` off, as ApportionBudget. Exact in total.
VTKASMFILTERS_EXPORT std::vector<Index> ApportionWithCoverage(
  const std::vector<double>& share, const std::vector<Index>& capacity, Index total, bool cover);
} // namespace asmcore

#endif
