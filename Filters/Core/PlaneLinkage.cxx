// SPDX-License-Identifier: BSD-3-Clause
// The single linkage of PlaneClusters.h (LinkInPlane): the connected
// components of points at most a distance apart in a cell's plane.
#include "PlaneClusters.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

namespace asmcore
{
namespace
{
// Union-find with path halving over positions 0..n-1.
struct DisjointSets
{
  std::vector<Index> Parent;
  explicit DisjointSets(std::size_t n)
    : Parent(n)
  {
    std::iota(this->Parent.begin(), this->Parent.end(), Index(0));
  }
  Index Find(Index x)
  {
    while (this->Parent[x] != x)
    {
      this->Parent[x] = this->Parent[this->Parent[x]];
      x = this->Parent[x];
    }
    return x;
  }
  void Union(Index a, Index b)
  {
    a = this->Find(a);
    b = this->Find(b);
    if (a != b)
    {
      // The smaller root wins: labels do not depend on the visiting order.
      this->Parent[std::max(a, b)] = std::min(a, b);
    }
  }
};

using BinKey = std::pair<std::int64_t, std::int64_t>;

// Up to this many points (at most 64: one bit each), LinkInPlane tests
// every pair. (Paper mode on a bumpy sphere: bands of up to 32 points hold 8
// on average, larger ones 67, which hold three quarters of the points;
// LinkInPlane costs a quarter less with 64 here than with 32.)
constexpr std::size_t SmallLinkSize = 64;
static_assert(SmallLinkSize <= 64, "one bit per point of a small band");

// The position of the lowest set bit of a non-zero mask.
int LowestBit(std::uint64_t mask)
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_ctzll(mask);
#else
  int k = 0;
  while (!(mask & 1))
  {
    mask >>= 1;
    ++k;
  }
  return k;
#endif
}

// LinkInPlane of at most SmallLinkSize points: each point's links as a bit
// mask, then each component as the closure of its first member. Components
// come in order of their first member, members in subset order: what
// Components gives for the same links.
Clusters LinkSmallInPlane(const LocalPoints& q, const std::vector<Index>& subset, double d2)
{
  const std::size_t n = subset.size();
  double u[SmallLinkSize], v[SmallLinkSize];
  std::uint64_t links[SmallLinkSize];
  for (std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3d& p = q[subset[i]];
    u[i] = p[0];
    v[i] = p[1];
    links[i] = std::uint64_t(1) << i;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    std::uint64_t mask = 0;
    for (std::size_t j = i + 1; j < n; ++j)
    {
      const double dx = u[i] - u[j], dy = v[i] - v[j];
      const std::uint64_t linked = dx * dx + dy * dy <= d2 ? 1 : 0;
      mask |= linked << j;
      links[j] |= linked << i;
    }
    links[i] |= mask;
  }
  Clusters out;
  out.Members.reserve(n);
  std::uint64_t left = n == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << n) - 1;
  while (left)
  {
    std::uint64_t component = left & (~left + 1); // its first member
    std::uint64_t frontier = component;
    while (frontier)
    {
      const std::uint64_t fresh = links[LowestBit(frontier)] & ~component;
      frontier &= frontier - 1;
      component |= fresh;
      frontier |= fresh;
    }
    left &= ~component;
    for (; component; component &= component - 1)
    {
      out.Members.push_back(subset[LowestBit(component)]);
    }
    out.Offsets.push_back(static_cast<Index>(out.Members.size()));
  }
  return out;
}

std::int64_t BinOf(double u, double side)
{
  const double t = std::floor(u / side);
  const double lim = 4.0e18;
  return static_cast<std::int64_t>(std::max(-lim, std::min(lim, t)));
}

// The clusters of `subset` given the components of positions in `sets`.
Clusters Components(const std::vector<Index>& subset, DisjointSets& sets)
{
  Clusters out;
  const std::size_t n = subset.size();
  // Roots are the smallest position of each component, so walking positions
  // in order meets components in order of their first member.
  std::vector<Index> label(n, -1);
  std::vector<Index> counts;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Index root = sets.Find(static_cast<Index>(i));
    if (label[root] < 0)
    {
      label[root] = static_cast<Index>(counts.size());
      counts.push_back(0);
    }
    ++counts[label[root]];
  }
  out.Offsets.assign(counts.size() + 1, 0);
  for (std::size_t k = 0; k < counts.size(); ++k)
  {
    out.Offsets[k + 1] = out.Offsets[k] + counts[k];
  }
  out.Members.resize(n);
  std::vector<Index> fill(out.Offsets.begin(), out.Offsets.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    out.Members[fill[label[sets.Find(static_cast<Index>(i))]]++] = subset[i];
  }
  return out;
}

// LinkInPlane when the bins touched by the points fit in a small dense
// array (the usual band of a cell): the same links as the sorted-bin search
// (same bin, or at most two bins apart and within d), found through the
// array instead of binary searches (the same components). Returns false, doing nothing, when the
// array would be too large.
bool LinkDenseInPlane(const LocalPoints& q, const std::vector<Index>& subset, double side,
  double d2, DisjointSets& sets)
{
  struct Scratch
  {
    std::vector<std::int64_t> X, Y;
    std::vector<Index> Start, Order;
  };
  thread_local Scratch scratch; // reused by the cells a thread processes
  const std::size_t n = subset.size();
  scratch.X.resize(n);
  scratch.Y.resize(n);
  std::int64_t lo[2] = { 0, 0 }, hi[2] = { 0, 0 };
  for (std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3d& p = q[subset[i]];
    const std::int64_t x = BinOf(p[0], side), y = BinOf(p[1], side);
    scratch.X[i] = x;
    scratch.Y[i] = y;
    lo[0] = i == 0 ? x : std::min(lo[0], x);
    hi[0] = i == 0 ? x : std::max(hi[0], x);
    lo[1] = i == 0 ? y : std::min(lo[1], y);
    hi[1] = i == 0 ? y : std::max(hi[1], y);
  }
  // Differences of bins far apart could overflow: test in double first.
  const double w = static_cast<double>(hi[0]) - static_cast<double>(lo[0]) + 1.0;
  const double h = static_cast<double>(hi[1]) - static_cast<double>(lo[1]) + 1.0;
  if (!(w * h <= 4.0 * static_cast<double>(n) + 64.0))
  {
    return false;
  }
  const std::int64_t width = hi[0] - lo[0] + 1, height = hi[1] - lo[1] + 1;
  // Counting sort of the positions by bin (stable).
  scratch.Start.assign(static_cast<std::size_t>(width * height + 1), 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    scratch.X[i] -= lo[0];
    scratch.Y[i] -= lo[1];
    ++scratch.Start[static_cast<std::size_t>(scratch.Y[i] * width + scratch.X[i] + 1)];
  }
  for (std::size_t b = 1; b < scratch.Start.size(); ++b)
  {
    scratch.Start[b] += scratch.Start[b - 1];
  }
  scratch.Order.resize(n);
  {
    std::vector<Index>& next = scratch.Start; // shifted by one: fill, then shift back
    for (std::size_t i = 0; i < n; ++i)
    {
      const auto bin = static_cast<std::size_t>(scratch.Y[i] * width + scratch.X[i]);
      scratch.Order[static_cast<std::size_t>(next[bin]++)] = static_cast<Index>(i);
    }
    for (std::size_t b = next.size() - 1; b > 0; --b)
    {
      next[b] = next[b - 1];
    }
    next[0] = 0;
  }
  // A bin is connected (its first point joins the others); then each pair
  // of bins at most two apart is linked by its first pair within d, unless
  // the two bins are connected already.
  const Index* start = scratch.Start.data();
  const Index* order = scratch.Order.data();
  for (std::int64_t y = 0; y < height; ++y)
  {
    for (std::int64_t x = 0; x < width; ++x)
    {
      const std::int64_t bin = y * width + x;
      if (start[bin] == start[bin + 1])
      {
        continue;
      }
      const Index first = order[start[bin]];
      for (Index k = start[bin] + 1; k < start[bin + 1]; ++k)
      {
        sets.Union(first, order[k]);
      }
      // The 12 neighbours after this bin: each pair of bins once.
      for (std::int64_t dy = 0; dy <= 2 && y + dy < height; ++dy)
      {
        for (std::int64_t dx = -2; dx <= 2; ++dx)
        {
          if ((dy == 0 && dx <= 0) || x + dx < 0 || x + dx >= width)
          {
            continue;
          }
          const std::int64_t other = bin + dy * width + dx;
          if (start[other] == start[other + 1] ||
            sets.Find(first) == sets.Find(order[start[other]]))
          {
            continue;
          }
          bool linked = false;
          for (Index k = start[bin]; k < start[bin + 1] && !linked; ++k)
          {
            const Eigen::Vector3d& p = q[subset[order[k]]];
            for (Index m = start[other]; m < start[other + 1]; ++m)
            {
              const Eigen::Vector3d& r = q[subset[order[m]]];
              const double dx2 = p[0] - r[0], dy2 = p[1] - r[1];
              if (dx2 * dx2 + dy2 * dy2 <= d2)
              {
                sets.Union(order[k], order[m]);
                linked = true;
                break;
              }
            }
          }
        }
      }
    }
  }
  return true;
}
} // namespace

Clusters LinkInPlane(const LocalPoints& q, const std::vector<Index>& subset, double linkDistance)
{
  Clusters out;
  const std::size_t n = subset.size();
  if (n == 0)
  {
    return out;
  }
  if (!(linkDistance > 0.0) || n == 1)
  {
    out.Add(subset.begin(), subset.end());
    return out;
  }
  // Bins of side d/2: two points in one bin are closer than d, so a bin is
  // connected; points at most d apart lie at most two bins apart.
  const double side = 0.5 * linkDistance;
  const double d2 = linkDistance * linkDistance;
  if (n <= SmallLinkSize)
  {
    // Few points (the usual band of a cell): every pair, cheaper than the
    // bins; the same links, so the same components.
    return LinkSmallInPlane(q, subset, d2);
  }
  {
    DisjointSets sets(n);
    if (LinkDenseInPlane(q, subset, side, d2, sets))
    {
      return Components(subset, sets);
    }
  }
  std::vector<std::pair<BinKey, Index>> binned(n); // (bin, position in subset)
  for (std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3d& p = q[subset[i]];
    binned[i] = { { BinOf(p[0], side), BinOf(p[1], side) }, static_cast<Index>(i) };
  }
  std::sort(binned.begin(), binned.end());
  std::vector<BinKey> binKeys;
  std::vector<std::size_t> binStart;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (i == 0 || binned[i].first != binned[i - 1].first)
    {
      binKeys.push_back(binned[i].first);
      binStart.push_back(i);
    }
  }
  binStart.push_back(n);

  DisjointSets sets(n);
  for (std::size_t b = 0; b < binKeys.size(); ++b)
  {
    for (std::size_t i = binStart[b] + 1; i < binStart[b + 1]; ++i)
    {
      sets.Union(binned[binStart[b]].second, binned[i].second);
    }
  }
  for (std::size_t a = 0; a < binKeys.size(); ++a)
  {
    for (std::int64_t dx = -2; dx <= 2; ++dx)
    {
      for (std::int64_t dy = -2; dy <= 2; ++dy)
      {
        // Visit each pair of bins once: only neighbours after `a` in key order.
        if (dx < 0 || (dx == 0 && dy <= 0))
        {
          continue;
        }
        const BinKey target = { binKeys[a].first + dx, binKeys[a].second + dy };
        const auto found = std::lower_bound(binKeys.begin(), binKeys.end(), target);
        if (found == binKeys.end() || *found != target)
        {
          continue;
        }
        const auto b = static_cast<std::size_t>(found - binKeys.begin());
        if (sets.Find(binned[binStart[a]].second) == sets.Find(binned[binStart[b]].second))
        {
          continue;
        }
        bool linked = false;
        for (std::size_t i = binStart[a]; i < binStart[a + 1] && !linked; ++i)
        {
          const Eigen::Vector3d& p = q[subset[binned[i].second]];
          for (std::size_t j = binStart[b]; j < binStart[b + 1]; ++j)
          {
            const Eigen::Vector3d& r = q[subset[binned[j].second]];
            const double dx2 = p[0] - r[0], dy2 = p[1] - r[1];
            if (dx2 * dx2 + dy2 * dy2 <= d2)
            {
              sets.Union(binned[i].second, binned[j].second);
              linked = true;
              break;
            }
          }
        }
      }
    }
  }
  return Components(subset, sets);
}
} // namespace asmcore
