// SPDX-License-Identifier: BSD-3-Clause
// The paper mode's samples in a cell (PaperSimplify.cxx, paper §3.3): a
// budget below the number of key clusters keeps a random choice of them
// (iv); a budget above the key clusters and the middle band together peels
// the points farthest from each key cluster's extreme off as samples of
// their own (iii), so that every key cluster keeps its extreme point.
#include "Core/Simplify.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

using asmcore::Index;
using asmtest::AllIds;
using asmtest::Cloud;

namespace
{
// Two parallel 5 x 5 grids, 0.25 apart in x and y, at z = 0 and z = 0.3,
// each with its centre moved 0.01 outwards: the cell's normal is z, both
// faces lie wholly in the bands (no middle band), and each face is one key
// cluster whose extreme point is its centre (ids 12 and 37).
Cloud TwoFaces()
{
  Cloud c;
  for (int face = 0; face < 2; ++face)
  {
    for (int j = 0; j < 5; ++j)
    {
      for (int i = 0; i < 5; ++i)
      {
        const double bump = (i == 2 && j == 2) ? 0.01 : 0.0;
        asmtest::Add(c, -0.5 + 0.25 * i, -0.5 + 0.25 * j, face == 0 ? -bump : 0.3 + bump);
      }
    }
  }
  return c;
}

double Distance(const Cloud& c, Index a, Index b)
{
  return std::hypot(c[3 * a] - c[3 * b], c[3 * a + 1] - c[3 * b + 1], c[3 * a + 2] - c[3 * b + 2]);
}
} // namespace

TEST(PaperSampling, PeeledPointsAreTheFarthestFromTheirKeyPoint)
{
  const Cloud c = TwoFaces();
  const auto ids = AllIds(c);
  const Index centre[2] = { 12, 37 };
  asmcore::SimplifyParameters p;
  p.Mode = asmcore::SimplifyMode::Paper;
  p.CellSize = 10.0; // one cell: its budget is N_s
  // 10: the first face gives 8 points; 40: the first face all but its
  // centre (24), the second face 14.
  for (Index budget : { 10, 40 })
  {
    p.NumberOfSamples = budget;
    const auto r = asmcore::Simplify(c.data(), ids, nullptr, p);
    ASSERT_EQ(static_cast<Index>(r.Samples.size()), budget);
    EXPECT_EQ(r.NumberOfKeyPoints, 2) << "budget " << budget;
    std::vector<Index> peeled;
    std::vector<std::vector<Index>> kept(2);
    for (const asmcore::Sample& s : r.Samples)
    {
      const Index* first = r.Members.data() + s.MemberBegin;
      const std::vector<Index> members(first, first + s.ClusterSize);
      if (!s.Key)
      {
        ASSERT_EQ(members.size(), 1u) << "a peeled point is a sample of its own";
        peeled.push_back(members[0]);
        continue;
      }
      // Each key cluster keeps its extreme point.
      const int face = members.empty() ? -1 : (members[0] < 25 ? 0 : 1);
      ASSERT_GE(face, 0) << "budget " << budget << ": an empty key cluster";
      EXPECT_NE(std::find(members.begin(), members.end(), centre[face]), members.end())
        << "budget " << budget << ", face " << face;
      kept[face] = members;
    }
    EXPECT_EQ(static_cast<Index>(peeled.size()), budget - 2);
    if (budget == 40)
    {
      EXPECT_EQ(kept[0], std::vector<Index>{ centre[0] }) << "peeled down to its extreme";
    }
    // Every peeled point is at least as far from its face's extreme as
    // every point its face's cluster kept.
    for (Index q : peeled)
    {
      const int face = q < 25 ? 0 : 1;
      for (Index m : kept[face])
      {
        EXPECT_GE(Distance(c, q, centre[face]), Distance(c, m, centre[face]))
          << "budget " << budget << ": peeled " << q << ", kept " << m;
      }
    }
  }
}

TEST(PaperSampling, RandomKeySelectionFollowsTheSeed)
{
  // Many key clusters per cell, a budget of one: the kept key point is random.
  const Cloud c = asmtest::Sphere(4000, 1.0, 5);
  const auto ids = AllIds(c);
  asmcore::SimplifyParameters p;
  p.Mode = asmcore::SimplifyMode::Paper; // the literal pipeline's key points
  p.NumberOfSamples = 1;
  p.CellSize = 10.0;
  std::set<Index> kept;
  for (std::uint64_t seed = 1; seed <= 20; ++seed)
  {
    p.RandomSeed = seed;
    const auto r = asmcore::Simplify(c.data(), ids, nullptr, p);
    ASSERT_EQ(r.Samples.size(), 1u);
    EXPECT_TRUE(r.Samples[0].Key);
    kept.insert(r.Samples[0].Representative);
    const auto again = asmcore::Simplify(c.data(), ids, nullptr, p);
    EXPECT_EQ(again.Samples[0].Representative, r.Samples[0].Representative);
  }
  EXPECT_GT(kept.size(), 1u) << "different seeds pick different key points";
}
