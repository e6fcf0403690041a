// SPDX-License-Identifier: BSD-3-Clause
// The automatic cell size (CellSize.h): about the target number of
// non-empty cells, and the dense surface's cells, not stray points', when
// far outliers would drive the count. (Its fast paths and its distributed
// form: TestFastPaths.cxx.)
#include "Core/CellSize.h"
#include "Core/Grid.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using asmcore::Index;
using asmtest::AllIds;
using asmtest::Cloud;

TEST(CellSize, HitsTheTargetOccupancy)
{
  const Cloud c = asmtest::Sphere(40000, 1.0);
  const auto ids = AllIds(c);
  const auto bounds = asmcore::ComputeBounds(c.data(), ids);
  for (double target : { 10.0, 100.0, 1000.0 })
  {
    const double h = asmcore::AutomaticCellSize(c.data(), ids, bounds, target);
    const double count = static_cast<double>(
      asmcore::CountOccupiedCells(c.data(), ids, asmcore::GridSpec::Make(bounds, h)));
    EXPECT_GT(count, 0.7 * target) << "target " << target;
    EXPECT_LT(count, 1.4 * target) << "target " << target;
  }
  // A single cell for a target of one.
  const double h = asmcore::AutomaticCellSize(c.data(), ids, bounds, 1.0);
  EXPECT_EQ(asmcore::CountOccupiedCells(c.data(), ids, asmcore::GridSpec::Make(bounds, h)), 1);
}

TEST(CellSize, FarOutliersDoNotTakeTheSurfacesCells)
{
  // A sphere of 20 000 points and 150 outliers, each alone in its cell,
  // scattered in the box around it. Counted plainly, the outliers' cells
  // would be more than a third of a 400-cell target and the sphere would get
  // about 250 cells. They make up more than a fifth of the count, so each
  // cell counts by its share of the points a sample needs (about 6 here),
  // and the sphere gets nearly the whole target.
  const Index spherePoints = 20000;
  Cloud c = asmtest::Sphere(spherePoints, 1.0, 8);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  for (int added = 0; added < 150;)
  {
    const double x = u(rng), y = u(rng), z = u(rng);
    if (std::sqrt(x * x + y * y + z * z) > 1.5)
    {
      asmtest::Add(c, x, y, z);
      ++added;
    }
  }
  const auto ids = AllIds(c);
  const std::vector<Index> sphere(ids.begin(), ids.begin() + spherePoints);
  const auto bounds = asmcore::ComputeBounds(c.data(), ids);
  const double target = 400.0;
  const asmcore::GridSpec spec =
    asmcore::GridSpec::Make(bounds, asmcore::AutomaticCellSize(c.data(), ids, bounds, target));
  const auto sphereCells = static_cast<double>(asmcore::CountOccupiedCells(c.data(), sphere, spec));
  const auto allCells = static_cast<double>(asmcore::CountOccupiedCells(c.data(), ids, spec));
  EXPECT_EQ(allCells - sphereCells, 150.0) << "each outlier alone in its cell";
  EXPECT_GT(sphereCells, 0.85 * target);
  EXPECT_LT(sphereCells, 1.05 * target);
  // The grid built in the same search has that cell size.
  EXPECT_EQ(
    asmcore::BuildAutomaticCellGrid(c.data(), ids, bounds, target).Spec.CellSize, spec.CellSize);
}
