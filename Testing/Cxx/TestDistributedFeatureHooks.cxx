// SPDX-License-Identifier: BSD-3-Clause
// The hooks of the feature-preserving mode used by distributed runs (Grid,
// CellBudget with TRUE budgets for halo cells, OutputCell, CloudCentroid):
// a cloud cut into slabs of grid cells, each slab simplified with a halo of
// InfluenceRingsOf + 2 rings (vtkASMDistributed.h, HaloRingsFor), gives
// exactly the serial samples and clusters (FillHoles off, as distributed runs
// have it). And the serial result of both modes does not depend on the order
// of the input points.
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
#include <map>
#include <random>

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
  p.FillHoles = false; // global: off in distributed runs
  p.BoundSnappedHoles = false; // likewise
  p.FinalLloydIterations = 0;  // likewise
  return p;
}

void CheckSlabs(int crossCellIterations, int slabs)
{
  const asmtest::Cloud cloud = asmtest::Sphere(20000, 2.0, 5);
  const std::vector<Index> ids = asmtest::AllIds(cloud);
  asmcore::SimplifyParameters p = FeatureParameters();
  p.CrossCellIterations = crossCellIterations;
  const asmcore::SimplifyResult serial = asmcore::Simplify(cloud.data(), ids, nullptr, p);
  ASSERT_EQ(serial.Samples.size(), 4000u);

  // The global grid and budgets, as a distributed run computes them.
  const asmtest::GlobalCells cells(cloud, ids, serial.CellSize);
  const asmcore::GridSpec& spec = cells.Spec;
  const std::vector<Index> budget = asmcore::ApportionWithCoverage(
    asmcore::CellShares(cells.Capacity, cells.Variation, p, p.BudgetExponent), cells.Capacity, 4000, p.CoverEveryCell);
  const std::map<std::uint64_t, Index> budgetOf = cells.ByKey(budget);
  const double* centroid = cells.Centroid;

  // Slabs of x indices, each with its halo.
  const int halo = asmcore::InfluenceRingsOf(p) + 2;
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
  for (int part = 0; part < slabs; ++part)
  {
    std::vector<Index> mine;
    for (Index id : ids)
    {
      const std::int64_t i = xIndex(spec.KeyOf(&cloud[3 * id]));
      if (slabOf(std::max<std::int64_t>(0, i - halo)) <= part &&
        part <= slabOf(std::min<std::int64_t>(dim - 1, i + halo)))
      {
        mine.push_back(id);
      }
    }
    smallestPart = std::min(smallestPart, mine.size());
    asmcore::SimplifyParameters q = p;
    q.Grid = &spec;
    q.CloudCentroid = centroid;
    q.CellBudget = [&](std::uint64_t key) { return budgetOf.at(key); };
    q.OutputCell = [&](std::uint64_t key) { return slabOf(xIndex(key)) == part; };
    const asmcore::SimplifyResult result = asmcore::Simplify(cloud.data(), mine, nullptr, q);
    for (const auto& sample : result.Samples)
    {
      members += sample.ClusterSize;
    }
    const auto partial = Sorted(result);
    merged.insert(merged.end(), partial.begin(), partial.end());
  }
  EXPECT_LT(smallestPart, ids.size()) << "a slab's halo must not cover the whole cloud";
  std::sort(merged.begin(), merged.end());
  EXPECT_EQ(members, static_cast<Index>(ids.size())) << "every point in exactly one cluster";
  const auto expected = Sorted(serial);
  ASSERT_EQ(merged.size(), expected.size());
  for (std::size_t i = 0; i < merged.size(); ++i)
  {
    for (int c = 0; c < 5; ++c)
    {
      ASSERT_EQ(merged[i][c], expected[i][c]) << "sample " << i << ", column " << c;
    }
  }
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
        ASSERT_NEAR(shuffled[i][c], reference[i][c], tolerance) << "seed " << seed << ", sample " << i;
      }
      ASSERT_EQ(shuffled[i][4], reference[i][4]) << "seed " << seed << ", sample " << i;
    }
  }
}
} // namespace

TEST(DistributedFeatureHooks, SlabsWithHaloGiveTheSerialSamples)
{
  CheckSlabs(1, 4);
}

TEST(DistributedFeatureHooks, SlabsWithHaloGiveTheSerialSamplesTwoCrossCellSteps)
{
  CheckSlabs(2, 3);
}

TEST(DistributedFeatureHooks, FeatureResultDoesNotDependOnPointOrder)
{
  CheckOrder(FeatureParameters());
}

TEST(DistributedFeatureHooks, PaperResultDoesNotDependOnPointOrder)
{
  asmcore::SimplifyParameters p;
  p.Mode = asmcore::SimplifyMode::Paper;
  p.NumberOfSamples = 1500;
  CheckOrder(p);
}
