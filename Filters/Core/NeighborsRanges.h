// SPDX-License-Identifier: BSD-3-Clause
/**
 * The k-d tree build's work on one range of entries (NeighborsBuild.cxx):
 * loading an entry, a range's bounds, and the partition that takes both
 * parts' bounds as it classifies each entry.
 */
#ifndef asm_core_NeighborsRanges_h
#define asm_core_NeighborsRanges_h

#include "Neighbors.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>

namespace asmcore
{
namespace kdranges
{
// The entry of point `id`: its numbers as they are (a compact entry is
// built from a float cloud only, see Neighbors::Build).
template <typename Entry>
Entry LoadEntry(Coordinates xyz, Index id);
template <>
inline WideEntry LoadEntry<WideEntry>(Coordinates xyz, Index id)
{
  WideEntry e;
  xyz.Get(id, e.P);
  e.Id = id;
  return e;
}
template <>
inline CompactEntry LoadEntry<CompactEntry>(Coordinates xyz, Index id)
{
  CompactEntry e;
  std::copy_n(xyz.Floats + 3 * id, 3, e.P);
  e.Id = static_cast<std::int32_t>(id);
  return e;
}

// Bounds and smallest id of entries [begin, end) (not empty), into lo, hi.
template <typename Entry>
void RangeBounds(
  const Entry* points, Index begin, Index end, double lo[3], double hi[3], Index& minId)
{
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = hi[a] = static_cast<double>(points[begin].P[a]);
  }
  minId = static_cast<Index>(points[begin].Id);
  for (Index i = begin + 1; i < end; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], static_cast<double>(points[i].P[a]));
      hi[a] = std::max(hi[a], static_cast<double>(points[i].P[a]));
    }
    minId = std::min(minId, static_cast<Index>(points[i].Id));
  }
}
// Partitions entries [begin, end) (Hoare) into those less than `pivot`
// (first) and the others, and takes the bounds and smallest id of each part
// as each entry is classified (once); returns where the second part begins.
// A part may be empty (the caller then splits at the median).
template <typename Entry, typename Less, typename Part>
Index PartitionWithBounds(Entry* points, Index begin, Index end, const Entry& pivot,
  const Less& less, Part& left, Part& right)
{
  double lo[2][3], hi[2][3]; // 0: left, 1: right (locals: kept in registers)
  Index minId[2] = { std::numeric_limits<Index>::max(), std::numeric_limits<Index>::max() };
  for (int a = 0; a < 3; ++a)
  {
    lo[0][a] = lo[1][a] = std::numeric_limits<double>::infinity();
    hi[0][a] = hi[1][a] = -std::numeric_limits<double>::infinity();
  }
  auto add = [&](int part, const Entry& e) {
    for (int a = 0; a < 3; ++a)
    {
      lo[part][a] = std::min(lo[part][a], static_cast<double>(e.P[a]));
      hi[part][a] = std::max(hi[part][a], static_cast<double>(e.P[a]));
    }
    minId[part] = std::min(minId[part], static_cast<Index>(e.Id));
  };
  Index i = begin, j = end - 1;
  for (;;)
  {
    while (i <= j && less(points[i], pivot))
    {
      add(0, points[i++]);
    }
    while (i <= j && !less(points[j], pivot))
    {
      add(1, points[j--]);
    }
    if (i >= j)
    {
      break;
    }
    std::swap(points[i], points[j]);
    add(0, points[i++]);
    add(1, points[j--]);
  }
  for (int a = 0; a < 3; ++a)
  {
    left.Lo[a] = lo[0][a];
    left.Hi[a] = hi[0][a];
    right.Lo[a] = lo[1][a];
    right.Hi[a] = hi[1][a];
  }
  left.MinId = minId[0];
  right.MinId = minId[1];
  return i;
}
} // namespace kdranges
} // namespace asmcore

#endif
