// SPDX-License-Identifier: BSD-3-Clause
/**
 * A selection (like std::nth_element) for small arrays whose order a branch
 * cannot predict: a cell's points in their canonical (hash) order. Used by
 * the paper mode's median splits (SplitInPlane).
 */
#ifndef asm_core_Quickselect_h
#define asm_core_Quickselect_h

#include "Common.h"

#include <algorithm>

namespace asmcore
{
/// Moves the entries of e[0, n) that come before `pivot` (before(x, pivot))
/// to the front, through the scratch `tmp` of n entries, and returns their
/// count. Every entry is written to both ends of `tmp` and only the end it
/// belongs to advances, so the loop has no branch on the comparison (whose
/// own evaluation should be branch-free too).
template <typename T, typename Before>
Index PartitionBefore(T* e, Index n, const T& pivot, Before&& before, T* tmp)
{
  Index front = 0, back = n - 1;
  for (Index i = 0; i < n; ++i)
  {
    const T x = e[i];
    const bool isBefore = before(x, pivot);
    tmp[front] = x;
    tmp[back] = x;
    front += isBefore;
    back -= !isBefore;
  }
  std::copy(tmp, tmp + n, e);
  return front;
}

/// Rearranges e[0, n) so that its first `nth` entries are the `nth` first in
/// the strict total order `before` (the order within each side is this
/// function's own). `tmp` is scratch space of n entries. Quickselect with a
/// median-of-three pivot, ranges of 16 or fewer finished by std::sort; after
/// `maxRounds` rounds std::nth_element (introselect) finishes, which bounds
/// the work on an input built to defeat the pivot. Returns whether it did.
template <typename T, typename Before>
bool SelectFirst(T* e, Index n, Index nth, Before&& before, T* tmp, int maxRounds = 64)
{
  Index lo = 0, hi = n;
  // Each round removes at least one entry: a median of three distinct
  // entries has one on each side.
  for (int round = 0; hi - lo > 16; ++round)
  {
    if (round == maxRounds)
    {
      std::nth_element(e + lo, e + nth, e + hi, before);
      return true;
    }
    const T& a = e[lo];
    const T& b = e[lo + (hi - lo) / 2];
    const T& c = e[hi - 1];
    const T pivot = before(a, b) ? (before(b, c) ? b : (before(a, c) ? c : a))
                                 : (before(a, c) ? a : (before(b, c) ? c : b));
    const Index middle = lo + PartitionBefore(e + lo, hi - lo, pivot, before, tmp);
    if (nth == middle)
    {
      return false;
    }
    (nth < middle ? hi : lo) = middle;
  }
  std::sort(e + lo, e + hi, before);
  return false;
}
} // namespace asmcore

#endif
