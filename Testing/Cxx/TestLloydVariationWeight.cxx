// SPDX-License-Identifier: BSD-3-Clause
// The variation-weighted final Lloyd iterations of the feature-preserving
// mode (LloydVariationWeight): the weighted assignment splits where the
// weighted distances are equal, a cluster's variation is its PCA's, the
// factors follow the formula, and on a creased surface the samples move
// towards the crease.
#include "Core/Assignment.h"
#include "Core/Lloyd.h"

#include "FeatureShapes.h"
#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using asmcore::Index;
using asmtest::Cloud;

namespace
{
// A roof: z = -|x| over [-1, 1]^2 (a 90 degree crease along x = 0),
// n x n points of a jittered grid.
Cloud Roof(int n, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.4, 0.4);
  Cloud c;
  const double step = 2.0 / n;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      const double x = -1.0 + step * (i + 0.5 + jitter(rng));
      const double y = -1.0 + step * (j + 0.5 + jitter(rng));
      asmtest::Add(c, x, y, -std::abs(x));
    }
  }
  return c;
}

// One sample per cell of the grid: the cell's first point.
asmcore::SampleSet FirstPointSamples(const Cloud& c, const asmcore::CellGrid& grid)
{
  asmcore::SampleSet samples;
  samples.Start.assign(static_cast<std::size_t>(grid.NumberOfCells()) + 1, 0);
  for (Index cell = 0; cell < grid.NumberOfCells(); ++cell)
  {
    const double* p = c.data() + 3 * grid.CellPoints(cell)[0];
    samples.Position.insert(samples.Position.end(), p, p + 3);
    samples.Fixed.push_back(0);
    samples.Start[cell + 1] = samples.Start[cell] + 1;
  }
  return samples;
}
} // namespace

TEST(LloydVariationWeight, WeightedAssignmentSplitsWhereTheWeightedDistancesMeet)
{
  // Points on the segment [0, 1] of the x axis, samples at its two ends,
  // factors 1 and 4: x^2 = 4 (1 - x)^2 at x = 2/3.
  Cloud c;
  const int n = 301;
  for (int i = 0; i < n; ++i)
  {
    asmtest::Add(c, static_cast<double>(i) / (n - 1), 0.0, 0.0);
  }
  const asmtest::GriddedCloud gridded = asmtest::Gridded(c, 2.0); // one cell
  ASSERT_EQ(gridded.Grid.NumberOfCells(), 1);
  asmcore::SampleSet samples;
  samples.Position = { 0.0, 0.0, 0.0, 1.0, 0.0, 0.0 };
  samples.Fixed = { 0, 0 };
  samples.Start = { 0, 2 };
  const std::vector<double> scale = { 1.0, 4.0 };
  asmcore::PointArray<asmcore::SampleId> plain, weighted;
  asmcore::AssignToSamples(c.data(), gridded.Grid, gridded.Neighbors, samples, plain, {});
  asmcore::AssignToSamples(
    c.data(), gridded.Grid, gridded.Neighbors, samples, weighted, {}, scale.data());
  for (Index slot = 0; slot < gridded.Grid.NumberOfPoints(); ++slot)
  {
    const double x = c[3 * gridded.Grid.PointAt(slot)];
    if (std::abs(x - 0.5) > 1e-9)
    {
      EXPECT_EQ(plain[slot], x < 0.5 ? 0 : 1) << x;
    }
    if (std::abs(x - 2.0 / 3.0) > 1e-9)
    {
      EXPECT_EQ(weighted[slot], x < 2.0 / 3.0 ? 0 : 1) << x;
    }
  }
  // Factors of 1 give the plain assignment.
  const std::vector<double> ones = { 1.0, 1.0 };
  asmcore::PointArray<asmcore::SampleId> same;
  asmcore::AssignToSamples(
    c.data(), gridded.Grid, gridded.Neighbors, samples, same, {}, ones.data());
  EXPECT_TRUE(std::equal(plain.begin(), plain.end(), same.begin()));
}

TEST(LloydVariationWeight, WeightedAssignmentIsTheLeastWeightedDistance)
{
  // One cell owning 40 samples (the two-pass search) or 100 (more than
  // LargeCellBudget: the k-d tree search), random factors in [1, 4]: every
  // point gets the sample of least scale * d^2 (ties: the lower index).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Cloud c;
  for (int i = 0; i < 3000; ++i)
  {
    asmtest::Add(c, u(rng), u(rng), 0.01 * u(rng));
  }
  const asmtest::GriddedCloud gridded = asmtest::Gridded(c, 2.0);
  ASSERT_EQ(gridded.Grid.NumberOfCells(), 1);
  for (const Index count : { Index(40), Index(100) })
  {
    asmcore::SampleSet samples;
    std::vector<double> scale;
    for (Index s = 0; s < count; ++s)
    {
      const double* p = c.data() + 3 * (7 * s);
      samples.Position.insert(samples.Position.end(), p, p + 3);
      samples.Fixed.push_back(0);
      scale.push_back(1.0 + 3.0 * u(rng));
    }
    samples.Start = { 0, count };
    asmcore::PointArray<asmcore::SampleId> assign;
    asmcore::AssignToSamples(c.data(), gridded.Grid, gridded.Neighbors, samples, assign,
      asmtest::UnevenTwoThreads(), scale.data());
    for (Index slot = 0; slot < gridded.Grid.NumberOfPoints(); ++slot)
    {
      const double* p = c.data() + 3 * gridded.Grid.PointAt(slot);
      Index best = -1;
      double bestD = std::numeric_limits<double>::infinity();
      for (Index s = 0; s < count; ++s)
      {
        const double d = scale[s] * asmcore::SquaredDistance(p, samples.Position.data() + 3 * s);
        if (d < bestD)
        {
          bestD = d;
          best = s;
        }
      }
      ASSERT_EQ(assign[slot], best) << count << " samples, slot " << slot;
    }
  }
}

TEST(LloydVariationWeight, ClusterVariationIsZeroOnAPlaneAndLargeAcrossACrease)
{
  const Cloud roof = Roof(120, 3);
  const asmtest::GriddedCloud gridded = asmtest::Gridded(roof, 0.25);
  const asmcore::SampleSet samples = FirstPointSamples(roof, gridded.Grid);
  asmcore::PointArray<asmcore::SampleId> assign;
  asmcore::AssignToSamples(roof.data(), gridded.Grid, gridded.Neighbors, samples, assign, {});
  const std::vector<double> serial =
    asmcore::ClusterVariations(roof.data(), gridded.Grid, gridded.Neighbors, assign, samples, {});
  const std::vector<double> threaded = asmcore::ClusterVariations(
    roof.data(), gridded.Grid, gridded.Neighbors, assign, samples, asmtest::UnevenTwoThreads());
  EXPECT_EQ(serial, threaded);
  // Per cluster: its points' PCA, lambda_0 / trace; a cluster on one slope
  // is flat, one that straddles the crease is not.
  std::vector<int> sides(static_cast<std::size_t>(samples.Size()), 0); // bit 1: x < 0, bit 2: x > 0
  for (Index slot = 0; slot < gridded.Grid.NumberOfPoints(); ++slot)
  {
    const double x = roof[3 * gridded.Grid.PointAt(slot)];
    sides[assign[slot]] |= x < -0.02 ? 1 : (x > 0.02 ? 2 : 0);
  }
  int flat = 0, creased = 0;
  for (Index s = 0; s < samples.Size(); ++s)
  {
    if (sides[s] == 3)
    {
      EXPECT_GT(serial[s], 0.01) << s;
      ++creased;
    }
    else if (std::abs(samples.Position[3 * s]) > 0.3)
    {
      EXPECT_LT(serial[s], 1e-12) << s;
      ++flat;
    }
  }
  EXPECT_GT(flat, 20);
  EXPECT_GT(creased, 4);
}

TEST(LloydVariationWeight, ScalesFollowTheFormula)
{
  // mean 3: ratios 0, 1/3, 2/3, 3; capped at 2.
  const std::vector<double> v = { 0.0, 1.0, 2.0, 9.0 };
  const std::vector<double> s = asmcore::VariationScales(v, 0.75, 2.0);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_DOUBLE_EQ(s[0], 1.0);
  EXPECT_DOUBLE_EQ(s[1], 1.0 + 0.75 / 3.0);
  EXPECT_DOUBLE_EQ(s[2], 1.0 + 0.75 * 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(s[3], 1.0 + 0.75 * 2.0);
  // No variation anywhere: plain distances.
  EXPECT_EQ(asmcore::VariationScales({ 0.0, 0.0 }, 0.75, 4.0), (std::vector<double>{ 1.0, 1.0 }));
  // Uncapped.
  EXPECT_DOUBLE_EQ(
    asmcore::VariationScales(v, 1.0, std::numeric_limits<double>::infinity())[3], 4.0);
}

TEST(LloydVariationWeight, SamplesMoveTowardsTheCrease)
{
  // The roof at 2 %: the weighted final iterations leave more samples next
  // to the crease than plain ones, and the same count and determinism.
  const Cloud roof = Roof(160, 9);
  const std::int64_t target = 512;
  auto nearCrease = [&](double weight) {
    const auto r =
      asmtest::SimplifyWith(roof, target, [weight](auto& p) { p.LloydVariationWeight = weight; });
    EXPECT_EQ(static_cast<std::int64_t>(r.Samples.size()), target);
    int near = 0;
    for (const auto& s : r.Samples)
    {
      near += std::abs(s.Position[0]) < 0.03 ? 1 : 0; // about a third of a sample spacing
    }
    return near;
  };
  const int plain = nearCrease(0.0), weighted = nearCrease(0.75), strong = nearCrease(3.0);
  EXPECT_GT(weighted, plain);
  EXPECT_GT(strong, weighted);
}

TEST(LloydVariationWeight, ExactMeanDoesNotDependOnOrderOrParts)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> value(0.0, 1.0 / 3.0);
  std::vector<double> v(10000);
  double sum = 0.0;
  for (double& x : v)
  {
    x = value(rng) * value(rng); // (many small values, as surface variations)
    sum += x;
  }
  asmcore::ExactMean whole;
  for (double x : v)
  {
    whole.Add(x);
  }
  EXPECT_NEAR(whole.Value(), sum / static_cast<double>(v.size()), 1e-12);
  // Three parts in another order, their sums added: the same mean, exactly.
  std::shuffle(v.begin(), v.end(), rng);
  asmcore::ExactMean parts[3];
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    parts[i % 3].Add(v[i]);
  }
  asmcore::ExactMean merged;
  for (const auto& part : parts)
  {
    for (std::size_t k = 0; k < merged.Sums.size(); ++k)
    {
      merged.Sums[k] += part.Sums[k];
    }
  }
  EXPECT_EQ(merged.Value(), whole.Value());
  EXPECT_EQ(merged.Sums, whole.Sums);
  // Empty: 0; out-of-range terms clamped.
  EXPECT_EQ(asmcore::ExactMean().Value(), 0.0);
  asmcore::ExactMean clamped;
  clamped.Add(-1.0);
  clamped.Add(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(clamped.Value(), 0.0);
}
