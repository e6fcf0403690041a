// SPDX-License-Identifier: BSD-3-Clause
// The searches' fast paths give the results of their plain definitions:
// the in-plane linking (dense bins), the level-by-level kd-tree, the paper
// mode's search for the sample nearest an unclaimed point (the cells' rings
// first), the incremental assignment, the fused metric queries, float
// coordinates read in place and slot ids of either width. (The grid's:
// TestFastPaths.cxx.)
#include "Core/Assignment.h"
#include "Core/CellFrame.h"
#include "Core/CellNeighbors.h"
#include "Core/Curvature.h"
#include "Core/Grid.h"
#include "Core/KeyPoints.h"
#include "Core/Lloyd.h"
#include "Core/Metrics.h"
#include "Core/Neighbors.h"
#include "Core/Simplify.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <utility>

using asmcore::Index;
using asmtest::AllIds;
using asmtest::Cloud;
using asmtest::UnevenTwoThreads;

TEST(FastPaths, LinkInPlaneMatchesConnectedComponents)
{
  // Clumps of points: few and many points (up to 64, all pairs as bit
  // masks; the first trials sit on that border), dense and sparse bins (the
  // sparse ones take the sorted-bin path).
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 34; ++trial)
  {
    const std::size_t n = trial < 4
      ? 62 + static_cast<std::size_t>(trial)
      : 2 + static_cast<std::size_t>(u(rng) * (trial < 19 ? 120 : 600));
    const double spread = trial % 3 == 0 ? 100.0 : 1.0;
    asmcore::LocalPoints q;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double cx = std::floor(u(rng) * 4) * 0.3 * spread;
      q.emplace_back(cx + 0.1 * u(rng), 0.1 * u(rng) + (i % 2) * 0.05 * spread, u(rng));
    }
    std::vector<Index> subset(n);
    std::iota(subset.begin(), subset.end(), Index(0));
    std::shuffle(subset.begin(), subset.end(), rng);
    const double d = 0.02 + 0.05 * u(rng);
    const auto clusters = asmcore::LinkInPlane(q, subset, d);
    // Reference: label propagation over all pairs within d.
    std::vector<Index> label(n);
    std::iota(label.begin(), label.end(), Index(0));
    for (bool changed = true; changed;)
    {
      changed = false;
      for (std::size_t i = 0; i < n; ++i)
      {
        for (std::size_t j = 0; j < n; ++j)
        {
          const Eigen::Vector3d& a = q[subset[i]];
          const Eigen::Vector3d& b = q[subset[j]];
          const double dx = a[0] - b[0], dy = a[1] - b[1];
          if (dx * dx + dy * dy <= d * d && label[j] < label[i])
          {
            label[i] = label[j];
            changed = true;
          }
        }
      }
    }
    // Same partition, clusters ordered by first member, members in subset order.
    std::vector<std::vector<Index>> expected;
    std::vector<Index> slot(n, -1);
    for (std::size_t i = 0; i < n; ++i)
    {
      if (slot[label[i]] < 0)
      {
        slot[label[i]] = static_cast<Index>(expected.size());
        expected.emplace_back();
      }
      expected[slot[label[i]]].push_back(subset[i]);
    }
    ASSERT_EQ(clusters.Size(), static_cast<Index>(expected.size())) << "trial " << trial;
    for (Index k = 0; k < clusters.Size(); ++k)
    {
      EXPECT_EQ(std::vector<Index>(clusters.Begin(k), clusters.End(k)), expected[k]);
    }
  }
}

TEST(FastPaths, KdTreeBuiltInParallelAnswersAlike)
{
  const Cloud c = asmtest::Sphere(20000, 1.0, 8);
  const auto ids = AllIds(c);
  const asmcore::Neighbors one(c.data(), ids);
  const asmcore::Neighbors two(c.data(), ids, UnevenTwoThreads());
  std::vector<Index> a, b;
  std::vector<double> da, db;
  for (Index i = 0; i < 2000; i += 7)
  {
    one.KNearest(c.data() + 3 * i, 12, a, da);
    two.KNearest(c.data() + 3 * i, 12, b, db);
    EXPECT_EQ(a, b);
    EXPECT_EQ(da, db);
  }
}

// In the paper mode, every point that no sample placed (a cell without
// budget, a key cluster left out) joins the nearest sample of all (ties: the
// lower index): searched in the cells' rings, else globally (a far outlier;
// a cell next to very many samples, where the ring search would be slow).
TEST(FastPaths, PaperModeJoinsUnclaimedPointsToTheNearestSample)
{
  // A rough sphere (many key clusters per cell: some are left out) and three
  // far outliers (cells without budget and without samples in their rings).
  Cloud sphere;
  {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> noise(-0.03, 0.03);
    const Cloud smooth = asmtest::Sphere(20000, 1.0, 9);
    for (std::size_t i = 0; i < smooth.size(); i += 3)
    {
      const double f = 1.0 + noise(rng);
      asmtest::Add(sphere, f * smooth[i], f * smooth[i + 1], f * smooth[i + 2]);
    }
    asmtest::Add(sphere, 6.0, 0.0, 0.0);
    asmtest::Add(sphere, 0.0, -6.0, 0.5);
    asmtest::Add(sphere, 0.1, 0.0, 7.0);
  }
  // A wavy sheet filling the cell [0, 1)^2 x [0, 1) (CellSize 1, the origin
  // at the bounds' minimum) and two points in the next cell along x, too few
  // for a sample of their own, next to the sheet's 3000 samples.
  Cloud sheet;
  for (int i = 0; i < 150; ++i)
  {
    for (int j = 0; j < 150; ++j)
    {
      const double x = 0.0066 * i, y = 0.0066 * j;
      asmtest::Add(sheet, x, y, 0.02 + 0.01 * std::sin(9.0 * x) * std::cos(7.0 * y));
    }
  }
  asmtest::Add(sheet, 1.001, 0.5, 0.02);
  asmtest::Add(sheet, 1.002, 0.2, 0.03);
  // Cells of 0.01 (below 1, where h and h^2 differ): two blobs of 1500
  // points near the left sides of cells 1 and 4 along x, and two points
  // alone, at x = 0 (it sets the grid's origin) and at the right side of
  // cell 2. The latter's ring (cells 1 to 3) holds the first blob's samples,
  // about 2 cells away, but the second blob's, outside the ring, are nearer.
  Cloud tiny;
  {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> across(0.0, 0.004), along(0.0, 0.0003);
    for (double left : { 0.0101, 0.0401 })
    {
      for (int i = 0; i < 1500; ++i)
      {
        const double x = left + along(rng);
        const double y = across(rng);
        asmtest::Add(tiny, x, y, across(rng));
      }
    }
    asmtest::Add(tiny, 0.0, 0.0, 0.0);
    asmtest::Add(tiny, 0.0299, 0.002, 0.002);
  }
  struct Case
  {
    const Cloud* Points;
    Index Target;
    double CellSize;
    Index Outliers; // joined points farther than half a cell from their sample, at least
  };
  for (const Case& run : { Case{ &sphere, 400, 0.0, 3 }, Case{ &sphere, 1000, 0.0, 3 },
         Case{ &sheet, 3000, 1.0, 0 }, Case{ &tiny, 20, 0.01, 2 } })
  {
    const Cloud& c = *run.Points;
    const auto ids = AllIds(c);
    asmcore::SimplifyParameters parameters;
    parameters.Mode = asmcore::SimplifyMode::Paper;
    parameters.NumberOfSamples = run.Target;
    parameters.CellSize = run.CellSize;
    parameters.SamplesPerCell = 2.0;
    const asmcore::SimplifyResult r = asmcore::Simplify(c.data(), ids, nullptr, parameters);
    ASSERT_EQ(static_cast<Index>(r.Samples.size()), run.Target);
    const asmcore::SimplifyResult two =
      asmcore::Simplify(c.data(), ids, nullptr, parameters, UnevenTwoThreads());
    ASSERT_EQ(r.Members, two.Members) << "target " << run.Target;
    std::vector<int> seen(ids.size(), 0);
    Index joined = 0, far = 0;
    std::vector<Index> ownerOf(ids.size(), -1);
    for (Index s = 0; s < static_cast<Index>(r.Samples.size()); ++s)
    {
      const asmcore::Sample& sample = r.Samples[s];
      for (Index m = sample.MemberBegin; m < sample.MemberBegin + sample.ClusterSize; ++m)
      {
        const double* p = c.data() + 3 * r.Members[m];
        ++seen[r.Members[m]];
        ownerOf[r.Members[m]] = s;
        if (m < sample.MemberBegin + sample.CoreSize)
        {
          continue;
        }
        // The nearest sample by brute force (ties: the first).
        Index best = -1;
        double bestD = 0.0;
        for (Index t = 0; t < static_cast<Index>(r.Samples.size()); ++t)
        {
          const double* q = r.Samples[t].Position;
          const double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
          const double d = dx * dx + dy * dy + dz * dz;
          if (best < 0 || d < bestD)
          {
            best = t;
            bestD = d;
          }
        }
        ASSERT_EQ(s, best) << "target " << run.Target << ": point " << r.Members[m];
        ++joined;
        far += bestD > 0.25 * r.CellSize * r.CellSize ? 1 : 0;
      }
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int k) { return k == 1; }))
      << "the members partition the points";
    // The cases reach the branches: points joined within half a cell of
    // their sample, and the outliers beyond.
    EXPECT_GT(joined - far, 1) << "target " << run.Target;
    EXPECT_GE(far, run.Outliers) << "target " << run.Target;
    const Index n = static_cast<Index>(ids.size());
    for (Index o = n - (run.Points == &sphere ? 3 : 2); o < n; ++o)
    {
      const asmcore::Sample& sample = r.Samples[ownerOf[o]];
      EXPECT_EQ(std::count(r.Members.begin() + sample.MemberBegin,
                  r.Members.begin() + sample.MemberBegin + sample.CoreSize, o),
        0)
        << "point " << o << " placed no sample";
    }
  }
}

TEST(FastPaths, UpdateAssignmentMatchesAFreshAssignment)
{
  // After a few samples move to other cells (as hole filling moves them),
  // the incremental update gives exactly the assignment searched afresh.
  const Cloud c = asmtest::Sphere(20000, 1.0, 11);
  const asmtest::GriddedCloud gridded = asmtest::Gridded(c, 0.2);
  const asmcore::CellGrid& grid = gridded.Grid;
  const asmcore::CellNeighborTable& neighbors = gridded.Neighbors;
  const Index cells = grid.NumberOfCells();
  // Four samples per cell, on points of the cell (every 4th sample of
  // every 3rd cell absent, so that some rings are thin); the most populous
  // cell owns more than LargeCellBudget (searched with a k-d tree).
  asmcore::SampleSet samples;
  samples.Start.assign(static_cast<std::size_t>(cells) + 1, 0);
  std::vector<Index> ownerOf;
  Index large = 0;
  for (Index cell = 0; cell < cells; ++cell)
  {
    large = grid.CellSizeOf(cell) > grid.CellSizeOf(large) ? cell : large;
  }
  ASSERT_GT(grid.CellSizeOf(large), asmcore::LargeCellBudget);
  for (Index cell = 0; cell < cells; ++cell)
  {
    const Index n = cell == large ? asmcore::LargeCellBudget + 8
                                  : std::min<Index>(cell % 3 == 0 ? 3 : 4, grid.CellSizeOf(cell));
    for (Index k = 0; k < n; ++k)
    {
      const double* p = c.data() + 3 * grid.CellPoints(cell)[k * grid.CellSizeOf(cell) / n];
      samples.Position.insert(samples.Position.end(), p, p + 3);
      samples.Fixed.push_back(0);
      ownerOf.push_back(cell);
    }
    samples.Start[cell + 1] = samples.Start[cell] + n;
  }
  asmcore::PointArray<asmcore::SampleId> assign, check;
  asmcore::AssignToSamples(c.data(), grid, neighbors, samples, assign, {});
  // Move every 17th sample onto a point of a cell 5 cells further, and
  // regroup by owner (stable), as FillHoles does.
  const Index count = samples.Size();
  std::vector<double> position(samples.Position);
  for (Index s = 0; s < count; s += 17)
  {
    const Index to = (ownerOf[s] + 5) % cells;
    const double* p = c.data() + 3 * grid.CellPoints(to)[0];
    std::copy(p, p + 3, position.begin() + 3 * s);
    ownerOf[s] = to;
  }
  std::vector<Index> order(static_cast<std::size_t>(count));
  std::iota(order.begin(), order.end(), Index(0));
  std::stable_sort(
    order.begin(), order.end(), [&](Index a, Index b) { return ownerOf[a] < ownerOf[b]; });
  asmcore::SampleSet after;
  after.Start.assign(static_cast<std::size_t>(cells) + 1, 0);
  std::vector<char> moved(static_cast<std::size_t>(count), 0);
  for (Index s = 0; s < count; ++s)
  {
    after.Position.insert(
      after.Position.end(), position.begin() + 3 * order[s], position.begin() + 3 * order[s] + 3);
    after.Fixed.push_back(0);
    ++after.Start[ownerOf[order[s]] + 1];
    moved[s] = order[s] % 17 == 0 ? 1 : 0;
  }
  std::partial_sum(after.Start.begin(), after.Start.end(), after.Start.begin());
  ASSERT_GT(after.Start[large + 1] - after.Start[large], asmcore::LargeCellBudget);
  asmcore::AssignToSamples(c.data(), grid, neighbors, after, check, {});
  asmcore::UpdateAssignment(
    c.data(), grid, neighbors, after, order, moved, assign, UnevenTwoThreads());
  EXPECT_EQ(assign, check);
  Index changed = 0;
  for (Index i = 0; i < static_cast<Index>(check.size()); ++i)
  {
    changed += check[i] >= 0 && order[check[i]] % 17 == 0 ? 1 : 0;
  }
  EXPECT_GT(changed, 0) << "some points must now belong to a moved sample";
}

// The metric queries in blocks (SurfaceDistances) give, for every point
// whatever the order of the ids, the definitions: exactly the distance to
// the nearest surface point, and to rounding the distance to the PCA plane
// of the k nearest (by squared distance, ties by id; by brute force). A
// plane kept for a neighbour set is the set's own.
TEST(FastPaths, SurfaceDistancesAreTheDefinitions)
{
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Cloud surface, queries;
  for (int i = 0; i < 3000; ++i)
  {
    const double x = u(rng), y = u(rng);
    asmtest::Add(surface, x, y, 0.2 * x * x - 0.1 * y + 0.01 * u(rng));
  }
  for (int i = 0; i < 5000; ++i)
  {
    asmtest::Add(queries, 1.2 * u(rng), 1.2 * u(rng), 0.3 * u(rng));
  }
  asmtest::Add(surface, 0.5, 0.5, 0.0); // a duplicate pair: ties by id
  asmtest::Add(surface, 0.5, 0.5, 0.0);
  std::vector<Index> sids(surface.size() / 3), qids(queries.size() / 3);
  std::iota(sids.begin(), sids.end(), Index(0));
  std::iota(qids.begin(), qids.end(), Index(0));
  std::shuffle(qids.begin(), qids.end(), rng); // a random order of the queries
  const asmcore::Neighbors tree(surface.data(), sids);
  const int k = 8;
  std::vector<double> plane, nearest;
  asmcore::SurfaceDistances(queries.data(), qids, tree, k, &plane, &nearest, UnevenTwoThreads());
  ASSERT_EQ(qids.size(), plane.size());
  ASSERT_EQ(qids.size(), nearest.size());
  EXPECT_EQ(nearest, asmcore::NearestDistances(queries.data(), qids, tree));
  EXPECT_EQ(plane, asmcore::PointToPlaneDistances(queries.data(), qids, tree, k));
  double worst = 0.0;
  for (std::size_t i = 0; i < qids.size(); ++i)
  {
    const double* p = queries.data() + 3 * qids[i];
    std::vector<std::pair<double, Index>> ranked;
    for (Index s : sids)
    {
      const double* x = surface.data() + 3 * s;
      const double dx = x[0] - p[0], dy = x[1] - p[1], dz = x[2] - p[2];
      ranked.emplace_back(dx * dx + dy * dy + dz * dz, s);
    }
    std::partial_sort(ranked.begin(), ranked.begin() + k, ranked.end());
    ASSERT_EQ(std::sqrt(ranked[0].first), nearest[i]) << i;
    std::vector<Index> near(k);
    for (int j = 0; j < k; ++j)
    {
      near[j] = ranked[j].second;
    }
    const asmcore::CellFrame fit = asmcore::ComputeCellFrame(
      surface.data(), asmcore::IdView(near.data(), static_cast<std::size_t>(k)));
    // (The closed-form eigensolver of the metric agrees with ComputeCellFrame's
    // iterative one to rounding.)
    const double definition =
      std::abs(fit.Normal().dot(Eigen::Vector3d(p[0], p[1], p[2]) - fit.Centroid));
    worst = std::max(worst, std::abs(definition - plane[i]));
  }
  // (6.7e-13 measured: the queries lie up to 0.3 off the surface, whose
  // spacing is about 0.04.)
  EXPECT_LT(worst, 1e-11);
}

TEST(FastPaths, FloatCoordinatesReadInPlaceGiveTheDoubleResult)
{
  // The filter hands a float cloud to the core as floats (no double copy):
  // every step must see the same numbers as with the cloud widened to
  // doubles, so the results must be identical, sample for sample. 250 k
  // points reach the cell-size subsample; the second case lists its ids
  // (every seventh point left out, as for non-finite points).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> noise(-0.01, 0.01);
  const Cloud smooth = asmtest::Sphere(250000, 1.0, 4);
  std::vector<float> floats(smooth.size());
  Cloud widened(smooth.size());
  for (std::size_t i = 0; i < smooth.size(); ++i)
  {
    floats[i] = static_cast<float>(smooth[i] * (1.0 + noise(rng)));
    widened[i] = static_cast<double>(floats[i]);
  }
  const std::vector<Index> all = AllIds(widened);
  std::vector<Index> some;
  for (Index id = 0; id < 40000; ++id)
  {
    if (id % 7 != 3)
    {
      some.push_back(id);
    }
  }
  for (const auto mode : { asmcore::SimplifyMode::FeaturePreserving, asmcore::SimplifyMode::Paper })
  {
    for (const bool listed : { false, true })
    {
      const asmcore::IdView ids =
        listed ? asmcore::IdView(some) : asmcore::IdView::Identity(all.size());
      asmcore::SimplifyParameters parameters;
      parameters.Mode = mode;
      parameters.NumberOfSamples = static_cast<Index>(ids.size() / 40);
      const std::string what =
        std::string(mode == asmcore::SimplifyMode::Paper ? "paper" : "default") +
        (listed ? ", listed ids" : ", identity");
      const asmcore::SimplifyResult reference =
        asmcore::Simplify(widened.data(), ids, nullptr, parameters);
      const asmcore::SimplifyResult r =
        asmcore::Simplify(floats.data(), ids, nullptr, parameters, UnevenTwoThreads());
      ASSERT_EQ(r.Samples.size(), static_cast<std::size_t>(parameters.NumberOfSamples)) << what;
      ASSERT_EQ(r.Samples.size(), reference.Samples.size()) << what;
      ASSERT_EQ(r.Members, reference.Members) << what;
      EXPECT_EQ(r.CellSize, reference.CellSize) << what;
      EXPECT_GT(r.NumberOfKeyPoints, 0) << what;
      EXPECT_EQ(r.NumberOfKeyPoints, reference.NumberOfKeyPoints) << what;
      for (std::size_t s = 0; s < r.Samples.size(); ++s)
      {
        const asmcore::Sample& a = r.Samples[s];
        const asmcore::Sample& b = reference.Samples[s];
        ASSERT_TRUE(std::equal(a.Position, a.Position + 3, b.Position)) << what << ", sample " << s;
        ASSERT_TRUE(std::equal(a.Normal, a.Normal + 3, b.Normal)) << what << ", sample " << s;
        ASSERT_EQ(a.Representative, b.Representative) << what << ", sample " << s;
        ASSERT_EQ(a.ClusterSize, b.ClusterSize) << what << ", sample " << s;
        ASSERT_EQ(a.Key, b.Key) << what << ", sample " << s;
      }
    }
  }
  // The curvature's k-d tree and estimates read floats in place too.
  const asmcore::IdView ids = asmcore::IdView::Identity(all.size());
  const asmcore::Neighbors fromFloats(floats.data(), ids, UnevenTwoThreads());
  const asmcore::Neighbors fromDoubles(widened.data(), ids);
  std::vector<double> queries;
  for (std::size_t i = 0; i < widened.size(); i += 3 * 997)
  {
    queries.insert(queries.end(), { widened[i] + 1e-3, widened[i + 1], widened[i + 2] });
  }
  const auto nq = static_cast<Index>(queries.size() / 3);
  const auto a = asmcore::EstimateCurvature(
    floats.data(), ids, fromFloats, queries.data(), nq, nullptr, 0, UnevenTwoThreads());
  const auto b = asmcore::EstimateCurvature(
    widened.data(), ids, fromDoubles, queries.data(), nq, nullptr, 0, {});
  ASSERT_EQ(a.size(), static_cast<std::size_t>(nq));
  ASSERT_EQ(b.size(), a.size());
  Index fits = 0;
  for (std::size_t q = 0; q < a.size(); ++q)
  {
    ASSERT_EQ(a[q].MeanCurvature, b[q].MeanCurvature) << "query " << q;
    ASSERT_EQ(a[q].SurfaceVariation, b[q].SurfaceVariation) << "query " << q;
    ASSERT_TRUE(std::equal(a[q].Normal, a[q].Normal + 3, b[q].Normal)) << "query " << q;
    fits += a[q].QuadricFit ? 1 : 0;
  }
  EXPECT_GT(fits, nq / 2);
}

TEST(FastPaths, SlotIdsKeepEveryIdInEitherWidth)
{
  // 32 bits when every id fits, the 64-bit order itself when one does not;
  // either way the order is taken over (released).
  asmcore::PointArray<Index> narrow = { 5, 2, 7, 4294967295LL };
  const asmcore::SlotIds small(narrow, UnevenTwoThreads());
  EXPECT_TRUE(narrow.empty());
  EXPECT_EQ(small[0], 5);
  EXPECT_EQ(small[2], 7);
  EXPECT_EQ(small[3], 4294967295LL);
  asmcore::PointArray<Index> wide = { 1, Index(1) << 33, 3 };
  const asmcore::SlotIds large(wide, UnevenTwoThreads());
  EXPECT_TRUE(wide.empty());
  EXPECT_EQ(large[0], 1);
  EXPECT_EQ(large[1], Index(1) << 33);
  EXPECT_EQ(large[2], 3);
}
