// SPDX-License-Identifier: BSD-3-Clause
#include "CellPartition.h"

#include "Selection.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace asmcore
{
namespace
{
// At most this many counts per box and level travel (a box longer than that
// is cut at a multiple of length / MaxBins cells).
constexpr std::int64_t MaxBins = std::int64_t(1) << 14;

// A box of cells [Lo, Hi) still to cut between Count processes from First,
// with its counts along each axis (Bins[a] of them, 0 for a side of one
// cell) at Offset[a] in the level's histogram.
struct Pending
{
  int Node = 0;
  std::int64_t Lo[3] = { 0, 0, 0 };
  std::int64_t Hi[3] = { 1, 1, 1 };
  int First = 0;
  int Count = 1;
  std::int64_t Bins[3] = { 0, 0, 0 };
  std::size_t Offset[3] = { 0, 0, 0 };

  std::int64_t Length(int a) const { return this->Hi[a] - this->Lo[a]; }
  // The bin of index i along axis a, and the first index of bin b.
  std::int64_t BinOf(int a, std::int64_t i) const
  {
    return (i - this->Lo[a]) * this->Bins[a] / this->Length(a);
  }
  std::int64_t StartOf(int a, std::int64_t b) const
  {
    return this->Lo[a] + (b * this->Length(a) + this->Bins[a] - 1) / this->Bins[a];
  }
};

// The best cut of `box` along axis a: the bin boundary whose count below
// comes nearest to `target` (the first on a tie), and how far it misses.
std::pair<std::int64_t, long double> BestCut(
  const Pending& box, int a, const std::vector<long long>& histogram, long double target)
{
  std::int64_t best = 1;
  long double bestGap = -1.0L;
  long long below = 0;
  for (std::int64_t b = 1; b < box.Bins[a]; ++b)
  {
    below += histogram[box.Offset[a] + static_cast<std::size_t>(b - 1)];
    const long double gap = std::fabs(static_cast<long double>(below) - target);
    if (bestGap < 0.0L || gap < bestGap)
    {
      bestGap = gap;
      best = b;
    }
  }
  return { best, bestGap };
}
} // namespace

CellPartition MakeCellPartition(const GridSpec& grid, int processes, Coordinates xyz, IdView ids,
  const std::function<void(std::vector<long long>&)>& sum, const Execution& execution)
{
  CellPartition partition;
  partition.Grid = grid;
  partition.Nodes.emplace_back(); // the root: a leaf of rank 0 until cut
  std::vector<Pending> level;
  {
    Pending root;
    for (int a = 0; a < 3; ++a)
    {
      root.Hi[a] = grid.Dims[a];
    }
    root.Count = std::max(1, processes);
    level.push_back(root);
  }
  std::vector<int> pendingOf; // per node: its index in `level` (-1: none)
  while (!level.empty())
  {
    // The boxes that can be cut (two processes or more, two cells or more
    // along the longest side), their counts laid end to end.
    std::vector<Pending> cut;
    std::size_t counts = 0;
    for (Pending p : level)
    {
      partition.Nodes[p.Node].Rank = p.First;
      if (p.Count < 2)
      {
        continue;
      }
      bool cuttable = false;
      for (int a = 0; a < 3; ++a)
      {
        p.Bins[a] = p.Length(a) < 2 ? 0 : std::min(p.Length(a), MaxBins);
        p.Offset[a] = counts;
        counts += static_cast<std::size_t>(p.Bins[a]);
        cuttable = cuttable || p.Bins[a] > 0;
      }
      if (cuttable)
      {
        cut.push_back(p);
      }
    }
    if (cut.empty())
    {
      break;
    }
    pendingOf.assign(partition.Nodes.size(), -1);
    for (std::size_t k = 0; k < cut.size(); ++k)
    {
      pendingOf[cut[k].Node] = static_cast<int>(k);
    }
    // (Fixed blocks of the points, each with its own counts, added up:
    // integers, so the same counts whatever the thread count. At most
    // 4 bytes per point of counts.)
    const auto n = static_cast<Index>(ids.size());
    const Index blocks = std::max<Index>(1,
      std::min<Index>(
        selection::BlockCount(n, Index(1) << 16), n / (2 * static_cast<Index>(counts) + 1)));
    std::vector<std::vector<long long>> partial(static_cast<std::size_t>(blocks));
    execution.Run(0, blocks, [&](Index first, Index last) {
      for (Index b = first; b < last; ++b)
      {
        std::vector<long long>& counted = partial[static_cast<std::size_t>(b)];
        counted.assign(counts, 0);
        for (Index j = selection::BlockBegin(n, blocks, b);
             j < selection::BlockBegin(n, blocks, b + 1); ++j)
        {
          double p[3];
          xyz.Get(ids[j], p);
          std::int64_t ijk[3];
          partition.CellOfPoint(p, ijk);
          const int node = partition.LeafOf(ijk);
          if (pendingOf[node] >= 0)
          {
            const Pending& box = cut[pendingOf[node]];
            for (int a = 0; a < 3; ++a)
            {
              if (box.Bins[a] > 0)
              {
                ++counted[box.Offset[a] + static_cast<std::size_t>(box.BinOf(a, ijk[a]))];
              }
            }
          }
        }
      }
    });
    std::vector<long long> histogram(counts, 0);
    for (const std::vector<long long>& counted : partial)
    {
      for (std::size_t c = 0; c < counts; ++c)
      {
        histogram[c] += counted[c];
      }
    }
    if (sum)
    {
      sum(histogram);
    }
    // Each box is cut across its longest side, unless a cut across another
    // side comes nearer to the low side's share by more than 1 % of the
    // box's points (a thin part of the cloud, few cells across): then
    // across the side whose cut comes nearest.
    std::vector<Pending> next;
    for (const Pending& box : cut)
    {
      const int low = box.Count / 2;
      int longest = 0;
      for (int a = 1; a < 3; ++a)
      {
        longest = box.Length(a) > box.Length(longest) ? a : longest;
      }
      long long total = 0;
      for (std::int64_t b = 0; b < box.Bins[longest]; ++b)
      {
        total += histogram[box.Offset[longest] + static_cast<std::size_t>(b)];
      }
      const long double target = static_cast<long double>(total) * low / box.Count;
      int axis = longest;
      auto [best, gap] = BestCut(box, longest, histogram, target);
      int other = -1; // the other side whose cut comes nearest
      std::pair<std::int64_t, long double> otherCut;
      for (int a = 0; a < 3; ++a)
      {
        if (a != longest && box.Bins[a] > 0)
        {
          const auto c = BestCut(box, a, histogram, target);
          if (other < 0 || c.second < otherCut.second)
          {
            other = a;
            otherCut = c;
          }
        }
      }
      if (other >= 0 && otherCut.second + 0.01L * total < gap)
      {
        axis = other;
        best = otherCut.first;
      }
      Pending lowBox = box;
      Pending highBox = box;
      const std::int64_t split = box.StartOf(axis, best);
      lowBox.Hi[axis] = split;
      highBox.Lo[axis] = split;
      lowBox.Count = low;
      highBox.First = box.First + low;
      highBox.Count = box.Count - low;
      lowBox.Node = static_cast<int>(partition.Nodes.size());
      highBox.Node = lowBox.Node + 1;
      CellPartition::Node& n = partition.Nodes[box.Node];
      n.Axis = axis;
      n.Split = split;
      n.Low = lowBox.Node;
      n.High = highBox.Node;
      partition.Nodes.emplace_back();
      partition.Nodes.emplace_back();
      next.push_back(lowBox);
      next.push_back(highBox);
    }
    level.swap(next);
  }
  return partition;
}
} // namespace asmcore
