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
    return this->Count < this->K ||
      NeighborPrecedes(d, id, this->D[this->K - 1], this->Ids[this->K - 1]);
  }
  bool Visit(double rd, Index minId) const { return this->Accepts(rd, minId); }
  void Add(double d, Index id)
  {
    int i = this->Count < this->K ? this->Count++ : this->K - 1;
    while (i > 0 && NeighborPrecedes(d, id, this->D[i - 1], this->Ids[i - 1]))
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

namespace
{
// The queries, on a tree of either layout.
template <typename Tree>
void KNearestIn(const Tree& tree, const double p[3], int k, std::vector<Index>& ids,
  std::vector<double>& sqDist)
{
  ids.clear();
  sqDist.clear();
  if (k <= 0 || tree.Empty() || !Finite(p))
  {
    return;
  }
  if (static_cast<Index>(k) >= tree.Size())
  {
    // Every point: no tree needed.
    const auto& entries = tree.Entries();
    std::vector<std::pair<double, Index>> all(entries.size());
    for (std::size_t i = 0; i < all.size(); ++i)
    {
      all[i] = { SquaredDistance(entries[i].P, p), entries[i].Id };
    }
    Unzip(all, ids, &sqDist);
    return;
  }
  if (k <= 32)
  {
    ids.resize(static_cast<std::size_t>(k));
    sqDist.resize(static_cast<std::size_t>(k));
    SortedKnn result(k, ids.data(), sqDist.data());
    tree.Search(p, result);
    return; // k < Size(): the result is full
  }
  HeapKnn result(k);
  tree.Search(p, result);
  Unzip(result.Heap, ids, &sqDist);
}

template <typename Tree>
NearestPoint NearestIn(const Tree& tree, const double p[3])
{
  NearestPoint nearest;
  nearest.Distance = std::numeric_limits<double>::infinity();
  if (tree.Empty() || !Finite(p))
  {
    return nearest;
  }
  Index id = -1;
  double d = 0.0;
  SortedKnn result(1, &id, &d);
  tree.Search(p, result);
  nearest.Id = id;
  nearest.Distance = std::sqrt(d);
  return nearest;
}

template <typename Tree>
void RadiusIn(const Tree& tree, const double p[3], double r, std::vector<Index>& ids,
  std::vector<double>* sqDist)
{
  ids.clear();
  if (sqDist)
  {
    sqDist->clear();
  }
  if (tree.Empty() || !Finite(p) || !(r >= 0.0) || !std::isfinite(r))
  {
    return;
  }
  RadiusSet result(r * r);
  tree.Search(p, result);
  Unzip(result.Found, ids, sqDist);
}
} // namespace

void Neighbors::KNearest(
  const double p[3], int k, std::vector<Index>& ids, std::vector<double>& sqDist) const
{
  this->HasCompactLayout() ? KNearestIn(this->Compact, p, k, ids, sqDist)
                  : KNearestIn(this->Wide, p, k, ids, sqDist);
}

NearestPoint Neighbors::Nearest(const double p[3]) const
{
  return this->HasCompactLayout() ? NearestIn(this->Compact, p) : NearestIn(this->Wide, p);
}

void Neighbors::Radius(const double p[3], double r, std::vector<Index>& ids) const
{
  this->HasCompactLayout() ? RadiusIn(this->Compact, p, r, ids, nullptr)
                  : RadiusIn(this->Wide, p, r, ids, nullptr);
}

void Neighbors::Radius(
  const double p[3], double r, std::vector<Index>& ids, std::vector<double>& sqDist) const
{
  this->HasCompactLayout() ? RadiusIn(this->Compact, p, r, ids, &sqDist)
                  : RadiusIn(this->Wide, p, r, ids, &sqDist);
}
} // namespace asmcore
