// SPDX-License-Identifier: BSD-3-Clause
#include "Selection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
namespace
{
// Fixed blocks (never the thread count): the same cuts on every run.
Index BlockCount(Index n, Index minBlock)
{
  return std::max<Index>(1, std::min<Index>(64, n / minBlock));
}

Index BlockBegin(Index n, Index blocks, Index b)
{
  return n / blocks * b + (n % blocks) * b / blocks;
}
} // namespace

void SortRanked(std::vector<RankedValue>& values, const Execution& execution)
{
  const Index n = static_cast<Index>(values.size());
  // A power of two of blocks, so that the merges pair them up evenly.
  Index blocks = 1;
  while (blocks < 16 && n / (2 * blocks) >= (1 << 14))
  {
    blocks *= 2;
  }
  auto begin = [&](Index b) { return values.begin() + BlockBegin(n, blocks, b); };
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index b = first; b < last; ++b)
    {
      std::sort(begin(b), begin(b + 1), RanksBefore);
    }
  });
  // Merge rounds: sorted runs of `width` blocks, pairwise into the buffer
  // and back (a total order: the result is the one full sort would give).
  std::vector<RankedValue> buffer(blocks > 1 ? values.size() : 0);
  for (Index width = 1; width < blocks; width *= 2)
  {
    execution.Run(0, blocks / (2 * width), [&](Index first, Index last) {
      for (Index m = first; m < last; ++m)
      {
        const Index lo = 2 * width * m;
        std::merge(begin(lo), begin(lo + width), begin(lo + width), begin(lo + 2 * width),
          buffer.begin() + BlockBegin(n, blocks, lo), RanksBefore);
      }
    });
    values.swap(buffer);
  }
}

std::vector<Index> LargestFinite(const double* values, Index n, Index look, const Execution& execution)
{
  std::vector<Index> largest;
  if (look <= 0 || n == 0)
  {
    return largest;
  }
  const Index blocks = BlockCount(n, 1 << 15);
  // Every (value, index) whose finite value is at least `threshold`, in
  // index order.
  auto collect = [&](double threshold) {
    std::vector<std::vector<RankedValue>> part(static_cast<std::size_t>(blocks));
    execution.Run(0, blocks, [&](Index first, Index last) {
      for (Index b = first; b < last; ++b)
      {
        for (Index i = BlockBegin(n, blocks, b); i < BlockBegin(n, blocks, b + 1); ++i)
        {
          if (values[i] >= threshold && std::isfinite(values[i]))
          {
            part[b].emplace_back(values[i], i);
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
      for (Index i = BlockBegin(n, blocks, b); i < BlockBegin(n, blocks, b + 1); i += Stride)
      {
        if (std::isfinite(values[i]))
        {
          part[b].push_back(values[i]);
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
    std::nth_element(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(rank), sample.end(),
      std::greater<double>());
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
} // namespace asmcore
