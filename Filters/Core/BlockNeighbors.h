// SPDX-License-Identifier: BSD-3-Clause
/**
 * The k nearest points of a cloud for many query points at once (the
 * metrics of vtkKeyPointError: every original point against the simplified
 * cloud). The queries are grouped by the cells of a grid about as fine as
 * the typical k-th neighbour distance (up to twice as coarse when that
 * leaves fewer than 32 queries a block). For a block (the queries of one
 * cell, centroid c, all within R of c), every query q's k nearest lie
 * within r_c + 2R of c, r_c being c's own k-th neighbour distance: the k
 * points nearest c are within r_c + |q - c| of q, so q's k-th distance is
 * at most that, and a point x among q's k nearest has
 * |x - c| <= |x - q| + |q - c| <= r_c + 2R. One k-nearest and one radius
 * search of the tree per block then give a few dozen candidates, and each
 * query ranks them itself, skipping those farther from c than its k-th
 * distance plus |q - c|.
 *
 * The answers are those of Neighbors::KNearestByPosition, bit for bit: the
 * squared distances are evaluated as the tree evaluates them, and the k
 * least (squared distance, position, id) are kept in the same order. Among
 * equally near points the choice goes by position, so that it does not
 * depend on the ids (the order a simplified cloud was gathered in: MPI
 * runs with different process counts). Blocks pay when
 * the queries are denser than the cloud (an original against its
 * simplification: tens of queries per block); sparser queries are searched
 * one by one, in the grid's order (a spatially coherent walk of the tree).
 */
#ifndef asm_core_BlockNeighbors_h
#define asm_core_BlockNeighbors_h

#include "Common.h"

#include <functional>
#include <vector>

namespace asmcore
{
class Neighbors;

/// What a query's visit receives: its position in the query list, its
/// point, and its nearest points (ids sorted by squared distance, then
/// position, then id;
/// their coordinates side by side, 3 per id, from the tree's own copies).
struct KNearestAnswer
{
  Index Query;
  const double* Point;
  const std::vector<Index>& Ids;
  const std::vector<double>& SqDist;
  const double* Xyz;
};
/// Called once per query with a finite point.
using KNearestVisit = std::function<void(const KNearestAnswer&)>;
/// Makes the visit of one range of blocks (ranges run on different threads:
/// a visit made here may keep state of its own, e.g. a cache).
using KNearestVisitMaker = std::function<KNearestVisit()>;

/// For each position i of `ids` whose point xyz[3 * ids[i]] is finite: a
/// visit (Query i) with the min(k, surface.Size()) points of `surface` nearest
/// it, exactly as surface.KNearestByPosition gives them. The visits run on
/// `execution`'s threads, in no fixed order; each query is visited once,
/// and what a visit receives does not depend on the thread count. k <= 0 or
/// an empty surface: no visit.
VTKASMFILTERS_EXPORT void ForEachKNearest(const double* xyz, IdView ids, const Neighbors& surface,
  int k, const KNearestVisit& visit, const Execution& execution = {});
/// The same, each range of blocks with a visit of its own from `makeVisit`.
VTKASMFILTERS_EXPORT void ForEachKNearest(const double* xyz, IdView ids, const Neighbors& surface,
  int k, const KNearestVisitMaker& makeVisit, const Execution& execution = {});
} // namespace asmcore

#endif
