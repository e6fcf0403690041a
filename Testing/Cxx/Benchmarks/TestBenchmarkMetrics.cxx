// SPDX-License-Identifier: BSD-3-Clause
// The benchmarks' measuring instruments (Benchmarks/): quality measures on
// clouds whose answers are known by hand, the synthetic shapes, and the
// peers driven to the requested count. Built into asm_tests when the
// benchmarks are built (ASM_BUILD_BENCHMARKS).
#include "BenchmarkData.h"
#include "BenchmarkMethods.h"
#include "QualityMetrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace
{
/// The 11 x 11 grid {0..10}^2 at z = 0, spacing 1 (diagonal sqrt(200)).
std::vector<double> Grid()
{
  std::vector<double> xyz;
  for (int i = 0; i <= 10; ++i)
  {
    for (int j = 0; j <= 10; ++j)
    {
      xyz.insert(xyz.end(), { double(i), double(j), 0.0 });
    }
  }
  return xyz;
}

/// Its points with both coordinates even (6 x 6).
std::vector<double> EvenGrid()
{
  std::vector<double> xyz;
  for (int i = 0; i <= 10; i += 2)
  {
    for (int j = 0; j <= 10; j += 2)
    {
      xyz.insert(xyz.end(), { double(i), double(j), 0.0 });
    }
  }
  return xyz;
}

const double Diagonal = std::sqrt(200.0);
} // namespace

TEST(BenchmarkMetrics, SubsetOfAPlane)
{
  const asmbench::Reference reference(Grid(), { 0, 0, 0, 1, 1, 0 });
  EXPECT_DOUBLE_EQ(reference.Diagonal(), Diagonal);
  const asmbench::Quality q = reference.Measure(EvenGrid());
  // Coplanar samples: no distance to their plane.
  EXPECT_NEAR(q.PlaneMean, 0.0, 1e-12);
  EXPECT_NEAR(q.PlaneMax, 0.0, 1e-12);
  // Largest hole: a point with both coordinates odd, sqrt(2) from a sample.
  EXPECT_NEAR(q.Hole, std::sqrt(2.0) / Diagonal, 1e-12);
  // Original -> samples: 36 at 0, 60 at 1, 25 at sqrt(2); samples -> original: all 0.
  EXPECT_NEAR(q.NNRms, std::sqrt(0.5 * (60.0 + 25.0 * 2.0) / 121.0) / Diagonal, 1e-12);
  // Feature points: (0,0,0) is a sample, (1,1,0) is sqrt(2) from one.
  ASSERT_TRUE(q.HasTips);
  EXPECT_NEAR(q.TipMean, 0.5 * std::sqrt(2.0) / Diagonal, 1e-12);
  EXPECT_NEAR(q.TipMax, std::sqrt(2.0) / Diagonal, 1e-12);
}

TEST(BenchmarkMetrics, ShiftedCopy)
{
  const asmbench::Reference reference(Grid(), {});
  std::vector<double> shifted = Grid();
  for (std::size_t i = 2; i < shifted.size(); i += 3)
  {
    shifted[i] += 0.5;
  }
  const asmbench::Quality q = reference.Measure(shifted);
  EXPECT_NEAR(q.PlaneMean, 0.5 / Diagonal, 1e-12);
  EXPECT_NEAR(q.PlaneMax, 0.5 / Diagonal, 1e-12);
  EXPECT_NEAR(q.NNRms, 0.5 / Diagonal, 1e-12);
  EXPECT_NEAR(q.Hole, 0.5 / Diagonal, 1e-12);
  EXPECT_FALSE(q.HasTips);
}

TEST(BenchmarkMetrics, MedianQualityTakesEachMeasuresMiddle)
{
  // Three draws whose measures peak in different draws: the median is taken
  // measure by measure, not the draw that is middle on one of them.
  std::vector<asmbench::Quality> draws(3);
  const double values[3][6] = { { 1, 9, 5, 2, 7, 3 }, { 3, 8, 4, 6, 1, 2 }, { 2, 7, 6, 4, 3, 1 } };
  for (int d = 0; d < 3; ++d)
  {
    asmbench::Quality& q = draws[d];
    q.PlaneMean = values[d][0];
    q.PlaneMax = values[d][1];
    q.NNRms = values[d][2];
    q.Hole = values[d][3];
    q.TipMean = values[d][4];
    q.TipMax = values[d][5];
    q.HasTips = true;
  }
  const asmbench::Quality m = asmbench::MedianQuality(draws);
  EXPECT_EQ(m.PlaneMean, 2.0);
  EXPECT_EQ(m.PlaneMax, 8.0);
  EXPECT_EQ(m.NNRms, 5.0);
  EXPECT_EQ(m.Hole, 4.0);
  EXPECT_EQ(m.TipMean, 3.0);
  EXPECT_EQ(m.TipMax, 2.0);
  EXPECT_TRUE(m.HasTips);
  // An even count gives the mean of the two middle values; one draw is itself.
  draws.pop_back();
  EXPECT_EQ(asmbench::MedianQuality(draws).PlaneMean, 2.0);
  EXPECT_EQ(asmbench::MedianQuality({ draws[1] }).Hole, 6.0);
}

TEST(BenchmarkData, SyntheticShapesAreSeededAndOnTheirSurface)
{
  const asmbench::Input a = asmbench::MakeSpikes(5000);
  const asmbench::Input b = asmbench::MakeSpikes(5000);
  ASSERT_EQ(a.NumberOfPoints(), 5000);
  EXPECT_EQ(asmbench::Coordinates(a.Data), asmbench::Coordinates(b.Data));
  ASSERT_EQ(a.Features.size(), 12u * 3u);
  for (std::size_t i = 0; i < a.Features.size(); i += 3)
  {
    EXPECT_NEAR(std::hypot(a.Features[i], a.Features[i + 1], a.Features[i + 2]), 1.6, 1e-12);
  }
  const std::vector<double> xyz = asmbench::Coordinates(a.Data);
  for (std::size_t i = 0; i < xyz.size(); i += 3)
  {
    const double r = std::hypot(xyz[i], xyz[i + 1], xyz[i + 2]);
    ASSERT_GE(r, 1.0 - 1e-6);
    ASSERT_LE(r, 1.6 + 1e-6);
  }
  const asmbench::Input bracket = asmbench::MakeBracket(4000);
  EXPECT_EQ(bracket.Features.size(), 12u * 3u);
  const asmbench::Input terrain = asmbench::MakeTerrain(4000);
  EXPECT_EQ(terrain.Features.size(), 9u * 3u);
  // Each summit is the highest point of the terrain around it.
  const std::vector<double> t = asmbench::Coordinates(terrain.Data);
  for (std::size_t f = 0; f < terrain.Features.size(); f += 3)
  {
    for (std::size_t i = 0; i < t.size(); i += 3)
    {
      if (std::hypot(t[i] - terrain.Features[f], t[i + 1] - terrain.Features[f + 1]) < 0.05)
      {
        ASSERT_LE(t[i + 2], terrain.Features[f + 2] + 1e-6);
      }
    }
  }
  // Several generation chunks (65536 points each): no repeated points.
  std::vector<double> bumps = asmbench::Coordinates(asmbench::MakeInput("bumps:200k").Data);
  ASSERT_EQ(bumps.size(), 3u * 200000u);
  std::vector<std::array<double, 3>> sorted(200000);
  for (std::size_t i = 0; i < sorted.size(); ++i)
  {
    sorted[i] = { bumps[3 * i], bumps[3 * i + 1], bumps[3 * i + 2] };
  }
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::unique(sorted.begin(), sorted.end()) - sorted.begin(), 200000);
  EXPECT_EQ(asmbench::ParseCount("14M"), 14000000);
  EXPECT_EQ(asmbench::ParseCount("100k"), 100000);
  EXPECT_EQ(asmbench::ParseCount("x"), -1);
  EXPECT_EQ(asmbench::ParseCount("0"), -1);
  EXPECT_EQ(asmbench::ParseCount("1e12"), -2); // more than MaxPointCount
  EXPECT_EQ(
    asmbench::ParseFractionList("--fractions", "0.05,1"), std::vector<double>({ 0.05, 1.0 }));
  EXPECT_THROW(asmbench::ParseFractionList("--fractions", "0.05,0.05"), asmbench::UsageError);
  EXPECT_THROW(asmbench::ParseIntegerList("--threads", ",", 1), asmbench::UsageError);
}

TEST(BenchmarkMethods, SearchScaleFindsTheCount)
{
  vtkIdType found = 0;
  const double s =
    asmbench::SearchScale([](double v) { return static_cast<vtkIdType>(1e6 / (v * v)); }, 1000, 1.0,
      2.0, 0.01, 40, found);
  EXPECT_NEAR(static_cast<double>(found), 1000.0, 10.0);
  EXPECT_NEAR(s, std::sqrt(1000.0), 0.5);
}

TEST(BenchmarkMethods, PeersAreDrivenToTheCount)
{
  const asmbench::Input kitten = asmbench::ReadPLY(ASM_TEST_DATA_DIR "/kitten.ply");
  ASSERT_EQ(kitten.NumberOfPoints(), 5210);
  for (vtkIdType target : { 52, 261, 1042 })
  {
    const auto voxel = asmbench::MakeVoxelGrid(kitten.Data, target).Run(true);
    EXPECT_LE(std::abs(static_cast<double>(voxel.Count - target)), std::max(0.5, 0.01 * target));
    EXPECT_EQ(voxel.Xyz.size(), static_cast<std::size_t>(3 * voxel.Count));
    EXPECT_EQ(asmbench::MakeMaskPoints(kitten.Data, target, 1).Run(false).Count, target);
    if (asmbench::HaveCGAL())
    {
      const auto grid = asmbench::MakeCgalGrid(kitten.Data, target).Run(false);
      EXPECT_LE(std::abs(static_cast<double>(grid.Count - target)), std::max(0.5, 0.01 * target));
    }
  }
  const asmbench::AsmConfig paper{ "paper", asmbench::AsmMode::Paper, false };
  EXPECT_EQ(asmbench::MakeAsm(kitten.Data, 261, paper).Run(false).Count, 261);
}

// vtkVoxelGrid allocates every bin: the divisions the search tries must never
// exceed MaxVoxelBins (2^28), whatever the cell size asked for (a tiny or
// non-finite one, a flat box), else std::bad_array_new_length on big clouds.
TEST(BenchmarkMethods, VoxelDivisionsStayWithinTheBinBound)
{
  const double cube[6] = { -1.2, 1.2, -1.4, 1.4, -1.1, 1.1 };
  const double flat[6] = { 0.0, 100.0, 0.0, 50.0, 0.0, 0.0 };
  for (const double* bounds : { cube, flat })
  {
    for (double s :
      std::vector<double>{ 1.0, 1e-2, 1e-3, 1e-5, 1e-9, 0.0, -1.0, std::nan(""), HUGE_VAL })
    {
      const std::array<int, 3> d = asmbench::VoxelDivisions(bounds, s);
      EXPECT_TRUE(asmbench::DivisionsFit(d)) << "s = " << s;
      EXPECT_LE(double(d[0]) * d[1] * d[2], asmbench::MaxVoxelBins) << "s = " << s;
    }
  }
  // A cell large enough is used as asked: round(range / s) per axis.
  const std::array<int, 3> d = asmbench::VoxelDivisions(cube, 0.01);
  EXPECT_EQ(d, (std::array<int, 3>{ 240, 280, 220 }));
  EXPECT_EQ(asmbench::VoxelDivisions(flat, 1.0), (std::array<int, 3>{ 100, 50, 1 }));
  // The finest grid of a cube is close to the bound (cube root of 2^28 = 645 per unit axis).
  const std::array<int, 3> fine = asmbench::VoxelDivisions(cube, 1e-9);
  EXPECT_GT(double(fine[0]) * fine[1] * fine[2], 0.9 * asmbench::MaxVoxelBins);
  EXPECT_FALSE(asmbench::DivisionsFit({ 2000, 2000, 2000 }));
  EXPECT_FALSE(asmbench::DivisionsFit({ 0, 10, 10 }));
}
