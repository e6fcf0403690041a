// SPDX-License-Identifier: BSD-3-Clause
#include "Neighbors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace asmcore
{
namespace
{
// Squared distance, always evaluated in this order: the lower bounds of the
// search (built from the same per-axis differences) then never exceed it,
// even after rounding, so no tie is pruned by mistake.
inline double SquaredDistance(const double a[3], const double b[3])
{
  const double dx = a[0] - b[0];
  const double dy = a[1] - b[1];
  const double dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

inline bool Finite(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// Result sets of the search. Each says whether an entry (d, id) would enter
// the result (Accepts) and whether a subtree whose points are at squared
// distance >= rd and have ids >= minId may hold such an entry (Visit).

// The k best entries, kept sorted by insertion into the caller's arrays:
// fastest for the small k of neighbourhood queries.
class SortedKnn
{
public:
  SortedKnn(int k, Index* ids, double* d)
    : K(k)
    , Ids(ids)
    , D(d)
  {
  }
  bool Accepts(double d, Index id) const
  {
    return this->Count < this->K || d < this->D[this->K - 1] ||
      (d == this->D[this->K - 1] && id < this->Ids[this->K - 1]);
  }
  bool Visit(double rd, Index minId) const { return this->Accepts(rd, minId); }
  void Add(double d, Index id)
  {
    int i = this->Count < this->K ? this->Count++ : this->K - 1;
    while (i > 0 && (this->D[i - 1] > d || (this->D[i - 1] == d && this->Ids[i - 1] > id)))
    {
      this->D[i] = this->D[i - 1];
      this->Ids[i] = this->Ids[i - 1];
      --i;
    }
    this->D[i] = d;
    this->Ids[i] = id;
  }
  int Count = 0;

private:
  int K;
  Index* Ids;
  double* D;
};

// The k best entries in a max-heap on (d, id): for large k.
class HeapKnn
{
public:
  explicit HeapKnn(int k)
    : K(static_cast<std::size_t>(k))
  {
    this->Heap.reserve(this->K);
  }
  bool Accepts(double d, Index id) const
  {
    return this->Heap.size() < this->K || std::make_pair(d, id) < this->Heap.front();
  }
  bool Visit(double rd, Index minId) const { return this->Accepts(rd, minId); }
  void Add(double d, Index id)
  {
    if (this->Heap.size() == this->K)
    {
      std::pop_heap(this->Heap.begin(), this->Heap.end());
      this->Heap.pop_back();
    }
    this->Heap.emplace_back(d, id);
    std::push_heap(this->Heap.begin(), this->Heap.end());
  }
  std::vector<std::pair<double, Index>> Heap;

private:
  std::size_t K;
};

// Every entry within squared distance R2.
class RadiusSet
{
public:
  explicit RadiusSet(double r2)
    : R2(r2)
  {
  }
  bool Accepts(double d, Index) const { return d <= this->R2; }
  bool Visit(double rd, Index) const { return rd <= this->R2; }
  void Add(double d, Index id) { this->Found.emplace_back(d, id); }
  std::vector<std::pair<double, Index>> Found;

private:
  double R2;
};

void Unzip(std::vector<std::pair<double, Index>>& pairs, std::vector<Index>& ids,
  std::vector<double>* sqDist)
{
  std::sort(pairs.begin(), pairs.end());
  ids.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    ids[i] = pairs[i].second;
  }
  if (sqDist)
  {
    sqDist->resize(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i)
    {
      (*sqDist)[i] = pairs[i].first;
    }
  }
}
} // namespace

Neighbors::Neighbors(const double* xyz, const std::vector<Index>& ids, const Execution& execution)
{
  this->Build(xyz, ids, execution);
}

/// A range of points waiting to become a node, with its bounds.
struct Neighbors::Task
{
  Index Begin = 0;
  Index End = 0;
  int Depth = 0;
  double Lo[3] = { 0, 0, 0 };
  double Hi[3] = { 0, 0, 0 };
  Index MinId = 0;
};

/// A node built level by level, with its children in that order.
struct Neighbors::Built
{
  Node Value;
  Index Left = -1;
  Index Right = -1;
};

namespace
{
// Bounds and smallest id of entries [begin, end) (not empty), into lo, hi.
template <typename Entry>
void RangeBounds(const Entry* points, Index begin, Index end, double lo[3], double hi[3], Index& minId)
{
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = hi[a] = points[begin].P[a];
  }
  minId = points[begin].Id;
  for (Index i = begin + 1; i < end; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], points[i].P[a]);
      hi[a] = std::max(hi[a], points[i].P[a]);
    }
    minId = std::min(minId, points[i].Id);
  }
}
// Partitions entries [begin, end) (Hoare) into those less than `pivot`
// (first) and the others, and takes the bounds and smallest id of each part
// as each entry is classified (once); returns where the second part begins.
// A part may be empty (the caller then splits at the median).
template <typename Entry, typename Less, typename Part>
Index PartitionWithBounds(
  Entry* points, Index begin, Index end, const Entry& pivot, const Less& less, Part& left, Part& right)
{
  double lo[2][3], hi[2][3]; // 0: left, 1: right (locals: kept in registers)
  Index minId[2] = { std::numeric_limits<Index>::max(), std::numeric_limits<Index>::max() };
  for (int a = 0; a < 3; ++a)
  {
    lo[0][a] = lo[1][a] = std::numeric_limits<double>::infinity();
    hi[0][a] = hi[1][a] = -std::numeric_limits<double>::infinity();
  }
  auto add = [&](int part, const Entry& e) {
    for (int a = 0; a < 3; ++a)
    {
      lo[part][a] = std::min(lo[part][a], e.P[a]);
      hi[part][a] = std::max(hi[part][a], e.P[a]);
    }
    minId[part] = std::min(minId[part], e.Id);
  };
  Index i = begin, j = end - 1;
  for (;;)
  {
    while (i <= j && less(points[i], pivot))
    {
      add(0, points[i++]);
    }
    while (i <= j && !less(points[j], pivot))
    {
      add(1, points[j--]);
    }
    if (i >= j)
    {
      break;
    }
    std::swap(points[i], points[j]);
    add(0, points[i++]);
    add(1, points[j--]);
  }
  for (int a = 0; a < 3; ++a)
  {
    left.Lo[a] = lo[0][a];
    left.Hi[a] = hi[0][a];
    right.Lo[a] = lo[1][a];
    right.Hi[a] = hi[1][a];
  }
  left.MinId = minId[0];
  right.MinId = minId[1];
  return i;
}
} // namespace

void Neighbors::Build(const double* xyz, const std::vector<Index>& ids, const Execution& execution)
{
  this->Points.clear();
  this->Nodes.clear();
  this->Points.resize(ids.size());
  const Index n = static_cast<Index>(ids.size());
  execution.Run(0, n, [&](Index b, Index e) {
    for (Index i = b; i < e; ++i)
    {
      const double* p = xyz + 3 * ids[i];
      this->Points[i] = Entry{ { p[0], p[1], p[2] }, ids[i] };
    }
  });
  if (this->Points.empty())
  {
    return;
  }
  Task root;
  root.End = n;
  RangeBounds(this->Points.data(), 0, n, root.Lo, root.Hi, root.MinId);
  std::copy(root.Lo, root.Lo + 3, this->BoxMin);
  std::copy(root.Hi, root.Hi + 3, this->BoxMax);

  // Level by level: the tasks of a level touch disjoint ranges of Points.
  std::vector<Built> built;
  std::vector<Task> level = { root };
  while (!level.empty())
  {
    const auto base = static_cast<Index>(built.size());
    const auto count = static_cast<Index>(level.size());
    built.resize(static_cast<std::size_t>(base + count));
    std::vector<Task> children(static_cast<std::size_t>(2 * count));
    std::vector<char> split(static_cast<std::size_t>(count), 0);
    execution.Run(0, count, [&](Index b, Index e) {
      for (Index t = b; t < e; ++t)
      {
        bool s = false;
        this->BuildTask(level[t], built[base + t], &children[2 * t], s);
        split[t] = s ? 1 : 0;
      }
    });
    std::vector<Task> next;
    std::vector<Index> nextParent;
    for (Index t = 0; t < count; ++t)
    {
      if (split[t])
      {
        for (int c = 0; c < 2; ++c)
        {
          next.push_back(children[2 * t + c]);
          nextParent.push_back(base + t);
        }
      }
    }
    // Children come in pairs, left first.
    const auto nextBase = static_cast<Index>(built.size());
    for (std::size_t k = 0; k < next.size(); k += 2)
    {
      built[nextParent[k]].Left = nextBase + static_cast<Index>(k);
      built[nextParent[k]].Right = nextBase + static_cast<Index>(k) + 1;
    }
    level.swap(next);
  }
  // Depth-first layout: the left child right after its parent.
  this->Nodes.reserve(built.size());
  this->EmitDepthFirst(built, 0);
}

void Neighbors::BuildTask(const Task& task, Built& built, Task children[2], bool& split)
{
  Entry* const points = this->Points.data();
  const Index begin = task.Begin, end = task.End;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (task.Hi[a] - task.Lo[a] > task.Hi[axis] - task.Lo[axis])
    {
      axis = a;
    }
  }
  Node& node = built.Value;
  node.Begin = begin;
  node.End = end;
  node.MinId = task.MinId;
  split = false;
  if (!(task.Hi[axis] - task.Lo[axis] > 0.0))
  {
    // Coincident points: one leaf, by id, so a query can stop early.
    node.Coincident = true;
    std::sort(points + begin, points + end,
      [](const Entry& x, const Entry& y) { return x.Id < y.Id; });
    return;
  }
  if (end - begin <= LeafSize || task.Depth >= MaxDepth)
  {
    return;
  }
  // Split on (coordinate, id), so that the halves are ordered even when many
  // points share a coordinate: around the median of an evenly spaced sample
  // of the range, in one partition pass that also takes the halves' bounds;
  // when that leaves either half with fewer than 3/8 of the points, at the
  // exact median (nth_element) instead. Queries are exact whatever the split.
  auto less = [axis](const Entry& x, const Entry& y) {
    return x.P[axis] < y.P[axis] || (x.P[axis] == y.P[axis] && x.Id < y.Id);
  };
  Task& left = children[0];
  Task& right = children[1];
  const Index n = end - begin;
  Index mid = -1;
  {
    constexpr Index SampleSize = 63;
    const Index m = std::min(n, SampleSize);
    Entry sample[SampleSize];
    for (Index k = 0; k < m; ++k)
    {
      sample[k] = points[begin + k * n / m];
    }
    std::nth_element(sample, sample + m / 2, sample + m, less);
    const Entry pivot = sample[m / 2];
    mid = PartitionWithBounds(points, begin, end, pivot, less, left, right);
    if (8 * (mid - begin) < 3 * n || 8 * (end - mid) < 3 * n)
    {
      mid = -1;
    }
  }
  if (mid < 0)
  {
    mid = begin + n / 2;
    std::nth_element(points + begin, points + mid, points + end, less);
    RangeBounds(points, begin, mid, left.Lo, left.Hi, left.MinId);
    RangeBounds(points, mid, end, right.Lo, right.Hi, right.MinId);
  }
  node.Axis = axis;
  node.HighMin = right.Lo[axis];
  left.Begin = begin;
  left.End = mid;
  right.Begin = mid;
  right.End = end;
  left.Depth = right.Depth = task.Depth + 1;
  node.LowMax = left.Hi[axis];
  split = true;
}

Index Neighbors::EmitDepthFirst(const std::vector<Built>& built, Index b)
{
  const auto self = static_cast<Index>(this->Nodes.size());
  this->Nodes.push_back(built[b].Value);
  if (built[b].Left >= 0)
  {
    this->EmitDepthFirst(built, built[b].Left); // self + 1
    const Index right = this->EmitDepthFirst(built, built[b].Right);
    this->Nodes[self].Right = right;
  }
  return self;
}

template <typename Result>
void Neighbors::Search(const double p[3], Result& result) const
{
  // Per-axis distance from p to the box of the current node.
  double off[3];
  for (int a = 0; a < 3; ++a)
  {
    off[a] = p[a] < this->BoxMin[a] ? this->BoxMin[a] - p[a]
      : p[a] > this->BoxMax[a]      ? p[a] - this->BoxMax[a]
                                    : 0.0;
  }
  const double rd = off[0] * off[0] + off[1] * off[1] + off[2] * off[2];
  if (result.Visit(rd, this->Nodes[0].MinId))
  {
    this->SearchNode(0, p, rd, off, result);
  }
}

template <typename Result>
void Neighbors::SearchNode(
  Index index, const double p[3], double rd, double off[3], Result& result) const
{
  const Node& node = this->Nodes[index];
  if (node.Right < 0)
  {
    const Entry* first = this->Points.data() + node.Begin;
    const Entry* last = this->Points.data() + node.End;
    if (node.Coincident)
    {
      // One distance; ids ascending: the first rejected id ends the scan.
      const double d = SquaredDistance(first->P, p);
      for (; first != last && result.Accepts(d, first->Id); ++first)
      {
        result.Add(d, first->Id);
      }
      return;
    }
    for (; first != last; ++first)
    {
      const double d = SquaredDistance(first->P, p);
      if (result.Accepts(d, first->Id))
      {
        result.Add(d, first->Id);
      }
    }
    return;
  }

  // Visit the child on p's side first, then the other one if its box may
  // still hold an entry. The far child's offset along the axis is the gap
  // between p and the child's nearest coordinate (>= the current offset).
  const int a = node.Axis;
  const bool leftFirst = p[a] - node.LowMax < node.HighMin - p[a];
  const Index nearChild = leftFirst ? index + 1 : node.Right;
  const Index farChild = leftFirst ? node.Right : index + 1;
  const double gap = leftFirst ? node.HighMin - p[a] : p[a] - node.LowMax;
  this->SearchNode(nearChild, p, rd, off, result);

  const double saved = off[a];
  off[a] = std::max(saved, gap);
  // Recomputed, not updated incrementally, so that rounding cannot raise
  // the bound above a true distance (see SquaredDistance).
  const double farRd = off[0] * off[0] + off[1] * off[1] + off[2] * off[2];
  if (result.Visit(farRd, this->Nodes[farChild].MinId))
  {
    this->SearchNode(farChild, p, farRd, off, result);
  }
  off[a] = saved;
}

void Neighbors::KNearest(
  const double p[3], int k, std::vector<Index>& ids, std::vector<double>& sqDist) const
{
  ids.clear();
  sqDist.clear();
  if (k <= 0 || this->Points.empty() || !Finite(p))
  {
    return;
  }
  if (static_cast<Index>(k) >= this->Size())
  {
    // Every point: no tree needed.
    std::vector<std::pair<double, Index>> all(this->Points.size());
    for (std::size_t i = 0; i < all.size(); ++i)
    {
      all[i] = { SquaredDistance(this->Points[i].P, p), this->Points[i].Id };
    }
    Unzip(all, ids, &sqDist);
    return;
  }
  if (k <= 32)
  {
    ids.resize(static_cast<std::size_t>(k));
    sqDist.resize(static_cast<std::size_t>(k));
    SortedKnn result(k, ids.data(), sqDist.data());
    this->Search(p, result);
    return; // k < Size(): the result is full
  }
  HeapKnn result(k);
  this->Search(p, result);
  Unzip(result.Heap, ids, &sqDist);
}

NearestPoint Neighbors::Nearest(const double p[3]) const
{
  NearestPoint nearest;
  nearest.Distance = std::numeric_limits<double>::infinity();
  if (this->Points.empty() || !Finite(p))
  {
    return nearest;
  }
  Index id = -1;
  double d = 0.0;
  SortedKnn result(1, &id, &d);
  this->Search(p, result);
  nearest.Id = id;
  nearest.Distance = std::sqrt(d);
  return nearest;
}

void Neighbors::Radius(const double p[3], double r, std::vector<Index>& ids) const
{
  std::vector<double>* noDistances = nullptr;
  ids.clear();
  if (this->Points.empty() || !Finite(p) || !(r >= 0.0) || !std::isfinite(r))
  {
    return;
  }
  RadiusSet result(r * r);
  this->Search(p, result);
  Unzip(result.Found, ids, noDistances);
}

void Neighbors::Radius(
  const double p[3], double r, std::vector<Index>& ids, std::vector<double>& sqDist) const
{
  ids.clear();
  sqDist.clear();
  if (this->Points.empty() || !Finite(p) || !(r >= 0.0) || !std::isfinite(r))
  {
    return;
  }
  RadiusSet result(r * r);
  this->Search(p, result);
  Unzip(result.Found, ids, &sqDist);
}
} // namespace asmcore
