// SPDX-License-Identifier: BSD-3-Clause
/**
 * The records of the hole filling (HoleFilling.h) that travel between the
 * processes of a distributed run, and the regrouping of a run's samples
 * after the moves. Internal to the hole filling (HoleFillingSteps.h).
 */
#ifndef asm_core_HoleFillingRecords_h
#define asm_core_HoleFillingRecords_h

#include "Grid.h"
#include "Lloyd.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace asmcore
{
namespace holes
{
inline Index CellOfSample(const SampleSet& samples, Index s)
{
  return static_cast<Index>(
    std::upper_bound(samples.Start.begin(), samples.Start.end(), s) - samples.Start.begin() - 1);
}

// A sample's identity over the processes: its owner cell's key and its rank
// among that cell's samples. Keys order samples as a one-process run numbers
// them (cells in key order, then their own order). Gap points are named the
// same way (cell key, rank among the cell's points).
struct SampleKey
{
  std::uint64_t Cell = 0;
  Index Rank = 0;
  bool operator<(const SampleKey& o) const
  {
    return this->Cell < o.Cell || (this->Cell == o.Cell && this->Rank < o.Rank);
  }
  bool operator==(const SampleKey& o) const { return this->Cell == o.Cell && this->Rank == o.Rank; }
};

// Keys travel as doubles: a cell key as two exact 32-bit halves.
inline void PutKey(std::vector<double>& out, const SampleKey& key)
{
  AppendAsDoubles(out, key.Cell);
  out.push_back(static_cast<double>(key.Rank));
}

inline SampleKey GetKey(const double* in)
{
  return { FromDoubles(in), static_cast<Index>(in[2]) };
}

constexpr std::uint64_t NoCell = ~std::uint64_t(0);

// The keys of the 27 cells around the cell `key`, in CellNeighborsOf's ring
// order (dx fastest), NoCell outside the grid.
inline void RingKeys(const GridSpec& spec, std::uint64_t key, std::uint64_t out[27])
{
  std::int64_t ijk[3];
  spec.Unpack(key, ijk);
  int k = 0;
  for (int dz = -1; dz <= 1; ++dz)
  {
    for (int dy = -1; dy <= 1; ++dy)
    {
      for (int dx = -1; dx <= 1; ++dx, ++k)
      {
        const std::int64_t c[3] = { ijk[0] + dx, ijk[1] + dy, ijk[2] + dz };
        bool inside = true;
        for (int a = 0; a < 3; ++a)
        {
          inside = inside && c[a] >= 0 && c[a] < spec.Dims[a];
        }
        const std::uint64_t u[3] = { static_cast<std::uint64_t>(c[0]),
          static_cast<std::uint64_t>(c[1]), static_cast<std::uint64_t>(c[2]) };
        out[k] = inside ? GridSpec::PackKey(u) : NoCell;
      }
    }
  }
}

// A map from cell keys to indices (-1: absent), in one open-addressing
// array that doubles when half full: no heap block per entry (tens of
// thousands of those a round fragmented the heap).
class KeyTable
{
public:
  explicit KeyTable(std::size_t expected = 0)
  {
    this->Slots.assign(SizeFor(expected), { NoCell, -1 });
  }
  Index Find(std::uint64_t key) const { return this->Slots[this->SlotOf(key)].second; }
  void Set(std::uint64_t key, Index value)
  {
    auto* slot = &this->Slots[this->SlotOf(key)];
    if (slot->first == NoCell)
    {
      if (2 * (this->Used + 1) > this->Slots.size())
      {
        std::vector<std::pair<std::uint64_t, Index>> old(SizeFor(this->Used + 1), { NoCell, -1 });
        old.swap(this->Slots);
        for (const auto& entry : old)
        {
          if (entry.first != NoCell)
          {
            this->Slots[this->SlotOf(entry.first)] = entry;
          }
        }
        slot = &this->Slots[this->SlotOf(key)];
      }
      ++this->Used;
    }
    *slot = { key, value };
  }

private:
  static std::size_t SizeFor(std::size_t entries)
  {
    std::size_t size = 16;
    while (size < 2 * entries + 2)
    {
      size *= 2;
    }
    return size;
  }
  std::size_t SlotOf(std::uint64_t key) const
  {
    const std::size_t mask = this->Slots.size() - 1;
    std::size_t at = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 20) & mask;
    while (this->Slots[at].first != NoCell && this->Slots[at].first != key)
    {
      at = (at + 1) & mask;
    }
    return at;
  }
  std::vector<std::pair<std::uint64_t, Index>> Slots;
  std::size_t Used = 0;
};

// A free sample that may move: ranked by its negated spread.
struct Candidate
{
  double NegatedSpread = -std::numeric_limits<double>::infinity();
  SampleKey Key;
  Index Local = -1; // its number in this run when this run ranks it (an owned cell)
  Index Held = -1;  // its number in this run when its cell is held here
};

// A gap: a point far from every sample.
struct Gap
{
  double Distance2 = 0.0;
  SampleKey Point; // (cell key, rank among the cell's points)
  double Position[3] = { 0, 0, 0 };
};

// Every Stride-th value of a process's ranked list travels first, to find
// how much of each list may be among the best (RankThreshold).
constexpr Index RankStride = 64;

// A value that at least `keep` of the processes' values reach (or -infinity
// when they have fewer), from each process's every `stride`-th value
// (sampled[q]: the values at ranks 0, stride, 2 stride, ... of process q's
// list, largest first): a process whose n sampled values reach t has at
// least (n - 1) stride + 1 values that do. The largest such value, so that
// few values beyond the best `keep` reach it (at most about
// keep + (processes + 1) stride without ties).
inline double RankThreshold(
  const std::vector<std::vector<double>>& sampled, Index stride, Index keep)
{
  std::vector<std::pair<double, std::size_t>> all; // (value, process)
  for (std::size_t q = 0; q < sampled.size(); ++q)
  {
    for (double v : sampled[q])
    {
      all.emplace_back(v, q);
    }
  }
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Index> reached(sampled.size(), 0);
  Index lowerBound = 0; // values that surely reach the current one
  for (std::size_t k = 0; k < all.size();)
  {
    const double v = all[k].first;
    for (; k < all.size() && all[k].first == v; ++k)
    {
      lowerBound += reached[all[k].second]++ == 0 ? 1 : stride;
    }
    if (lowerBound >= keep)
    {
      return v;
    }
  }
  return -std::numeric_limits<double>::infinity();
}

// Every process's best records of `width` doubles (the first, the value they
// are ranked by, larger first; `values`: this process's, best first),
// gathered, parsed and sorted; the first `keep` are kept. Only the records
// that may be among the best `keep` travel: every RankStride-th value of
// each list is gathered first (RankThreshold), then the records that reach
// the threshold.
template <typename Record, typename Parse, typename Before>
std::vector<Record> GatherRanked(const std::function<void(std::vector<double>&)>& gather,
  std::vector<double>& values, std::size_t width, Parse&& parse, Before&& before, Index keep)
{
  const std::size_t count = values.size() / width;
  std::vector<double> sampled{ 0.0 }; // (how many, then the values)
  for (std::size_t k = 0; k < count; k += static_cast<std::size_t>(RankStride))
  {
    sampled.push_back(values[width * k]);
  }
  sampled[0] = static_cast<double>(sampled.size() - 1);
  gather(sampled);
  std::vector<std::vector<double>> perProcess;
  for (std::size_t at = 0; at < sampled.size();)
  {
    const auto n = static_cast<std::size_t>(sampled[at]);
    perProcess.emplace_back(sampled.begin() + static_cast<std::ptrdiff_t>(at + 1),
      sampled.begin() + static_cast<std::ptrdiff_t>(at + 1 + n));
    at += 1 + n;
  }
  const double threshold = RankThreshold(perProcess, RankStride, keep);
  std::size_t send = 0;
  while (send < count && values[width * send] >= threshold)
  {
    ++send;
  }
  values.resize(width * send);
  gather(values);
  std::vector<Record> all(values.size() / width);
  for (std::size_t k = 0; k < all.size(); ++k)
  {
    all[k] = parse(values.data() + width * k);
  }
  std::vector<double>().swap(values);
  std::sort(all.begin(), all.end(), before);
  all.resize(std::min(all.size(), static_cast<std::size_t>(std::max<Index>(0, keep))));
  return all;
}

// After the moves `made` (sample, gap), regroups this run's samples by
// owner cell, stably: within a cell, in the order of their keys (a one-process
// run's order: the samples that stayed, and the moved ones merged in).
// A sample that moved out of the cells held here leaves; one that moved in
// from elsewhere arrives (order -1). See FillHoles for `order` and `moved`.
template <typename CellIndexOf, typename LocalOf, typename KeyOf>
void Regroup(const CellGrid& grid, const std::vector<std::pair<SampleKey, Index>>& made,
  const std::vector<Gap>& gaps, CellIndexOf&& cellIndexOf, LocalOf&& localOf, KeyOf&& keyOf,
  SampleSet& samples, std::vector<Index>& order, std::vector<char>& moved)
{
  const Index count = samples.Size();
  const Index cells = grid.NumberOfCells();
  struct Arrival
  {
    Index Owner;
    SampleKey Key;
    Index Old; // (-1: from a cell not held here)
    const double* Position;
  };
  std::vector<char> left(static_cast<std::size_t>(count), 0);
  std::vector<Arrival> arriving;
  arriving.reserve(made.size());
  std::vector<Index> start(static_cast<std::size_t>(cells) + 1, 0);
  for (Index c = 0; c < cells; ++c)
  {
    start[c + 1] = samples.Start[c + 1] - samples.Start[c];
  }
  for (const auto& m : made)
  {
    const Gap& g = gaps[m.second];
    const Index from = localOf(m.first);
    if (from >= 0)
    {
      left[from] = 1;
      --start[CellOfSample(samples, from) + 1];
    }
    const Index to = cellIndexOf(g.Point.Cell);
    if (to >= 0)
    {
      arriving.push_back({ to, m.first, from, g.Position });
      ++start[to + 1];
    }
  }
  std::sort(arriving.begin(), arriving.end(), [](const Arrival& a, const Arrival& b) {
    return a.Owner < b.Owner || (a.Owner == b.Owner && a.Key < b.Key);
  });
  for (Index c = 0; c < cells; ++c)
  {
    start[c + 1] += start[c];
  }
  const Index newCount = start[cells];
  // The new order: the samples that stayed (in order) merged with the
  // arrivals (sorted), by (owner cell, key).
  std::vector<Index> newOrder(static_cast<std::size_t>(newCount));
  std::vector<char> newMoved(static_cast<std::size_t>(newCount), 0);
  Index a = 0;
  Index cellOfA = 0; // (the cell of sample a)
  std::size_t b = 0;
  for (Index k = 0; k < newCount; ++k)
  {
    while (a < count && left[a])
    {
      ++a;
    }
    while (a < count && a >= samples.Start[cellOfA + 1])
    {
      ++cellOfA;
    }
    const bool arrival = b < arriving.size() &&
      (a >= count || arriving[b].Owner < cellOfA ||
        (arriving[b].Owner == cellOfA && arriving[b].Key < keyOf(a, cellOfA)));
    newOrder[k] = arrival ? arriving[b++].Old : a++;
    newMoved[k] = arrival ? 1 : 0;
  }
  // The positions and flags follow, in place (no new arrays to fault in):
  // the samples that stayed close up in order (forward: a value only moves
  // down), then, from the end, each slot takes the last value not yet
  // placed or the arrival that the new order puts there (backward: a value
  // only moves up).
  auto reorder = [&](auto& values, int width, auto arrivalValue) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    auto move = [width](const T* from, T* to) {
      for (int c = 0; c < width && from != to; ++c)
      {
        to[c] = from[c];
      }
    };
    Index kept = 0;
    for (Index s = 0; s < count; ++s)
    {
      if (!left[s])
      {
        move(values.data() + width * s, values.data() + width * kept++);
      }
    }
    values.resize(static_cast<std::size_t>(width * std::max(count, newCount)));
    std::size_t nextArrival = arriving.size();
    for (Index k = newCount - 1; k >= 0; --k)
    {
      if (newMoved[k])
      {
        const Arrival& from = arriving[--nextArrival];
        for (int c = 0; c < width; ++c)
        {
          values[width * k + c] = arrivalValue(from, c);
        }
      }
      else
      {
        move(values.data() + width * --kept, values.data() + width * k);
      }
    }
    values.resize(static_cast<std::size_t>(width * newCount));
  };
  reorder(samples.Position, 3, [](const Arrival& from, int c) { return from.Position[c]; });
  reorder(samples.Fixed, 1, [](const Arrival&, int) { return char(0); }); // (candidates are free)
  samples.Start.swap(start);
  order.swap(newOrder);
  moved.swap(newMoved);
}
} // namespace holes
} // namespace asmcore

#endif
