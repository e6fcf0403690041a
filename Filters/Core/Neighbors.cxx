// SPDX-License-Identifier: BSD-3-Clause
// The queries of the kd-tree of Neighbors.h (its build: NeighborsBuild.cxx).
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
// (A float entry is widened first: the same value as in a double entry.)
template <typename Real>
inline double SquaredDistance(const Real a[3], const double b[3])
{
  const double dx = static_cast<double>(a[0]) - b[0];
  const double dy = static_cast<double>(a[1]) - b[1];
  const double dz = static_cast<double>(a[2]) - b[2];
  return dx * dx + dy * dy + dz * dz;
}

inline bool Finite(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// Result sets of the search, over the entries of one layout. Each says
// whether an entry (d, id) would enter the result (Accepts) and whether a
// subtree whose points are at squared distance >= rd and have ids >= minId
// may hold such an entry (Visit); Add takes the entry itself, so that the
// answer can give its coordinates (the tree's copy: no read of the caller's
// cloud, whose order may be random).

// The k best entries, kept sorted by insertion into arrays of the caller:
// fastest for the small k of neighbourhood queries.
template <typename Entry>
class SortedKnn
{
public:
  SortedKnn(int k, double* d, const Entry** entries)
    : K(k)
    , D(d)
    , E(entries)
  {
  }
  bool Accepts(double d, Index id) const
  {
    return this->Count < this->K ||
      NeighborPrecedes(d, id, this->D[this->K - 1], this->E[this->K - 1]->Id);
  }
  bool Visit(double rd, Index minId) const { return this->Accepts(rd, minId); }
  /// Entries a coincident leaf may give (ids ascending; see SearchNode).
  static constexpr Index CoincidentLimit() { return std::numeric_limits<Index>::max(); }
  void Add(double d, const Entry& entry)
  {
    int i = this->Count < this->K ? this->Count++ : this->K - 1;
    // Past the farther entries, then past the as near ones of larger id
    // (rare: the second loop reads ids only on exact ties).
    while (i > 0 && d < this->D[i - 1])
    {
      this->D[i] = this->D[i - 1];
      this->E[i] = this->E[i - 1];
      --i;
    }
    while (i > 0 && d == this->D[i - 1] && entry.Id < this->E[i - 1]->Id)
    {
      this->D[i] = this->D[i - 1];
      this->E[i] = this->E[i - 1];
      --i;
    }
    this->D[i] = d;
    this->E[i] = &entry;
  }
  /// Offers every entry of [first, last): the first K fill the result,
  /// the others are compared with the current k-th, kept in registers.
  void Scan(const Entry* first, const Entry* last, const double p[3])
  {
    for (; first != last && this->Count < this->K; ++first)
    {
      this->Add(SquaredDistance(first->P, p), *first);
    }
    if (first == last)
    {
      return;
    }
    double bound = this->D[this->K - 1];
    Index boundId = this->E[this->K - 1]->Id;
    for (; first != last; ++first)
    {
      const double d = SquaredDistance(first->P, p);
      if (d <= bound && NeighborPrecedes(d, first->Id, bound, boundId))
      {
        this->Add(d, *first);
        bound = this->D[this->K - 1];
        boundId = this->E[this->K - 1]->Id;
      }
    }
  }
  int Count = 0;

private:
  int K;
  double* D;
  const Entry** E;
};

// One entry of an answer, ordered by (squared distance, id).
template <typename Entry>
struct Found
{
  double D;
  Index Id;
  const Entry* E;
  bool operator<(const Found& other) const { return NeighborPrecedes(D, Id, other.D, other.Id); }
};

// Offers every entry of [first, last) to `result`: each one it accepts is
// added (the plain scan of a leaf, for the sets without a faster one).
template <typename Result, typename Entry>
void OfferEach(Result& result, const Entry* first, const Entry* last, const double p[3])
{
  for (; first != last; ++first)
  {
    const double d = SquaredDistance(first->P, p);
    if (result.Accepts(d, first->Id))
    {
      result.Add(d, *first);
    }
  }
}

// The k best entries in a max-heap on (d, id): for large k.
template <typename Entry>
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
    return this->Heap.size() < this->K ||
      NeighborPrecedes(d, id, this->Heap.front().D, this->Heap.front().Id);
  }
  bool Visit(double rd, Index minId) const { return this->Accepts(rd, minId); }
  static constexpr Index CoincidentLimit() { return std::numeric_limits<Index>::max(); }
  void Add(double d, const Entry& entry)
  {
    if (this->Heap.size() == this->K)
    {
      std::pop_heap(this->Heap.begin(), this->Heap.end());
      this->Heap.pop_back();
    }
    this->Heap.push_back({ d, entry.Id, &entry });
    std::push_heap(this->Heap.begin(), this->Heap.end());
  }
  /// Offers every entry of [first, last).
  void Scan(const Entry* first, const Entry* last, const double p[3])
  {
    OfferEach(*this, first, last, p);
  }
  std::vector<Found<Entry>> Heap;

private:
  std::size_t K;
};

// Every entry within squared distance R2; from a coincident leaf (its
// points at one position, ids ascending) the first `limit` only.
template <typename Entry>
class RadiusSet
{
public:
  explicit RadiusSet(double r2, Index limit = std::numeric_limits<Index>::max())
    : R2(r2)
    , Limit(limit)
  {
  }
  bool Accepts(double d, Index) const { return d <= this->R2; }
  bool Visit(double rd, Index) const { return rd <= this->R2; }
  Index CoincidentLimit() const { return this->Limit; }
  void Add(double d, const Entry& entry) { this->Hits.push_back({ d, entry.Id, &entry }); }
  /// Offers every entry of [first, last).
  void Scan(const Entry* first, const Entry* last, const double p[3])
  {
    OfferEach(*this, first, last, p);
  }
  std::vector<Found<Entry>> Hits;

private:
  double R2;
  Index Limit;
};

// Where an answer goes: ids, and optionally squared distances and
// coordinates (3 per id, widened to double).
struct Answer
{
  std::vector<Index>& Ids;
  std::vector<double>* SqDist;
  std::vector<double>* Xyz;

  void Clear() const
  {
    this->Ids.clear();
    if (this->SqDist)
    {
      this->SqDist->clear();
    }
    if (this->Xyz)
    {
      this->Xyz->clear();
    }
  }
  /// The n entries e(i), with their squared distances d(i).
  template <typename EntryAt, typename DistanceAt>
  void Write(std::size_t n, const EntryAt& e, const DistanceAt& d) const
  {
    this->Ids.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      this->Ids[i] = e(i)->Id;
    }
    if (this->SqDist)
    {
      this->SqDist->resize(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        (*this->SqDist)[i] = d(i);
      }
    }
    if (this->Xyz)
    {
      this->Xyz->resize(3 * n);
      for (std::size_t i = 0; i < n; ++i)
      {
        for (int a = 0; a < 3; ++a)
        {
          (*this->Xyz)[3 * i + a] = static_cast<double>(e(i)->P[a]);
        }
      }
    }
  }
  /// Found entries in any order: sorted, then written.
  template <typename Entry>
  void Write(std::vector<Found<Entry>>& found) const
  {
    std::sort(found.begin(), found.end());
    this->Write(
      found.size(), [&](std::size_t i) { return found[i].E; },
      [&](std::size_t i) { return found[i].D; });
  }
};
} // namespace

template <typename E>
template <typename Result>
void BasicNeighbors<E>::Search(const double p[3], Result& result) const
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

template <typename E>
template <typename Result>
void BasicNeighbors<E>::SearchNode(
  Index index, const double p[3], double rd, double off[3], Result& result) const
{
  const Node& node = this->Nodes[index];
  if (node.Right < 0)
  {
    const Entry* first = this->Points.data() + node.Begin;
    const Entry* last = this->Points.data() + node.End;
    if (node.Coincident)
    {
      // One distance; ids ascending: the first rejected id ends the scan,
      // and so does the result's limit.
      const double d = SquaredDistance(first->P, p);
      if (last - first > result.CoincidentLimit())
      {
        last = first + result.CoincidentLimit();
      }
      for (; first != last && result.Accepts(d, first->Id); ++first)
      {
        result.Add(d, *first);
      }
      return;
    }
    result.Scan(first, last, p);
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

namespace
{
// The queries, on a tree of either layout.
template <typename Tree>
void KNearestIn(const Tree& tree, const double p[3], int k, const Answer& answer)
{
  using Entry = typename Tree::Entry;
  answer.Clear();
  if (k <= 0 || tree.Empty() || !Finite(p))
  {
    return;
  }
  if (static_cast<Index>(k) >= tree.Size())
  {
    // Every point: no tree needed.
    const auto& entries = tree.Entries();
    std::vector<Found<Entry>> all(entries.size());
    for (std::size_t i = 0; i < all.size(); ++i)
    {
      all[i] = { SquaredDistance(entries[i].P, p), entries[i].Id, &entries[i] };
    }
    answer.Write(all);
    return;
  }
  if (k <= 32)
  {
    double d[32];
    const Entry* e[32];
    SortedKnn<Entry> result(k, d, e);
    tree.Search(p, result); // k < Size(): the result is full
    answer.Write(
      static_cast<std::size_t>(k), [&](std::size_t i) { return e[i]; },
      [&](std::size_t i) { return d[i]; });
    return;
  }
  HeapKnn<Entry> result(k);
  tree.Search(p, result);
  answer.Write(result.Heap);
}

template <typename Tree>
NearestPoint NearestIn(const Tree& tree, const double p[3])
{
  using Entry = typename Tree::Entry;
  NearestPoint nearest;
  nearest.Distance = std::numeric_limits<double>::infinity();
  if (tree.Empty() || !Finite(p))
  {
    return nearest;
  }
  double d = 0.0;
  const Entry* e = nullptr;
  SortedKnn<Entry> result(1, &d, &e);
  tree.Search(p, result);
  nearest.Id = e->Id;
  nearest.Distance = std::sqrt(d);
  return nearest;
}

template <typename Tree>
void RadiusIn(const Tree& tree, const double p[3], double r, const Answer& answer,
  Index coincidentLimit = std::numeric_limits<Index>::max())
{
  answer.Clear();
  if (tree.Empty() || !Finite(p) || !(r >= 0.0) || !std::isfinite(r))
  {
    return;
  }
  RadiusSet<typename Tree::Entry> result(r * r, coincidentLimit);
  tree.Search(p, result);
  answer.Write(result.Hits);
}
} // namespace

void Neighbors::KNearest(
  const double p[3], int k, std::vector<Index>& ids, std::vector<double>& sqDist) const
{
  const Answer answer{ ids, &sqDist, nullptr };
  this->HasCompactLayout() ? KNearestIn(this->Compact, p, k, answer)
                           : KNearestIn(this->Wide, p, k, answer);
}

void Neighbors::KNearest(const double p[3], int k, std::vector<Index>& ids,
  std::vector<double>& sqDist, std::vector<double>& xyz) const
{
  const Answer answer{ ids, &sqDist, &xyz };
  this->HasCompactLayout() ? KNearestIn(this->Compact, p, k, answer)
                           : KNearestIn(this->Wide, p, k, answer);
}

void Neighbors::KNearestByPosition(const double p[3], int k, std::vector<Index>& ids,
  std::vector<double>& sqDist, std::vector<double>& xyz) const
{
  this->KNearest(p, k < 0 ? k : k + 1, ids, sqDist, xyz);
  auto count = static_cast<Index>(ids.size());
  if (count > k && k > 0 && sqDist[k] == sqDist[k - 1])
  {
    // More points as near as the k-th: all of them, but at most k of each
    // coincident leaf (its points share one position; ids ascending): the
    // rest of such a leaf comes after its first k in any order by position
    // then id. (A cloud of n identical points: k of them, not n.)
    const double d = sqDist[k - 1];
    double r = std::sqrt(d);
    while (r * r < d)
    {
      r = std::nextafter(r, std::numeric_limits<double>::infinity());
    }
    this->RadiusForKNearest(p, r, k, ids, sqDist, xyz);
    count = static_cast<Index>(ids.size());
    while (count > 0 && sqDist[count - 1] > d)
    {
      --count;
    }
  }
  // Runs of equal distance by position (the answer is sorted by distance,
  // then id: only points as near as each other move).
  auto before = [&](Index a, Index b) { // (a and b as near)
    const double* pa = xyz.data() + 3 * a;
    const double* pb = xyz.data() + 3 * b;
    return PositionThenIdBefore(pa, ids[a], pb, ids[b]);
  };
  for (Index i = 1; i < count; ++i)
  {
    for (Index j = i; j > 0 && sqDist[j] == sqDist[j - 1] && before(j, j - 1); --j)
    {
      std::swap(ids[j], ids[j - 1]);
      std::swap(sqDist[j], sqDist[j - 1]);
      for (int c = 0; c < 3; ++c)
      {
        std::swap(xyz[3 * j + c], xyz[3 * (j - 1) + c]);
      }
    }
  }
  count = std::min<Index>(count, std::max(k, 0));
  ids.resize(static_cast<std::size_t>(count));
  sqDist.resize(static_cast<std::size_t>(count));
  xyz.resize(static_cast<std::size_t>(3 * count));
}

NearestPoint Neighbors::Nearest(const double p[3]) const
{
  return this->HasCompactLayout() ? NearestIn(this->Compact, p) : NearestIn(this->Wide, p);
}

void Neighbors::Radius(const double p[3], double r, std::vector<Index>& ids) const
{
  const Answer answer{ ids, nullptr, nullptr };
  this->HasCompactLayout() ? RadiusIn(this->Compact, p, r, answer)
                           : RadiusIn(this->Wide, p, r, answer);
}

void Neighbors::Radius(
  const double p[3], double r, std::vector<Index>& ids, std::vector<double>& sqDist) const
{
  const Answer answer{ ids, &sqDist, nullptr };
  this->HasCompactLayout() ? RadiusIn(this->Compact, p, r, answer)
                           : RadiusIn(this->Wide, p, r, answer);
}

void Neighbors::Radius(const double p[3], double r, std::vector<Index>& ids,
  std::vector<double>& sqDist, std::vector<double>& xyz) const
{
  const Answer answer{ ids, &sqDist, &xyz };
  this->HasCompactLayout() ? RadiusIn(this->Compact, p, r, answer)
                           : RadiusIn(this->Wide, p, r, answer);
}

void Neighbors::RadiusForKNearest(const double p[3], double r, int k, std::vector<Index>& ids,
  std::vector<double>& sqDist, std::vector<double>& xyz) const
{
  const Answer answer{ ids, &sqDist, &xyz };
  const Index limit = std::max<Index>(k, 1);
  this->HasCompactLayout() ? RadiusIn(this->Compact, p, r, answer, limit)
                           : RadiusIn(this->Wide, p, r, answer, limit);
}
} // namespace asmcore
