// SPDX-License-Identifier: BSD-3-Clause
// SplitInPlane against a plain reference: the same clusters, member for
// member, whatever order the selection leaves inside its halves.
#include "Core/PlaneClusters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

using asmcore::Index;

namespace
{
using Split = std::vector<std::vector<Index>>;

// The median splits as SplitInPlane documents them, by full sorts: the axis
// of larger (u0, u1) extent, the first nLeft points by (coordinate, index)
// go left, left half first; `points` stays in the order it came in.
void ReferenceSplit(
  const asmcore::LocalPoints& q, const std::vector<Index>& points, Index k, Split& out)
{
  const auto n = static_cast<Index>(points.size());
  if (k <= 1 || n <= 1)
  {
    out.push_back(points);
    return;
  }
  double lo[2] = { q[points[0]][0], q[points[0]][1] }, hi[2] = { lo[0], lo[1] };
  for (const Index i : points)
  {
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], q[i][a]);
      hi[a] = std::max(hi[a], q[i][a]);
    }
  }
  const int axis = (hi[1] - lo[1]) > (hi[0] - lo[0]) ? 1 : 0;
  const Index kLeft = k / 2, kRight = k - kLeft;
  Index nLeft = static_cast<Index>(std::llround(static_cast<double>(n) * kLeft / k));
  nLeft = std::max(kLeft, std::min(n - kRight, nLeft));
  std::vector<Index> sorted = points;
  std::sort(sorted.begin(), sorted.end(), [&](Index a, Index b) {
    return q[a][axis] < q[b][axis] || (q[a][axis] == q[b][axis] && a < b);
  });
  std::vector<char> isLeft(q.size(), 0);
  for (Index i = 0; i < nLeft; ++i)
  {
    isLeft[sorted[i]] = 1;
  }
  std::vector<Index> left, right;
  for (const Index i : points)
  {
    (isLeft[i] ? left : right).push_back(i);
  }
  ReferenceSplit(q, left, kLeft, out);
  ReferenceSplit(q, right, kRight, out);
}

Split SplitOf(const asmcore::LocalPoints& q, std::vector<Index> points, Index k)
{
  asmcore::Clusters clusters;
  asmcore::SplitInPlane(q, points.data(), points.data() + points.size(), k, clusters);
  Split out;
  for (Index c = 0; c < clusters.Size(); ++c)
  {
    out.emplace_back(clusters.Begin(c), clusters.End(c));
  }
  return out;
}

Split Reference(const asmcore::LocalPoints& q, const std::vector<Index>& points, Index k)
{
  Split out;
  ReferenceSplit(q, points, k, out);
  return out;
}
} // namespace

TEST(PlaneClusters, SplitInPlaneBreaksTiesByIndex)
{
  // A 7 x 3 grid, longer along u0: 21 points, k = 2 gives 11 on the left,
  // the 9 points of u0 = 0, 1, 2 and the two of u0 = 3 with the lowest
  // indices.
  asmcore::LocalPoints q;
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 7; ++i)
    {
      q.emplace_back(i, j, 0.0);
    }
  }
  std::vector<Index> all(q.size());
  std::iota(all.begin(), all.end(), Index(0));
  const Split split = SplitOf(q, all, 2);
  ASSERT_EQ(split.size(), 2u);
  const std::vector<Index> left = { 0, 1, 2, 3, 7, 8, 9, 10, 14, 15, 16 };
  EXPECT_EQ(split[0], left);
  EXPECT_EQ(split, Reference(q, all, 2));
}

TEST(PlaneClusters, SplitInPlaneMatchesFullSorts)
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::uniform_int_distribution<int> coarse(0, 3); // many exact ties
  for (const Index n : { 2, 15, 17, 40, 300, 2000 })
  {
    for (int layout = 0; layout < 5; ++layout)
    {
      asmcore::LocalPoints q(static_cast<std::size_t>(n));
      for (Index i = 0; i < n; ++i)
      {
        const double u = layout == 1 ? static_cast<double>(i) : uniform(random);
        const double v = layout == 2 ? 0.0 : uniform(random);
        q[i] = layout == 3 ? Eigen::Vector3d(coarse(random), coarse(random), 0.0)
          : layout == 4    ? Eigen::Vector3d(static_cast<double>(n - i), 0.5 * v, 0.0)
                           : Eigen::Vector3d(u, v, uniform(random));
      }
      // A subset in a scrambled order: the clusters keep that order.
      std::vector<Index> subset;
      for (Index i = 0; i < n; ++i)
      {
        if (i % 5 != 3 || n < 20)
        {
          subset.push_back(i);
        }
      }
      std::shuffle(subset.begin(), subset.end(), random);
      const auto size = static_cast<Index>(subset.size());
      for (const Index k : { Index(1), Index(2), Index(3), Index(7), size / 3 + 1, size })
      {
        if (k > size)
        {
          continue;
        }
        SCOPED_TRACE("n " + std::to_string(n) + " layout " + std::to_string(layout) + " k " +
          std::to_string(k));
        EXPECT_EQ(SplitOf(q, subset, k), Reference(q, subset, k));
      }
    }
  }
}

TEST(PlaneClusters, PointsExactlyTheLinkDistanceApartAreLinked)
{
  // Square lattices whose spacing is the link distance, exactly (multiples
  // of 0.25): one cluster each, through the pair masks of a small band (5 x
  // 5) and through the bins of a larger one (12 x 12). Half the spacing
  // more, and every point is a cluster of its own.
  for (int side : { 5, 12 })
  {
    asmcore::LocalPoints q;
    for (int j = 0; j < side; ++j)
    {
      for (int i = 0; i < side; ++i)
      {
        q.emplace_back(0.25 * i, 0.25 * j, 0.01 * ((i + j) % 2));
      }
    }
    std::vector<Index> subset(q.size());
    std::iota(subset.begin(), subset.end(), Index(0));
    EXPECT_EQ(asmcore::LinkInPlane(q, subset, 0.25).Size(), 1) << side << " x " << side;
    EXPECT_EQ(asmcore::LinkInPlane(q, subset, 0.125).Size(), static_cast<Index>(q.size()))
      << side << " x " << side;
  }
}
