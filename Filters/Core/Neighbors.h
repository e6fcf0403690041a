// SPDX-License-Identifier: BSD-3-Clause
/**
 * Nearest-neighbour queries on a point cloud: a static kd-tree, built once
 * and queried many times (k nearest, nearest, within a radius). Used by the
 * key point error and the curvature estimate, which look up neighbourhoods
 * in the original cloud.
 *
 * Layout: the points (coordinates and id: 32 bytes each, 16 for a float
 * cloud, see Neighbors) are copied into one array, reordered so that every
 * node covers a contiguous range of it; the nodes live in a second flat
 * array (left child right after its parent). No
 * per-node allocation, and a leaf is scanned in a single sweep of memory.
 * The tree does not refer to the caller's arrays after Build().
 *
 * Build: the points are first grouped (a parallel stable counting sort) into
 * the cells of a grid of up to 4096 buckets over the cloud's box, made as if
 * the longest side were halved again and again, so that the cells nest as
 * binary midpoint splits and a Morton order of the cells lists every split's
 * halves as contiguous ranges: the top levels of the tree in one pass over
 * memory. Each bucket's subtree is then built depth first by one thread
 * while its points are in cache, the same way with grids of up to 256
 * buckets (one counting pass that also takes the buckets' bounds, then the
 * points regrouped through a spare array, or in place for ranges of more
 * than SpareSize points), down to leaves of at most LeafSize points. A split
 * that would keep more than 3/4 of a range in one bucket (clustered data),
 * or a box too thin to divide, is made at the median instead: along the
 * axis of largest extent, on (coordinate, id), around the median of 63
 * evenly spaced entries in one partition pass (at the exact median,
 * std::nth_element, when that leaves either half with less than 3/8). So a
 * level keeps at most 3/4 of a range whatever the data, and the depth is at
 * most log(N / LeafSize) / log(4/3) + 1 grids (and MaxDepth). The answers
 * do not depend on where the splits fall. A range whose points
 * all coincide becomes one leaf, sorted by id, whatever its size: a cloud of
 * a million identical points is a single leaf, and a k-nearest query on it
 * reads k + 1 of them (all share one distance and the scan stops at the
 * first point that cannot enter the result).
 *
 * Complexity (N points, k neighbours, m points reported):
 *  - Build: O(N log N) time (about log_256(N / LeafSize) + 1 counting passes
 *    per point, all but the first in cache; the buckets' subtrees are built
 *    in parallel; the tree is the same whatever the thread count). Memory:
 *    32 N bytes of points (16 N for a float cloud) + about N / 10 nodes of
 *    56 bytes (under 40 bytes per point in all, 24 for a float cloud), and
 *    while building, a spare array of at most SpareSize points per thread.
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

#include <cstdint>

namespace asmcore
{
/// The order of every answer: (squared distance d1, id1) comes before
/// (d2, id2) when nearer, or as near with a smaller id.
inline bool NeighborPrecedes(double d1, Index id1, double d2, Index id2)
{
  return d1 < d2 || (d1 == d2 && id1 < id2);
}

/// One nearest point: its id and (not squared) distance.
struct VTKASMFILTERS_EXPORT NearestPoint
{
  Index Id = -1;         ///< -1 when the tree is empty or the query is not finite
  double Distance = 0.0; ///< +infinity when Id == -1
};

/// The limits of the tree (Neighbors and its two layouts).
struct VTKASMFILTERS_EXPORT NeighborsLimits
{
  /// Most points in a leaf (ranges of coincident points excepted, and
  /// ranges at MaxDepth); a grid split leaves 1 to LeafSize points per leaf.
  /// Of 24 to 128, 64 built fastest and answered k = 20 queries about as
  /// fast as 128 (4 M points on a surface).
  static constexpr Index LeafSize = 64;
  /// Depth bound in splits (each a grid of buckets or a median split), a
  /// safeguard: splits that keep at most 3/4 of a range reach it only
  /// beyond 2^44 points; a range at this depth is one leaf.
  static constexpr int MaxDepth = 96;
  /// Ranges of at most this many points are split through a spare array.
  static constexpr Index SpareSize = Index(1) << 16;
};

/// One point of a tree: a copy of its coordinates and its id. Wide: doubles
/// and 64-bit ids (32 bytes); compact: the floats of a float cloud and
/// 32-bit ids (16 bytes), for a cloud whose ids all fit.
struct WideEntry
{
  double P[3];
  Index Id;
};
struct CompactEntry
{
  float P[3];
  std::int32_t Id;
};

/// The kd-tree itself, over entries of one layout (see Neighbors, which
/// picks the layout; the answers are the same in both, as the distances are
/// computed in double from the same numbers).
template <typename EntryType>
class BasicNeighbors : public NeighborsLimits
{
public:
  using Entry = EntryType;
  void Build(Coordinates xyz, IdView ids, const Execution& execution);
  Index Size() const { return static_cast<Index>(this->Points.size()); }
  bool Empty() const { return this->Points.empty(); }
  /// The entries, in tree order.
  const std::vector<Entry>& Entries() const { return this->Points; }
  /// Offers the result set (see Neighbors.cxx) every entry it may accept.
  template <typename Result>
  void Search(const double p[3], Result& result) const;

private:
  /// A node: a contiguous range of Points. Inner nodes split it in two
  /// contiguous parts along Axis, every left coordinate <= LowMax and every
  /// right one >= HighMin; the left child is the next node, the right child
  /// is node Right.
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
  struct Piece;
  struct Scratch;
  void BuildTask(const Task& task, Piece& piece, Scratch& scratch);
  void SplitNodes(const Task& task, const Scratch& scratch, Piece& piece);
  void MedianSplit(const Task& task, Piece& piece);
  static bool Splits(const Task& task);
  Node Leaf(const Task& task);
  int AddChild(const Task& task, Index begin, Index end, const double lo[3], const double hi[3],
    Index minId, Piece& piece);
  void BuildSubtree(const Task& task, std::vector<Node>& out, Scratch& scratch);
  template <typename Pending>
  Index Emit(const Piece& piece, int local, std::vector<Node>& out, const Pending& pending);
  template <typename Result>
  void SearchNode(Index node, const double p[3], double rd, double off[3], Result& result) const;

  std::vector<Entry> Points;
  std::vector<Node> Nodes; ///< Nodes[0] is the root (when not empty)
  double BoxMin[3] = { 0, 0, 0 };
  double BoxMax[3] = { 0, 0, 0 };
};

/// A static kd-tree over the points xyz[id], id in ids. A float cloud whose
/// ids fit in 32 bits gets the compact layout (16 bytes per point instead
/// of 32); the answers do not depend on the layout.
class VTKASMFILTERS_EXPORT Neighbors : public NeighborsLimits
{
public:
  /// An empty tree: every query returns nothing.
  Neighbors() = default;
  /// Same as Build(xyz, ids, execution).
  Neighbors(Coordinates xyz, IdView ids, const Execution& execution = {});

  /// (Re)build the tree over the points xyz[id], id in ids, which must be
  /// finite (see FinitePointIds). Ids need not be sorted or contiguous;
  /// listing an id twice makes two (coincident) entries. The tree is built
  /// level by level, the nodes of a level in parallel (`execution`); it is
  /// the same whatever the thread count.
  void Build(Coordinates xyz, IdView ids, const Execution& execution = {});

  /// Number of points in the tree.
  Index Size() const { return this->Compact.Size() + this->Wide.Size(); } // (one is empty)
  bool Empty() const { return this->Size() == 0; }
  /// Whether the tree holds the compact layout (floats and 32-bit ids; an
  /// empty tree holds neither).
  bool HasCompactLayout() const { return !this->Compact.Empty(); }

  /// The min(k, Size()) points nearest p, sorted by squared distance then by
  /// id, in `ids` and `sqDist` (resized; their capacity is reused, so a
  /// thread querying in a loop does not allocate). k <= 0, an empty tree or
  /// a non-finite p give empty results.
  void KNearest(
    const double p[3], int k, std::vector<Index>& ids, std::vector<double>& sqDist) const;

  /// Same, and the points' coordinates in `xyz` (3 per id, side by side):
  /// the tree's own copies, the same numbers as the cloud's (a float
  /// cloud's widened), read without touching the cloud.
  void KNearest(const double p[3], int k, std::vector<Index>& ids, std::vector<double>& sqDist,
    std::vector<double>& xyz) const;

  /// The min(k, Size()) points nearest p as KNearest (with coordinates), but
  /// points as near as each other ordered by position (x, then y, then z,
  /// then id), the choice among those as near as the k-th included: the
  /// answer does not depend on the points' ids, i.e. on the order the cloud
  /// came in, even on gridded clouds where many points are equally near.
  /// One more point than k is searched, and every point as near as the
  /// k-th only when that one is as near.
  void KNearestByPosition(const double p[3], int k, std::vector<Index>& ids,
    std::vector<double>& sqDist, std::vector<double>& xyz) const;

  /// The point nearest p (ties: the smaller id).
  NearestPoint Nearest(const double p[3]) const;

  /// The points within distance r of p (squared distance <= r * r), sorted
  /// by squared distance then id. r < 0, an empty tree or a non-finite p or
  /// r give an empty result.
  void Radius(const double p[3], double r, std::vector<Index>& ids) const;
  /// Same, with the squared distances.
  void Radius(
    const double p[3], double r, std::vector<Index>& ids, std::vector<double>& sqDist) const;
  /// Same, with the squared distances and the coordinates (as KNearest).
  void Radius(const double p[3], double r, std::vector<Index>& ids, std::vector<double>& sqDist,
    std::vector<double>& xyz) const;
  /// Same, but of the points at one position (as the tree keeps them
  /// together: a leaf of coincident points) only the k of smallest id: the
  /// others are never among any query's k nearest by distance, position
  /// then id (KNearestByPosition). What candidates for such queries need,
  /// without reading every copy of a many-times repeated point.
  void RadiusForKNearest(const double p[3], double r, int k, std::vector<Index>& ids,
    std::vector<double>& sqDist, std::vector<double>& xyz) const;

private:
  BasicNeighbors<WideEntry> Wide;
  BasicNeighbors<CompactEntry> Compact; ///< (at most one of the two is filled)
};
} // namespace asmcore

#endif
