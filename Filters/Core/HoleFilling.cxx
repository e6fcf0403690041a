// SPDX-License-Identifier: BSD-3-Clause
#include "HoleFilling.h"

#include "GroupBy.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

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
  std::vector<double> finite;
  finite.reserve(distance2.size());
  for (double d : distance2)
  {
    if (std::isfinite(d))
    {
      finite.push_back(d);
    }
  }
  look = std::min<Index>(look, static_cast<Index>(finite.size()));
  std::vector<Index> far;
  if (look <= 0)
  {
    return far;
  }
  std::nth_element(finite.begin(), finite.begin() + (look - 1), finite.end(), std::greater<double>());
  const double threshold = finite[static_cast<std::size_t>(look - 1)];
  finite = std::vector<double>();
  // Every point above the threshold (fewer than `look`), then the lowest
  // slots at it.
  const Index blocks = std::max<Index>(1, std::min<Index>(64, n / (1 << 15)));
  auto blockBegin = [&](Index b) { return n / blocks * b + (n % blocks) * b / blocks; };
  std::vector<std::vector<Index>> over(static_cast<std::size_t>(blocks));
  std::vector<std::vector<Index>> at(static_cast<std::size_t>(blocks));
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index b = first; b < last; ++b)
    {
      for (Index i = blockBegin(b); i < blockBegin(b + 1); ++i)
      {
        if (distance2[i] > threshold && std::isfinite(distance2[i]))
        {
          over[b].push_back(i);
        }
        else if (distance2[i] == threshold)
        {
          at[b].push_back(i);
        }
      }
    }
  });
  far.reserve(static_cast<std::size_t>(look));
  for (const auto& part : over)
  {
    far.insert(far.end(), part.begin(), part.end());
  }
  for (const auto& part : at)
  {
    for (Index i : part)
    {
      if (static_cast<Index>(far.size()) >= look)
      {
        break;
      }
      far.push_back(i);
    }
  }
  std::sort(far.begin(), far.end(), [&](Index a, Index b) {
    return distance2[a] > distance2[b] || (distance2[a] == distance2[b] && a < b);
  });
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
  // Members of each sample (point slots), by counting sort.
  std::vector<Index> start;
  std::vector<Index> members;
  GroupBy(
    points, count, [&](Index i) { return assign[i]; }, [](Index i) { return i; }, start, members,
    execution);
  // Candidates: the free samples with the most points per unit of spread
  // first (small clusters in dense areas), a few per move.
  std::vector<double> radius(static_cast<std::size_t>(count), Infinity);
  execution.Run(0, count, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      if (samples.Fixed[s] || start[s + 1] == start[s])
      {
        continue;
      }
      double r = 0.0;
      for (Index m = start[s]; m < start[s + 1]; ++m)
      {
        r = std::max(r, distance2[members[m]]);
      }
      radius[s] = r;
    }
  });
  std::vector<Index> candidates(static_cast<std::size_t>(count));
  std::iota(candidates.begin(), candidates.end(), Index(0));
  const Index keep = std::min<Index>(count, 8 * maxMoves);
  auto smaller = [&](Index a, Index b) { return radius[a] < radius[b] || (radius[a] == radius[b] && a < b); };
  std::partial_sort(candidates.begin(), candidates.begin() + keep, candidates.end(), smaller);
  candidates.resize(static_cast<std::size_t>(keep));
  while (!candidates.empty() && !std::isfinite(radius[candidates.back()]))
  {
    candidates.pop_back();
  }
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
    for (Index m = start[s]; m < start[s + 1]; ++m)
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
