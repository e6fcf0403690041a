// SPDX-License-Identifier: BSD-3-Clause
// The hole filling of the feature-preserving mode and its ranking helpers:
// the parallel selections are their plain definitions, and the removal costs
// computed ahead in parallel batches give the moves of a serial scan.
#include "Core/Assignment.h"
#include "Core/CellNeighbors.h"
#include "Core/Grid.h"
#include "Core/HoleFilling.h"
#include "Core/HoleFillingRecords.h"
#include "Core/Selection.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>

using asmcore::Index;
using asmtest::Cloud;
using asmtest::UnevenTwoThreads;

namespace
{
// Values with many ties, and (optionally) infinities and NaNs.
std::vector<double> TiedValues(Index n, bool nonFinite, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> level(0, 500);
  std::uniform_int_distribution<int> kind(0, 40);
  std::vector<double> v(static_cast<std::size_t>(n));
  for (auto& x : v)
  {
    x = 0.01 * level(rng) - 2.0;
    const int k = kind(rng);
    if (nonFinite && k == 0)
    {
      x = std::numeric_limits<double>::infinity();
    }
    else if (nonFinite && k == 1)
    {
      x = -std::numeric_limits<double>::infinity();
    }
    else if (nonFinite && k == 2)
    {
      x = std::numeric_limits<double>::quiet_NaN();
    }
  }
  return v;
}

// The largest finite values by definition: all finite (value, index) pairs
// fully sorted, the first `look` indices.
std::vector<Index> ReferenceLargest(const std::vector<double>& v, Index look)
{
  std::vector<asmcore::RankedValue> all;
  for (Index i = 0; i < static_cast<Index>(v.size()); ++i)
  {
    if (std::isfinite(v[i]))
    {
      all.emplace_back(v[i], i);
    }
  }
  std::sort(all.begin(), all.end(), asmcore::RanksBefore);
  std::vector<Index> ids;
  for (Index k = 0; k < std::min<Index>(look, static_cast<Index>(all.size())); ++k)
  {
    ids.push_back(all[k].second);
  }
  return ids;
}
} // namespace

TEST(HoleFilling, SortRankedIsAFullSort)
{
  for (Index n : { Index(0), Index(1), Index(1000), Index(40000), Index(300001) })
  {
    const std::vector<double> v = TiedValues(n, false, 3);
    std::vector<asmcore::RankedValue> pairs;
    for (Index i = n - 1; i >= 0; --i) // reversed: the blocks start unsorted
    {
      pairs.emplace_back(v[i], i);
    }
    std::vector<asmcore::RankedValue> reference(pairs);
    std::sort(reference.begin(), reference.end(), asmcore::RanksBefore);
    std::vector<asmcore::RankedValue> serial(pairs), parallel(pairs);
    asmcore::SortRanked(serial, {});
    asmcore::SortRanked(parallel, UnevenTwoThreads());
    EXPECT_EQ(serial, reference) << n;
    EXPECT_EQ(parallel, reference) << n;
  }
}

TEST(HoleFilling, LargestFiniteIsTheDefinition)
{
  for (Index n : { Index(0), Index(7), Index(5000), Index(200000) })
  {
    const std::vector<double> v = TiedValues(n, true, 5);
    for (Index look : { Index(0), Index(1), Index(10), n / 50, n / 3, n, 2 * n + 3 })
    {
      const std::vector<Index> reference = ReferenceLargest(v, look);
      EXPECT_EQ(asmcore::LargestFinite(v, look, {}), reference) << n << " " << look;
      EXPECT_EQ(asmcore::LargestFinite(v, look, UnevenTwoThreads()), reference) << n << " " << look;
    }
  }
  // All equal: the lowest indices, in order.
  const std::vector<double> flat(100000, 1.5);
  const std::vector<Index> first = asmcore::LargestFinite(flat, 3, UnevenTwoThreads());
  EXPECT_EQ(first, (std::vector<Index>{ 0, 1, 2 }));
}

// The threshold below which no process need send its ranked records: at
// least `keep` of all values reach it, so the best `keep` all do, and few
// more than `keep` reach it.
TEST(HoleFilling, RankThresholdKeepsTheBestAndLittleElse)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Index stride = asmcore::holes::RankStride;
  for (int processes : { 1, 2, 5 })
  {
    for (Index keep : { Index(0), Index(1), Index(100), Index(5000), Index(40000) })
    {
      std::vector<std::vector<double>> lists(static_cast<std::size_t>(processes));
      std::vector<std::vector<double>> sampled(lists.size());
      std::vector<double> all;
      for (std::size_t q = 0; q < lists.size(); ++q)
      {
        lists[q].resize(static_cast<std::size_t>(1000 + 3000 * q)); // (uneven)
        for (double& v : lists[q])
        {
          v = q == 1 ? 0.5 * uniform(random) : uniform(random); // (one process's values lower)
        }
        std::sort(lists[q].rbegin(), lists[q].rend());
        for (std::size_t k = 0; k < lists[q].size(); k += static_cast<std::size_t>(stride))
        {
          sampled[q].push_back(lists[q][k]);
        }
        all.insert(all.end(), lists[q].begin(), lists[q].end());
      }
      const double t = asmcore::holes::RankThreshold(sampled, stride, keep);
      const auto reach =
        static_cast<Index>(std::count_if(all.begin(), all.end(), [t](double v) { return v >= t; }));
      const auto total = static_cast<Index>(all.size());
      EXPECT_GE(reach, std::min(keep, total)) << processes << " " << keep;
      EXPECT_LE(reach, std::min(total, keep + (processes + 1) * stride))
        << processes << " " << keep;
      if (keep > total)
      {
        EXPECT_EQ(t, -std::numeric_limits<double>::infinity());
      }
    }
  }
}

// The hole filling's map from cell keys to indices (gap heads, touched
// cells) against std::map, through several doublings, with overwrites and
// keys that collide in the low bits.
TEST(HoleFilling, KeyTableIsAMap)
{
  asmcore::holes::KeyTable table(4);
  std::map<std::uint64_t, asmcore::Index> reference;
  std::mt19937_64 rng(9);
  for (int k = 0; k < 20000; ++k)
  {
    const std::uint64_t key = (rng() % 5000) << (k % 3 == 0 ? 42 : 0);
    const auto value = static_cast<asmcore::Index>(k);
    table.Set(key, value);
    reference[key] = value;
    const std::uint64_t probe = rng() % 6000;
    const auto it = reference.find(probe);
    ASSERT_EQ(table.Find(probe), it == reference.end() ? -1 : it->second) << probe;
  }
  for (const auto& entry : reference)
  {
    EXPECT_EQ(table.Find(entry.first), entry.second);
  }
}

TEST(HoleFilling, BatchedRemovalCostsGiveTheSerialMoves)
{
  // A sphere sampled unevenly: six samples in each cell of the x > 0 half,
  // one in each cell of the other half (large gaps), so that many samples
  // move and moves change the removal costs of candidates computed ahead.
  const Cloud c = asmtest::Sphere(30000, 1.0, 19);
  const asmtest::GriddedCloud gridded = asmtest::Gridded(c, 0.15);
  const asmcore::CellGrid& grid = gridded.Grid;
  const asmcore::CellNeighborTable& neighbors = gridded.Neighbors;
  const Index cells = grid.NumberOfCells();
  asmcore::SampleSet samples;
  samples.Start.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (Index cell = 0; cell < cells; ++cell)
  {
    const Index n0 = grid.CellSizeOf(cell);
    const double* first = c.data() + 3 * grid.CellPoints(cell)[0];
    const Index n = std::min<Index>(first[0] > 0.0 ? 6 : 1, n0);
    for (Index k = 0; k < n; ++k)
    {
      const double* p = c.data() + 3 * grid.CellPoints(cell)[k * n0 / n];
      samples.Position.insert(samples.Position.end(), p, p + 3);
      samples.Fixed.push_back(k == 0 && cell % 5 == 0 ? 1 : 0);
    }
    samples.Start[cell + 1] = samples.Start[cell] + n;
  }
  asmcore::PointArray<asmcore::SampleId> assign;
  asmcore::AssignToSamples(c.data(), grid, neighbors, samples, assign, {});
  // The largest squared distance from a point to its sample.
  auto largestHole = [&](const asmcore::SampleSet& set) {
    double hole = 0.0;
    for (Index i = 0; i < static_cast<Index>(assign.size()); ++i)
    {
      hole = std::max(hole, asmcore::AssignedDistance2(c.data(), grid, set, assign, i));
    }
    return hole;
  };
  const double holeBefore = largestHole(samples);
  const Index maxMoves = samples.Size() / 8;

  asmcore::SampleSet serial = samples;
  std::vector<Index> serialOrder;
  std::vector<char> serialMoved;
  const Index serialMoves = asmcore::FillHoles(
    c.data(), grid, neighbors, assign, maxMoves, serial, serialOrder, serialMoved, {}, 1);
  ASSERT_GT(serialMoves, 20) << "the set-up must move many samples";
  for (Index firstBatch : { Index(2), Index(32), Index(5000) })
  {
    asmcore::SampleSet batched = samples;
    std::vector<Index> batchedOrder;
    std::vector<char> batchedMoved;
    const Index batchedMoves = asmcore::FillHoles(c.data(), grid, neighbors, assign, maxMoves,
      batched, batchedOrder, batchedMoved, UnevenTwoThreads(), firstBatch);
    EXPECT_EQ(batchedMoves, serialMoves) << firstBatch;
    EXPECT_EQ(batchedOrder, serialOrder) << firstBatch;
    EXPECT_EQ(batched.Start, serial.Start) << firstBatch;
    EXPECT_EQ(batched.Position, serial.Position) << firstBatch;
    EXPECT_EQ(batched.Fixed, serial.Fixed) << firstBatch;
    EXPECT_EQ(batchedMoved, serialMoved) << firstBatch;
  }
  // The regrouping is a stable grouping by owner cell: a sample that stayed
  // keeps its cell, position and flag; a moved one sits in the cell of the
  // input point it moved to.
  ASSERT_EQ(serialOrder.size(), static_cast<std::size_t>(samples.Size()));
  Index movedCount = 0;
  for (Index cell = 0; cell < grid.NumberOfCells(); ++cell)
  {
    for (Index s = serial.Start[cell]; s < serial.Start[cell + 1]; ++s)
    {
      const Index old = serialOrder[s];
      EXPECT_EQ(serial.Fixed[s], samples.Fixed[old]);
      const bool stayed = std::equal(serial.Position.begin() + 3 * s,
        serial.Position.begin() + 3 * s + 3, samples.Position.begin() + 3 * old);
      const Index oldCell =
        static_cast<Index>(std::upper_bound(samples.Start.begin(), samples.Start.end(), old) -
          samples.Start.begin() - 1);
      const std::uint64_t key = grid.Spec.KeyOf(serial.Position.data() + 3 * s);
      const Index newCell = static_cast<Index>(
        std::lower_bound(grid.CellKey.begin(), grid.CellKey.end(), key) - grid.CellKey.begin());
      EXPECT_EQ(stayed ? oldCell : newCell, cell) << s;
      EXPECT_EQ(serialMoved[s], stayed ? 0 : 1) << s;
      movedCount += stayed ? 0 : 1;
      if (s > serial.Start[cell])
      {
        EXPECT_LT(serialOrder[s - 1], old) << "stable within cell " << cell;
      }
    }
  }
  EXPECT_EQ(movedCount, serialMoves);
  // Fixed samples never move, and the largest hole shrinks.
  for (Index s = 0; s < serial.Size(); ++s)
  {
    if (serial.Fixed[s])
    {
      const Index old = serialOrder[s];
      EXPECT_TRUE(std::equal(serial.Position.begin() + 3 * s, serial.Position.begin() + 3 * s + 3,
        samples.Position.begin() + 3 * old));
    }
  }
  asmcore::AssignToSamples(c.data(), grid, neighbors, serial, assign, {});
  EXPECT_LT(largestHole(serial), 0.7 * holeBefore);
}

// One round hole in an even sampling (a plane): the gaps are the points
// farthest from every sample, one per gap, a point counting as a gap of its
// own when no gap taken before lies within its own distance to the samples.
// So a hole wider than the sampling's spacing gets several samples (its
// centre, then its outer ring), and no two gaps are within the smaller one's
// distance of each other.
TEST(HoleFilling, AWideHoleGetsSeveralSamplesEachAtAGapOfItsOwn)
{
  Cloud c; // 41 x 41 points, 0.05 apart
  for (int i = 0; i <= 40; ++i)
  {
    for (int j = 0; j <= 40; ++j)
    {
      asmtest::Add(c, 0.05 * i, 0.05 * j, 0.0);
    }
  }
  const asmtest::GriddedCloud gridded = asmtest::Gridded(c, 0.5);
  const asmcore::CellGrid& grid = gridded.Grid;
  // Samples 0.1 apart, none within 0.35 of the centre (1, 1).
  const double centre[3] = { 1.0, 1.0, 0.0 }, radius = 0.35;
  std::vector<std::vector<double>> byCell(static_cast<std::size_t>(grid.NumberOfCells()));
  std::vector<double> before;
  for (int i = 0; i <= 20; ++i)
  {
    for (int j = 0; j <= 20; ++j)
    {
      const double p[3] = { 0.1 * i, 0.1 * j, 0.0 };
      if (std::hypot(p[0] - centre[0], p[1] - centre[1]) < radius)
      {
        continue;
      }
      const auto key = grid.Spec.KeyOf(p);
      const auto cell =
        std::lower_bound(grid.CellKey.begin(), grid.CellKey.end(), key) - grid.CellKey.begin();
      byCell[cell].insert(byCell[cell].end(), p, p + 3);
      before.insert(before.end(), p, p + 3);
    }
  }
  asmcore::SampleSet samples;
  samples.Start.assign(1, 0);
  for (const std::vector<double>& cell : byCell)
  {
    samples.Position.insert(samples.Position.end(), cell.begin(), cell.end());
    samples.Start.push_back(samples.Start.back() + static_cast<Index>(cell.size() / 3));
  }
  samples.Fixed.assign(static_cast<std::size_t>(samples.Start.back()), 0);
  asmcore::PointArray<asmcore::SampleId> assign;
  asmcore::AssignToSamples(c.data(), grid, gridded.Neighbors, samples, assign, {});
  // The distance of a position to the samples before any move.
  auto gapOf = [&](const double* p) {
    double best = 1e300;
    for (std::size_t k = 0; k < before.size(); k += 3)
    {
      best = std::min(best, std::hypot(p[0] - before[k], p[1] - before[k + 1]));
    }
    return best;
  };
  std::vector<Index> order;
  std::vector<char> moved;
  const Index moves =
    asmcore::FillHoles(c.data(), grid, gridded.Neighbors, assign, 12, samples, order, moved, {});
  ASSERT_GT(moves, 0);
  std::vector<const double*> gaps;
  Index inHole = 0;
  for (Index s = 0; s < samples.Size(); ++s)
  {
    if (moved[s])
    {
      const double* p = samples.Position.data() + 3 * s;
      gaps.push_back(p);
      inHole += std::hypot(p[0] - centre[0], p[1] - centre[1]) < radius ? 1 : 0;
    }
  }
  EXPECT_GE(inHole, 3) << moves << " moves";
  for (std::size_t a = 0; a < gaps.size(); ++a)
  {
    for (std::size_t b = a + 1; b < gaps.size(); ++b)
    {
      const double apart = std::hypot(gaps[a][0] - gaps[b][0], gaps[a][1] - gaps[b][1]);
      EXPECT_GT(apart, std::min(gapOf(gaps[a]), gapOf(gaps[b])))
        << "(" << gaps[a][0] << ", " << gaps[a][1] << ") and (" << gaps[b][0] << ", " << gaps[b][1]
        << ")";
    }
  }
}

// RingKeys (the distributed hole filling's ring, by cell keys) lists the 27
// cells around a cell in the order of the neighbour table's rings (dx
// fastest): a candidate's member cells are bits of that order.
TEST(HoleFilling, RingKeysAreTheNeighbourTablesRing)
{
  const Cloud c = asmtest::Sphere(5000, 1.0, 3);
  for (double h : { 0.2, 0.7 })
  {
    const asmtest::GriddedCloud gridded = asmtest::Gridded(c, h);
    const asmcore::CellGrid& grid = gridded.Grid;
    for (Index cell = 0; cell < grid.NumberOfCells(); ++cell)
    {
      std::uint64_t keys[27];
      asmcore::holes::RingKeys(grid.Spec, grid.CellKey[cell], keys);
      const asmcore::CellRef* ring = gridded.Neighbors.Of(cell);
      EXPECT_EQ(keys[13], grid.CellKey[cell]);
      for (int r = 0; r < 27; ++r)
      {
        if (ring[r] >= 0)
        {
          EXPECT_EQ(keys[r], grid.CellKey[ring[r]]) << "cell " << cell << ", entry " << r;
        }
        else
        {
          EXPECT_FALSE(std::binary_search(grid.CellKey.begin(), grid.CellKey.end(), keys[r]))
            << "cell " << cell << ", entry " << r << ": an occupied cell";
        }
      }
    }
  }
}
