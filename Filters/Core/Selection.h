// SPDX-License-Identifier: BSD-3-Clause
/**
 * Ranking helpers of the hole filling, in parallel and with the same result
 * whatever the thread count: the k largest finite values of an array, and a
 * sort of (value, index) pairs.
 */
#ifndef asm_core_Selection_h
#define asm_core_Selection_h

#include "Common.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
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

namespace selection
{
// Fixed blocks (never the thread count): the same cuts on every run.
inline Index BlockCount(Index n, Index minBlock)
{
  return std::max<Index>(1, std::min<Index>(64, n / minBlock));
}

inline Index BlockBegin(Index n, Index blocks, Index b)
{
  return n / blocks * b + (n % blocks) * b / blocks;
}
} // namespace selection

/// The indices of the `look` largest finite values among value(0), ...,
/// value(n - 1) (as LargestFinite below), computed where they are needed
/// instead of read from an array. When look > 0, value(i) is called for
/// every i at least once and at most twice, from any thread (FillHoles
/// raises its samples' spreads in the same calls).
template <typename ValueOf>
std::vector<Index> LargestFiniteOf(Index n, ValueOf&& value, Index look, const Execution& execution)
{
  std::vector<Index> largest;
  if (look <= 0 || n == 0)
  {
    return largest;
  }
  const Index blocks = selection::BlockCount(n, 1 << 15);
  // Every (value, index) whose finite value is at least `threshold`, in
  // index order.
  auto collect = [&](double threshold) {
    std::vector<std::vector<RankedValue>> part(static_cast<std::size_t>(blocks));
    execution.Run(0, blocks, [&](Index first, Index last) {
      for (Index b = first; b < last; ++b)
      {
        for (Index i = selection::BlockBegin(n, blocks, b);
             i < selection::BlockBegin(n, blocks, b + 1); ++i)
        {
          const double v = value(i);
          if (v >= threshold && std::isfinite(v))
          {
            part[b].emplace_back(v, i);
          }
        }
      }
    });
    std::vector<RankedValue> all;
    for (const auto& p : part)
    {
      all.insert(all.end(), p.begin(), p.end());
    }
    return all;
  };
  // A threshold from every 32nd value, below the value of rank `look` in
  // that sample with a margin (a quarter, and 16 sample values: twenty
  // standard deviations of the count at large `look`): usually 1.25 times
  // `look` values pass; if fewer than `look` do, every finite value is
  // taken. The threshold only bounds the work: the answer is exact either
  // way.
  constexpr Index Stride = 32;
  std::vector<std::vector<double>> part(static_cast<std::size_t>(blocks));
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index b = first; b < last; ++b)
    {
      for (Index i = selection::BlockBegin(n, blocks, b);
           i < selection::BlockBegin(n, blocks, b + 1); i += Stride)
      {
        const double v = value(i);
        if (std::isfinite(v))
        {
          part[b].push_back(v);
        }
      }
    }
  });
  std::vector<double> sample;
  for (const auto& p : part)
  {
    sample.insert(sample.end(), p.begin(), p.end());
  }
  const auto rank = static_cast<std::size_t>(5 * look / (4 * Stride) + 16);
  std::vector<RankedValue> pool;
  if (rank < sample.size())
  {
    std::nth_element(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(rank),
      sample.end(), std::greater<double>());
    pool = collect(sample[rank]);
  }
  if (static_cast<Index>(pool.size()) < look)
  {
    pool = collect(-std::numeric_limits<double>::infinity());
  }
  SortRanked(pool, execution);
  look = std::min<Index>(look, static_cast<Index>(pool.size()));
  largest.resize(static_cast<std::size_t>(look));
  execution.Run(0, look, [&](Index b, Index e) {
    for (Index k = b; k < e; ++k)
    {
      largest[k] = pool[k].second;
    }
  });
  return largest;
}

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
