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
/// Returns whether two of the points share a position (exact duplicates,
/// which this order puts next to each other).
VTKASMFILTERS_EXPORT bool CanonicalOrder(const double* xyz, const Index* ids, Index n,
  std::vector<Index>& order, CanonicalOrderScratch& scratch);

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
  /// Two of the gathered points share a position (CanonicalOrder).
  bool SharedPositions = false;

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
