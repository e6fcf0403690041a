// SPDX-License-Identifier: BSD-3-Clause
/**
 * Nearest-neighbour queries on a point cloud: a static kd-tree, built once
 * and queried many times (k nearest, nearest, within a radius). Used by the
 * key point error and the curvature estimate, which look up neighbourhoods
 * in the original cloud.
 *
 * Layout: the points (coordinates and id, 32 bytes each) are copied into one
 * array, reordered so that every node covers a contiguous range of it; the
 * nodes live in a second flat array (left child right after its parent). No
 * per-node allocation, and a leaf is scanned in a single sweep of memory.
 * The tree does not refer to the caller's arrays after Build().
 *
 * Splits are on (coordinate, id) along the axis of largest extent, around
 * the median of 63 evenly spaced entries of the range, in one partition pass
 * that also takes the two halves' bounds; a split that would leave either
 * half with less than 3/8 of the range is made at the exact median
 * (std::nth_element) instead. So each split keeps at most 5/8 of its range
 * whatever the data: the depth is at most log(N / LeafSize) / log(8/5) + 1
 * (and MaxDepth). The answers do not depend on where the splits fall. A range whose points
 * all coincide becomes one leaf, sorted by id, whatever its size: a cloud of
 * a million identical points is a single leaf, and a k-nearest query on it
 * reads k + 1 of them (all share one distance and the scan stops at the
 * first point that cannot enter the result).
 *
 * Complexity (N points, k neighbours, m points reported):
 *  - Build: O(N log N) time (one partition pass per level, which takes the
 *    children's bounds too; the nodes of a level are built in parallel); memory: 32 N bytes of points + fewer than 4 N / LeafSize
 *    nodes of 56 bytes (under 39 bytes per point in all).
 *  - KNearest / Nearest: O(log N + k log k) expected for points sampled
 *    from a surface or volume; O(N log N) when k >= N (all points, sorted).
 *  - Radius: O(log N + m log m) expected.
 * Worst cases of kd-trees (e.g. a query far from a degenerate cloud, or
 * many points at exactly the same distance) visit more leaves, at worst all
 * of them (O(N) distance evaluations), but stay correct.
 *
 * Queries are const and use no shared mutable state: any number of threads
 * may query one tree at once (each with its own output vectors).
 *
 * Results are deterministic: sorted by squared distance, ties broken by the
 * smaller point id, independent of the tree's shape.
 */
#ifndef asm_core_Neighbors_h
#define asm_core_Neighbors_h

#include "Common.h"

namespace asmcore
{
/// One nearest point: its id and (not squared) distance.
struct VTKASMFILTERS_EXPORT NearestPoint
{
  Index Id = -1;         ///< -1 when the tree is empty or the query is not finite
  double Distance = 0.0; ///< +infinity when Id == -1
};

/// A static kd-tree over the points xyz[3*id], id in ids.
class VTKASMFILTERS_EXPORT Neighbors
{
public:
  /// Most points in a leaf (ranges of coincident points excepted); leaves
  /// hold LeafSize / 2 to LeafSize points. Of 12 to 64, 32 answered k = 20
  /// queries fastest (and builds faster than smaller leaves).
  static constexpr Index LeafSize = 32;
  /// Depth bound, a safeguard: median splits reach it only beyond 2^52 points.
  static constexpr int MaxDepth = 48;

  /// An empty tree: every query returns nothing.
  Neighbors() = default;
  /// Same as Build(xyz, ids, execution).
  Neighbors(const double* xyz, const std::vector<Index>& ids, const Execution& execution = {});

  /// (Re)build the tree over the points xyz[3*id], id in ids, which must be
  /// finite (see FinitePointIds). Ids need not be sorted or contiguous;
  /// listing an id twice makes two (coincident) entries. The tree is built
  /// level by level, the nodes of a level in parallel (`execution`); it is
  /// the same whatever the thread count.
  void Build(const double* xyz, const std::vector<Index>& ids, const Execution& execution = {});

  /// Number of points in the tree.
  Index Size() const { return static_cast<Index>(this->Points.size()); }
  bool Empty() const { return this->Points.empty(); }

  /// The min(k, Size()) points nearest p, sorted by squared distance then by
  /// id, in `ids` and `sqDist` (resized; their capacity is reused, so a
  /// thread querying in a loop does not allocate). k <= 0, an empty tree or
  /// a non-finite p give empty results.
  void KNearest(
    const double p[3], int k, std::vector<Index>& ids, std::vector<double>& sqDist) const;

  /// The point nearest p (ties: the smaller id).
  NearestPoint Nearest(const double p[3]) const;

  /// The points within distance r of p (squared distance <= r * r), sorted
  /// by squared distance then id. r < 0, an empty tree or a non-finite p or
  /// r give an empty result.
  void Radius(const double p[3], double r, std::vector<Index>& ids) const;
  /// Same, with the squared distances.
  void Radius(
    const double p[3], double r, std::vector<Index>& ids, std::vector<double>& sqDist) const;

private:
  /// One point of the tree: a copy of its coordinates and its id.
  struct Entry
  {
    double P[3];
    Index Id;
  };
  /// A node: a contiguous range of Points. Inner nodes split it at
  /// [Begin, Begin + (End - Begin) / 2) | [..., End) along Axis; the left
  /// child is the next node, the right child is node Right.
  struct Node
  {
    Index Begin = 0;
    Index End = 0;
    Index Right = -1;        ///< -1 for a leaf
    Index MinId = 0;         ///< smallest point id in the range (for tie pruning)
    double LowMax = 0.0;     ///< inner: largest coordinate along Axis in the left child
    double HighMin = 0.0;    ///< inner: smallest coordinate along Axis in the right child
    int Axis = 0;            ///< inner: split axis
    bool Coincident = false; ///< leaf: all its points coincide; sorted by id
  };

  struct Task;
  struct Built;
  void BuildTask(const Task& task, Built& built, Task children[2], bool& split);
  Index EmitDepthFirst(const std::vector<Built>& built, Index b);
  template <typename Result>
  void Search(const double p[3], Result& result) const;
  template <typename Result>
  void SearchNode(Index node, const double p[3], double rd, double off[3], Result& result) const;

  std::vector<Entry> Points;
  std::vector<Node> Nodes; ///< Nodes[0] is the root (when not empty)
  double BoxMin[3] = { 0, 0, 0 };
  double BoxMax[3] = { 0, 0, 0 };
};
} // namespace asmcore

#endif
