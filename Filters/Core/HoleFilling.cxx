// SPDX-License-Identifier: BSD-3-Clause
#include "HoleFilling.h"

#include "Assignment.h"
#include "GroupBy.h"
#include "HoleFillingRecords.h"
#include "Selection.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <type_traits>
#include <unordered_map>

namespace asmcore
{
using namespace holes; // (HoleFillingRecords.h)
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();

Index CellOfSlot(const CellGrid& grid, Index slot)
{
  return static_cast<Index>(
    std::upper_bound(grid.CellStart.begin(), grid.CellStart.end(), slot) - grid.CellStart.begin() - 1);
}

// The spread of every sample, negated: minus the largest squared distance
// of its members (-infinity for fixed samples and samples without members),
// so that the smallest spreads are the largest values. A maximum does not
// depend on the order of its terms: the points are cut in blocks that raise
// shared per-sample maxima atomically.
template <typename DistanceOf>
std::vector<double> NegatedSpreads(const PointArray<SampleId>& assign, DistanceOf&& distance2,
  const SampleSet& samples, const Execution& execution)
{
  const Index count = samples.Size();
  const Index points = static_cast<Index>(assign.size());
  std::unique_ptr<std::atomic<double>[]> spread(new std::atomic<double>[static_cast<std::size_t>(count)]);
  execution.Run(0, count, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      spread[s].store(-1.0, std::memory_order_relaxed);
    }
  });
  execution.Run(0, points, [&](Index b, Index e) {
    for (Index i = b; i < e; ++i)
    {
      const Index s = assign[i];
      if (s < 0)
      {
        continue;
      }
      const double d = distance2(i);
      double current = spread[s].load(std::memory_order_relaxed);
      while (d > current && !spread[s].compare_exchange_weak(current, d, std::memory_order_relaxed))
      {
      }
    }
  });
  std::vector<double> negated(static_cast<std::size_t>(count));
  execution.Run(0, count, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      const double r = spread[s].load(std::memory_order_relaxed);
      negated[s] = samples.Fixed[s] || r < 0.0 ? -Infinity : -r;
    }
  });
  return negated;
}

} // namespace

Index FillHoles(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const PointArray<SampleId>& assign, Index maxMoves, SampleSet& samples, std::vector<Index>& order,
  std::vector<char>& moved, const Execution& execution, Index firstBatch, const HoleFillScope& scope)
{
  const Index count = samples.Size();
  const Index cells = grid.NumberOfCells();
  const Index points = static_cast<Index>(assign.size());
  const bool distributed = static_cast<bool>(scope.Gather);
  const Index total = scope.TotalSamples >= 0 ? scope.TotalSamples : count;
  order.resize(static_cast<std::size_t>(count));
  std::iota(order.begin(), order.end(), Index(0));
  moved.assign(static_cast<std::size_t>(count), 0);
  if (maxMoves <= 0 || total < 2)
  {
    return 0;
  }
  auto ranks = [&](Index cell) { return scope.Owned.empty() || scope.Owned[cell]; };
  auto cellIndexOf = [&](std::uint64_t key) -> Index {
    const auto it = std::lower_bound(grid.CellKey.begin(), grid.CellKey.end(), key);
    return it != grid.CellKey.end() && *it == key ? static_cast<Index>(it - grid.CellKey.begin()) : -1;
  };
  // This run's number of a sample (-1: its cell is not held here).
  auto localOf = [&](const SampleKey& key) -> Index {
    const Index c = cellIndexOf(key.Cell);
    return c < 0 || key.Rank >= samples.Start[c + 1] - samples.Start[c] ? -1 : samples.Start[c] + key.Rank;
  };
  auto keyOf = [&](Index s, Index cell) { return SampleKey{ grid.CellKey[cell], s - samples.Start[cell] }; };
  // Each point's squared distance to its sample, as the assignment compared
  // it (read before any sample moves).
  auto distance2 = [&](Index i) { return AssignedDistance2(xyz, grid, samples, assign, i); };

  // Candidates: the free samples with the most points per unit of spread
  // first (small clusters in dense areas), a few per move. The spread of a
  // sample is the largest squared distance of its members (infinite for
  // fixed samples and samples without members).
  // The smallest spreads first (ties: the lower sample); infinite spreads
  // are never candidates. A distributed run ranks its own cells' samples,
  // and the best of every process's make the list.
  const Index look = std::min<Index>(total, 8 * maxMoves);
  std::vector<Candidate> candidates;
  {
    std::vector<double> negated = NegatedSpreads(assign, distance2, samples, execution);
    if (!scope.Owned.empty())
    {
      execution.Run(0, cells, [&](Index b, Index e) {
        for (Index c = b; c < e; ++c)
        {
          if (!ranks(c))
          {
            std::fill(negated.begin() + samples.Start[c], negated.begin() + samples.Start[c + 1], -Infinity);
          }
        }
      });
    }
    const std::vector<Index> ranked = LargestFinite(negated, look, execution);
    candidates.resize(ranked.size());
    execution.Run(0, static_cast<Index>(ranked.size()), [&](Index b, Index e) {
      for (Index k = b; k < e; ++k)
      {
        // (The key only when it travels: a serial run names its moves at the end.)
        const Index s = ranked[k];
        candidates[k] = { negated[s], distributed ? keyOf(s, CellOfSample(samples, s)) : SampleKey(), s, s };
      }
    });
  }
  if (distributed)
  {
    std::vector<double> values;
    values.reserve(4 * candidates.size());
    for (const Candidate& c : candidates)
    {
      values.push_back(c.NegatedSpread);
      PutKey(values, c.Key);
    }
    candidates = GatherRanked<Candidate>(
      scope.Gather, values, 4,
      [](const double* in) { return Candidate{ in[0], GetKey(in + 1), -1, -1 }; },
      [](const Candidate& a, const Candidate& b) {
        return a.NegatedSpread > b.NegatedSpread || (a.NegatedSpread == b.NegatedSpread && a.Key < b.Key);
      },
      look);
    for (Candidate& c : candidates)
    {
      const Index cell = cellIndexOf(c.Key.Cell);
      c.Held = localOf(c.Key);
      c.Local = cell >= 0 && ranks(cell) ? c.Held : -1;
    }
  }
  const Index candidateCount = static_cast<Index>(candidates.size());
  // The candidate each sample held here is (-1: none); members (point
  // slots) of this run's own candidates only, by counting sort.
  std::vector<Index> candidateOf(static_cast<std::size_t>(count), -1);
  for (Index k = 0; k < candidateCount; ++k)
  {
    if (candidates[k].Held >= 0)
    {
      candidateOf[candidates[k].Held] = k;
    }
  }
  std::vector<Index> start;
  std::vector<Index> members;
  GroupBy(
    points, candidateCount,
    [&](Index i) {
      const Index k = assign[i] >= 0 ? candidateOf[assign[i]] : Index(-1);
      return k >= 0 && candidates[k].Local >= 0 ? k : Index(-1);
    },
    [](Index i) { return i; }, start, members, execution);
  // Bounded work: a sample among more than 4 * LargeCellBudget ring samples
  // is not a candidate (moving one of many changes little anyway).
  auto ringSampleCount = [&](Index cell) {
    Index n = 0;
    for (int r = 0; r < 27; ++r)
    {
      const Index nb = neighbors.Of(cell)[r];
      n += nb < 0 ? 0 : samples.Start[nb + 1] - samples.Start[nb];
    }
    return n;
  };
  // The cost of removing candidate k, and who takes over its members
  // (`heirs`). Stops as soon as the cost reaches `limit` (the move is then
  // refused whatever the rest would add; `heirs` is complete only below the
  // limit). Reads the positions of the samples of its members' rings.
  auto removalCost = [&](Index k, double limit, std::vector<Index>& heirs) {
    double cost = 0.0;
    heirs.clear();
    const Index s = candidates[k].Local;
    if (ringSampleCount(CellOfSample(samples, s)) > 4 * LargeCellBudget)
    {
      return Infinity;
    }
    for (Index m = start[k]; m < start[k + 1]; ++m)
    {
      const Index slot = members[m];
      double p[3];
      xyz.Get(grid.PointAt(slot), p);
      const CellRef* ring = neighbors.Of(CellOfSlot(grid, slot));
      double best = Infinity;
      Index heir = -1;
      for (int r = 0; r < 27; ++r)
      {
        const Index nb = ring[r];
        for (Index t = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && t < samples.Start[nb + 1]; ++t)
        {
          const double d = SquaredDistance(p, samples.Position.data() + 3 * t);
          if (t != s && d < best)
          {
            best = d;
            heir = t;
          }
        }
      }
      cost = std::max(cost, best);
      if (!(cost < limit))
      {
        return cost;
      }
      if (heir >= 0 && std::find(heirs.begin(), heirs.end(), heir) == heirs.end())
      {
        heirs.push_back(heir);
      }
    }
    return cost;
  };
  // The cells of candidate k's members, as bits of its cell's ring (a
  // member joined a sample of its own ring): a move out of the ring of one
  // of them changes the candidate's cost.
  auto memberCells = [&](Index k) {
    const CellRef* ring = neighbors.Of(CellOfSample(samples, candidates[k].Local));
    std::uint32_t bits = 0;
    Index cell = -1;
    for (Index m = start[k]; m < start[k + 1]; ++m)
    {
      const Index slot = members[m];
      if (cell >= 0 && slot >= grid.CellStart[cell] && slot < grid.CellStart[cell + 1])
      {
        continue;
      }
      cell = CellOfSlot(grid, slot);
      int r = 0;
      while (r < 27 && ring[r] != cell)
      {
        ++r;
      }
      bits |= r < 27 ? std::uint32_t(1) << r : (std::uint32_t(1) << 27) - 1;
    }
    return bits;
  };

  // Gaps: the points farthest from every sample, one per gap (a point
  // within its own gap distance of a gap taken already, in its cell's ring,
  // belongs to that gap). A distributed run ranks its own cells' points.
  const Index farLook =
    static_cast<Index>(std::min<double>(static_cast<double>(points), 20.0 * static_cast<double>(maxMoves)));
  std::vector<Index> farthest;
  {
    std::vector<char> rankedSlot; // (distributed: the points of this run's cells)
    if (!scope.Owned.empty())
    {
      rankedSlot.assign(static_cast<std::size_t>(points), 0);
      execution.Run(0, cells, [&](Index b, Index e) {
        for (Index c = b; c < e; ++c)
        {
          std::fill(rankedSlot.begin() + grid.CellStart[c], rankedSlot.begin() + grid.CellStart[c + 1],
            static_cast<char>(ranks(c) ? 1 : 0));
        }
      });
    }
    farthest = LargestFiniteOf(
      points, [&](Index i) { return rankedSlot.empty() || rankedSlot[i] ? distance2(i) : -Infinity; },
      farLook, execution);
  }
  auto gapAt = [&](Index i) {
    Gap g;
    const Index cell = CellOfSlot(grid, i);
    g.Distance2 = distance2(i);
    g.Point = { grid.CellKey[cell], i - grid.CellStart[cell] };
    xyz.Get(grid.PointAt(i), g.Position);
    return g;
  };
  std::vector<Gap> far; // (distributed: every process's farthest points)
  if (distributed)
  {
    std::vector<double> values;
    values.reserve(7 * farthest.size());
    for (Index i : farthest)
    {
      const Gap g = gapAt(i);
      values.push_back(g.Distance2);
      PutKey(values, g.Point);
      values.insert(values.end(), g.Position, g.Position + 3);
    }
    far = GatherRanked<Gap>(
      scope.Gather, values, 7,
      [](const double* in) {
        return Gap{ in[0], GetKey(in + 1), { in[4], in[5], in[6] } };
      },
      [](const Gap& a, const Gap& b) {
        return a.Distance2 > b.Distance2 || (a.Distance2 == b.Distance2 && a.Point < b.Point);
      },
      static_cast<Index>(20.0 * static_cast<double>(std::min<Index>(maxMoves, Index(1) << 40))));
  }
  std::vector<Gap> gaps;
  {
    std::unordered_map<std::uint64_t, Index> head; // gaps per cell, chained
    std::vector<Index> chain;
    const std::size_t farCount = distributed ? far.size() : farthest.size();
    for (std::size_t j = 0; j < farCount; ++j)
    {
      if (static_cast<Index>(gaps.size()) >= maxMoves)
      {
        break;
      }
      const Gap f = distributed ? far[j] : gapAt(farthest[j]);
      std::uint64_t ring[27];
      RingKeys(grid.Spec, f.Point.Cell, ring);
      bool separate = true;
      for (int r = 0; r < 27 && separate; ++r)
      {
        const auto it = ring[r] == NoCell ? head.end() : head.find(ring[r]);
        for (Index g = it == head.end() ? -1 : it->second; g >= 0 && separate; g = chain[g])
        {
          separate = SquaredDistance(f.Position, gaps[g].Position) > f.Distance2;
        }
      }
      if (separate)
      {
        const auto it = head.find(f.Point.Cell);
        chain.push_back(it == head.end() ? -1 : it->second);
        head[f.Point.Cell] = static_cast<Index>(gaps.size());
        gaps.push_back(f);
      }
    }
  }

  // Cheapest candidates into the largest gaps, while it pays.
  // The removal costs are computed ahead, in parallel batches of the next
  // candidates, with the limit of the gap at hand: gaps come largest first,
  // so a cost that reaches it refuses every later gap too, and a cost below
  // it is complete. A move changes one sample's position: a candidate with
  // a member in the ring of that sample's cell (`touched` after its batch)
  // has its cost computed again when its turn comes. The decisions are those
  // of a serial scan. A distributed run computes its own candidates' costs
  // and gathers every process's: every process makes the same decisions.
  std::vector<double> cost(static_cast<std::size_t>(candidateCount), Infinity);
  std::vector<std::uint32_t> ringBits(static_cast<std::size_t>(candidateCount), 0);
  // (Heirs and blocks only matter for candidates: by candidate number.)
  std::vector<std::vector<Index>> heirsOf(static_cast<std::size_t>(candidateCount));
  std::vector<Index> batchOf(static_cast<std::size_t>(candidateCount), -1); // moves made before it
  std::vector<char> blocked(static_cast<std::size_t>(candidateCount), 0);
  // The last move out of each cell's ring: by cell here (serial), by cell
  // key for cells held anywhere (distributed).
  std::vector<Index> touchedCell(distributed ? 0 : static_cast<std::size_t>(cells), -1);
  std::unordered_map<std::uint64_t, Index> touchedKey;
  Index moves = 0;
  auto isBlocked = [&](Index k) { return blocked[k] != 0; };
  auto computeCosts = [&](const std::vector<Index>& which, double limit) {
    auto range = [&](Index b, Index e) {
      thread_local std::vector<Index> heirs;
      for (Index j = b; j < e; ++j)
      {
        const Index k = which[j];
        if (candidates[k].Local < 0)
        {
          continue;
        }
        cost[k] = removalCost(k, limit, heirs);
        ringBits[k] = memberCells(k);
        heirsOf[k].clear();
        for (Index t : heirs)
        {
          if (candidateOf[t] >= 0)
          {
            heirsOf[k].push_back(candidateOf[t]);
          }
        }
      }
    };
    // (A candidate at its turn alone: no parallel loop to start.)
    const auto n = static_cast<Index>(which.size());
    if (n < 4)
    {
      range(0, n);
    }
    else
    {
      execution.Run(0, n, range);
    }
    for (Index k : which)
    {
      batchOf[k] = moves;
    }
    if (distributed)
    {
      // (k, cost, member cells, heirs, each heir's candidate number)
      std::vector<double> values;
      for (Index k : which)
      {
        if (candidates[k].Local >= 0)
        {
          values.insert(values.end(), { static_cast<double>(k), cost[k], static_cast<double>(ringBits[k]),
                                        static_cast<double>(heirsOf[k].size()) });
          for (Index h : heirsOf[k])
          {
            values.push_back(static_cast<double>(h));
          }
        }
      }
      scope.Gather(values);
      for (std::size_t at = 0; at < values.size();)
      {
        const auto k = static_cast<Index>(values[at]);
        cost[k] = values[at + 1];
        ringBits[k] = static_cast<std::uint32_t>(values[at + 2]);
        const auto heirs = static_cast<std::size_t>(values[at + 3]);
        at += 4;
        heirsOf[k].resize(heirs);
        for (std::size_t h = 0; h < heirs; ++h, ++at)
        {
          heirsOf[k][h] = static_cast<Index>(values[at]);
        }
      }
    }
  };
  auto isCurrent = [&](Index k) {
    if (!distributed)
    {
      const CellRef* ring = neighbors.Of(CellOfSample(samples, candidates[k].Local));
      for (int r = 0; r < 27; ++r)
      {
        if ((ringBits[k] & (std::uint32_t(1) << r)) && ring[r] >= 0 && touchedCell[ring[r]] >= batchOf[k])
        {
          return false;
        }
      }
      return true;
    }
    std::uint64_t ring[27];
    RingKeys(grid.Spec, candidates[k].Key.Cell, ring);
    for (int r = 0; r < 27; ++r)
    {
      if (ringBits[k] & (std::uint32_t(1) << r))
      {
        const auto it = ring[r] == NoCell ? touchedKey.end() : touchedKey.find(ring[r]);
        if (it != touchedKey.end() && it->second >= batchOf[k])
        {
          return false;
        }
      }
    }
    return true;
  };
  // The most crowded candidates are tried in turn for each gap, from the
  // largest; a candidate whose removal would leave a hole as large as this
  // gap is passed over (it cannot pay for a smaller gap either), and a gap
  // no candidate pays for is left for the next one (the smaller gaps still
  // shorten the nearest-neighbour distances).
  Index computed = 0; // candidates [0, computed) have a cost
  Index batch = std::max<Index>(1, firstBatch); // doubles up to 1024 (1: stays)
  Index next = 0;
  std::vector<std::pair<SampleKey, Index>> made; // (sample, gap)
  std::vector<Index> which;
  for (std::size_t gap = 0; gap < gaps.size(); ++gap)
  {
    const double limit = gaps[gap].Distance2;
    for (int tries = 0; tries < 8; ++tries)
    {
      while (next < candidateCount && isBlocked(next))
      {
        ++next;
      }
      if (next >= candidateCount)
      {
        break;
      }
      const Index k = next++;
      if (k >= computed)
      {
        const Index end = std::min(candidateCount, k + batch);
        which.clear();
        for (Index j = k; j < end; ++j)
        {
          if (!isBlocked(j))
          {
            which.push_back(j);
          }
        }
        computeCosts(which, limit);
        computed = end;
        batch = batch > 1 ? std::min<Index>(1024, 2 * batch) : 1;
      }
      if (!isCurrent(k))
      {
        // (Distributed: with the next stale candidates of the batch, one
        // gather for up to 64.)
        which.assign(1, k);
        for (Index j = k + 1; distributed && j < computed && which.size() < 64; ++j)
        {
          if (!isBlocked(j) && !isCurrent(j))
          {
            which.push_back(j);
          }
        }
        computeCosts(which, limit);
      }
      if (!(cost[k] < limit))
      {
        continue;
      }
      blocked[k] = 1;
      for (Index t : heirsOf[k])
      {
        blocked[t] = 1;
      }
      const Index s = candidates[k].Held;
      if (s >= 0)
      {
        std::copy_n(gaps[gap].Position, 3, samples.Position.data() + 3 * s);
      }
      if (distributed)
      {
        std::uint64_t ring[27];
        RingKeys(grid.Spec, candidates[k].Key.Cell, ring);
        for (std::uint64_t key : ring)
        {
          if (key != NoCell)
          {
            touchedKey[key] = moves;
          }
        }
        made.emplace_back(candidates[k].Key, static_cast<Index>(gap));
      }
      else
      {
        const Index cell = CellOfSample(samples, s);
        for (int r = 0; r < 27; ++r)
        {
          if (neighbors.Of(cell)[r] >= 0)
          {
            touchedCell[neighbors.Of(cell)[r]] = moves;
          }
        }
        made.emplace_back(keyOf(s, cell), static_cast<Index>(gap));
      }
      ++moves;
      break;
    }
  }
  if (moves == 0)
  {
    return 0;
  }
  Regroup(grid, made, gaps, cellIndexOf, localOf, keyOf, samples, order, moved);
  return moves;
}
} // namespace asmcore
