// SPDX-License-Identifier: BSD-3-Clause
/**
 * The canonical order of a cell's points: an order that depends on the
 * points alone, not on the order they come in (the input's, or a
 * process's share in an MPI run), so that the per-cell steps, which sum,
 * split and break exact ties in this order, give the same result for any
 * order of the input, even on gridded clouds whose points tie everywhere.
 */
#ifndef asm_core_CanonicalOrder_h
#define asm_core_CanonicalOrder_h

#include "Common.h"

#include <cstdint>
#include <vector>

namespace asmcore
{
/// Scratch space of CanonicalOrder (reused from cell to cell).
struct CanonicalOrderScratch
{
  std::vector<std::uint64_t> Hash;
  std::vector<std::uint64_t> Sorted;
  std::vector<std::uint32_t> Count;
};

/// The canonical order of the n points of a cell, given their coordinates
/// `xyz` (3n) and ids: order[k] is the index (0 .. n-1) of the k-th point,
/// by a hash of its coordinates (-0 as +0), then x, y, z,
/// then id. The order is a function of the points alone, not of the order
/// in which they come, so the per-cell steps, which sum, split and break
/// exact ties in this order, give the same result whatever the order of
/// the input, even on gridded clouds whose points tie everywhere (the
/// serial path and distributed runs, whose points reach a process in
/// another order, alike). A counting sort on the hash's leading bits, then
/// the few points of a bucket by the whole key: linear in n.
VTKASMFILTERS_EXPORT void CanonicalOrder(const double* xyz, const Index* ids, Index n,
  std::vector<Index>& order, CanonicalOrderScratch& scratch);

/// Calls visit(j) for every point j != r of [first, last) at exactly point
/// r's position (-0 as +0), for points in canonical order (CanonicalOrder,
/// cell after cell), where such duplicates are r's neighbours: only those
/// are read. get(j, p) writes point j's coordinates into p[3].
template <typename Get, typename Visit>
void ForEachDuplicate(Index r, Index first, Index last, Get&& get, Visit&& visit);

/// Whether point r has a duplicate in [first, last) (as ForEachDuplicate):
/// reads its two neighbours only.
template <typename Get>
bool HasDuplicate(Index r, Index first, Index last, Get&& get)
{
  double at[3], p[3];
  get(r, at);
  auto same = [&](Index j) {
    get(j, p);
    return p[0] == at[0] && p[1] == at[1] && p[2] == at[2];
  };
  return (r - 1 >= first && same(r - 1)) || (r + 1 < last && same(r + 1));
}

/// ForEachDuplicate for the representatives of a cell's or a cloud's
/// samples, so that a group of duplicates holding several representatives
/// is listed once (not once per representative: a cloud of n identical
/// points and m samples would list m n pairs): visit(r, j) for every
/// duplicate j of r unless r's group was listed before; `listed` (one flag
/// per point of [first, last), sized by the caller, zero at first) marks
/// the listed groups. The first representative met lists its group.
template <typename Get, typename Visit>
void ListDuplicatesOnce(
  Index r, Index first, Index last, Get&& get, std::vector<char>& listed, Visit&& visit)
{
  if (listed[static_cast<std::size_t>(r - first)])
  {
    return;
  }
  listed[static_cast<std::size_t>(r - first)] = 1;
  ForEachDuplicate(r, first, last, get, [&](Index j) {
    listed[static_cast<std::size_t>(j - first)] = 1;
    visit(r, j);
  });
}

template <typename Get, typename Visit>
void ForEachDuplicate(Index r, Index first, Index last, Get&& get, Visit&& visit)
{
  double at[3], p[3];
  get(r, at);
  auto same = [&](Index j) {
    get(j, p);
    return p[0] == at[0] && p[1] == at[1] && p[2] == at[2];
  };
  for (Index j = r - 1; j >= first && same(j); --j)
  {
    visit(j);
  }
  for (Index j = r + 1; j < last && same(j); ++j)
  {
    visit(j);
  }
}

/// A cell's points gathered as doubles (floats widened exactly) in the
/// cell's canonical order (CanonicalOrder), with their ids: local slot i is
/// point Ids[i], at Xyz[3i .. 3i+2] (IdView::Identity(n) lists the slots).
/// The per-cell steps read them from here (cache-resident) instead of from
/// the scattered input. Reused from cell to cell.
class VTKASMFILTERS_EXPORT CanonicalCell
{
public:
  std::vector<double> Xyz;
  std::vector<Index> Ids;

  void Gather(Coordinates xyz, IdView points);
  void Gather(Coordinates xyz, const Index* points, Index n)
  {
    this->Gather(xyz, IdView(points, static_cast<std::size_t>(n)));
  }

private:
  std::vector<double> Gathered;
  std::vector<Index> GatheredIds;
  std::vector<Index> Order;
  CanonicalOrderScratch Scratch;
};
} // namespace asmcore

#endif
