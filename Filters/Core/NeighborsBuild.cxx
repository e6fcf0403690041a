// SPDX-License-Identifier: BSD-3-Clause
// The build of the kd-tree of Neighbors.h (the queries are in Neighbors.cxx).
#include "Neighbors.h"

#include "Grid.h"
#include "GroupBy.h"
#include "NeighborsRanges.h"
#include "SpatialBuckets.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <utility>

namespace asmcore
{
using buckets::BucketSet;
using buckets::LargestBucket;
using buckets::SplitPlan;
using kdranges::LoadEntry;
using kdranges::PartitionWithBounds;
using kdranges::RangeBounds;

Neighbors::Neighbors(Coordinates xyz, IdView ids, const Execution& execution)
{
  this->Build(xyz, ids, execution);
}

/// A range of points waiting to become a node, with its bounds.
template <typename E>
struct BasicNeighbors<E>::Task
{
  Index Begin = 0;
  Index End = 0;
  int Depth = 0;
  double Lo[3] = { 0, 0, 0 };
  double Hi[3] = { 0, 0, 0 };
  Index MinId = 0;
};

/// What one task makes: a small binary subtree (node 0 is the task's own
/// node; children are local indices) whose leaves are either leaves of the
/// tree or ranges left to split further (Pending >= 0: the index of their
/// task in Children).
template <typename E>
struct BasicNeighbors<E>::Piece
{
  struct Local
  {
    Node Value;
    int Left = -1;
    int Right = -1;
    int Pending = -1;
  };
  std::vector<Local> Nodes;
  std::vector<Task> Children;
};

/// Per-thread scratch of the build: reused, so that the many small ranges
/// near the leaves allocate nothing.
template <typename E>
struct BasicNeighbors<E>::Scratch
{
  SplitPlan Plan;
  BucketSet Buckets;
  std::vector<Piece> Pieces = std::vector<Piece>(MaxDepth + 2); // one per depth
  std::vector<std::uint8_t> Bucket; // of each entry of the range being split
  std::vector<Entry> Spare;         // the range, bucket by bucket, before it is copied back
};

template <typename E>
void BasicNeighbors<E>::Build(Coordinates xyz, IdView ids, const Execution& execution)
{
  this->Points.clear();
  this->Nodes.clear();
  const Index n = static_cast<Index>(ids.size());
  if (n == 0)
  {
    return;
  }
  Task root;
  root.End = n;
  const Bounds bounds = ComputeBounds(xyz, ids, execution);
  std::copy(bounds.Min, bounds.Min + 3, root.Lo);
  std::copy(bounds.Max, bounds.Max + 3, root.Hi);
  root.MinId = *std::min_element(ids.begin(), ids.end());
  std::copy(root.Lo, root.Lo + 3, this->BoxMin);
  std::copy(root.Hi, root.Hi + 3, this->BoxMax);

  // The root's split is made while the points are copied in: a parallel
  // stable counting sort of the points by bucket (up to 4096 of them). Then
  // the subtree of each bucket is built depth first by one thread, while
  // its points are in cache, into its own array; last, the root's nodes
  // and the subtrees are laid out depth first (the left child right after
  // its parent).
  Piece top;
  std::vector<std::vector<Node>> subtrees; // by bucket when byBucket, else by child of top
  bool byBucket = false;
  Scratch rootScratch;
  SplitPlan& plan = rootScratch.Plan;
  const bool spatial = n > LeafSize &&
    (root.Lo[0] < root.Hi[0] || root.Lo[1] < root.Hi[1] || root.Lo[2] < root.Hi[2]) &&
    plan.Make(root.Lo, root.Hi, n, LeafSize, SplitPlan::MostBits);
  BucketSet& buckets = rootScratch.Buckets;
  if (spatial)
  {
    buckets.Reset(plan.Buckets());
    GroupBy(
      n, plan.Buckets(),
      [&](Index i) {
        double p[3];
        xyz.Get(ids[i], p);
        return plan.BucketOf(p);
      },
      [&](Index i) { return LoadEntry<Entry>(xyz, ids[i]); }, buckets.Start, this->Points,
      execution);
  }
  else
  {
    this->Points.resize(ids.size());
    execution.Run(0, n, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i)
      {
        this->Points[i] = LoadEntry<Entry>(xyz, ids[i]);
      }
    });
  }
  if (spatial && 4 * LargestBucket(buckets) <= 3 * n)
  {
    byBucket = true;
    subtrees.resize(static_cast<std::size_t>(plan.Buckets()));
    execution.Run(0, plan.Buckets(), [&](Index b, Index e) {
      Scratch scratch;
      for (Index k = b; k < e; ++k)
      {
        if (buckets.Count(k) == 0)
        {
          continue;
        }
        Task task;
        task.Begin = buckets.Start[k];
        task.End = buckets.Start[k + 1];
        task.Depth = root.Depth + 1;
        RangeBounds(this->Points.data(), task.Begin, task.End, task.Lo, task.Hi, task.MinId);
        std::copy(task.Lo, task.Lo + 3, &buckets.Lo[3 * k]);
        std::copy(task.Hi, task.Hi + 3, &buckets.Hi[3 * k]);
        buckets.MinId[k] = task.MinId;
        if (Splits(task))
        {
          this->BuildSubtree(task, subtrees[k], scratch);
        }
      }
    });
    top.Nodes.emplace_back();
    Node& node = top.Nodes[0].Value;
    node.Begin = 0;
    node.End = n;
    node.MinId = root.MinId;
    this->SplitNodes(root, rootScratch, top);
  }
  else
  {
    // Clustered, tiny or coincident: the root splits at the median.
    this->BuildTask(root, top, rootScratch);
    subtrees.resize(top.Children.size());
    execution.Run(0, static_cast<Index>(top.Children.size()), [&](Index b, Index e) {
      Scratch scratch;
      for (Index k = b; k < e; ++k)
      {
        this->BuildSubtree(top.Children[k], subtrees[k], scratch);
      }
    });
  }
  this->Nodes.clear();
  this->Nodes.reserve(top.Nodes.size() +
    std::accumulate(subtrees.begin(), subtrees.end(), std::size_t(0),
      [](std::size_t sum, const std::vector<Node>& t) { return sum + t.size(); }));
  this->Emit(top, 0, this->Nodes, [&](int k) {
    // A subtree laid out on its own: its right-child links move by `base`.
    std::size_t which = static_cast<std::size_t>(k);
    if (byBucket)
    {
      which = static_cast<std::size_t>(
        std::upper_bound(buckets.Start.begin(), buckets.Start.end(), top.Children[which].Begin) -
        buckets.Start.begin() - 1);
    }
    const auto base = static_cast<Index>(this->Nodes.size());
    for (Node node : subtrees[which])
    {
      node.Right += node.Right >= 0 ? base : 0;
      this->Nodes.push_back(node);
    }
    std::vector<Node>().swap(subtrees[which]);
  });
}

template <typename E>
void BasicNeighbors<E>::BuildSubtree(const Task& task, std::vector<Node>& out, Scratch& scratch)
{
  Piece& piece = scratch.Pieces[static_cast<std::size_t>(task.Depth)];
  piece.Nodes.clear();
  piece.Children.clear();
  this->BuildTask(task, piece, scratch);
  this->Emit(piece, 0, out,
    [&](int k) { this->BuildSubtree(piece.Children[static_cast<std::size_t>(k)], out, scratch); });
}

template <typename E>
template <typename Pending>
Index BasicNeighbors<E>::Emit(
  const Piece& piece, int local, std::vector<Node>& out, const Pending& pending)
{
  const auto self = static_cast<Index>(out.size());
  const typename Piece::Local& node = piece.Nodes[static_cast<std::size_t>(local)];
  if (node.Pending >= 0)
  {
    pending(node.Pending);
    return self;
  }
  out.push_back(node.Value);
  if (node.Left >= 0)
  {
    this->Emit(piece, node.Left, out, pending); // self + 1
    const Index right = this->Emit(piece, node.Right, out, pending);
    out[static_cast<std::size_t>(self)].Right = right;
  }
  return self;
}

template <typename E>
bool BasicNeighbors<E>::Splits(const Task& task)
{
  const bool coincident =
    task.Lo[0] == task.Hi[0] && task.Lo[1] == task.Hi[1] && task.Lo[2] == task.Hi[2];
  return !coincident && task.End - task.Begin > LeafSize && task.Depth < MaxDepth;
}

template <typename E>
int BasicNeighbors<E>::AddChild(const Task& task, Index begin, Index end, const double lo[3],
  const double hi[3], Index minId, Piece& piece)
{
  Task child;
  child.Begin = begin;
  child.End = end;
  child.Depth = task.Depth + 1;
  std::copy(lo, lo + 3, child.Lo);
  std::copy(hi, hi + 3, child.Hi);
  child.MinId = minId;
  const int local = static_cast<int>(piece.Nodes.size());
  piece.Nodes.emplace_back();
  if (Splits(child))
  {
    piece.Nodes.back().Pending = static_cast<int>(piece.Children.size());
    piece.Children.push_back(child);
  }
  else
  {
    piece.Nodes.back().Value = Leaf(child);
  }
  return local;
}

template <typename E>
typename BasicNeighbors<E>::Node BasicNeighbors<E>::Leaf(const Task& task)
{
  Node node;
  node.Begin = task.Begin;
  node.End = task.End;
  node.MinId = task.MinId;
  if (task.Lo[0] == task.Hi[0] && task.Lo[1] == task.Hi[1] && task.Lo[2] == task.Hi[2])
  {
    // Coincident points: one leaf, by id, so a query can stop early.
    node.Coincident = true;
    std::sort(this->Points.data() + task.Begin, this->Points.data() + task.End,
      [](const Entry& x, const Entry& y) { return x.Id < y.Id; });
  }
  return node;
}

template <typename E>
void BasicNeighbors<E>::BuildTask(const Task& task, Piece& piece, Scratch& scratch)
{
  piece.Nodes.emplace_back();
  if (!Splits(task))
  {
    piece.Nodes[0].Value = this->Leaf(task); // only the root can be a leaf here
    return;
  }
  Node& node = piece.Nodes[0].Value;
  node.Begin = task.Begin;
  node.End = task.End;
  node.MinId = task.MinId;
  // A spatial split into up to 256 buckets: one counting pass (which takes
  // the buckets' bounds too), then the entries bucket by bucket, through a
  // spare array when the range is small enough to stay in cache, else in
  // place (American flag sort). The median split when it would leave most
  // points together (clustered data) or the box is too thin to divide.
  Entry* const points = this->Points.data();
  const Index begin = task.Begin, end = task.End, n = end - begin;
  SplitPlan& plan = scratch.Plan;
  BucketSet& buckets = scratch.Buckets;
  if (plan.Make(task.Lo, task.Hi, n, LeafSize, 8))
  {
    const int count = plan.Buckets();
    buckets.Reset(count);
    std::vector<Index>& start = buckets.Start;
    const bool spare = n <= SpareSize;
    if (spare)
    {
      scratch.Bucket.resize(static_cast<std::size_t>(n));
    }
    for (Index i = begin; i < end; ++i)
    {
      const Entry& e = points[i];
      const int b = plan.BucketOf(e.P);
      if (spare)
      {
        scratch.Bucket[static_cast<std::size_t>(i - begin)] = static_cast<std::uint8_t>(b);
      }
      ++start[b + 1];
      for (int a = 0; a < 3; ++a)
      {
        buckets.Lo[3 * b + a] = std::min(buckets.Lo[3 * b + a], static_cast<double>(e.P[a]));
        buckets.Hi[3 * b + a] = std::max(buckets.Hi[3 * b + a], static_cast<double>(e.P[a]));
      }
      buckets.MinId[b] = std::min(buckets.MinId[b], static_cast<Index>(e.Id));
    }
    start[0] = begin;
    for (int b = 0; b < count; ++b)
    {
      start[b + 1] += start[b];
    }
    if (4 * LargestBucket(buckets) <= 3 * n)
    {
      Index fill[1 << 8];
      std::copy(start.begin(), start.end() - 1, fill);
      if (spare)
      {
        scratch.Spare.resize(static_cast<std::size_t>(n));
        for (Index i = begin; i < end; ++i)
        {
          scratch.Spare[static_cast<std::size_t>(fill[scratch.Bucket[i - begin]]++ - begin)] =
            points[i];
        }
        std::copy(scratch.Spare.begin(), scratch.Spare.begin() + n, points + begin);
      }
      else
      {
        for (int b = 0; b < count; ++b)
        {
          while (fill[b] < start[b + 1])
          {
            Entry carried = points[fill[b]];
            int target = plan.BucketOf(carried.P);
            while (target != b)
            {
              std::swap(carried, points[fill[target]++]);
              target = plan.BucketOf(carried.P);
            }
            points[fill[b]++] = carried;
          }
        }
      }
      this->SplitNodes(task, scratch, piece);
      return;
    }
  }
  this->MedianSplit(task, piece);
}

template <typename E>
void BasicNeighbors<E>::SplitNodes(const Task& task, const Scratch& scratch, Piece& piece)
{
  // The binary nodes over buckets [bl, bh), split on the axis of bit j of
  // the bucket index; node 0 is the task's own (it always splits: no bucket
  // holds every point). Empty halves are skipped.
  const SplitPlan& plan = scratch.Plan;
  const BucketSet& buckets = scratch.Buckets;
  const std::vector<Index>& start = buckets.Start;
  std::function<int(int, int, int, int)> make = [&](int bl, int bh, int j, int self) -> int {
    if (bh - bl == 1)
    {
      const auto corner = static_cast<std::size_t>(3) * static_cast<std::size_t>(bl);
      return this->AddChild(task, start[bl], start[bh], &buckets.Lo[corner], &buckets.Hi[corner],
        buckets.MinId[bl], piece);
    }
    const int half = (bl + bh) / 2;
    if (start[half] == start[bl] || start[bh] == start[half])
    {
      return start[half] == start[bl] ? make(half, bh, j + 1, self) : make(bl, half, j + 1, self);
    }
    const int local = self >= 0 ? self : static_cast<int>(piece.Nodes.size());
    if (self < 0)
    {
      piece.Nodes.emplace_back();
    }
    const int axis = plan.Sequence[j];
    Node value;
    value.Begin = start[bl];
    value.End = start[bh];
    value.Axis = axis;
    value.LowMax = -std::numeric_limits<double>::infinity();
    value.HighMin = std::numeric_limits<double>::infinity();
    value.MinId = std::numeric_limits<Index>::max();
    for (int b = bl; b < bh; ++b)
    {
      if (buckets.Count(b) > 0)
      {
        value.MinId = std::min(value.MinId, buckets.MinId[b]);
        if (b < half)
        {
          value.LowMax = std::max(value.LowMax, buckets.Hi[3 * b + axis]);
        }
        else
        {
          value.HighMin = std::min(value.HighMin, buckets.Lo[3 * b + axis]);
        }
      }
    }
    const int left = make(bl, half, j + 1, -1);
    const int right = make(half, bh, j + 1, -1);
    piece.Nodes[local].Value = value;
    piece.Nodes[local].Left = left;
    piece.Nodes[local].Right = right;
    return local;
  };
  make(0, plan.Buckets(), 0, 0);
}

template <typename E>
void BasicNeighbors<E>::MedianSplit(const Task& task, Piece& piece)
{
  // Split on (coordinate, id) along the longest axis, so that the halves
  // are ordered even when many points share a coordinate: around the median
  // of an evenly spaced sample of the range, in one partition pass that also
  // takes the halves' bounds; when that leaves either half with fewer than
  // 3/8 of the points, at the exact median (nth_element) instead.
  Entry* const points = this->Points.data();
  const Index begin = task.Begin, end = task.End, n = end - begin;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (task.Hi[a] - task.Lo[a] > task.Hi[axis] - task.Lo[axis])
    {
      axis = a;
    }
  }
  auto less = [axis](const Entry& x, const Entry& y) {
    return x.P[axis] < y.P[axis] || (x.P[axis] == y.P[axis] && x.Id < y.Id);
  };
  Task left, right;
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
  Node& node = piece.Nodes[0].Value;
  node.Axis = axis;
  node.LowMax = left.Hi[axis];
  node.HighMin = right.Lo[axis];
  const int l = this->AddChild(task, begin, mid, left.Lo, left.Hi, left.MinId, piece);
  const int r = this->AddChild(task, mid, end, right.Lo, right.Hi, right.MinId, piece);
  piece.Nodes[0].Left = l;
  piece.Nodes[0].Right = r;
}
void Neighbors::Build(Coordinates xyz, IdView ids, const Execution& execution)
{
  // The compact layout when it holds the same numbers: floats, ids < 2^31.
  const Index most = std::numeric_limits<std::int32_t>::max();
  bool compact = xyz.Floats != nullptr;
  if (compact && ids.IsIdentity())
  {
    compact = static_cast<Index>(ids.size()) - 1 <= most;
  }
  for (Index i = 0; compact && !ids.IsIdentity() && i < static_cast<Index>(ids.size()); ++i)
  {
    compact = ids[i] <= most;
  }
  this->Wide = BasicNeighbors<WideEntry>();
  this->Compact = BasicNeighbors<CompactEntry>();
  if (compact)
  {
    this->Compact.Build(xyz, ids, execution);
  }
  else
  {
    this->Wide.Build(xyz, ids, execution);
  }
}
} // namespace asmcore
