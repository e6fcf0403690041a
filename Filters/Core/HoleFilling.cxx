// SPDX-License-Identifier: BSD-3-Clause
#include "HoleFilling.h"

#include "GroupBy.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <utility>

namespace asmcore
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();


// The `look` points with the largest finite distance2, farthest first
// (ties: the lower slot): the threshold value is found on a copy of the
// values, then the points above it (and as many at it as needed, lowest
// slots first) are collected in parallel blocks, in slot order.
std::vector<Index> FarthestPoints(
  const std::vector<double>& distance2, Index look, const Execution& execution)
{
  const Index n = static_cast<Index>(distance2.size());
  std::vector<Index> far;
  if (look <= 0 || n == 0)
  {
    return far;
  }
  const Index blocks = std::max<Index>(1, std::min<Index>(64, n / (1 << 15)));
  auto blockBegin = [&](Index b) { return n / blocks * b + (n % blocks) * b / blocks; };
  // Every point whose finite value is at least `threshold`, in slot order.
  auto collect = [&](double threshold) {
    std::vector<std::vector<Index>> part(static_cast<std::size_t>(blocks));
    execution.Run(0, blocks, [&](Index first, Index last) {
      for (Index b = first; b < last; ++b)
      {
        for (Index i = blockBegin(b); i < blockBegin(b + 1); ++i)
        {
          if (distance2[i] >= threshold && std::isfinite(distance2[i]))
          {
            part[b].push_back(i);
          }
        }
      }
    });
    std::vector<Index> all;
    for (const auto& p : part)
    {
      all.insert(all.end(), p.begin(), p.end());
    }
    return all;
  };
  // A threshold from every 16th value, below the value of rank look in
  // that sample (with a margin): usually a little over `look` points pass;
  // if fewer do, all finite points are taken.
  std::vector<double> sample;
  for (Index i = 0; i < n; i += 16)
  {
    if (std::isfinite(distance2[i]))
    {
      sample.push_back(distance2[i]);
    }
  }
  const auto rank = static_cast<std::size_t>(2 * look / 16 + 16);
  std::vector<Index> pool;
  if (rank < sample.size())
  {
    std::nth_element(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(rank), sample.end(),
      std::greater<double>());
    pool = collect(sample[rank]);
  }
  if (static_cast<Index>(pool.size()) < look)
  {
    pool = collect(-Infinity);
  }
  // Ranked on (value, slot) pairs: contiguous reads, not distance2[slot].
  std::vector<std::pair<double, Index>> ranked(pool.size());
  execution.Run(0, static_cast<Index>(pool.size()), [&](Index b, Index e) {
    for (Index k = b; k < e; ++k)
    {
      ranked[k] = { distance2[pool[k]], pool[k] };
    }
  });
  auto fartherFirst = [](const std::pair<double, Index>& a, const std::pair<double, Index>& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  };
  look = std::min<Index>(look, static_cast<Index>(ranked.size()));
  std::nth_element(ranked.begin(), ranked.begin() + (look - 1), ranked.end(), fartherFirst);
  ranked.resize(static_cast<std::size_t>(look));
  std::sort(ranked.begin(), ranked.end(), fartherFirst);
  far.resize(ranked.size());
  std::transform(ranked.begin(), ranked.end(), far.begin(), [](const std::pair<double, Index>& r) { return r.second; });
  return far;
}

Index CellOfSlot(const CellGrid& grid, Index slot)
{
  return static_cast<Index>(
    std::upper_bound(grid.CellStart.begin(), grid.CellStart.end(), slot) - grid.CellStart.begin() - 1);
}
} // namespace

Index FillHoles(const double* xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const std::vector<Index>& assign, const std::vector<double>& distance2, Index maxMoves,
  SampleSet& samples, std::vector<Index>& order, const Execution& execution)
{
  const Index count = samples.Size();
  const Index cells = grid.NumberOfCells();
  const Index points = static_cast<Index>(assign.size());
  order.resize(static_cast<std::size_t>(count));
  std::iota(order.begin(), order.end(), Index(0));
  if (maxMoves <= 0 || count < 2)
  {
    return 0;
  }
  // Candidates: the free samples with the most points per unit of spread
  // first (small clusters in dense areas), a few per move. The spread of a
  // sample is the largest squared distance of its members (infinite for
  // fixed samples and samples without members).
  std::vector<double> radius(static_cast<std::size_t>(count), -1.0);
  for (Index i = 0; i < points; ++i)
  {
    const Index s = assign[i];
    if (s >= 0)
    {
      radius[s] = std::max(radius[s], distance2[i]);
    }
  }
  for (Index s = 0; s < count; ++s)
  {
    if (samples.Fixed[s] || radius[s] < 0.0)
    {
      radius[s] = Infinity;
    }
  }
  std::vector<Index> candidates(static_cast<std::size_t>(count));
  std::iota(candidates.begin(), candidates.end(), Index(0));
  const Index keep = std::min<Index>(count, 8 * maxMoves);
  auto smaller = [&](Index a, Index b) { return radius[a] < radius[b] || (radius[a] == radius[b] && a < b); };
  if (keep < count)
  {
    std::nth_element(candidates.begin(), candidates.begin() + keep, candidates.end(), smaller);
  }
  candidates.resize(static_cast<std::size_t>(keep));
  std::sort(candidates.begin(), candidates.end(), smaller);
  while (!candidates.empty() && !std::isfinite(radius[candidates.back()]))
  {
    candidates.pop_back();
  }
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
  // Cost of removing candidate s, and who takes over its members.
  std::vector<Index> heirs;
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
  // Stops as soon as the cost reaches `limit` (the move is then refused
  // whatever the rest would add; `heirs` is complete only below the limit).
  auto removalCost = [&](Index s, double limit) {
    double cost = 0.0;
    heirs.clear();
    const Index cell = static_cast<Index>(
      std::upper_bound(samples.Start.begin(), samples.Start.end(), s) - samples.Start.begin() - 1);
    if (ringSampleCount(cell) > 4 * LargeCellBudget)
    {
      return Infinity;
    }
    const Index k = candidateOf[s];
    for (Index m = start[k]; m < start[k + 1]; ++m)
    {
      const Index slot = members[m];
      const double* p = xyz + 3 * grid.Order[slot];
      const Index* ring = neighbors.Of(CellOfSlot(grid, slot));
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
  const std::vector<Index> far = FarthestPoints(distance2,
    static_cast<Index>(std::min<double>(static_cast<double>(points), 20.0 * static_cast<double>(maxMoves))),
    execution);
  std::vector<Index> gaps;
  std::vector<Index> head(static_cast<std::size_t>(cells), -1); // gaps per cell, chained
  std::vector<Index> chain;
  for (Index i : far)
  {
    if (static_cast<Index>(gaps.size()) >= maxMoves)
    {
      break;
    }
    const double* p = xyz + 3 * grid.Order[i];
    const Index cell = CellOfSlot(grid, i);
    const Index* ring = neighbors.Of(cell);
    bool separate = true;
    for (int k = 0; k < 27 && separate; ++k)
    {
      for (Index g = ring[k] < 0 ? -1 : head[ring[k]]; g >= 0 && separate; g = chain[g])
      {
        separate = SquaredDistance(p, xyz + 3 * grid.Order[gaps[g]]) > distance2[i];
      }
    }
    if (separate)
    {
      chain.push_back(head[cell]);
      head[cell] = static_cast<Index>(gaps.size());
      gaps.push_back(i);
    }
  }
  // Cheapest candidates into the largest gaps, while it pays.
  std::vector<char> blocked(static_cast<std::size_t>(count), 0);
  std::vector<Index> owner(static_cast<std::size_t>(count));
  for (Index c = 0; c < cells; ++c)
  {
    std::fill(owner.begin() + samples.Start[c], owner.begin() + samples.Start[c + 1], c);
  }
  // The most crowded candidates are tried in turn for each gap, from the
  // largest; a candidate whose removal would leave a hole as large as this
  // gap is passed over (it cannot pay for a smaller gap either), and a gap
  // no candidate pays for is left for the next one (the smaller gaps still
  // shorten the nearest-neighbour distances).
  Index moves = 0;
  std::size_t next = 0;
  for (Index g : gaps)
  {
    for (int tries = 0; tries < 8; ++tries)
    {
      while (next < candidates.size() && blocked[candidates[next]])
      {
        ++next;
      }
      if (next >= candidates.size())
      {
        break;
      }
      const Index s = candidates[next++];
      if (!(removalCost(s, distance2[g]) < distance2[g]))
      {
        continue;
      }
      blocked[s] = 1;
      for (Index t : heirs)
      {
        blocked[t] = 1;
      }
      std::copy(xyz + 3 * grid.Order[g], xyz + 3 * grid.Order[g] + 3, samples.Position.data() + 3 * s);
      owner[s] = CellOfSlot(grid, g);
      ++moves;
      break;
    }
  }
  if (moves == 0)
  {
    return 0;
  }
  // Regroup by owner cell (stable: the order within a cell is kept).
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return owner[a] < owner[b]; });
  std::vector<double> position(samples.Position.size());
  std::vector<char> fixed(samples.Fixed.size());
  std::fill(samples.Start.begin(), samples.Start.end(), 0);
  for (Index s = 0; s < count; ++s)
  {
    std::copy(samples.Position.data() + 3 * order[s], samples.Position.data() + 3 * order[s] + 3,
      position.data() + 3 * s);
    fixed[s] = samples.Fixed[order[s]];
    ++samples.Start[owner[order[s]] + 1];
  }
  for (Index c = 0; c < cells; ++c)
  {
    samples.Start[c + 1] += samples.Start[c];
  }
  samples.Position.swap(position);
  samples.Fixed.swap(fixed);
  return moves;
}
} // namespace asmcore
