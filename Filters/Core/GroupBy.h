// SPDX-License-Identifier: BSD-3-Clause
/**
 * A stable counting sort in fixed blocks: items grouped by an integer key,
 * in parallel, with the same result whatever the thread count (within a
 * group, items keep their order). Used for the points of each grid cell and
 * for the members of each sample.
 */
#ifndef asm_core_GroupBy_h
#define asm_core_GroupBy_h

#include "Common.h"

#include <algorithm>
#include <vector>

namespace asmcore
{
/// Groups the items i in [0, n) by key(i) in [0, keys) (items with a
/// negative key are left out): group k is out[start[k], start[k + 1]),
/// holding value(i) in increasing i. At most `maxBlocks` blocks of at least
/// `minBlock` items each; fewer while the per-block counts would exceed
/// about `scratchPerItem` Index slots per item.
template <typename KeyOf, typename ValueOf, typename Output>
void GroupBy(Index n, Index keys, KeyOf&& key, ValueOf&& value, std::vector<Index>& start,
  Output& out, const Execution& execution, Index maxBlocks = 8, Index minBlock = 1 << 16,
  double scratchPerItem = 0.5)
{
  auto blockBegin = [n](
                      Index blocks, Index b) { return n / blocks * b + (n % blocks) * b / blocks; };
  Index blocks = std::max<Index>(1, std::min<Index>(maxBlocks, n / std::max<Index>(1, minBlock)));
  while (blocks > 1 && static_cast<double>(blocks * keys) > scratchPerItem * static_cast<double>(n))
  {
    --blocks; // bounded scratch for the per-block counts
  }
  // visit(block, i, key) for every item with a key, block by block.
  auto eachItem = [&](auto&& visit) {
    execution.Run(0, blocks, [&](Index first, Index last) {
      for (Index b = first; b < last; ++b)
      {
        const Index end = blockBegin(blocks, b + 1);
        for (Index i = blockBegin(blocks, b); i < end; ++i)
        {
          const Index k = key(i);
          if (k >= 0)
          {
            visit(b, i, k);
          }
        }
      }
    });
  };
  // Per-block counts; each block clears its own row (no serial zero fill).
  PointArray<Index> offset(static_cast<std::size_t>(blocks * keys));
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index b = first; b < last; ++b)
    {
      Index* row = offset.data() + b * keys;
      std::fill(row, row + keys, Index(0));
      const Index end = blockBegin(blocks, b + 1);
      for (Index i = blockBegin(blocks, b); i < end; ++i)
      {
        const Index k = key(i);
        if (k >= 0)
        {
          ++row[k];
        }
      }
    }
  });
  // Group sizes, their running sum, then each block's offset in its group.
  start.resize(static_cast<std::size_t>(keys) + 1);
  execution.Run(0, keys, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      Index size = 0;
      for (Index b = 0; b < blocks; ++b)
      {
        size += offset[b * keys + k];
      }
      start[k] = size;
    }
  });
  Index running = 0;
  for (Index k = 0; k < keys; ++k)
  {
    const Index size = start[k];
    start[k] = running;
    running += size;
  }
  start[keys] = running;
  execution.Run(0, keys, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      Index next = start[k];
      for (Index b = 0; b < blocks; ++b)
      {
        const Index count = offset[b * keys + k];
        offset[b * keys + k] = next;
        next += count;
      }
    }
  });
  out.resize(static_cast<std::size_t>(running));
  eachItem([&](Index b, Index i, Index k) {
    out[static_cast<std::size_t>(offset[b * keys + k]++)] = value(i);
  });
}
} // namespace asmcore

#endif
