// SPDX-License-Identifier: BSD-3-Clause
/**
 * Ranking helpers of the hole filling, in parallel and with the same result
 * whatever the thread count: the k largest finite values of an array, and a
 * sort of (value, index) pairs.
 */
#ifndef asm_core_Selection_h
#define asm_core_Selection_h

#include "Common.h"

#include <utility>
#include <vector>

namespace asmcore
{
/// A (value, index) pair ranked larger value first, then lower index.
using RankedValue = std::pair<double, Index>;

/// True when a ranks before b: larger value, then lower index (a total order).
inline bool RanksBefore(const RankedValue& a, const RankedValue& b)
{
  return a.first > b.first || (a.first == b.first && a.second < b.second);
}

/// Sorts `values` by RanksBefore: blocks sorted in parallel, then merged.
VTKASMFILTERS_EXPORT void SortRanked(std::vector<RankedValue>& values, const Execution& execution);

/// The indices of the `look` largest finite values of values[0, n) (fewer if
/// there are fewer finite values), largest first, ties by lower index.
/// Infinite and NaN values are never chosen.
VTKASMFILTERS_EXPORT std::vector<Index> LargestFinite(
  const double* values, Index n, Index look, const Execution& execution);

/// LargestFinite of a whole array.
template <typename Allocator>
std::vector<Index> LargestFinite(
  const std::vector<double, Allocator>& values, Index look, const Execution& execution)
{
  return LargestFinite(values.data(), static_cast<Index>(values.size()), look, execution);
}
} // namespace asmcore

#endif
