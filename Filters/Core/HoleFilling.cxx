// SPDX-License-Identifier: BSD-3-Clause
#include "HoleFilling.h"

#include "Assignment.h"
#include "GroupBy.h"
#include "Selection.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <type_traits>

namespace asmcore
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();

Index CellOfSlot(const CellGrid& grid, Index slot)
{
  return static_cast<Index>(
    std::upper_bound(grid.CellStart.begin(), grid.CellStart.end(), slot) - grid.CellStart.begin() - 1);
}

Index CellOfSample(const SampleSet& samples, Index s)
{
  return static_cast<Index>(
    std::upper_bound(samples.Start.begin(), samples.Start.end(), s) - samples.Start.begin() - 1);
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
  const PointArray<SampleId>& assign, Index maxMoves,
  SampleSet& samples, std::vector<Index>& order, std::vector<char>& moved, const Execution& execution,
  Index firstBatch)
{
  const Index count = samples.Size();
  const Index cells = grid.NumberOfCells();
  const Index points = static_cast<Index>(assign.size());
  order.resize(static_cast<std::size_t>(count));
  std::iota(order.begin(), order.end(), Index(0));
  moved.assign(static_cast<std::size_t>(count), 0);
  if (maxMoves <= 0 || count < 2)
  {
    return 0;
  }
  // Each point's squared distance to its sample, as the assignment compared
  // it (read before any sample moves).
  auto distance2 = [&](Index i) { return AssignedDistance2(xyz, grid, samples, assign, i); };
  // Candidates: the free samples with the most points per unit of spread
  // first (small clusters in dense areas), a few per move. The spread of a
  // sample is the largest squared distance of its members (infinite for
  // fixed samples and samples without members).
  // The smallest spreads first (ties: the lower sample); infinite spreads
  // are never candidates.
  const std::vector<Index> candidates = LargestFinite(
    NegatedSpreads(assign, distance2, samples, execution), std::min<Index>(count, 8 * maxMoves), execution);
  // Members (point slots) of the candidates only, by counting sort.
  std::vector<Index> candidateOf(static_cast<std::size_t>(count), -1);
  for (std::size_t k = 0; k < candidates.size(); ++k)
  {
    candidateOf[candidates[k]] = static_cast<Index>(k);
  }
  std::vector<Index> start;
  std::vector<Index> members;
  GroupBy(
    points, static_cast<Index>(candidates.size()),
    [&](Index i) { return assign[i] >= 0 ? candidateOf[assign[i]] : Index(-1); },
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
    const Index s = candidates[k];
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
  // Gaps: the points farthest from every sample, one per gap (a point
  // within its own gap distance of a gap taken already, in its cell's ring,
  // belongs to that gap).
  const std::vector<Index> far = LargestFiniteOf(points, distance2,
    static_cast<Index>(std::min<double>(static_cast<double>(points), 20.0 * static_cast<double>(maxMoves))),
    execution);
  std::vector<Index> gaps;
  std::vector<double> gapDistance2; // (of each gap, before the moves)
  std::vector<Index> head(static_cast<std::size_t>(cells), -1); // gaps per cell, chained
  std::vector<Index> chain;
  for (Index i : far)
  {
    if (static_cast<Index>(gaps.size()) >= maxMoves)
    {
      break;
    }
    double p[3];
    xyz.Get(grid.PointAt(i), p);
    const double d2 = distance2(i);
    const Index cell = CellOfSlot(grid, i);
    const CellRef* ring = neighbors.Of(cell);
    bool separate = true;
    for (int k = 0; k < 27 && separate; ++k)
    {
      for (Index g = ring[k] < 0 ? -1 : head[ring[k]]; g >= 0 && separate; g = chain[g])
      {
        separate = SquaredDistance(p, xyz.At(grid.PointAt(gaps[g])).data()) > d2;
      }
    }
    if (separate)
    {
      chain.push_back(head[cell]);
      head[cell] = static_cast<Index>(gaps.size());
      gaps.push_back(i);
      gapDistance2.push_back(d2);
    }
  }
  // Cheapest candidates into the largest gaps, while it pays.
  std::vector<char> blocked(static_cast<std::size_t>(count), 0);
  std::vector<Index> owner(static_cast<std::size_t>(count));
  execution.Run(0, cells, [&](Index b, Index e) {
    for (Index c = b; c < e; ++c)
    {
      std::fill(owner.begin() + samples.Start[c], owner.begin() + samples.Start[c + 1], c);
    }
  });
  // The removal costs are computed ahead, in parallel batches of the next
  // candidates, with the limit of the gap at hand: gaps come largest first,
  // so a cost that reaches it refuses every later gap too, and a cost below
  // it is complete. A move changes one sample's position: a candidate with
  // a member in the ring of that sample's cell (`touched` after its batch)
  // has its cost computed again when its turn comes. The decisions are those
  // of a serial scan.
  const Index candidateCount = static_cast<Index>(candidates.size());
  std::vector<double> cost(static_cast<std::size_t>(candidateCount), Infinity);
  std::vector<std::vector<Index>> heirsOf(static_cast<std::size_t>(candidateCount));
  std::vector<Index> batchOf(static_cast<std::size_t>(candidateCount), -1); // moves made before it
  std::vector<Index> touched(static_cast<std::size_t>(cells), -1);          // last move in the ring
  Index computed = 0;  // candidates [0, computed) have a cost
  Index batch = std::max<Index>(1, firstBatch); // doubles up to 1024 (1: stays)
  auto isCurrent = [&](Index k) {
    for (Index m = start[k]; m < start[k + 1]; ++m)
    {
      if (touched[CellOfSlot(grid, members[m])] >= batchOf[k])
      {
        return false;
      }
    }
    return true;
  };
  // The most crowded candidates are tried in turn for each gap, from the
  // largest; a candidate whose removal would leave a hole as large as this
  // gap is passed over (it cannot pay for a smaller gap either), and a gap
  // no candidate pays for is left for the next one (the smaller gaps still
  // shorten the nearest-neighbour distances).
  Index moves = 0;
  Index next = 0;
  std::vector<Index> movedSamples;
  std::vector<char> wasMoved(static_cast<std::size_t>(count), 0);
  for (std::size_t gap = 0; gap < gaps.size(); ++gap)
  {
    const Index g = gaps[gap];
    const double limit = gapDistance2[gap];
    for (int tries = 0; tries < 8; ++tries)
    {
      while (next < candidateCount && blocked[candidates[next]])
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
        execution.Run(k, end, [&](Index b, Index e) {
          for (Index j = b; j < e; ++j)
          {
            if (!blocked[candidates[j]])
            {
              cost[j] = removalCost(j, limit, heirsOf[j]);
              batchOf[j] = moves;
            }
          }
        });
        computed = end;
        batch = batch > 1 ? std::min<Index>(1024, 2 * batch) : 1;
      }
      if (!isCurrent(k))
      {
        cost[k] = removalCost(k, limit, heirsOf[k]);
      }
      if (!(cost[k] < limit))
      {
        continue;
      }
      const Index s = candidates[k];
      blocked[s] = 1;
      for (Index t : heirsOf[k])
      {
        blocked[t] = 1;
      }
      xyz.Get(grid.PointAt(g), samples.Position.data() + 3 * s);
      owner[s] = CellOfSlot(grid, g);
      movedSamples.push_back(s);
      wasMoved[s] = 1;
      for (int r = 0; r < 27; ++r)
      {
        const Index nb = neighbors.Of(CellOfSample(samples, s))[r];
        if (nb >= 0)
        {
          touched[nb] = moves;
        }
      }
      ++moves;
      break;
    }
  }
  if (moves == 0)
  {
    return 0;
  }
  // Regroup by owner cell, stably (the order within a cell is kept): the
  // samples that stayed are in owner order already; the moved ones, sorted
  // by (owner, index), are merged in.
  auto before = [&](Index a, Index b) { return owner[a] < owner[b] || (owner[a] == owner[b] && a < b); };
  std::sort(movedSamples.begin(), movedSamples.end(), before);
  std::vector<Index> stayed;
  stayed.reserve(static_cast<std::size_t>(count - moves));
  for (Index s = 0; s < count; ++s)
  {
    if (!wasMoved[s])
    {
      stayed.push_back(s);
    }
  }
  std::merge(stayed.begin(), stayed.end(), movedSamples.begin(), movedSamples.end(), order.begin(), before);
  // Cell c starts after the samples owned by earlier cells: its old start,
  // less the moved samples that left an earlier cell, plus those that
  // joined one.
  std::vector<Index> left(movedSamples.size()), joined(movedSamples.size());
  for (std::size_t k = 0; k < movedSamples.size(); ++k)
  {
    left[k] = CellOfSample(samples, movedSamples[k]);
    joined[k] = owner[movedSamples[k]];
  }
  std::sort(left.begin(), left.end()); // (joined is sorted already)
  execution.Run(0, cells + 1, [&](Index b, Index e) {
    for (Index c = b; c < e; ++c)
    {
      samples.Start[c] += (std::lower_bound(joined.begin(), joined.end(), c) - joined.begin()) -
        (std::lower_bound(left.begin(), left.end(), c) - left.begin());
    }
  });
  // The positions and flags follow, in place (no new arrays to fault in):
  // the moved samples' values are set aside, the others close up in order
  // (forward: a value only moves down), then, from the end, each slot takes
  // the last value not yet placed or the moved sample that `order` puts
  // there (backward: a value only moves up).
  auto reorder = [&](auto* values, int width) {
    using T = std::remove_pointer_t<decltype(values)>;
    std::vector<T> aside;
    for (Index s : movedSamples)
    {
      aside.insert(aside.end(), values + width * s, values + width * (s + 1));
    }
    // (Element by element: std::copy of one to three numbers is a call to
    // memmove per sample. Ranges of one value never overlap unless equal.)
    auto move = [width](const T* from, T* to) {
      for (int a = 0; a < width && from != to; ++a)
      {
        to[a] = from[a];
      }
    };
    Index kept = 0;
    for (Index s = 0; s < count; ++s)
    {
      if (!wasMoved[s])
      {
        move(values + width * s, values + width * kept++);
      }
    }
    Index nextAside = moves;
    for (Index k = count - 1; k >= 0; --k)
    {
      move(wasMoved[order[k]] ? aside.data() + width * --nextAside : values + width * --kept, values + width * k);
    }
  };
  reorder(samples.Position.data(), 3);
  reorder(samples.Fixed.data(), 1);
  execution.Run(0, count, [&](Index b, Index e) {
    for (Index k = b; k < e; ++k)
    {
      moved[k] = wasMoved[order[k]];
    }
  });
  return moves;
}
} // namespace asmcore
