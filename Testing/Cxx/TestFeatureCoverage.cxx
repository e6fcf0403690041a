// SPDX-License-Identifier: BSD-3-Clause
// Tests of the quality options of the feature-preserving mode (issue 7):
// covering refinement (CoveringRounds), the budget that follows the surface
// variation (VariationBudget) on finer cells (FeatureSamplesPerCell), tips
// alone in sparse cells (SparseCellKeyPoints), the bound on the holes that
// snapping leaves (BoundSnappedHoles), the order-independent choice of a
// sample's input point, the cap on the variation weight (VariationCap), a
// free sample in every cell of two or more (ReserveFreeSample) and the Lloyd
// steps after the hole filling (FinalLloydIterations).
#include "Core/Simplify.h"
#include "Core/SnappedHoles.h"

#include "FeatureShapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>
#include <set>

using asmcore::Index;
using namespace asmtest;

namespace
{

// The largest hole: the input point farthest from every sample (brute force).
double LargestHole(const Cloud& c, const asmcore::SimplifyResult& r)
{
  double hole = 0.0;
  for (std::size_t i = 0; i < c.size(); i += 3)
  {
    double best = 1e300;
    for (const auto& s : r.Samples)
    {
      best = std::min(
        best, std::hypot(c[i] - s.Position[0], c[i + 1] - s.Position[1], c[i + 2] - s.Position[2]));
    }
    hole = std::max(hole, best);
  }
  return hole;
}

bool IsInputPoint(const Cloud& c, const double* p)
{
  for (std::size_t i = 0; i < c.size(); i += 3)
  {
    if (c[i] == p[0] && c[i + 1] == p[1] && c[i + 2] == p[2])
    {
      return true;
    }
  }
  return false;
}

std::set<std::array<double, 3>> Positions(const asmcore::SimplifyResult& r)
{
  std::set<std::array<double, 3>> out;
  for (const auto& s : r.Samples)
  {
    out.insert({ s.Position[0], s.Position[1], s.Position[2] });
  }
  return out;
}
} // namespace

TEST(FeatureCoverage, MinimaxCentreIsNearTheSmallestBall)
{
  // Known smallest balls: two points (their midpoint), a square's corners
  // (its centre), a regular tetrahedron (its circumcentre), each started
  // from a vertex; the radius returned is the reach from the centre
  // returned, at least the exact one and within 5 % of it.
  const double t = 1.0 / std::sqrt(2.0);
  const std::vector<std::pair<Cloud, double>> cases = { { { 0, 0, 0, 2, 0, 0 }, 1.0 },
    { { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 }, std::sqrt(2.0) },
    { { 1, 0, -t, -1, 0, -t, 0, 1, t, 0, -1, t }, std::sqrt(6.0) / 2.0 } };
  for (const auto& [points, exact] : cases)
  {
    const Index n = static_cast<Index>(points.size() / 3);
    std::vector<Index> ids(static_cast<std::size_t>(n));
    std::iota(ids.begin(), ids.end(), Index(0));
    double centre[3];
    const double r2 = asmcore::MinimaxCentre(points.data(), ids.data(), n, points.data(), centre);
    double reach = 0.0;
    for (Index i = 0; i < n; ++i)
    {
      const double* p = points.data() + 3 * i;
      reach = std::max(reach, std::hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]));
    }
    EXPECT_NEAR(std::sqrt(r2), reach, 1e-12);
    EXPECT_GE(reach, exact * (1.0 - 1e-12));
    EXPECT_LE(reach, exact * 1.05) << n << " points";
  }
  double centre[3];
  const double start[3] = { 1, 2, 3 };
  EXPECT_EQ(asmcore::MinimaxCentre(nullptr, nullptr, 0, start, centre), 0.0);
  EXPECT_EQ(centre[2], 3.0);
}

// A moved sample goes just far enough: its cluster's reach ends within the
// bound, and within 1e-5 of it (20 halvings of the move).
TEST(FeatureCoverage, AMovedSampleReachesNoFurtherThanTheBound)
{
  // A cluster of 21 points on [0, 2] along x, its sample on the first; its
  // centre (1, 0, 0). For a bound of b (squared), the sample stops near
  // x = 2 - sqrt(b), where the reach to x = 2 is sqrt(b).
  Cloud points;
  for (int i = 0; i <= 20; ++i)
  {
    asmtest::Add(points, 0.1 * i, 0.0, 0.0);
  }
  std::vector<Index> members(21);
  std::iota(members.begin(), members.end(), Index(0));
  const std::vector<Index> memberStart = { 0, 21 };
  for (double bound : { 1.5, 2.0, 3.0, 3.9 })
  {
    std::vector<double> position = { 0.0, 0.0, 0.0 };
    const std::vector<double> reach =
      asmcore::SnappedReaches(points.data(), memberStart, members.data(), position.data());
    ASSERT_DOUBLE_EQ(reach[0], 4.0);
    const auto candidates = asmcore::SnapCandidates(
      points.data(), memberStart, members.data(), { 1 }, reach, 0.0, position.data());
    ASSERT_EQ(candidates.size(), 1u);
    asmcore::MoveSnappedSamples(
      points.data(), memberStart, members.data(), candidates, bound, position.data());
    const double moved =
      asmcore::SnappedReaches(points.data(), memberStart, members.data(), position.data())[0];
    EXPECT_LE(moved, bound) << "bound " << bound;
    EXPECT_GT(moved, bound * (1.0 - 1e-5)) << "bound " << bound;
    EXPECT_NEAR(position[0], 2.0 - std::sqrt(bound), 1e-5);
  }
}

TEST(FeatureCoverage, BoundSnappedHolesShrinkTheLargestHoleMovingFewSamples)
{
  // 20 % of a sphere and of a bumpy box (keys), with hole filling on (the
  // default) and two covering rounds (samples already near their minimax
  // centres: the bound moves few of them; without the rounds, the default,
  // 2-15 % of the samples move on the bundled and shared scans).
  for (const Cloud& cloud : { Sphere(6000, 1.0, 3), Box(20000).Points })
  {
    const Index n = static_cast<Index>(cloud.size() / 3), target = n / 5;
    auto run = [&](bool bound) {
      return SimplifyWith(cloud, target, [bound](auto& p) {
        p.BoundSnappedHoles = bound;
        p.CoveringRounds = 2;
      });
    };
    const auto off = run(false), on = run(true);
    ASSERT_EQ(static_cast<Index>(on.Samples.size()), target);
    const double holeOff = LargestHole(cloud, off), holeOn = LargestHole(cloud, on);
    EXPECT_LT(holeOn, holeOff) << "the bound shrinks the largest hole";
    // Off: every sample an input point. On: the same samples, but those
    // whose cluster reached past the bound left their input point (their
    // representative), by less than the reach.
    Index moved = 0;
    ASSERT_EQ(on.Samples.size(), off.Samples.size());
    for (std::size_t k = 0; k < on.Samples.size(); ++k)
    {
      const auto& a = off.Samples[k];
      const auto& b = on.Samples[k];
      ASSERT_TRUE(IsInputPoint(cloud, a.Position));
      EXPECT_EQ(a.Representative, b.Representative);
      EXPECT_EQ(a.Key, b.Key);
      if (!std::equal(a.Position, a.Position + 3, b.Position))
      {
        ++moved;
        EXPECT_FALSE(b.Key) << "key samples stay on their extreme point";
        EXPECT_LT(std::hypot(a.Position[0] - b.Position[0], a.Position[1] - b.Position[1],
                    a.Position[2] - b.Position[2]),
          holeOff);
      }
    }
    EXPECT_GT(moved, 0);
    EXPECT_LT(moved, target / 10) << "only the widest clusters' samples move";
    // SnapToInputPoints is the user's demand for input points: nothing moves.
    const auto snapped = SimplifyWith(cloud, target, [](auto& p) {
      p.Snap = true;
      p.BoundSnappedHoles = true;
    });
    for (const auto& s : snapped.Samples)
    {
      EXPECT_TRUE(IsInputPoint(cloud, s.Position));
    }
  }
}

TEST(FeatureCoverage, BoundSnappedHolesInStepsOverPartsIsTheWholeBound)
{
  // Distributed runs take the bound after the core, in steps, each process on
  // its own samples (vtkASMDistributed.h, BoundSnappedHolesAcross). Here the
  // samples of one result are split into two parts (interleaved) and the
  // steps run part by part: the positions must be those of the whole bound
  // applied in the core.
  const Cloud cloud = Sphere(6000, 1.0, 3);
  const Index n = static_cast<Index>(cloud.size() / 3), target = n / 5;
  const auto unbounded = SimplifyWith(cloud, target, [](auto& p) { p.BoundSnappedHoles = false; });
  const auto bounded = SimplifyWith(cloud, target, [](auto& p) { p.BoundSnappedHoles = true; });
  ASSERT_EQ(unbounded.Samples.size(), bounded.Samples.size());
  const asmcore::Coordinates xyz(cloud.data());
  struct Part
  {
    std::vector<Index> Samples, MemberStart{ 0 }, Members;
    std::vector<char> Snapped;
    std::vector<double> Positions;
  };
  Part parts[2];
  for (std::size_t k = 0; k < unbounded.Samples.size(); ++k)
  {
    const asmcore::Sample& s = unbounded.Samples[k];
    Part& part = parts[k % 2];
    part.Samples.push_back(static_cast<Index>(k));
    part.Members.insert(part.Members.end(), unbounded.Members.begin() + s.MemberBegin,
      unbounded.Members.begin() + s.MemberBegin + s.ClusterSize);
    part.MemberStart.push_back(static_cast<Index>(part.Members.size()));
    part.Snapped.push_back(!s.Key && s.ClusterSize > 1 ? 1 : 0);
    part.Positions.insert(part.Positions.end(), s.Position, s.Position + 3);
  }
  // Step 1 on each part; the start is the larger of the two.
  std::vector<double> reach[2];
  double start = 0.0;
  for (int q = 0; q < 2; ++q)
  {
    reach[q] = asmcore::SnappedReaches(
      xyz, parts[q].MemberStart, parts[q].Members.data(), parts[q].Positions.data());
    start = std::max(start, asmcore::FixedReach(reach[q], parts[q].Snapped));
  }
  // Step 2: each part's candidates, then the bound from both, widest first.
  std::vector<asmcore::SnapCandidate> candidates[2];
  std::vector<std::pair<double, double>> all;
  for (int q = 0; q < 2; ++q)
  {
    candidates[q] = asmcore::SnapCandidates(xyz, parts[q].MemberStart, parts[q].Members.data(),
      parts[q].Snapped, reach[q], start, parts[q].Positions.data());
    for (const auto& c : candidates[q])
    {
      all.emplace_back(c.Reach, c.Radius);
    }
  }
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  const double limit = asmcore::SnapBound(start, all);
  EXPECT_GT(limit, start) << "the widest clusters raise the bound";
  // Step 3: each part moves its own samples.
  Index moved = 0;
  for (int q = 0; q < 2; ++q)
  {
    asmcore::MoveSnappedSamples(xyz, parts[q].MemberStart, parts[q].Members.data(), candidates[q],
      limit, parts[q].Positions.data());
    for (std::size_t j = 0; j < parts[q].Samples.size(); ++j)
    {
      const asmcore::Sample& whole = bounded.Samples[parts[q].Samples[j]];
      const asmcore::Sample& before = unbounded.Samples[parts[q].Samples[j]];
      const double* p = parts[q].Positions.data() + 3 * j;
      EXPECT_TRUE(std::equal(p, p + 3, whole.Position)) << "sample " << parts[q].Samples[j];
      moved += std::equal(p, p + 3, before.Position) ? 0 : 1;
    }
  }
  EXPECT_GT(moved, 0);
  EXPECT_LT(moved, target / 5);
}

TEST(FeatureCoverage, CoveringRoundsShrinkTheLargestHole)
{
  // 20 % of a sphere: five points per sample, where the input point nearest
  // a cluster's centre can sit well to one side of it.
  Shape sphere;
  sphere.Points = Sphere(6000, 1.0, 3);
  const Index target = 1200;
  auto rounds = [&](int k) {
    return SimplifyWith(sphere.Points, target, [k](auto& p) {
      p.CoveringRounds = k;
      p.FillHoles = false; // the refinement alone
      p.BoundSnappedHoles = false;
      p.LloydVariationWeight = 0.0; // (the weighted final Lloyd steps crowd creases, not holes)
    });
  };
  const auto none = rounds(0), one = rounds(1), two = rounds(2), four = rounds(4);
  const double h0 = LargestHole(sphere.Points, none), h1 = LargestHole(sphere.Points, one),
               h2 = LargestHole(sphere.Points, two), h4 = LargestHole(sphere.Points, four);
  // A round never lets the hole grow, and the refinement shrinks it.
  EXPECT_LE(h2, h1);
  EXPECT_LE(h4, h2);
  EXPECT_LT(h2, 0.99 * h0) << h0 << " " << h1 << " " << h2 << " " << h4;
  // Still exactly N_s samples, each an input point.
  ASSERT_EQ(static_cast<Index>(two.Samples.size()), target);
  for (const auto& s : two.Samples)
  {
    EXPECT_TRUE(IsInputPoint(sphere.Points, s.Position));
  }
  // Only with input-point samples: centroid samples do not change.
  auto centroids = [&](int k) {
    return Positions(SimplifyWith(sphere.Points, target, [k](auto& p) {
      p.CoveringRounds = k;
      p.InputPointSamples = false;
    }));
  };
  EXPECT_EQ(centroids(0), centroids(2));
  // The key samples stay on their extreme points.
  auto keys = [](const asmcore::SimplifyResult& r) {
    std::vector<std::array<double, 3>> at;
    for (const auto& s : r.Samples)
    {
      if (s.Key)
      {
        at.push_back({ s.Position[0], s.Position[1], s.Position[2] });
      }
    }
    std::sort(at.begin(), at.end());
    return at;
  };
  ASSERT_FALSE(keys(none).empty());
  EXPECT_EQ(keys(two), keys(none));
}

TEST(FeatureCoverage, BudgetFollowsTheSurfaceVariation)
{
  // A flat square next to a bumpy one (same area, same density): the bumpy
  // half has the larger surface variation and gets more of the samples.
  Cloud c;
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 40000; ++i)
  {
    const double x = 2.0 * u(rng), y = u(rng);
    Add(c, x, y, x < 1.0 ? 0.0 : 0.05 * std::sin(20.0 * x) * std::sin(20.0 * y));
  }
  auto bumpyShare = [&](double k) {
    const auto r = SimplifyWith(c, 2000, [k](auto& p) { p.VariationBudget = k; });
    double n = 0.0;
    for (const auto& s : r.Samples)
    {
      n += s.Position[0] > 1.0 ? 1.0 : 0.0;
    }
    return n / static_cast<double>(r.Samples.size());
  };
  const double uniform = bumpyShare(0.0), weighted = bumpyShare(0.5);
  EXPECT_GT(weighted, uniform + 0.02) << uniform << " " << weighted;
  // Paper mode ignores the option (and FeatureSamplesPerCell).
  auto paper = [&](double k, double cells) {
    return Positions(SimplifyWith(c, 2000, [k, cells](auto& p) {
      p.Mode = asmcore::SimplifyMode::Paper;
      p.VariationBudget = k;
      p.FeatureSamplesPerCell = cells;
    }));
  };
  EXPECT_EQ(paper(0.0, 8.0), paper(0.5, 4.0));
}

TEST(FeatureCoverage, FeatureSamplesPerCellSetsTheCellSize)
{
  const Shape box = Box(40000);
  const double fine = SimplifyWith(box.Points, 4000).CellSize;
  const double coarse =
    SimplifyWith(box.Points, 4000, [](auto& p) { p.FeatureSamplesPerCell = 8.0; }).CellSize;
  // About sqrt(2) on a surface: half the samples per cell, half the area.
  EXPECT_LT(fine, 0.85 * coarse);
  EXPECT_GT(fine, 0.55 * coarse);
  // <= 0: SamplesPerCell, as in Paper mode.
  const double fallback = SimplifyWith(box.Points, 4000, [](auto& p) {
    p.FeatureSamplesPerCell = 0.0;
    p.SamplesPerCell = 8.0;
  }).CellSize;
  EXPECT_EQ(fallback, coarse);
}

TEST(FeatureCoverage, TipAloneInASparseCellIsAKeyPoint)
{
  // With these cells the cone's apex falls in a cell of two points, too few
  // for a frame: only the sparse-cell rule makes it a key point.
  const Shape cone = Cone(40000);
  auto apexDistance = [&](bool sparse) {
    const auto r =
      SimplifyWith(cone.Points, 4000, [sparse](auto& p) { p.SparseCellKeyPoints = sparse; });
    double best = 1e300;
    bool key = false;
    for (const auto& s : r.Samples)
    {
      const double d = std::hypot(s.Position[0] - cone.Features[0][0],
        s.Position[1] - cone.Features[0][1], s.Position[2] - cone.Features[0][2]);
      if (d < best)
      {
        best = d;
        key = s.Key;
      }
    }
    return std::make_pair(best, key);
  };
  const auto with = apexDistance(true), without = apexDistance(false);
  EXPECT_EQ(with.first, 0.0);
  EXPECT_TRUE(with.second);
  EXPECT_GT(without.first, 0.0);
}

TEST(FeatureCoverage, TwoPointClustersDoNotDependOnTheInputOrder)
{
  // Far-apart pairs of points, one sample each: the centre of a pair is as
  // near to both (up to rounding), and the chosen point must not depend on
  // which comes first.
  Cloud pairs;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  for (int i = 0; i < 30; ++i)
  {
    for (int j = 0; j < 30; ++j)
    {
      const double x = i + 0.1 * u(rng), y = j + 0.1 * u(rng);
      Add(pairs, x + u(rng), y + u(rng), u(rng));
      Add(pairs, x + u(rng), y + u(rng), 0.01 + u(rng));
    }
  }
  Cloud reversed;
  for (std::size_t i = pairs.size(); i >= 3; i -= 3)
  {
    reversed.insert(reversed.end(), pairs.begin() + (i - 3), pairs.begin() + i);
  }
  for (int rounds : { 0, 2 })
  {
    auto configure = [rounds](auto& p) { p.CoveringRounds = rounds; };
    const auto a = SimplifyWith(pairs, 900, configure), b = SimplifyWith(reversed, 900, configure);
    EXPECT_EQ(Positions(a), Positions(b)) << "CoveringRounds " << rounds;
  }
}

TEST(FeatureCoverage, VariationCapDampsASharpCellsWeight)
{
  // Nine flat cells and one at ten times the mean variation, 100 points each.
  const std::vector<Index> capacity(10, 100);
  std::vector<double> variation(10, 0.0);
  variation[9] = 0.2; // mean 0.02: ratio 10
  asmcore::SimplifyParameters p;
  p.VariationBudget = 1.0;
  auto ratio = [&](const asmcore::SimplifyParameters& q) {
    const std::vector<double> share = asmcore::CellShares(capacity, variation, q, 1.0);
    return share[9] / share[0];
  };
  p.VariationCap = 2.5;
  EXPECT_DOUBLE_EQ(ratio(p), 1.0 + 5.0); // sqrt(2.5 * 10) past the cap
  p.VariationCap = 20.0;
  EXPECT_DOUBLE_EQ(ratio(p), 1.0 + 10.0); // below the cap
  p.VariationCap = 0.0;
  EXPECT_DOUBLE_EQ(ratio(p), 1.0 + 10.0); // no cap
  // The paper mode's weight (Eq. 4 with WeightMode::SurfaceVariation) is not capped.
  p.VariationCap = 2.5;
  p.Mode = asmcore::SimplifyMode::Paper;
  p.Weight = asmcore::WeightMode::SurfaceVariation;
  p.CurvatureWeight = 1.0;
  EXPECT_DOUBLE_EQ(ratio(p), 1.0 + 10.0);
}

TEST(FeatureCoverage, ReserveFreeSampleKeepsANonKeySampleInACell)
{
  // The corner of a cube (three faces meeting at the origin) in one cell:
  // it holds more key points than samples.
  Cloud c;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 3000; ++i)
  {
    const double a = u(rng), b = u(rng);
    const int face = i % 3;
    Add(c, face == 0 ? 0.0 : a, face == 1 ? 0.0 : (face == 0 ? a : b), face == 2 ? 0.0 : b);
  }
  auto keys = [&](Index target, bool reserve) {
    const auto r = SimplifyWith(c, target, [reserve](auto& p) {
      p.CellSize = 4.0;
      p.ReserveFreeSample = reserve;
    });
    EXPECT_EQ(r.NumberOfCells, 1);
    EXPECT_EQ(static_cast<Index>(r.Samples.size()), target);
    return std::count_if(r.Samples.begin(), r.Samples.end(), [](const auto& s) { return s.Key; });
  };
  for (Index target : { 2, 3, 5 })
  {
    EXPECT_EQ(keys(target, false), target) << "without the rule, keys take the whole budget";
    EXPECT_EQ(keys(target, true), target - 1) << target;
  }
  // A cell of one sample may still make it a key sample.
  EXPECT_EQ(keys(1, true), 1);
}

TEST(FeatureCoverage, FinalLloydIterationsTightenTheClusters)
{
  // With centroid samples, every Lloyd step lowers the sum of squared
  // distances from the points to their nearest sample (k-means energy).
  Cloud c;
  std::mt19937_64 rng(12);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < 20000; ++i)
  {
    double x = g(rng), y = g(rng), z = g(rng);
    const double n = std::sqrt(x * x + y * y + z * z);
    x /= n, y /= n, z /= n;
    const double r = 1.0 + 0.1 * std::sin(6.0 * x) * std::sin(5.0 * y); // bumps
    Add(c, r * x, r * y, r * z);
  }
  auto energy = [&](int iterations) {
    const auto r = SimplifyWith(c, 400, [iterations](auto& p) {
      p.InputPointSamples = false;
      p.BoundSnappedHoles = false;
      p.FinalLloydIterations = iterations;
    });
    EXPECT_EQ(r.Samples.size(), 400u);
    double e = 0.0;
    for (std::size_t i = 0; i < c.size(); i += 3)
    {
      double best = 1e300;
      for (const auto& s : r.Samples)
      {
        const double dx = c[i] - s.Position[0], dy = c[i + 1] - s.Position[1],
                     dz = c[i + 2] - s.Position[2];
        best = std::min(best, dx * dx + dy * dy + dz * dz);
      }
      e += best;
    }
    return e;
  };
  const double e0 = energy(0), e1 = energy(1), e4 = energy(4);
  EXPECT_LT(e1, e0);
  EXPECT_LE(e4, e1 * (1.0 + 1e-12));
  EXPECT_LT(e4, 0.999 * e0) << e0 << " " << e1 << " " << e4;
}
