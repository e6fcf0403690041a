// SPDX-License-Identifier: BSD-3-Clause
// Clusters in a cell's plane: centroids, representatives, median splits
// (the single linkage is in PlaneLinkage.cxx).
#include "PlaneClusters.h"

#include "Quickselect.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

namespace asmcore
{
Eigen::Vector3d Centroid(const LocalPoints& q, const Index* first, const Index* last)
{
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Index* it = first; it != last; ++it)
  {
    sum += q[*it];
  }
  const auto n = static_cast<double>(last - first);
  return n > 0 ? Eigen::Vector3d(sum / n) : sum;
}

Index NearestMember(
  const LocalPoints& q, const Index* first, const Index* last, const Eigen::Vector3d& target)
{
  Index best = -1;
  double bestDist = std::numeric_limits<double>::infinity();
  for (const Index* it = first; it != last; ++it)
  {
    const double d = (q[*it] - target).squaredNorm();
    // The first member whatever its distance: squares that overflow (inf or
    // NaN everywhere) still give a member.
    if (best < 0 || d < bestDist || (d == bestDist && *it < best))
    {
      bestDist = d;
      best = *it;
    }
  }
  return best;
}

Eigen::Vector3d Representative(
  const LocalPoints& q, const Index* first, const Index* last, bool snap)
{
  const Eigen::Vector3d c = Centroid(q, first, last);
  return snap ? q[NearestMember(q, first, last, c)] : c;
}

namespace
{
// A middle-band point during the splits: its (u0, u1) and its index in q.
struct SplitEntry
{
  double U[2];
  Index Id;
};

// The splits' strict order along one axis: the coordinate, then the index.
// Evaluated without branches: on a cell's points, in their canonical
// (hash) order, a branch on it mispredicts half the time.
inline bool SplitBefore(const SplitEntry& x, const SplitEntry& y, int axis)
{
  const double a = x.U[axis], b = y.U[axis];
  return (a < b) | ((a == b) & (x.Id < y.Id));
}
} // namespace

void SplitInPlane(const LocalPoints& q, Index* first, Index* last, Index k, Clusters& out)
{
  // The splits work on a copy of the points' (u0, u1) and index, so that
  // each comparison reads adjacent memory.
  struct Task
  {
    Index Begin;
    Index End;
    Index K;
  };
  thread_local std::vector<SplitEntry> entries; // reused by the cells a thread processes
  thread_local std::vector<SplitEntry> tmp;
  thread_local std::vector<Task> stack;
  thread_local std::vector<Index> clusterOf; // by index into q
  thread_local std::vector<Index> offsets;
  thread_local std::vector<Index> input;
  const Index count = last - first;
  entries.resize(static_cast<std::size_t>(count));
  tmp.resize(static_cast<std::size_t>(count));
  for (Index i = 0; i < count; ++i)
  {
    const Eigen::Vector3d& p = q[first[i]];
    entries[i] = SplitEntry{ { p[0], p[1] }, first[i] };
  }
  if (clusterOf.size() < q.size())
  {
    clusterOf.resize(q.size());
  }
  offsets.assign(1, 0);
  stack.assign(1, Task{ 0, count, k });
  while (!stack.empty())
  {
    const Task t = stack.back();
    stack.pop_back();
    SplitEntry* const e = entries.data() + t.Begin;
    const Index n = t.End - t.Begin;
    if (t.K <= 1 || n <= 1)
    {
      // A finished cluster, numbered in the order clusters are completed.
      const auto cluster = static_cast<Index>(offsets.size()) - 1;
      for (Index i = 0; i < n; ++i)
      {
        clusterOf[e[i].Id] = cluster;
      }
      offsets.push_back(offsets.back() + n);
      continue;
    }
    double lo[2] = { e[0].U[0], e[0].U[1] }, hi[2] = { e[0].U[0], e[0].U[1] };
    for (Index i = 1; i < n; ++i)
    {
      for (int a = 0; a < 2; ++a)
      {
        lo[a] = std::min(lo[a], e[i].U[a]);
        hi[a] = std::max(hi[a], e[i].U[a]);
      }
    }
    const int axis = (hi[1] - lo[1]) > (hi[0] - lo[0]) ? 1 : 0;
    const Index kLeft = t.K / 2;
    const Index kRight = t.K - kLeft;
    // Points shared in proportion to the budgets, each side keeping at least
    // as many points as samples it must produce.
    Index nLeft = static_cast<Index>(std::llround(static_cast<double>(n) * kLeft / t.K));
    nLeft = std::max(kLeft, std::min(n - kRight, nLeft));
    SelectFirst(
      e, n, nLeft,
      [axis](const SplitEntry& x, const SplitEntry& y) { return SplitBefore(x, y, axis); },
      tmp.data());
    // Left half first (depth first): clusters come out ordered along the split.
    stack.push_back({ t.Begin + nLeft, t.End, kRight });
    stack.push_back({ t.Begin, t.Begin + nLeft, kLeft });
  }
  // Each cluster lists its members in the order they came in [first, last):
  // the result depends on the splits' sets alone, not on the order the
  // selection leaves within them. (A stable counting sort by cluster.)
  input.assign(first, last);
  for (const Index id : input)
  {
    first[offsets[clusterOf[id]]++] = id;
  }
  Index begin = 0;
  for (std::size_t c = 0; c + 1 < offsets.size(); ++c)
  {
    out.Add(first + begin, first + offsets[c]);
    begin = offsets[c];
  }
}

double PlaneLinkDistance(const LocalPoints& q, double factor)
{
  if (q.empty())
  {
    return 0.0;
  }
  double lo[2] = { q[0][0], q[0][1] }, hi[2] = { q[0][0], q[0][1] };
  for (const auto& p : q)
  {
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  const double e0 = hi[0] - lo[0], e1 = hi[1] - lo[1];
  const auto n = static_cast<double>(q.size());
  // Points on an area e0 x e1 have a spacing of about sqrt(area / n); on a
  // segment (e1 ~ 0) of about e0 / n.
  const double spacing = (e1 > 1e-12 * e0) ? std::sqrt(e0 * e1 / n) : e0 / n;
  return factor * spacing;
}
} // namespace asmcore
