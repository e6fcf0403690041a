// SPDX-License-Identifier: BSD-3-Clause
#include "HoleFilling.h"

#include "HoleFillingSteps.h"
#include "Selection.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <memory>
#include <numeric>
#include <utility>

namespace asmcore
{
namespace holes
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();

// A gap at point slot i (read before any sample moves).
Gap GapAt(const Context& context, Index i)
{
  Gap g;
  const Index cell = context.CellOfSlot(i);
  g.Distance2 = context.Distance2(i);
  g.Point = { context.Grid.CellKey[cell], i - context.Grid.CellStart[cell] };
  context.Xyz.Get(context.Grid.PointAt(i), g.Position);
  return g;
}
} // namespace

// One pass over the points for both rankings: the spread of every sample
// (negated: minus the largest squared distance of its members, -infinity
// for fixed samples and samples without members, so that the smallest
// spreads are the largest values) and the points farthest from their
// sample (at most `farLook`, largest first; a distributed run ranks its own
// cells' points only). The spreads are maxima raised atomically while
// LargestFiniteOf evaluates every point's distance (at least once: a
// maximum does not mind a second time, nor the order of its terms).
PointRanking RankPoints(const Context& context, Index farLook)
{
  const SampleSet& samples = context.Samples;
  const CellGrid& grid = context.Grid;
  const Index count = samples.Size();
  const Index points = static_cast<Index>(context.Assign.size());
  std::unique_ptr<std::atomic<double>[]> spread(
    new std::atomic<double>[static_cast<std::size_t>(count)]);
  context.Exec.Run(0, count, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      spread[s].store(-1.0, std::memory_order_relaxed);
    }
  });
  std::vector<char> rankedSlot; // (distributed: the points of this run's cells)
  if (!context.Scope.Owned.empty())
  {
    rankedSlot.assign(static_cast<std::size_t>(points), 0);
    context.Exec.Run(0, grid.NumberOfCells(), [&](Index b, Index e) {
      for (Index c = b; c < e; ++c)
      {
        std::fill(rankedSlot.begin() + grid.CellStart[c],
          rankedSlot.begin() + grid.CellStart[c + 1], static_cast<char>(context.Ranks(c) ? 1 : 0));
      }
    });
  }
  PointRanking ranking;
  auto distanceOf = [&](Index i) {
    const Index s = context.Assign[i];
    if (s < 0)
    {
      return rankedSlot.empty() || rankedSlot[i] ? std::numeric_limits<double>::infinity()
                                                 : -Infinity;
    }
    const double d = context.Distance2(i);
    double current = spread[s].load(std::memory_order_relaxed);
    while (d > current && !spread[s].compare_exchange_weak(current, d, std::memory_order_relaxed))
    {
    }
    return rankedSlot.empty() || rankedSlot[i] ? d : -Infinity;
  };
  const Index look = std::min(points, farLook);
  ranking.Farthest = LargestFiniteOf(points, distanceOf, look, context.Exec);
  if (look <= 0)
  {
    // (Nothing to look for: LargestFiniteOf evaluated no point.)
    context.Exec.Run(0, points, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i)
      {
        distanceOf(i);
      }
    });
  }
  ranking.NegatedSpread.resize(static_cast<std::size_t>(count));
  context.Exec.Run(0, count, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      const double r = spread[s].load(std::memory_order_relaxed);
      ranking.NegatedSpread[s] = samples.Fixed[s] || r < 0.0 ? -Infinity : -r;
    }
  });
  return ranking;
}

// Candidates: the free samples with the most points per unit of spread
// first (small clusters in dense areas), a few per move. The spread of a
// sample is the largest squared distance of its members (infinite for fixed
// samples and samples without members, which are never candidates).
std::vector<Candidate> RankCandidates(
  const Context& context, std::vector<double> negated, Index look)
{
  const SampleSet& samples = context.Samples;
  const bool distributed = context.Distributed();
  std::vector<Candidate> candidates;
  {
    if (!context.Scope.Owned.empty())
    {
      context.Exec.Run(0, context.Grid.NumberOfCells(), [&](Index b, Index e) {
        for (Index c = b; c < e; ++c)
        {
          if (!context.Ranks(c))
          {
            std::fill(negated.begin() + samples.Start[c], negated.begin() + samples.Start[c + 1],
              -Infinity);
          }
        }
      });
    }
    const std::vector<Index> ranked = LargestFinite(negated, look, context.Exec);
    candidates.resize(ranked.size());
    context.Exec.Run(0, static_cast<Index>(ranked.size()), [&](Index b, Index e) {
      for (Index k = b; k < e; ++k)
      {
        // (The key only when it travels: a serial run names its moves at the end.)
        const Index s = ranked[k];
        candidates[k] = { negated[s],
          distributed ? context.KeyOf(s, CellOfSample(samples, s)) : SampleKey(), s, s };
      }
    });
  }
  if (!distributed)
  {
    return candidates;
  }
  std::vector<double> values;
  values.reserve(4 * candidates.size());
  for (const Candidate& c : candidates)
  {
    values.push_back(c.NegatedSpread);
    PutKey(values, c.Key);
  }
  candidates = GatherRanked<Candidate>(
    context.Scope.Gather, values, 4,
    [](const double* in) {
      return Candidate{ in[0], GetKey(in + 1), -1, -1 };
    },
    [](const Candidate& a, const Candidate& b) {
      return a.NegatedSpread > b.NegatedSpread ||
        (a.NegatedSpread == b.NegatedSpread && a.Key < b.Key);
    },
    look);
  for (Candidate& c : candidates)
  {
    const Index cell = context.CellIndexOf(c.Key.Cell);
    c.Held = context.LocalOf(c.Key);
    c.Local = cell >= 0 && context.Ranks(cell) ? c.Held : -1;
  }
  return candidates;
}

// Gaps: the points farthest from every sample, one per gap (a point within
// its own gap distance of a gap taken already, in its cell's ring, belongs
// to that gap). A distributed run ranks its own cells' points, and the best
// of every process's make the list.
std::vector<Gap> FindGaps(
  const Context& context, const std::vector<Index>& farthest, Index maxMoves)
{
  const CellGrid& grid = context.Grid;
  const bool distributed = context.Distributed();
  std::vector<Gap> far; // (distributed: every process's farthest points)
  if (distributed)
  {
    std::vector<double> values;
    values.reserve(7 * farthest.size());
    for (Index i : farthest)
    {
      const Gap g = GapAt(context, i);
      values.push_back(g.Distance2);
      PutKey(values, g.Point);
      values.insert(values.end(), g.Position, g.Position + 3);
    }
    far = GatherRanked<Gap>(
      context.Scope.Gather, values, 7,
      [](const double* in) {
        return Gap{ in[0], GetKey(in + 1), { in[4], in[5], in[6] } };
      },
      [](const Gap& a, const Gap& b) {
        return a.Distance2 > b.Distance2 || (a.Distance2 == b.Distance2 && a.Point < b.Point);
      },
      FarLook(maxMoves));
  }
  std::vector<Gap> gaps;
  std::vector<Index> chain;
  const std::size_t farCount = distributed ? far.size() : farthest.size();
  const std::size_t most =
    std::min(farCount, static_cast<std::size_t>(std::max<Index>(0, maxMoves)));
  KeyTable head(most); // the last gap taken in each cell (the others chained behind it)
  gaps.reserve(most);  // (reserved: no chain of small blocks left behind in the heap)
  chain.reserve(most);
  for (std::size_t j = 0; j < farCount && static_cast<Index>(gaps.size()) < maxMoves; ++j)
  {
    const Gap f = distributed ? far[j] : GapAt(context, farthest[j]);
    std::uint64_t ring[27];
    RingKeys(grid.Spec, f.Point.Cell, ring);
    bool separate = true;
    for (int r = 0; r < 27 && separate; ++r)
    {
      for (Index g = ring[r] == NoCell ? -1 : head.Find(ring[r]); g >= 0 && separate; g = chain[g])
      {
        separate = SquaredDistance(f.Position, gaps[g].Position) > f.Distance2;
      }
    }
    if (separate)
    {
      chain.push_back(head.Find(f.Point.Cell));
      head.Set(f.Point.Cell, static_cast<Index>(gaps.size()));
      gaps.push_back(f);
    }
  }
  return gaps;
}
} // namespace holes

Index FillHoles(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const PointArray<SampleId>& assign, Index maxMoves, SampleSet& samples, std::vector<Index>& order,
  std::vector<char>& moved, const Execution& execution, Index firstBatch,
  const HoleFillScope& scope)
{
  const Index count = samples.Size();
  const Index total = scope.TotalSamples >= 0 ? scope.TotalSamples : count;
  order.resize(static_cast<std::size_t>(count));
  std::iota(order.begin(), order.end(), Index(0));
  moved.assign(static_cast<std::size_t>(count), 0);
  if (maxMoves <= 0 || total < 2)
  {
    return 0;
  }
  const holes::Context context{ xyz, grid, neighbors, assign, samples, execution, scope };
  // (Both rankings read the assignment's distances: before any sample moves.)
  holes::PointRanking ranking = holes::RankPoints(context, holes::FarLook(maxMoves));
  const std::vector<holes::Candidate> candidates = holes::RankCandidates(
    context, std::move(ranking.NegatedSpread), std::min<Index>(total, 8 * maxMoves));
  const std::vector<holes::Gap> gaps = holes::FindGaps(context, ranking.Farthest, maxMoves);
  const std::vector<holes::Move> made = holes::MatchToGaps(context, candidates, gaps, firstBatch);
  if (made.empty())
  {
    return 0;
  }
  holes::Regroup(
    grid, made, gaps, [&](std::uint64_t key) { return context.CellIndexOf(key); },
    [&](const holes::SampleKey& key) { return context.LocalOf(key); },
    [&](Index s, Index cell) { return context.KeyOf(s, cell); }, samples, order, moved);
  return static_cast<Index>(made.size());
}
} // namespace asmcore
