// SPDX-License-Identifier: BSD-3-Clause
// The hooks of the feature-preserving mode used by distributed runs (Grid,
// CellBudget with TRUE budgets for halo cells, OutputCell, CloudCentroid,
// SumOverProcesses, GatherOverProcesses): a cloud cut into slabs of grid
// cells, each slab simplified with a halo of InfluenceRingsOf + 2 rings
// (vtkASMDistributed.h, HaloRingsFor), gives exactly the serial samples and
// clusters (the slabs run as concurrent threads, whose sums and gathers
// meet as MPI's would: the final Lloyd iterations' mean, the hole filling's
// rankings and removal costs).
// And the serial result of both modes does not depend on the order of the
// input points.
#include "Core/Budget.h"
#include "Core/CellFrame.h"
#include "Core/FeatureSimplify.h"
#include "Core/Grid.h"
#include "Core/Simplify.h"
#include "DistributedHelpers.h"
#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <random>
#include <thread>

namespace
{
using asmcore::Index;

// (x, y, z, cluster size, key flag) of every sample, sorted.
std::vector<std::array<double, 5>> Sorted(const asmcore::SimplifyResult& r)
{
  return asmtest::SortedSamples<5>(r, [](const asmcore::Sample& s, double* more) {
    more[0] = static_cast<double>(s.ClusterSize);
    more[1] = s.Key ? 1.0 : 0.0;
  });
}

asmcore::SimplifyParameters FeatureParameters()
{
  asmcore::SimplifyParameters p;
  p.NumberOfSamples = 4000;
  p.SamplesPerCell = 2.0;
  p.FillHoles = false;         // (see HoleFillingOverSlabs)
  p.BoundSnappedHoles = false; // likewise (taken after the run, over all processes)
  p.FinalLloydIterations = 0;  // (see FinalStepsOverSlabs)
  return p;
}

using asmtest::Concatenated;
using asmtest::SumOf;
using asmtest::ThreadCollective;

// Every slab's owned cells' samples (key, count, positions), gathered; each
// slab takes those of the cells it holds (ShareSamples).
void TakeOwnersSamples(const std::vector<double>& all, const std::vector<std::uint64_t>& keys,
  const std::vector<Index>& start, std::vector<double>& positions)
{
  for (std::size_t at = 0; at < all.size();)
  {
    const auto key = static_cast<std::uint64_t>(all[at]);
    const auto n = static_cast<Index>(all[at + 1]);
    at += 2;
    const auto it = std::lower_bound(keys.begin(), keys.end(), key);
    if (it != keys.end() && *it == key)
    {
      const auto c = static_cast<std::size_t>(it - keys.begin());
      ASSERT_EQ(start[c + 1] - start[c], n) << "the same samples in every copy of a cell";
      std::copy_n(
        all.begin() + static_cast<std::ptrdiff_t>(at), 3 * n, positions.begin() + 3 * start[c]);
    }
    at += static_cast<std::size_t>(3 * n);
  }
}

// Whether the slabs' samples and clusters, merged, are the serial ones.
// `exchange`: the halo cells' samples come from their owners after every
// step (ShareSamples), with a halo of InfluenceRingsPerStep + 2 rings
// instead of InfluenceRingsOf + 2; `narrower`: that many rings fewer.
// `given`: that cloud instead of a sphere of `points` points.
bool SlabsGiveTheSerialSamples(asmcore::SimplifyParameters p, int slabs, Index points = 20000,
  bool exchange = false, int narrower = 0, const asmtest::Cloud* given = nullptr)
{
  const asmtest::Cloud cloud = given ? *given : asmtest::Sphere(points, 2.0, 5);
  const std::vector<Index> ids = asmtest::AllIds(cloud);
  const asmcore::SimplifyResult serial = asmcore::Simplify(cloud.data(), ids, nullptr, p);
  EXPECT_EQ(serial.Samples.size(), static_cast<std::size_t>(p.NumberOfSamples));

  // The global grid and budgets, as a distributed run computes them.
  const asmtest::GlobalCells cells(cloud, ids, serial.CellSize);
  const asmcore::GridSpec& spec = cells.Spec;
  const std::vector<Index> budget = asmcore::ApportionWithCoverage(
    asmcore::CellShares(cells.Capacity, cells.Variation, p, p.BudgetExponent), cells.Capacity,
    p.NumberOfSamples, p.CoverEveryCell);
  const std::map<std::uint64_t, Index> budgetOf = cells.ByKey(budget);
  const double* centroid = cells.Centroid;

  // Slabs of x indices, each with its halo.
  const int halo =
    (exchange ? asmcore::InfluenceRingsPerStep(p) : asmcore::InfluenceRingsOf(p)) + 2 - narrower;
  const std::int64_t dim = spec.Dims[0];
  auto slabOf = [&](std::int64_t i) { return static_cast<int>(i * slabs / dim); };
  auto xIndex = [&](std::uint64_t key) {
    std::int64_t ijk[3];
    spec.Unpack(key, ijk);
    return ijk[0];
  };
  std::vector<std::array<double, 5>> merged;
  Index members = 0;
  std::size_t smallestPart = ids.size();
  std::vector<std::vector<Index>> mine(static_cast<std::size_t>(slabs));
  for (int part = 0; part < slabs; ++part)
  {
    for (Index id : ids)
    {
      const std::int64_t i = xIndex(spec.KeyOf(&cloud[3 * id]));
      if (slabOf(std::max<std::int64_t>(0, i - halo)) <= part &&
        part <= slabOf(std::min<std::int64_t>(dim - 1, i + halo)))
      {
        mine[part].push_back(id);
      }
    }
    smallestPart = std::min(smallestPart, mine[part].size());
  }
  // The slabs run at once (each one's sums wait for the others').
  ThreadCollective<long long> sums(slabs, SumOf);
  ThreadCollective<double> gather(slabs, Concatenated);
  ThreadCollective<double> shared(slabs, Concatenated);
  std::vector<asmcore::SimplifyResult> results(static_cast<std::size_t>(slabs));
  std::vector<std::thread> threads;
  for (int part = 0; part < slabs; ++part)
  {
    threads.emplace_back([&, part]() {
      asmcore::SimplifyParameters q = p;
      q.Grid = &spec;
      q.CloudCentroid = centroid;
      q.CellBudget = [&](std::uint64_t key) { return budgetOf.at(key); };
      q.OutputCell = [&, part](std::uint64_t key) { return slabOf(xIndex(key)) == part; };
      q.SumOverProcesses = [&, part](std::vector<long long>& v) { sums.Meet(part, v); };
      q.GatherOverProcesses = [&, part](std::vector<double>& v) { gather.Meet(part, v); };
      if (exchange)
      {
        q.ShareSamples = [&, part](const std::vector<std::uint64_t>& keys,
                           const std::vector<Index>& start, std::vector<double>& positions) {
          std::vector<double> mine;
          for (std::size_t c = 0; c < keys.size(); ++c)
          {
            if (slabOf(xIndex(keys[c])) == part)
            {
              mine.insert(mine.end(),
                { static_cast<double>(keys[c]), static_cast<double>(start[c + 1] - start[c]) });
              mine.insert(
                mine.end(), positions.begin() + 3 * start[c], positions.begin() + 3 * start[c + 1]);
            }
          }
          shared.Meet(part, mine);
          TakeOwnersSamples(mine, keys, start, positions);
        };
      }
      results[part] = asmcore::Simplify(cloud.data(), mine[part], nullptr, q);
    });
  }
  for (std::thread& t : threads)
  {
    t.join();
  }
  EXPECT_EQ(sums.Calls, slabs * asmcore::CollectiveSumsOf(p));
  EXPECT_EQ(gather.Calls > 0, p.FillHoles) << "the hole filling gathers (only)";
  EXPECT_EQ(shared.Calls > 0, exchange);
  for (const asmcore::SimplifyResult& result : results)
  {
    for (const auto& sample : result.Samples)
    {
      members += sample.ClusterSize;
    }
    const auto partial = Sorted(result);
    merged.insert(merged.end(), partial.begin(), partial.end());
  }
  EXPECT_LT(smallestPart, ids.size()) << "a slab's halo must not cover the whole cloud";
  std::sort(merged.begin(), merged.end());
  // Every point in exactly one cluster; (x, y, z, cluster size, key flag)
  // exactly.
  return members == static_cast<Index>(ids.size()) && merged == Sorted(serial);
}

void CheckOrder(asmcore::SimplifyParameters p)
{
  const asmtest::Cloud cloud = asmtest::Sphere(20000, 2.0, 9);
  std::vector<Index> ids = asmtest::AllIds(cloud);
  const auto reference = Sorted(asmcore::Simplify(cloud.data(), ids, nullptr, p));
  ASSERT_EQ(reference.size(), static_cast<std::size_t>(p.NumberOfSamples));
  const double tolerance = 1e-9 * 8.0; // 1e-9 of the bounding-box diagonal (about 7)
  for (unsigned seed : { 1u, 2u })
  {
    std::shuffle(ids.begin(), ids.end(), std::mt19937(seed));
    const auto shuffled = Sorted(asmcore::Simplify(cloud.data(), ids, nullptr, p));
    ASSERT_EQ(shuffled.size(), reference.size());
    for (std::size_t i = 0; i < reference.size(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_NEAR(shuffled[i][c], reference[i][c], tolerance)
          << "seed " << seed << ", sample " << i;
      }
      ASSERT_EQ(shuffled[i][4], reference[i][4]) << "seed " << seed << ", sample " << i;
    }
  }
}
} // namespace

TEST(DistributedFeatureHooks, SlabsWithHaloGiveTheSerialSamples)
{
  asmcore::SimplifyParameters p = FeatureParameters();
  p.CrossCellIterations = 1;
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 4));
}

TEST(DistributedFeatureHooks, SlabsWithHaloGiveTheSerialSamplesTwoCrossCellSteps)
{
  asmcore::SimplifyParameters p = FeatureParameters();
  p.CrossCellIterations = 2;
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 3));
}

// The final Lloyd iterations, weighted as by default (4 rings each and the
// mean variation of the whole cloud) and plain (2 rings each), on a finer
// grid so that the wider halo still leaves parts of the cloud out.
TEST(DistributedFeatureHooks, FinalStepsOverSlabs)
{
  asmcore::SimplifyParameters p = FeatureParameters();
  p.NumberOfSamples = 16000;
  p.FeatureSamplesPerCell = 1.0;
  p.FinalLloydIterations = asmcore::SimplifyParameters().FinalLloydIterations;
  ASSERT_GT(p.LloydVariationWeight, 0.0);
  ASSERT_EQ(asmcore::CollectiveSumsOf(p), 2);
  // Lemma 2: 1; the cross-cell step: 2; the first weighted step after it:
  // 2, the second: 4; the final clusters: 2 (the halo is 2 more).
  EXPECT_EQ(asmcore::InfluenceRingsOf(p), 11);
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 3, 80000));
  p.LloydVariationWeight = 0.0;
  ASSERT_EQ(asmcore::CollectiveSumsOf(p), 0);
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 4, 80000));
}

// The default steps, hole filling included, on a grid of about 100 cells
// across the sphere (200 k points).
namespace
{
asmcore::SimplifyParameters HoleFillingParameters()
{
  asmcore::SimplifyParameters p = FeatureParameters();
  p.FillHoles = true;
  p.NumberOfSamples = 50000;
  p.FeatureSamplesPerCell = 1.0;
  p.FinalLloydIterations = asmcore::SimplifyParameters().FinalLloydIterations;
  return p;
}
} // namespace

// The hole filling (as by default: four rounds, with the final Lloyd
// iterations after them): each slab ranks its own samples and points and
// computes its candidates' removal costs; the gathered rankings and costs
// give every slab the moves of the serial run. A grid of about 100 cells
// across the sphere, so that the 21-ring halo leaves parts of it out.
TEST(DistributedFeatureHooks, HoleFillingOverSlabs)
{
  asmcore::SimplifyParameters p = HoleFillingParameters();
  // Lemma 2: 1; the cross-cell step: 2; four rounds: 8; the final steps: 2
  // and 4; the final clusters: 2.
  EXPECT_EQ(asmcore::InfluenceRingsOf(p), 19);
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 3, 200000));
  p.FinalLloydIterations = 0;
  p.HoleFillRounds = 2;
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 4, 200000));
}

// Every step followed by an exchange of the halo cells' samples with their
// owners: a halo of 6 rings instead of 21 (defaults), and of 4 with plain
// final iterations, gives the serial samples too.
TEST(DistributedFeatureHooks, SharedSamplesNeedAHaloOfOneStep)
{
  asmcore::SimplifyParameters p = HoleFillingParameters();
  EXPECT_EQ(asmcore::InfluenceRingsPerStep(p), 4);
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 4, 200000, true));
  p.LloydVariationWeight = 0.0;
  EXPECT_EQ(asmcore::InfluenceRingsPerStep(p), 2);
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 6, 200000, true));
  // The exchange is what makes so narrow a halo enough: one ring fewer (3)
  // still gives the serial samples with it, and not without it.
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 6, 200000, true, 1));
  EXPECT_FALSE(SlabsGiveTheSerialSamples(
    p, 6, 200000, false, asmcore::InfluenceRingsOf(p) - asmcore::InfluenceRingsPerStep(p) + 1));
}

// Covering rounds (off by default) move each sample within its own
// cluster: local too, exact over slabs with the exchange after each round.
TEST(DistributedFeatureHooks, CoveringRoundsOverSlabs)
{
  asmcore::SimplifyParameters p = HoleFillingParameters();
  p.CoveringRounds = 2;
  EXPECT_EQ(asmcore::InfluenceRingsOf(p), 23); // (2 more per round)
  EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 4, 200000, true));
  // (The rounds move samples: the test is not that of the default.)
  const asmtest::Cloud cloud = asmtest::Sphere(200000, 2.0, 5);
  const std::vector<Index> ids = asmtest::AllIds(cloud);
  const auto covered = Sorted(asmcore::Simplify(cloud.data(), ids, nullptr, p));
  p.CoveringRounds = 0;
  EXPECT_NE(covered, Sorted(asmcore::Simplify(cloud.data(), ids, nullptr, p)));
}

TEST(DistributedFeatureHooks, FeatureResultDoesNotDependOnPointOrder)
{
  CheckOrder(FeatureParameters());
  asmcore::SimplifyParameters p = FeatureParameters();
  p.FillHoles = true; // (exact ties between gap points, rare: by cell, then place in the cell)
  CheckOrder(p);
}

TEST(DistributedFeatureHooks, PaperResultDoesNotDependOnPointOrder)
{
  asmcore::SimplifyParameters p;
  p.Mode = asmcore::SimplifyMode::Paper;
  p.NumberOfSamples = 1500;
  CheckOrder(p);
}

// Combinations of the feature-preserving mode's options (each switch, the
// iteration counts, the budget and the variation weights, over the values
// vtkASMSimplify's properties accept), drawn from a fixed seed and run as
// the filter runs them distributed (the halo cells' samples from their
// owners after every step): the slabs give the serial samples for each.
// (With a halo three rings narrower, four of the first six differ.)
TEST(DistributedFeatureHooks, OptionCombinationsOverSlabs)
{
  std::mt19937 random(2026);
  auto draw = [&](std::size_t n) { return static_cast<std::size_t>(random() % n); };
  auto coin = [&]() { return draw(2) == 1; };
  for (int trial = 0; trial < 10; ++trial)
  {
    asmcore::SimplifyParameters p = HoleFillingParameters();
    p.NumberOfSamples = 12000;
    p.FillHoles = coin();
    p.ValidateKeyPoints = coin();
    p.InPlaneKeyPoints = coin();
    p.ExtremeKeyPoints = coin();
    p.SparseCellKeyPoints = coin();
    p.CoverEveryCell = coin();
    p.ReserveFreeSample = coin();
    p.InputPointSamples = coin();
    p.KeyPointRadius = std::array<double, 3>{ 0.01, 0.7, 1.0 }[draw(3)];
    p.KeyPointProminence = std::array<double, 3>{ 0.0, 0.05, 0.5 }[draw(3)];
    p.BudgetExponent = std::array<double, 3>{ 0.0, 0.5, 1.0 }[draw(3)];
    p.LloydIterations = std::array<int, 3>{ 0, 1, 4 }[draw(3)];
    p.CrossCellIterations = static_cast<int>(draw(5));
    p.FinalLloydIterations = static_cast<int>(draw(4));
    p.CoveringRounds = draw(4) == 0 ? 1 : 0;
    p.HoleFillFraction = std::array<double, 3>{ 0.0, 0.02, 0.5 }[draw(3)];
    p.LloydVariationWeight = std::array<double, 3>{ 0.0, 0.75, 100.0 }[draw(3)];
    p.VariationBudget = std::array<double, 3>{ 0.0, 1.0, 10.0 }[draw(3)];
    p.VariationCap = std::array<double, 3>{ 0.0, 0.5, 4.0 }[draw(3)];
    SCOPED_TRACE(::testing::Message()
      << "trial " << trial << ": holes " << p.FillHoles << " validate " << p.ValidateKeyPoints
      << " in-plane " << p.InPlaneKeyPoints << " extreme " << p.ExtremeKeyPoints << " sparse "
      << p.SparseCellKeyPoints << " cover " << p.CoverEveryCell << " reserve "
      << p.ReserveFreeSample << " input points " << p.InputPointSamples << " radius "
      << p.KeyPointRadius << " prominence " << p.KeyPointProminence << " exponent "
      << p.BudgetExponent << " lloyd " << p.LloydIterations << " cross " << p.CrossCellIterations
      << " final " << p.FinalLloydIterations << " covering " << p.CoveringRounds << " fraction "
      << p.HoleFillFraction << " weight " << p.LloydVariationWeight << " budget "
      << p.VariationBudget << " cap " << p.VariationCap);
    EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 4, 50000, true));
  }
}

// An n x n lattice over [-3, 3]^2, every point twice: flat (variant 0), a
// smooth height field (1) or one with steps (2).
namespace
{
asmtest::Cloud LatticeTwice(int n, int variant)
{
  asmtest::Cloud cloud = asmtest::GridSurface(n, 3.0, [variant](double x, double y) {
    return variant == 0 ? 0.0
      : variant == 1    ? 0.3 * std::sin(x) * std::cos(y)
                        : std::floor(x + y) * 0.1;
  });
  const asmtest::Cloud copy = cloud;
  cloud.insert(cloud.end(), copy.begin(), copy.end());
  return cloud;
}
} // namespace

// Gridded data (a raster's points: a flat lattice, a smooth height field and
// one with steps), every point twice: exact ties everywhere (equal
// distances to samples, equal spreads and gaps, duplicate points split
// between clusters) break the same way over slabs as in the serial run.
// (With a halo of one ring, four of the six cases differ.)
TEST(DistributedFeatureHooks, LatticeWithDuplicatesOverSlabs)
{
  asmcore::SimplifyParameters p = HoleFillingParameters();
  p.BoundSnappedHoles = false;
  for (int variant = 0; variant < 3; ++variant)
  {
    const asmtest::Cloud cloud = LatticeTwice(300, variant);
    for (Index ns : { Index(2000), Index(18000) })
    {
      p.NumberOfSamples = ns;
      SCOPED_TRACE(::testing::Message() << "variant " << variant << " N_s " << ns);
      EXPECT_TRUE(SlabsGiveTheSerialSamples(p, 4, 0, true, 0, &cloud));
    }
  }
}

// Gridded clouds with every point twice, whose distinct points tie exactly
// everywhere, given in another order (the points themselves permuted, so
// that each has another id and the cells hold them in another order): both
// modes give the same samples, key flags and cluster sizes (positions to
// 1e-8, about 1e-9 of the diagonal: the output's order of the members, and
// so some sums, may differ). Without the canonical order within a cell
// (CanonicalOrder) 70-99 % of the samples moved on the flat and stepped
// lattices.
TEST(DistributedFeatureHooks, ResultOnALatticeWithDuplicatesDoesNotDependOnPointOrder)
{
  for (int variant = 0; variant < 3; ++variant)
  {
    const asmtest::Cloud cloud = LatticeTwice(150, variant);
    const std::vector<Index> ids = asmtest::AllIds(cloud);
    for (asmcore::SimplifyMode mode :
      { asmcore::SimplifyMode::FeaturePreserving, asmcore::SimplifyMode::Paper })
    {
      SCOPED_TRACE(::testing::Message()
        << "variant " << variant << (mode == asmcore::SimplifyMode::Paper ? " paper" : " feature"));
      asmcore::SimplifyParameters p;
      p.NumberOfSamples = 2000;
      p.Mode = mode;
      const auto reference = Sorted(asmcore::Simplify(cloud.data(), ids, nullptr, p));
      ASSERT_EQ(reference.size(), 2000u);
      for (unsigned seed : { 1u, 2u })
      {
        std::vector<Index> order = ids;
        std::shuffle(order.begin(), order.end(), std::mt19937(seed));
        asmtest::Cloud permuted;
        for (Index id : order)
        {
          asmtest::Add(permuted, cloud[3 * id], cloud[3 * id + 1], cloud[3 * id + 2]);
        }
        const auto other = Sorted(asmcore::Simplify(permuted.data(), ids, nullptr, p));
        ASSERT_EQ(other.size(), reference.size());
        for (std::size_t i = 0; i < reference.size(); ++i)
        {
          for (int c = 0; c < 3; ++c)
          {
            ASSERT_NEAR(other[i][c], reference[i][c], 1e-8) << "seed " << seed << ", sample " << i;
          }
          ASSERT_EQ(other[i][3], reference[i][3])
            << "seed " << seed << ", sample " << i << ": size";
          ASSERT_EQ(other[i][4], reference[i][4]) << "seed " << seed << ", sample " << i << ": key";
        }
      }
    }
  }
}
