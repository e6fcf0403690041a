// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the ASM core (no VTK): grid, PCA frame, budgets, key points.
#include "Core/Budget.h"
#include "Core/CanonicalOrder.h"
#include "Core/CellFrame.h"
#include "Core/Grid.h"
#include "Core/KeyPoints.h"
#include "Core/Simplify.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cfloat>
#include <numeric>
#include <random>
#include <set>
#include <string>

using asmcore::Index;
using asmtest::AllIds;
using asmtest::Cloud;

namespace
{

// The points of a cloud in their PCA frame.
asmcore::LocalPoints ToFrame(const Cloud& c, asmcore::CellFrame& frame)
{
  const auto ids = AllIds(c);
  frame = asmcore::ComputeCellFrame(c.data(), ids);
  asmcore::LocalPoints q;
  for (Index id : ids)
  {
    q.push_back(frame.ToLocal(c.data() + 3 * id));
  }
  return q;
}

Eigen::Vector3d World(const asmcore::CellFrame& frame, const Eigen::Vector3d& local)
{
  return frame.Centroid + frame.Axes * local;
}

// The key cluster whose extreme point is the origin, or -1.
Index ApexCluster(
  const asmcore::CellFrame& frame, const asmcore::LocalPoints& q, const asmcore::KeyClusters& kc)
{
  for (Index k = 0; k < kc.Key.Size(); ++k)
  {
    if (World(frame, q[kc.Extreme[k]]).norm() < 1e-9)
    {
      return k;
    }
  }
  return -1;
}

// z = -(x^2 + y^2) / 2 on [-1, 1]^2: apex at the origin, v2 = z. With the
// default 39 x 39 grid the apex is a grid point and no grid point lies exactly
// on a band threshold (x^2 + y^2 = 1/4 or 7/4), where rounding decides.
Cloud Paraboloid(int n = 39)
{
  return asmtest::GridSurface(n, 1.0, [](double x, double y) { return -0.5 * (x * x + y * y); });
}
} // namespace

//------------------------------------------------------------------------------
TEST(Budget, AddsUpExactlyAndRespectsCapacity)
{
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> share(0.0, 5.0);
  std::uniform_int_distribution<Index> cap(1, 50);
  for (int trial = 0; trial < 200; ++trial)
  {
    const std::size_t cells = 1 + trial % 37;
    std::vector<double> shares(cells);
    std::vector<Index> caps(cells);
    for (std::size_t c = 0; c < cells; ++c)
    {
      shares[c] = (c % 5 == 4) ? 0.0 : share(rng);
      caps[c] = cap(rng);
    }
    const Index room = std::accumulate(caps.begin(), caps.end(), Index(0));
    for (Index total : { Index(0), Index(1), room / 3, room - 1, room, room + 10 })
    {
      const auto budget = asmcore::ApportionBudget(shares, caps, total);
      ASSERT_EQ(std::accumulate(budget.begin(), budget.end(), Index(0)), std::min(total, room));
      for (std::size_t c = 0; c < cells; ++c)
      {
        ASSERT_GE(budget[c], 0);
        ASSERT_LE(budget[c], caps[c]);
      }
    }
  }
}

TEST(Budget, ProportionalWithLargestRemainders)
{
  // Shares 1:2:3:4 of 100 samples with room to spare: 10, 20, 30, 40.
  auto b = asmcore::ApportionBudget({ 1, 2, 3, 4 }, { 100, 100, 100, 100 }, 100);
  EXPECT_EQ(b, (std::vector<Index>{ 10, 20, 30, 40 }));
  // 10 among three equal cells: 3.33 each; the one unit left goes to the
  // first cell (equal remainders, lower index).
  b = asmcore::ApportionBudget({ 1, 1, 1 }, { 9, 9, 9 }, 10);
  EXPECT_EQ(b, (std::vector<Index>{ 4, 3, 3 }));
  // A cell whose quota exceeds its capacity is filled and the rest shared.
  b = asmcore::ApportionBudget({ 10, 1, 1 }, { 2, 50, 50 }, 20);
  EXPECT_EQ(b, (std::vector<Index>{ 2, 9, 9 }));
}

//------------------------------------------------------------------------------
TEST(Grid, CellsHoldTheirPoints)
{
  const Cloud c = asmtest::Sphere(5000, 2.0);
  const auto ids = AllIds(c);
  const auto bounds = asmcore::ComputeBounds(c.data(), ids);
  const auto spec = asmcore::GridSpec::Make(bounds, 0.5);
  const auto grid = asmcore::BuildCellGrid(c.data(), ids, spec);
  ASSERT_EQ(grid.Order.size(), ids.size());
  std::set<Index> seen(grid.Order.begin(), grid.Order.end());
  EXPECT_EQ(seen.size(), ids.size());
  for (Index cell = 0; cell < grid.NumberOfCells(); ++cell)
  {
    std::int64_t ijk[3];
    spec.Unpack(grid.CellKey[cell], ijk);
    for (Index i = 0; i < grid.CellSizeOf(cell); ++i)
    {
      const double* p = c.data() + 3 * grid.CellPoints(cell)[i];
      for (int a = 0; a < 3; ++a)
      {
        const double lo = spec.Origin[a] + ijk[a] * spec.CellSize;
        EXPECT_GE(p[a], lo - 1e-12);
        EXPECT_LE(p[a], lo + spec.CellSize + 1e-12);
      }
    }
    if (cell > 0)
    {
      EXPECT_LT(grid.CellKey[cell - 1], grid.CellKey[cell]);
    }
  }
  EXPECT_EQ(asmcore::CountOccupiedCells(c.data(), ids, spec), grid.NumberOfCells());
}

// A cell's canonical order is a function of its points: the same sequence
// of positions whatever order they come in (a lattice of ties, -0 and +0,
// duplicates), duplicates ordered by id.
TEST(Grid, CanonicalOrderDoesNotDependOnTheOrderOfThePoints)
{
  Cloud c;
  for (int i = 0; i < 12; ++i)
  {
    for (int j = 0; j < 12; ++j)
    {
      asmtest::Add(c, 0.1 * i, 0.1 * j, 0.0);
    }
  }
  asmtest::Add(c, -0.0, 0.5, 0.0);        // the same position as (0, 0.5, 0)
  asmtest::Add(c, 0.1 * 3, 0.1 * 3, 0.0); // a duplicate of point 39, id 145
  const Index n = static_cast<Index>(c.size() / 3);
  auto sequence = [&](std::vector<Index> ids) {
    std::vector<double> xyz;
    for (Index id : ids)
    {
      xyz.insert(xyz.end(), c.begin() + 3 * id, c.begin() + 3 * id + 3);
    }
    std::vector<Index> order;
    asmcore::CanonicalOrderScratch scratch;
    asmcore::CanonicalOrder(xyz.data(), ids.data(), n, order, scratch);
    std::vector<std::pair<std::array<double, 3>, Index>> out;
    for (Index k : order)
    {
      out.push_back({ { xyz[3 * k] + 0.0, xyz[3 * k + 1], xyz[3 * k + 2] }, ids[k] });
    }
    return out;
  };
  std::vector<Index> ids(static_cast<std::size_t>(n));
  std::iota(ids.begin(), ids.end(), Index(0));
  const auto reference = sequence(ids);
  ASSERT_EQ(reference.size(), static_cast<std::size_t>(n));
  std::set<Index> seen;
  for (const auto& entry : reference)
  {
    seen.insert(entry.second);
  }
  EXPECT_EQ(seen.size(), static_cast<std::size_t>(n)) << "a permutation";
  // The duplicates (points 39 and 145) by id.
  auto placeOf = [&](Index id) {
    return std::find_if(
      reference.begin(), reference.end(), [id](const auto& e) { return e.second == id; });
  };
  EXPECT_EQ(placeOf(39) + 1, placeOf(145));
  for (unsigned seed : { 1u, 2u, 3u })
  {
    std::shuffle(ids.begin(), ids.end(), std::mt19937(seed));
    const auto shuffled = sequence(ids);
    for (std::size_t k = 0; k < reference.size(); ++k)
    {
      ASSERT_EQ(shuffled[k].first, reference[k].first) << "seed " << seed << ", place " << k;
      // (The two points at x = -0 and +0 may come in either order: the
      // same position. Every other point keeps its id.)
      if (reference[k].first[0] != 0.0 || reference[k].first[1] != 0.5)
      {
        ASSERT_EQ(shuffled[k].second, reference[k].second) << "seed " << seed << ", place " << k;
      }
    }
  }
}

// Both modes list the representatives' exact duplicates, and nothing else: what lets the VTK layer
// choose among them by value.
TEST(Simplify, RepresentativeDuplicatesAreListed)
{
  const Cloud sphere = asmtest::Sphere(8000, 1.0, 3);
  const Index n = static_cast<Index>(sphere.size() / 3);
  Cloud twice = sphere;
  twice.insert(twice.end(), sphere.begin(), sphere.end()); // point i + n at point i
  // (Two more points, at x = 0 and x = -0: one position.)
  asmtest::Add(twice, 0.0, 0.6, 0.8);
  asmtest::Add(twice, -0.0, 0.6, 0.8);
  for (auto mode : { asmcore::SimplifyMode::Paper, asmcore::SimplifyMode::FeaturePreserving })
  {
    asmcore::SimplifyParameters p;
    p.NumberOfSamples = 400;
    p.Mode = mode;
    EXPECT_TRUE(asmcore::Simplify(sphere.data(), AllIds(sphere), nullptr, p)
                  .RepresentativeDuplicates.empty());
    const auto r = asmcore::Simplify(twice.data(), AllIds(twice), nullptr, p);
    ASSERT_EQ(r.Samples.size(), 400u);
    std::vector<std::pair<Index, Index>> expected;
    for (const auto& s : r.Samples)
    {
      const Index a = s.Representative;
      const Index twin = a >= 2 * n ? (a == 2 * n ? a + 1 : a - 1) : (a < n ? a + n : a - n);
      expected.emplace_back(a, twin);
    }
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(r.RepresentativeDuplicates, expected) << "mode " << int(mode);
  }
}

// A group of exact duplicates that holds many samples' representatives (a
// cloud of identical points) is listed once, under its first
// representative: n - 1 pairs, not one list per sample (m (n - 1) pairs,
// which took minutes and gigabytes). Every sample keeps a cluster of its own.
TEST(Simplify, AGroupOfDuplicatesIsListedOnce)
{
  const Index n = 20000;
  Cloud same;
  for (Index i = 0; i < n; ++i)
  {
    asmtest::Add(same, 0.25, 0.5, 0.75);
  }
  for (auto mode : { asmcore::SimplifyMode::Paper, asmcore::SimplifyMode::FeaturePreserving })
  {
    asmcore::SimplifyParameters p;
    p.NumberOfSamples = 2000;
    p.Mode = mode;
    const auto r = asmcore::Simplify(same.data(), AllIds(same), nullptr, p);
    ASSERT_EQ(r.Samples.size(), 2000u) << "mode " << int(mode);
    ASSERT_EQ(r.RepresentativeDuplicates.size(), static_cast<std::size_t>(n - 1))
      << "mode " << int(mode);
    const Index lead = r.RepresentativeDuplicates.front().first;
    std::vector<char> listed(static_cast<std::size_t>(n), 0);
    listed[static_cast<std::size_t>(lead)] = 1;
    for (const auto& pair : r.RepresentativeDuplicates)
    {
      ASSERT_EQ(pair.first, lead);
      ASSERT_FALSE(listed[static_cast<std::size_t>(pair.second)]) << pair.second;
      listed[static_cast<std::size_t>(pair.second)] = 1;
    }
    bool leadIsARepresentative = false;
    for (const auto& sample : r.Samples)
    {
      EXPECT_GE(sample.ClusterSize, 1) << "mode " << int(mode);
      leadIsARepresentative = leadIsARepresentative || sample.Representative == lead;
    }
    EXPECT_TRUE(leadIsARepresentative);
  }
}

TEST(Grid, TinyCellSizeIsEnlargedToTheKeyRange)
{
  const Cloud c = { 0, 0, 0, 1000, 1, 1 };
  const auto bounds = asmcore::ComputeBounds(c.data(), AllIds(c));
  const auto spec = asmcore::GridSpec::Make(bounds, 1e-30);
  EXPECT_LE(spec.Dims[0], asmcore::GridSpec::MaxDim);
  EXPECT_GT(spec.CellSize, 1000.0 / asmcore::GridSpec::MaxDim);
}

//------------------------------------------------------------------------------
TEST(CellFrame, PlaneNormalAndOrderedEigenvalues)
{
  // A tilted plane: normal (1, 1, 1)/sqrt(3).
  Cloud c = asmtest::GridSurface(20, 1.0, [](double x, double y) { return -x - y; });
  asmcore::CellFrame frame;
  ToFrame(c, frame);
  const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 1).normalized();
  EXPECT_NEAR(std::abs(frame.Normal().dot(n)), 1.0, 1e-12);
  EXPECT_GE(frame.Lambda[0], frame.Lambda[1]);
  EXPECT_GE(frame.Lambda[1], frame.Lambda[2]);
  EXPECT_NEAR(frame.Lambda[2], 0.0, 1e-12);
  EXPECT_NEAR(frame.SurfaceVariation(), 0.0, 1e-12);
  EXPECT_NEAR((frame.Axes.transpose() * frame.Axes - Eigen::Matrix3d::Identity()).norm(), 0, 1e-12);
  EXPECT_NEAR(frame.Axes.determinant(), 1.0, 1e-12);
}

// The axes' signs are fixed: v0's and v1's largest components positive, so
// both solvers give the same frame, whatever the cloud's orientation.
TEST(CellFrame, AxesSignsAreFixed)
{
  const Cloud flat = asmtest::GridSurface(15, 1.0, [](double x, double y) { return 0.1 * x * y; });
  for (int turn = 0; turn < 8; ++turn)
  {
    const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.9 * turn, Eigen::Vector3d(1, -2, 0.5 + turn).normalized())
        .toRotationMatrix();
    Cloud c;
    for (std::size_t i = 0; i < flat.size(); i += 3)
    {
      // (stretched along x: distinct eigenvalues)
      const Eigen::Vector3d r = rotation * Eigen::Vector3d(2.0 * flat[i], flat[i + 1], flat[i + 2]);
      asmtest::Add(c, r[0], r[1], r[2]);
    }
    const auto ids = AllIds(c);
    const asmcore::CellFrame a = asmcore::ComputeCellFrame(c.data(), ids);
    const asmcore::CellFrame b =
      asmcore::ComputeCellFrame(c.data(), ids, asmcore::FrameSolver::ClosedForm);
    for (int axis = 0; axis < 2; ++axis)
    {
      const Eigen::Vector3d v = a.Axes.col(axis);
      Eigen::Index k = 0;
      v.cwiseAbs().maxCoeff(&k);
      EXPECT_GT(v[k], 0.0) << "turn " << turn << ", axis " << axis;
      EXPECT_LT((v - b.Axes.col(axis)).norm(), 1e-9) << "turn " << turn << ", axis " << axis;
    }
    EXPECT_NEAR(a.Axes.determinant(), 1.0, 1e-12);
  }
}

TEST(CellFrame, DegenerateSetsGiveAValidFrame)
{
  for (const Cloud& c : { Cloud{ 1, 2, 3 }, Cloud{ 1, 2, 3, 1, 2, 3, 1, 2, 3 },
         Cloud{ 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3 } })
  {
    asmcore::CellFrame frame;
    ToFrame(c, frame);
    EXPECT_TRUE(frame.Axes.allFinite());
    EXPECT_TRUE(frame.Lambda.allFinite());
    EXPECT_NEAR(frame.Axes.determinant(), 1.0, 1e-9);
    EXPECT_NEAR(frame.Lambda[2], 0.0, 1e-12);
  }
}

//------------------------------------------------------------------------------
TEST(KeyPoints, LinkInPlaneSeparatesBlobs)
{
  asmcore::LocalPoints q;
  for (int i = 0; i < 10; ++i)
  {
    q.emplace_back(0.01 * i, 0.0, 0.0);       // blob A along a line
    q.emplace_back(5.0 + 0.01 * i, 0.0, 0.0); // blob B far away
  }
  std::vector<Index> all(q.size());
  std::iota(all.begin(), all.end(), Index(0));
  const auto clusters = asmcore::LinkInPlane(q, all, 0.05);
  ASSERT_EQ(clusters.Size(), 2);
  EXPECT_EQ(clusters.CountOf(0), 10);
  EXPECT_EQ(*clusters.Begin(0), 0); // ordered by first member
  EXPECT_EQ(*clusters.Begin(1), 1);
  // A link distance larger than the gap joins them.
  EXPECT_EQ(asmcore::LinkInPlane(q, all, 6.0).Size(), 1);
  // Coincident points are one cluster.
  asmcore::LocalPoints same(1000, Eigen::Vector3d(1, 2, 3));
  std::vector<Index> sameIds(same.size());
  std::iota(sameIds.begin(), sameIds.end(), Index(0));
  EXPECT_EQ(asmcore::LinkInPlane(same, sameIds, 0.1).Size(), 1);
}

TEST(KeyPoints, SplitInPlaneMakesExactlyKClusters)
{
  asmcore::CellFrame frame;
  const auto q = ToFrame(asmtest::Sphere(500, 1.0), frame);
  for (Index k : { 1, 2, 3, 17, 250, 499, 500 })
  {
    std::vector<Index> ids(q.size());
    std::iota(ids.begin(), ids.end(), Index(0));
    asmcore::Clusters out;
    asmcore::SplitInPlane(q, ids.data(), ids.data() + ids.size(), k, out);
    ASSERT_EQ(out.Size(), k);
    std::set<Index> seen;
    for (Index c = 0; c < out.Size(); ++c)
    {
      EXPECT_GT(out.CountOf(c), 0);
      seen.insert(out.Begin(c), out.End(c));
    }
    EXPECT_EQ(seen.size(), q.size());
  }
}

TEST(KeyPoints, ParaboloidApexIsATopKeyPoint)
{
  asmcore::CellFrame frame;
  const auto q = ToFrame(Paraboloid(), frame);
  asmcore::KeyPointOptions options;
  options.LinkDistance = asmcore::PlaneLinkDistance(q, 2.0);
  const auto kc = asmcore::FindKeyClusters(q, options);
  ASSERT_FALSE(kc.Flat);
  // v2 is +z or -z: one band holds the apex, the other the four corners.
  const Index top = kc.NumberOfTop, bottom = kc.Key.Size() - kc.NumberOfTop;
  EXPECT_EQ(std::min(top, bottom), 1) << "one bump, one cluster";
  EXPECT_EQ(std::max(top, bottom), 4) << "the four corners are separate clusters";
  const Eigen::Vector3d apex(0, 0, 0);
  const Index k = ApexCluster(frame, q, kc);
  ASSERT_GE(k, 0);
  const Eigen::Vector3d key = World(frame, asmcore::Centroid(q, kc.Key.Begin(k), kc.Key.End(k)));
  EXPECT_NEAR(key[0], 0.0, 1e-9);
  EXPECT_NEAR(key[1], 0.0, 1e-9);
  // The top band holds z >= -alpha * R with R = 1: a disk of radius 1/2
  // whose centroid lies at z = -1/16.
  EXPECT_NEAR(key[2], -1.0 / 16.0, 5e-3);
}

TEST(KeyPoints, ErrorToleranceBringsTheKeyPointToTheApex)
{
  asmcore::CellFrame frame;
  const auto q = ToFrame(Paraboloid(), frame);
  asmcore::KeyPointOptions options;
  options.LinkDistance = asmcore::PlaneLinkDistance(q, 2.0);
  for (double eps : { 0.03, 0.01, 0.001 })
  {
    options.ErrorTolerance = eps;
    const auto kc = asmcore::FindKeyClusters(q, options);
    EXPECT_LE(kc.MaxError, eps);
    EXPECT_LT(kc.Alpha, 0.125);
    EXPECT_GT(kc.Iterations, 1);
    const Index k = ApexCluster(frame, q, kc);
    ASSERT_GE(k, 0);
    const Eigen::Vector3d key = World(frame, asmcore::Centroid(q, kc.Key.Begin(k), kc.Key.End(k)));
    EXPECT_LE(key.norm(), eps + 1e-12) << "eps " << eps;
  }
  // Without the bound the apex's key point is 1/16 below it.
  options.ErrorTolerance = 0.0;
  const auto kc = asmcore::FindKeyClusters(q, options);
  const Index k = ApexCluster(frame, q, kc);
  ASSERT_GE(k, 0);
  EXPECT_NEAR(
    World(frame, asmcore::Centroid(q, kc.Key.Begin(k), kc.Key.End(k))).norm(), 1.0 / 16.0, 5e-3);
  EXPECT_GE(kc.MaxError, 1.0 / 16.0 - 5e-3);
}

TEST(KeyPoints, ErrorToleranceShrinksAlphaByAtLeastTenPercent)
{
  // Just above eps, Eq. 5 (alpha * eps / MKPE_c) would shrink alpha by a few
  // percent per pass; the step is at least 10 %. With eps above 0.9 of the
  // error at alpha = 1/8 and above the error at 0.9 / 8, one adaptation
  // takes alpha to exactly 0.9 / 8 and stops there.
  asmcore::CellFrame frame;
  const auto q = ToFrame(Paraboloid(101), frame); // fine enough for 10 % of alpha
  asmcore::KeyPointOptions options;
  options.LinkDistance = asmcore::PlaneLinkDistance(q, 2.0);
  const double first = asmcore::FindKeyClusters(q, options).MaxError;
  options.Alpha = 0.9 * 0.125;
  const double next = asmcore::FindKeyClusters(q, options).MaxError;
  const double floor = std::max(next, 0.9 * first);
  ASSERT_LT(floor, first) << "the sampling resolves the two bands";
  options.Alpha = 0.125;
  options.ErrorTolerance = 0.5 * (floor + first);
  const auto kc = asmcore::FindKeyClusters(q, options);
  EXPECT_EQ(kc.Iterations, 2);
  EXPECT_DOUBLE_EQ(kc.Alpha, 0.9 * 0.125);
  EXPECT_EQ(kc.MaxError, next);
}

TEST(KeyPoints, TwoBumpsGiveTwoTopKeyPoints)
{
  const auto bumps = [](double x, double y) {
    return 0.3 *
      (std::exp(-((x - 0.5) * (x - 0.5) + y * y) / 0.02) +
        std::exp(-((x + 0.5) * (x + 0.5) + y * y) / 0.02));
  };
  asmcore::CellFrame frame;
  const auto q = ToFrame(asmtest::GridSurface(61, 1.0, bumps), frame);
  asmcore::KeyPointOptions options;
  options.LinkDistance = asmcore::PlaneLinkDistance(q, 2.0);
  const auto kc = asmcore::FindKeyClusters(q, options);
  // The bumps' side of v2 holds two clusters, the flat floor one.
  const bool bumpsOnTop = frame.Normal()[2] > 0;
  ASSERT_EQ(kc.NumberOfTop, bumpsOnTop ? 2 : 1);
  ASSERT_EQ(kc.Key.Size(), 3);
  std::vector<double> xs;
  for (Index k = bumpsOnTop ? 0 : 1; k < (bumpsOnTop ? 2 : 3); ++k)
  {
    const Eigen::Vector3d key = World(frame, asmcore::Centroid(q, kc.Key.Begin(k), kc.Key.End(k)));
    xs.push_back(key[0]);
    EXPECT_NEAR(key[1], 0.0, 1e-9);
    EXPECT_GT(key[2], 0.3 * (1 - 0.125) - 1e-3);
  }
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs[0], -0.5, 1e-9);
  EXPECT_NEAR(xs[1], 0.5, 1e-9);
}

TEST(KeyPoints, FlatCellHasNoKeyPoints)
{
  asmcore::CellFrame frame;
  const auto q = ToFrame(
    asmtest::GridSurface(30, 1.0, [](double x, double y) { return 0.3 * x - 0.2 * y; }), frame);
  asmcore::KeyPointOptions options;
  options.LinkDistance = asmcore::PlaneLinkDistance(q, 2.0);
  options.FlatTolerance = 1e-9;
  const auto kc = asmcore::FindKeyClusters(q, options);
  EXPECT_TRUE(kc.Flat);
  EXPECT_EQ(kc.Key.Size(), 0);
  EXPECT_EQ(kc.Middle.size(), q.size());
}

// The flat tolerance covers the PCA's rounding too: exactly planar cells about
// the origin (where the coordinates' term vanishes), square or long and thin,
// in any orientation, are flat; a relief of 1e-9 of their size is not.
TEST(KeyPoints, PlanarCellsAboutTheOriginAreFlatWhateverTheirShape)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Double coordinates (a relief of 1e-9 of the size is kept), and the same
  // rounded to float (where the coordinates' rounding, relative to the
  // points' distance from the origin, dominates: a relief of 1e-5 is kept).
  for (const bool single : { false, true })
  {
    asmcore::KeyPointRule rule;
    rule.CoordinateEpsilon = single ? FLT_EPSILON : DBL_EPSILON;
    const double reliefKept = single ? 1e-5 : 1e-9;
    auto round = [single](double v) {
      volatile float f = static_cast<float>(v);   // (in memory: GCC 12's -O3 may drop
      return single ? static_cast<double>(f) : v; // a double -> float -> double rounding)
    };
    for (double size : { 1e-3, 50.0, 1e4 })
    {
      for (double aspect : { 1.0, 10.0, 100.0, 1000.0 })
      {
        for (int trial = 0; trial < 25; ++trial)
        {
          const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
          const Eigen::Matrix3d rotation = Eigen::AngleAxisd(3.0 * u(rng), axis).toRotationMatrix();
          const bool lattice = trial % 2 == 0;
          Cloud planar, bumped;
          for (int i = 0; i < 30; ++i)
          {
            for (int j = 0; j < 30; ++j)
            {
              const double x = lattice ? i / 14.5 - 1.0 : u(rng);
              const double y = (lattice ? j / 14.5 - 1.0 : u(rng)) / aspect;
              const double bump = i == 15 && j == 15 ? reliefKept : 0.0;
              const Eigen::Vector3d p = size * (rotation * Eigen::Vector3d(x, y, 0.0));
              const Eigen::Vector3d b = size * (rotation * Eigen::Vector3d(x, y, bump));
              asmtest::Add(planar, round(p[0]), round(p[1]), round(p[2]));
              asmtest::Add(bumped, round(b[0]), round(b[1]), round(b[2]));
            }
          }
          const std::string what = std::string(single ? "float" : "double") + ", size " +
            std::to_string(size) + ", aspect " + std::to_string(aspect) + ", trial " +
            std::to_string(trial);
          asmcore::LocalPoints q;
          const auto ids = AllIds(planar);
          const auto flat = asmcore::FindCellKeyClusters(
            planar.data(), ids, asmcore::ComputeCellFrame(planar.data(), ids), rule, q);
          EXPECT_TRUE(flat.Flat) << what;
          EXPECT_EQ(flat.Key.Size(), 0) << what;
          const auto relief = asmcore::FindCellKeyClusters(
            bumped.data(), ids, asmcore::ComputeCellFrame(bumped.data(), ids), rule, q);
          EXPECT_FALSE(relief.Flat) << what;
        }
      }
    }
  }
  // Points on a line (lambda1 = 0 up to rounding) have no relief either.
  for (int trial = 0; trial < 25; ++trial)
  {
    const Eigen::Vector3d direction = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    Cloud line;
    for (int i = 0; i < 30; ++i)
    {
      const Eigen::Vector3d p = (50.0 * (i / 14.5 - 1.0)) * direction;
      asmtest::Add(line, p[0], p[1], p[2]);
    }
    asmcore::LocalPoints q;
    const auto ids = AllIds(line);
    const auto frame = asmcore::ComputeCellFrame(line.data(), ids);
    EXPECT_TRUE(asmcore::FindCellKeyClusters(line.data(), ids, frame, {}, q).Flat)
      << "trial " << trial << ", lambda1 " << frame.Lambda[1];
  }
}

//------------------------------------------------------------------------------
TEST(Simplify, ExactCountForEveryTarget)
{
  const Cloud c = asmtest::Sphere(20000, 1.0);
  const auto ids = AllIds(c);
  for (Index target : { 1, 2, 3, 7, 64, 999, 1000, 5001, 19999, 20000, 25000 })
  {
    asmcore::SimplifyParameters p;
    p.NumberOfSamples = target;
    const auto r = asmcore::Simplify(c.data(), ids, nullptr, p);
    ASSERT_EQ(static_cast<Index>(r.Samples.size()), std::min<Index>(target, 20000));
    std::set<Index> members;
    Index total = 0;
    for (const auto& s : r.Samples)
    {
      ASSERT_GE(s.ClusterSize, 1);
      total += s.ClusterSize;
      for (Index m = 0; m < s.ClusterSize; ++m)
      {
        members.insert(r.Members[s.MemberBegin + m]);
      }
      EXPECT_NEAR(std::hypot(s.Normal[0], s.Normal[1], s.Normal[2]), 1.0, 1e-9);
    }
    EXPECT_EQ(static_cast<Index>(members.size()), total) << "a point belongs to one sample at most";
    EXPECT_LE(total, 20000);
  }
}

TEST(Simplify, ErrorToleranceBoundsMKPE)
{
  const Cloud c = asmtest::Sphere(30000, 1.0, 11);
  const auto ids = AllIds(c);
  asmcore::SimplifyParameters p;
  p.Mode = asmcore::SimplifyMode::Paper; // the literal pipeline's key points
  p.NumberOfSamples = 1500;
  const auto loose = asmcore::Simplify(c.data(), ids, nullptr, p);
  ASSERT_GT(loose.NumberOfKeyPoints, 0);
  const double eps = 0.25 * loose.MKPE;
  p.ErrorTolerance = eps;
  const auto bounded = asmcore::Simplify(c.data(), ids, nullptr, p);
  EXPECT_EQ(bounded.Samples.size(), 1500u);
  EXPECT_LE(bounded.MKPE, eps);
  EXPECT_LT(bounded.AKPE, loose.AKPE);
}

// The key point figures are over the key samples only: AKPE is the mean of
// their errors, MKPE the largest, and each error is the distance from the
// key sample to the extreme point it stands for, a member of its cluster.
TEST(Simplify, KeyPointFiguresAreOverTheKeySamplesOnly)
{
  const Cloud c = asmtest::Sphere(30000, 1.0, 11);
  const auto ids = AllIds(c);
  asmcore::SimplifyParameters p;
  p.Mode = asmcore::SimplifyMode::Paper; // key samples are key clusters' centroids: errors > 0
  p.NumberOfSamples = 1500;
  const auto r = asmcore::Simplify(c.data(), ids, nullptr, p);
  Index keys = 0;
  double sum = 0.0, largest = 0.0;
  for (const auto& s : r.Samples)
  {
    if (!s.Key)
    {
      continue;
    }
    ++keys;
    sum += s.KeyError;
    largest = std::max(largest, s.KeyError);
    double farthest = 0.0;
    for (Index m = 0; m < s.ClusterSize; ++m)
    {
      const double* x = &c[3 * r.Members[s.MemberBegin + m]];
      farthest = std::max(
        farthest, std::hypot(x[0] - s.Position[0], x[1] - s.Position[1], x[2] - s.Position[2]));
    }
    EXPECT_LE(s.KeyError, farthest + 1e-12);
  }
  ASSERT_GT(keys, 0);
  ASSERT_LT(keys, 1500) << "the figures must not count the other samples";
  ASSERT_GT(sum, 0.0);
  EXPECT_EQ(r.NumberOfKeyPoints, keys);
  EXPECT_NEAR(r.AKPE, sum / static_cast<double>(keys), 1e-15);
  EXPECT_EQ(r.MKPE, largest);
}

TEST(Simplify, RotatingTheInputRotatesTheKeyPoints)
{
  // 40 x 40: no grid point lies exactly on a band threshold, where rounding
  // after the rotation could move it across.
  const Cloud c = Paraboloid(40);
  const auto ids = AllIds(c);
  const Eigen::Matrix3d rotation =
    (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  Cloud rotated;
  for (std::size_t i = 0; i < c.size(); i += 3)
  {
    const Eigen::Vector3d r = rotation * Eigen::Vector3d(c[i], c[i + 1], c[i + 2]);
    asmtest::Add(rotated, r[0], r[1], r[2]);
  }
  asmcore::SimplifyParameters p;
  p.Mode = asmcore::SimplifyMode::Paper; // the literal pipeline's key points
  p.NumberOfSamples = 20;
  p.CellSize = 10.0; // one cell whatever the rotation
  const auto a = asmcore::Simplify(c.data(), ids, nullptr, p);
  const auto b = asmcore::Simplify(rotated.data(), ids, nullptr, p);
  ASSERT_EQ(a.NumberOfKeyPoints, 5);
  ASSERT_EQ(b.NumberOfKeyPoints, a.NumberOfKeyPoints);
  for (const auto& s : a.Samples)
  {
    if (!s.Key)
    {
      continue;
    }
    const Eigen::Vector3d expected =
      rotation * Eigen::Vector3d(s.Position[0], s.Position[1], s.Position[2]);
    double best = 1e300;
    for (const auto& t : b.Samples)
    {
      if (t.Key)
      {
        best = std::min(
          best, (Eigen::Vector3d(t.Position[0], t.Position[1], t.Position[2]) - expected).norm());
      }
    }
    EXPECT_LT(best, 1e-9);
  }
}
