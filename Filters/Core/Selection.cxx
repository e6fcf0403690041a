// SPDX-License-Identifier: BSD-3-Clause
#include "Selection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
using selection::BlockBegin;

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

std::vector<Index> LargestFinite(
  const double* values, Index n, Index look, const Execution& execution)
{
  return LargestFiniteOf(
    n, [values](Index i) { return values[i]; }, look, execution);
}
} // namespace asmcore
