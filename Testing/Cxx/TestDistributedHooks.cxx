// SPDX-License-Identifier: BSD-3-Clause
// The hooks of asmcore::SimplifyParameters used by distributed runs (Grid,
// Cells, CellBudget, CloudCentroid): a cloud cut into "processes" by grid cell, each
// part simplified with the global grid and budgets, gives exactly the serial
// samples (positions and the members that place them, CoreSize); halo cells
// (budget -1) add nothing, and every point joins exactly one sample.
#include "Core/Budget.h"
#include "Core/CellFrame.h"
#include "Core/Grid.h"
#include "Core/Simplify.h"
#include "DistributedHelpers.h"
#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>

namespace
{
using asmcore::Index;

std::vector<std::array<double, 4>> Sorted(const asmcore::SimplifyResult& r)
{
  return asmtest::SortedSamples<4>(
    r, [](const asmcore::Sample& s, double* more) { more[0] = static_cast<double>(s.CoreSize); });
}

void CheckSplit(asmcore::WeightMode weight,
  const asmtest::Cloud& cloud = asmtest::Sphere(6000, 2.0, 11), Index count = 701)
{
  const std::vector<Index> ids = asmtest::AllIds(cloud);
  asmcore::SimplifyParameters p;
  p.NumberOfSamples = count;
  p.Weight = weight;
  p.Mode = asmcore::SimplifyMode::Paper; // the hooks serve the paper mode (distributed runs)
  const asmcore::SimplifyResult serial = asmcore::Simplify(cloud.data(), ids, nullptr, p);
  ASSERT_EQ(serial.Samples.size(), static_cast<std::size_t>(count));

  // The serial grid and budgets, computed as a distributed run does: cells
  // in key order, CellShares, ApportionBudget.
  const asmtest::GlobalCells cells(cloud, ids, serial.CellSize);
  const asmcore::GridSpec& spec = cells.Spec;
  const std::vector<Index> budget = asmcore::ApportionBudget(
    asmcore::CellShares(cells.Capacity, cells.Variation, p), cells.Capacity, count);
  const std::map<std::uint64_t, Index> budgetOf = cells.ByKey(budget);
  const double* centroid = cells.Centroid;

  // Three "processes": cells by x index modulo 3; each also gets the cells
  // of the next index as a halo (budget -1 there: halo).
  std::vector<std::array<double, 4>> merged;
  Index members = 0;
  for (int part = 0; part < 3; ++part)
  {
    std::vector<Index> mine;
    for (Index id : ids)
    {
      std::int64_t ijk[3];
      spec.Unpack(spec.KeyOf(&cloud[3 * id]), ijk);
      if (ijk[0] % 3 == part || (ijk[0] + 1) % 3 == part)
      {
        mine.push_back(id);
      }
    }
    asmcore::SimplifyParameters q = p;
    q.Grid = &spec;
    q.CloudCentroid = centroid;
    q.CellBudget = [&](std::uint64_t key) {
      std::int64_t ijk[3];
      spec.Unpack(key, ijk);
      return ijk[0] % 3 == part ? budgetOf.at(key) : Index(-1);
    };
    const asmcore::SimplifyResult result = asmcore::Simplify(cloud.data(), mine, nullptr, q);
    for (const auto& sample : result.Samples)
    {
      members += sample.ClusterSize;
    }
    const auto partial = Sorted(result);
    merged.insert(merged.end(), partial.begin(), partial.end());
  }
  std::sort(merged.begin(), merged.end());
  EXPECT_EQ(members, static_cast<Index>(ids.size())) << "every point in exactly one cluster";
  const auto expected = Sorted(serial);
  ASSERT_EQ(merged.size(), expected.size());
  for (std::size_t i = 0; i < merged.size(); ++i)
  {
    for (int c = 0; c < 4; ++c)
    {
      EXPECT_NEAR(merged[i][c], expected[i][c], 1e-12) << "sample " << i;
    }
  }
}
} // namespace

TEST(DistributedHooks, CellSplitGivesTheSerialSamplesUniform)
{
  CheckSplit(asmcore::WeightMode::Uniform);
}

TEST(DistributedHooks, CellSplitGivesTheSerialSamplesSurfaceVariation)
{
  CheckSplit(asmcore::WeightMode::SurfaceVariation);
}

// Gridded data with every point twice (exact ties in the key clusters'
// extremes, the median splits and the random choice among key clusters).
TEST(DistributedHooks, CellSplitGivesTheSerialSamplesOnALatticeWithDuplicates)
{
  for (int variant = 0; variant < 2; ++variant)
  {
    asmtest::Cloud cloud = asmtest::GridSurface(120, 3.0, [variant](double x, double y) {
      return variant == 0 ? 0.3 * std::sin(x) * std::cos(y) : std::floor(x + y) * 0.1;
    });
    const asmtest::Cloud copy = cloud;
    cloud.insert(cloud.end(), copy.begin(), copy.end());
    SCOPED_TRACE(::testing::Message() << "variant " << variant);
    CheckSplit(asmcore::WeightMode::Uniform, cloud, 1440);
    CheckSplit(asmcore::WeightMode::SurfaceVariation, cloud, 1440);
  }
}

// SimplifyParameters::Cells (a distributed run's points arrive grouped by
// cell): BuildRunGrid takes the given cells as they are, with the ids as
// their order, instead of grouping the points again; for points in cell
// order that is the grid BuildCellGrid makes, so both modes give the same
// samples and members.
TEST(DistributedHooks, GivenCellsAreTakenAsTheGrid)
{
  const asmtest::Cloud cloud = asmtest::Sphere(5000, 2.0, 7);
  const std::vector<Index> ids = asmtest::AllIds(cloud);
  const asmcore::GridSpec spec =
    asmcore::GridSpec::Make(asmcore::ComputeBounds(cloud.data(), ids), 0.35);
  const asmcore::CellGrid grouped = asmcore::BuildCellGrid(cloud.data(), ids, spec);
  ASSERT_GT(grouped.NumberOfCells(), 20);
  // The points copied in cell order, as a distributed run holds them.
  asmtest::Cloud ordered;
  for (Index slot = 0; slot < static_cast<Index>(ids.size()); ++slot)
  {
    const double* p = &cloud[3 * grouped.Order[slot]];
    asmtest::Add(ordered, p[0], p[1], p[2]);
  }
  asmcore::CellGrid given;
  given.Spec = spec;
  given.CellStart = grouped.CellStart;
  given.CellKey = grouped.CellKey;
  given.SlotOrder = true;

  asmcore::SimplifyParameters p;
  p.NumberOfSamples = 400;
  p.Grid = &spec;
  asmcore::SimplifyParameters q = p;
  q.Cells = &given;
  const asmcore::CellGrid regrouped = asmcore::BuildRunGrid(ordered.data(), ids, p, 400);
  const asmcore::CellGrid taken = asmcore::BuildRunGrid(ordered.data(), ids, q, 400);
  EXPECT_EQ(taken.Order, regrouped.Order);
  EXPECT_EQ(taken.CellStart, regrouped.CellStart);
  EXPECT_EQ(taken.CellKey, regrouped.CellKey);
  EXPECT_FALSE(taken.SlotOrder);

  // Taken as given: two cells merged into one stay merged.
  asmcore::CellGrid merged = given;
  merged.CellStart.erase(merged.CellStart.begin() + 1);
  merged.CellKey.erase(merged.CellKey.begin() + 1);
  q.Cells = &merged;
  const asmcore::CellGrid mergedTaken = asmcore::BuildRunGrid(ordered.data(), ids, q, 400);
  EXPECT_EQ(mergedTaken.NumberOfCells(), grouped.NumberOfCells() - 1);
  EXPECT_EQ(mergedTaken.CellSizeOf(0), grouped.CellSizeOf(0) + grouped.CellSizeOf(1));

  q.Cells = &given;
  for (const auto mode : { asmcore::SimplifyMode::Paper, asmcore::SimplifyMode::FeaturePreserving })
  {
    p.Mode = q.Mode = mode;
    const asmcore::SimplifyResult a = asmcore::Simplify(ordered.data(), ids, nullptr, p);
    const asmcore::SimplifyResult b = asmcore::Simplify(ordered.data(), ids, nullptr, q);
    ASSERT_EQ(a.Samples.size(), 400u);
    ASSERT_EQ(a.Samples.size(), b.Samples.size());
    for (std::size_t s = 0; s < a.Samples.size(); ++s)
    {
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_EQ(a.Samples[s].Position[c], b.Samples[s].Position[c]) << "sample " << s;
      }
    }
    EXPECT_EQ(a.Members, b.Members);
  }
}
