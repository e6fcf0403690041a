// SPDX-License-Identifier: BSD-3-Clause
/**
 * The steps of FillHoles (HoleFilling.h), internal to the hole filling: one
 * pass over the points ranks them and the samples, then the candidates (the
 * most crowded free samples), the gaps (the points farthest from every
 * sample, one per gap) and the greedy matching of the one to the other.
 * HoleFilling.cxx holds the rankings and FillHoles, HoleFillingGreedy.cxx
 * the matching.
 */
#ifndef asm_core_HoleFillingSteps_h
#define asm_core_HoleFillingSteps_h

#include "Assignment.h"
#include "HoleFilling.h"
#include "HoleFillingRecords.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace asmcore
{
namespace holes
{
// What every step of one FillHoles call reads. `Samples` is written by the
// matching only (the moved samples' positions), after the ranking.
struct Context
{
  Coordinates Xyz;
  const CellGrid& Grid;
  const CellNeighborTable& Neighbors;
  const PointArray<SampleId>& Assign;
  SampleSet& Samples;
  const Execution& Exec;
  const HoleFillScope& Scope;

  bool Distributed() const { return static_cast<bool>(this->Scope.Gather); }

  // Whether this run ranks the cell's samples and points (one of its own
  // cells; every cell in a serial run).
  bool Ranks(Index cell) const { return this->Scope.Owned.empty() || this->Scope.Owned[cell]; }

  // The grid cell of the key (-1: not held here).
  Index CellIndexOf(std::uint64_t key) const
  {
    const auto it = std::lower_bound(this->Grid.CellKey.begin(), this->Grid.CellKey.end(), key);
    return it != this->Grid.CellKey.end() && *it == key
      ? static_cast<Index>(it - this->Grid.CellKey.begin())
      : -1;
  }

  // This run's number of a sample (-1: its cell is not held here).
  Index LocalOf(const SampleKey& key) const
  {
    const Index c = this->CellIndexOf(key.Cell);
    const auto& start = this->Samples.Start;
    return c < 0 || key.Rank >= start[c + 1] - start[c] ? -1 : start[c] + key.Rank;
  }

  // The key of sample s of `cell`.
  SampleKey KeyOf(Index s, Index cell) const
  {
    return SampleKey{ this->Grid.CellKey[cell], s - this->Samples.Start[cell] };
  }

  // The cell of a point slot of the grid.
  Index CellOfSlot(Index slot) const
  {
    const auto& start = this->Grid.CellStart;
    return static_cast<Index>(
      std::upper_bound(start.begin(), start.end(), slot) - start.begin() - 1);
  }

  // A point slot's squared distance to its sample, as the assignment
  // compared it (valid until a sample moves).
  double Distance2(Index slot) const
  {
    return AssignedDistance2(this->Xyz, this->Grid, this->Samples, this->Assign, slot);
  }
};

// How many of its points farthest from their sample each process ranks: 20
// per move.
inline Index FarLook(Index maxMoves)
{
  return static_cast<Index>(20.0 * static_cast<double>(std::min<Index>(maxMoves, Index(1) << 40)));
}

// The two rankings of one pass over the points (RankPoints, before any
// sample moves): every sample's spread, negated (minus the largest squared
// distance of its members; -infinity for fixed samples and samples without
// members), and this run's points farthest from their sample (at most
// `farLook`, largest first; a distributed run ranks its own cells' points).
struct PointRanking
{
  std::vector<double> NegatedSpread;
  std::vector<Index> Farthest;
};
PointRanking RankPoints(const Context& context, Index farLook);

// The best `look` candidates of the whole cloud: free samples, the smallest
// spread first (ties: the lower key), from `negated` (PointRanking). A
// distributed run ranks its own cells' samples and the best of every
// process's make the list.
std::vector<Candidate> RankCandidates(
  const Context& context, std::vector<double> negated, Index look);

// At most `maxMoves` gaps of the whole cloud, largest first, from this
// run's `farthest` points (PointRanking; a distributed run gathers every
// process's): those not within their own gap distance of a larger gap.
std::vector<Gap> FindGaps(
  const Context& context, const std::vector<Index>& farthest, Index maxMoves);

// A move: the sample that moved, and the gap it filled (an index of gaps).
using Move = std::pair<SampleKey, Index>;

// The cheapest candidates into the largest gaps, while it pays: the moves of
// a serial scan, made on `context.Samples` (the positions of the moved
// samples held here). See FillHoles for `firstBatch`.
std::vector<Move> MatchToGaps(const Context& context, const std::vector<Candidate>& candidates,
  const std::vector<Gap>& gaps, Index firstBatch);
} // namespace holes
} // namespace asmcore

#endif
