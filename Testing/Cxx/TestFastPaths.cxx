// SPDX-License-Identifier: BSD-3-Clause
// The grid's fast paths give the results of their plain definitions: the
// bitmap and hash paths, reciprocal keys, the counting sort, parallel cuts,
// the cell-size subsample and the neighbouring cells (one search per row).
// (The searches' fast paths: TestFastPathsSearch.cxx.)
#include "Core/CellFrame.h"
#include "Core/CellNeighbors.h"
#include "Core/CellSize.h"
#include "Core/Grid.h"
#include "Core/GroupBy.h"
#include "Core/Simplify.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <utility>

using asmcore::Index;
using asmtest::AllIds;
using asmtest::Cloud;
using asmtest::UnevenTwoThreads;

namespace
{
// The grid by its definition: (key, id) pairs sorted.
asmcore::CellGrid ReferenceGrid(
  const double* xyz, asmcore::IdView ids, const asmcore::GridSpec& spec)
{
  std::vector<std::pair<std::uint64_t, Index>> keyed;
  for (Index id : ids)
  {
    keyed.emplace_back(spec.KeyOf(xyz + 3 * id), id);
  }
  std::sort(keyed.begin(), keyed.end());
  asmcore::CellGrid grid;
  grid.Spec = spec;
  for (std::size_t i = 0; i < keyed.size(); ++i)
  {
    grid.Order.push_back(keyed[i].second);
    if (i == 0 || keyed[i].first != keyed[i - 1].first)
    {
      grid.CellKey.push_back(keyed[i].first);
      grid.CellStart.push_back(static_cast<Index>(i));
    }
  }
  grid.CellStart.push_back(static_cast<Index>(keyed.size()));
  return grid;
}

void ExpectSameGrid(const asmcore::CellGrid& a, const asmcore::CellGrid& b)
{
  EXPECT_EQ(a.CellKey, b.CellKey);
  EXPECT_EQ(a.CellStart, b.CellStart);
  EXPECT_EQ(a.Order, b.Order);
}

// Points exactly on cell borders (multiples of the cell size from the
// origin) and just beside them, where a reciprocal could round differently.
Cloud BorderCloud(double h, int n)
{
  Cloud c;
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> cell(0, n);
  std::uniform_int_distribution<int> nudge(-2, 2);
  for (int i = 0; i < 4000; ++i)
  {
    double p[3];
    for (double& x : p)
    {
      x = cell(rng) * h;
      for (int k = nudge(rng); k != 0; k += k < 0 ? 1 : -1)
      {
        x = std::nextafter(x, k < 0 ? -1e300 : 1e300);
      }
    }
    asmtest::Add(c, p[0], p[1], p[2]);
  }
  asmtest::Add(c, 0, 0, 0);
  return c;
}
} // namespace

TEST(FastPaths, GridMatchesDefinitionOnBitmapAndHashPaths)
{
  const Cloud c = asmtest::Sphere(20000, 1.0, 11, 3.0, -2.0, 0.5);
  const auto ids = AllIds(c);
  const auto bounds = asmcore::ComputeBounds(c.data(), ids);
  // 0.2: a small grid (bitmap); 1e-4: 2e4 cells per axis (hash table).
  for (double h : { 0.2, 0.013, 1e-4 })
  {
    const auto spec = asmcore::GridSpec::Make(bounds, h);
    const auto reference = ReferenceGrid(c.data(), ids, spec);
    ExpectSameGrid(asmcore::BuildCellGrid(c.data(), ids, spec), reference);
    ExpectSameGrid(asmcore::BuildCellGrid(c.data(), ids, spec, UnevenTwoThreads()), reference);
    EXPECT_EQ(asmcore::CountOccupiedCells(c.data(), ids, spec), reference.NumberOfCells());
    EXPECT_EQ(asmcore::CountOccupiedCells(c.data(), ids, spec, UnevenTwoThreads()),
      reference.NumberOfCells());
    // Every cell twice, its points far apart in the order: counted once.
    std::vector<Index> twice(ids);
    twice.insert(twice.end(), ids.rbegin(), ids.rend());
    EXPECT_EQ(asmcore::CountOccupiedCells(c.data(), twice, spec, UnevenTwoThreads()),
      reference.NumberOfCells());
    // The keys themselves, ascending (distributed runs send them around).
    EXPECT_EQ(asmcore::OccupiedCellKeys(c.data(), twice, spec), reference.CellKey);
    EXPECT_EQ(
      asmcore::OccupiedCellKeys(c.data(), ids, spec, UnevenTwoThreads()), reference.CellKey);
  }
}

TEST(FastPaths, GridKeysExactOnCellBorders)
{
  for (double h : { 0.1, 1.0 / 3.0, 0.7 })
  {
    const Cloud c = BorderCloud(h, 30);
    const auto ids = AllIds(c);
    const auto spec = asmcore::GridSpec::Make(asmcore::ComputeBounds(c.data(), ids), h);
    ExpectSameGrid(asmcore::BuildCellGrid(c.data(), ids, spec), ReferenceGrid(c.data(), ids, spec));
  }
}

TEST(FastPaths, BoundsAndCentroidOfALargeCloudAreThoseOfEveryPoint)
{
  // From 65 536 points the bounds and the centroid are taken in blocks of
  // points (on threads or not), then combined: the result is that of one
  // plain pass over every point (the centroid up to the order of its sums).
  const Cloud c = asmtest::Sphere(200000, 1.0, 12, 10.0, -3.0, 0.5);
  const auto ids = AllIds(c);
  double lo[3], hi[3], mean[3] = { 0, 0, 0 };
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = hi[a] = c[a];
  }
  for (std::size_t i = 0; i < c.size(); i += 3)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], c[i + a]);
      hi[a] = std::max(hi[a], c[i + a]);
      mean[a] += c[i + a];
    }
  }
  for (const asmcore::Execution& execution : { asmcore::Execution(), UnevenTwoThreads() })
  {
    const asmcore::Bounds bounds = asmcore::ComputeBounds(c.data(), ids, execution);
    double centroid[3];
    asmcore::ComputeCentroid(c.data(), ids, centroid, execution);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(bounds.Min[a], lo[a]);
      EXPECT_EQ(bounds.Max[a], hi[a]);
      const double expected = mean[a] / static_cast<double>(ids.size());
      EXPECT_NEAR(centroid[a], expected, 1e-12 * (1.0 + std::abs(expected)));
    }
  }
}

TEST(FastPaths, FloatCoordinatesAndEveryKindOfIdsGiveTheDefinition)
{
  // The streaming passes loop once per storage (floats or doubles) and kind
  // of ids (a list, the identity, a range): each of the six gives what the
  // definition gives on the same points as doubles, on cell borders too.
  Cloud c = BorderCloud(0.1, 30);
  const Cloud sphere = asmtest::Sphere(20000, 1.0, 11, 3.0, -2.0, 0.5);
  c.insert(c.end(), sphere.begin(), sphere.end());
  const std::vector<float> floats(c.begin(), c.end());
  const Cloud widened(floats.begin(), floats.end());
  const Index n = static_cast<Index>(c.size() / 3);
  std::vector<Index> listed = AllIds(c);
  std::shuffle(listed.begin(), listed.end(), std::mt19937_64(4));
  listed.resize(static_cast<std::size_t>(n / 2));
  for (const asmcore::IdView ids : { asmcore::IdView(listed), asmcore::IdView::Identity(n),
         asmcore::IdView::Range(n / 3, static_cast<std::size_t>(n / 2)) })
  {
    const std::vector<Index> idList(ids.begin(), ids.end());
    const Cloud* pair[2] = { &c, &widened };
    for (int k = 0; k < 2; ++k)
    {
      const Cloud& doubles = *pair[k];
      const asmcore::Coordinates xyz =
        k == 0 ? asmcore::Coordinates(doubles.data()) : asmcore::Coordinates(floats.data());
      const auto bounds = asmcore::ComputeBounds(xyz, ids, UnevenTwoThreads());
      const auto reference = asmcore::ComputeBounds(doubles.data(), idList);
      double centroid[3], expected[3];
      asmcore::ComputeCentroid(xyz, ids, centroid, UnevenTwoThreads());
      asmcore::ComputeCentroid(doubles.data(), idList, expected);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(bounds.Min[a], reference.Min[a]);
        EXPECT_EQ(bounds.Max[a], reference.Max[a]);
        EXPECT_EQ(centroid[a], expected[a]);
      }
      // 0.1: the border cells (bitmap); 1e-4: the hash table's path.
      for (double h : { 0.1, 1e-4 })
      {
        const auto spec = asmcore::GridSpec::Make(reference, h);
        const asmcore::CellGrid grid = ReferenceGrid(doubles.data(), idList, spec);
        ExpectSameGrid(asmcore::BuildCellGrid(xyz, ids, spec, UnevenTwoThreads()), grid);
        EXPECT_EQ(asmcore::CountOccupiedCells(xyz, ids, spec), grid.NumberOfCells());
        // (The hash path looks up the keys it inserted: points read two ways
        // would not find theirs.)
        ASSERT_FALSE(HasFailure());
      }
      // The subsample picks the same points (a 200 000-point cloud's rate).
      EXPECT_EQ(asmcore::CellSizeSubsample(xyz, ids, 200000.0, 400.0, UnevenTwoThreads()),
        asmcore::CellSizeSubsample(doubles.data(), idList, 200000.0, 400.0));
    }
  }
}

TEST(FastPaths, GridOrdersUnsortedIdsById)
{
  const Cloud c = asmtest::Sphere(5000, 2.0, 5);
  auto ids = AllIds(c);
  std::mt19937_64 rng(9);
  std::shuffle(ids.begin(), ids.end(), rng);
  ids.resize(4000);
  const auto spec = asmcore::GridSpec::Make(asmcore::ComputeBounds(c.data(), ids), 0.3);
  ExpectSameGrid(asmcore::BuildCellGrid(c.data(), ids, spec, UnevenTwoThreads()),
    ReferenceGrid(c.data(), ids, spec));
}

TEST(FastPaths, IdViewsOfEitherListGiveTheSameGrid)
{
  // The steps take an IdView: a std::vector of ids, a PointIds filled
  // without a zero fill, and a view of part of a list see the same ids.
  const Cloud c = asmtest::Sphere(5000, 2.0, 5);
  const std::vector<Index> ids = AllIds(c);
  asmcore::PointIds pointIds(ids.size());
  std::copy(ids.begin(), ids.end(), pointIds.begin());
  const auto spec = asmcore::GridSpec::Make(asmcore::ComputeBounds(c.data(), ids), 0.3);
  const asmcore::CellGrid reference = ReferenceGrid(c.data(), ids, spec);
  ExpectSameGrid(asmcore::BuildCellGrid(c.data(), pointIds, spec, UnevenTwoThreads()), reference);
  const asmcore::IdView part(ids.data() + 1000, 2000);
  ASSERT_EQ(part.size(), 2000u);
  EXPECT_EQ(part[0], ids[1000]);
  EXPECT_EQ(part[part.size() - 1], ids[2999]);
  ExpectSameGrid(asmcore::BuildCellGrid(c.data(), part, spec, UnevenTwoThreads()),
    ReferenceGrid(c.data(), std::vector<Index>(part.begin(), part.end()), spec));
  // The identity stands for 0 ... n - 1 without a list.
  const asmcore::IdView all = asmcore::IdView::Identity(ids.size());
  ASSERT_TRUE(all.IsIdentity());
  ASSERT_EQ(all.size(), ids.size());
  EXPECT_EQ(std::vector<Index>(all.begin(), all.end()), ids);
  EXPECT_EQ(all[4321], 4321);
  EXPECT_FALSE(asmcore::IdView(ids).IsIdentity());
  ExpectSameGrid(asmcore::BuildCellGrid(c.data(), all, spec, UnevenTwoThreads()),
    reference); // A range stands for first ... first + n - 1 (a cell's slots in slot
  // order: CellIds), and the frame over it is the frame over the listed ids.
  const asmcore::IdView range = asmcore::IdView::Range(1000, 2000);
  ASSERT_FALSE(range.IsIdentity());
  ASSERT_EQ(range.size(), 2000u);
  EXPECT_EQ(std::vector<Index>(range.begin(), range.end()),
    std::vector<Index>(ids.begin() + 1000, ids.begin() + 3000));
  EXPECT_EQ(range[1999], 2999);
  const asmcore::CellFrame a = asmcore::ComputeCellFrame(c.data(), range);
  const asmcore::CellFrame b = asmcore::ComputeCellFrame(c.data(), part);
  EXPECT_EQ(a.Centroid, b.Centroid);
  EXPECT_EQ(a.Axes, b.Axes);
  EXPECT_EQ(a.Lambda, b.Lambda);
  EXPECT_EQ(a.Count, 2000);
}

TEST(FastPaths, ResizeInParallelWritesEveryNewElement)
{
  // The samples' array writes nothing on resize(): every new element must
  // come from the parallel fill, and the old ones must stay.
  asmcore::UnwrittenArray<asmcore::Sample> samples;
  asmcore::Sample first;
  first.Representative = 7;
  first.Position[1] = 2.5;
  asmcore::ResizeInParallel(samples, 1000, first, UnevenTwoThreads());
  asmcore::Sample second; // the default member initialisers
  asmcore::ResizeInParallel(samples, 5000, second, UnevenTwoThreads());
  ASSERT_EQ(samples.size(), 5000u);
  for (std::size_t s = 0; s < samples.size(); ++s)
  {
    const asmcore::Sample& expected = s < 1000 ? first : second;
    ASSERT_EQ(samples[s].Representative, expected.Representative) << s;
    ASSERT_EQ(samples[s].Position[1], expected.Position[1]) << s;
    ASSERT_EQ(samples[s].Normal[2], 1.0) << s;
    ASSERT_FALSE(samples[s].Key) << s;
  }
}

TEST(FastPaths, BoundsAndCellSizeIndependentOfCuts)
{
  const Cloud c = asmtest::Sphere(30000, 1.5, 2);
  const auto ids = AllIds(c);
  const auto a = asmcore::ComputeBounds(c.data(), ids);
  const auto b = asmcore::ComputeBounds(c.data(), ids, UnevenTwoThreads());
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_EQ(a.Min[k], b.Min[k]);
    EXPECT_EQ(a.Max[k], b.Max[k]);
  }
  EXPECT_EQ(asmcore::AutomaticCellSize(c.data(), ids, a, 500.0),
    asmcore::AutomaticCellSize(c.data(), ids, a, 500.0, UnevenTwoThreads()));
}

TEST(FastPaths, CellSizeSubsampleIsIndependentOfOrderAndPartition)
{
  // The distributed search picks the same subsample as the serial one:
  // the points are chosen by their coordinates, not by position or process.
  const Cloud c = asmtest::Sphere(300000, 1.0, 5);
  std::vector<Index> ids = AllIds(c);
  const double target = 300000 * 0.05 / 8.0;
  auto sortedTriples = [](const asmcore::PointArray<double>& xyz) {
    std::vector<std::array<double, 3>> t(xyz.size() / 3);
    for (std::size_t i = 0; i < t.size(); ++i)
    {
      t[i] = { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
    }
    std::sort(t.begin(), t.end());
    return t;
  };
  const asmcore::PointArray<double> whole =
    asmcore::CellSizeSubsample(c.data(), ids, 300000.0, target);
  ASSERT_GT(whole.size(), 3u * 300000 / 40); // about one point in 7 (>= 1 in 4 * 2)
  ASSERT_LT(whole.size(), 3u * 300000 / 4);
  std::shuffle(ids.begin(), ids.end(), std::mt19937_64(3));
  const std::vector<Index> partA(ids.begin(), ids.begin() + 120000);
  const std::vector<Index> partB(ids.begin() + 120000, ids.end());
  asmcore::PointArray<double> parts = asmcore::CellSizeSubsample(c.data(), partA, 300000.0, target);
  const asmcore::PointArray<double> b =
    asmcore::CellSizeSubsample(c.data(), partB, 300000.0, target, UnevenTwoThreads());
  parts.insert(parts.end(), b.begin(), b.end());
  EXPECT_EQ(sortedTriples(parts), sortedTriples(whole));
  // Small clouds are searched on all points.
  EXPECT_TRUE(asmcore::CellSizeSubsample(c.data(), partA, 150000.0, target).empty());

  // The distributed form of the search (a start from the subsample's
  // counts, then all points' counts) finds the serial cell size.
  const std::vector<Index> all = AllIds(c);
  const auto bounds = asmcore::ComputeBounds(c.data(), all);
  std::vector<Index> subsetIds(whole.size() / 3);
  std::iota(subsetIds.begin(), subsetIds.end(), Index(0));
  const double start =
    asmcore::AutomaticCellSize(bounds, target, false, [&](const asmcore::GridSpec& spec) {
      return static_cast<double>(asmcore::CountOccupiedCells(whole.data(), subsetIds, spec));
    });
  const double distributed = asmcore::AutomaticCellSize(
    bounds, target, false,
    [&](const asmcore::GridSpec& spec) {
      return static_cast<double>(asmcore::CountOccupiedCells(c.data(), all, spec));
    },
    start);
  EXPECT_EQ(asmcore::AutomaticCellSize(c.data(), all, bounds, target), distributed);
  EXPECT_EQ(
    asmcore::BuildAutomaticCellGrid(c.data(), all, bounds, target).Spec.CellSize, distributed);
  // The grid built during the search is the grid of that cell size.
  const asmcore::CellGrid built = asmcore::BuildAutomaticCellGrid(c.data(), all, bounds, target);
  const asmcore::CellGrid plain =
    asmcore::BuildCellGrid(c.data(), all, asmcore::GridSpec::Make(bounds, distributed));
  EXPECT_EQ(built.CellKey, plain.CellKey);
  EXPECT_EQ(built.CellStart, plain.CellStart);
  EXPECT_EQ(built.Order, plain.Order);
}

TEST(FastPaths, CellNeighborsAreTheDefinition)
{
  // Cells at the grid's borders (a cloud filling its bounds) and sparse
  // rows: each of the 27 entries is the cell found by its key, or -1.
  Cloud c = asmtest::Sphere(3000, 1.0, 5);
  asmtest::Add(c, 1.0, 1.0, 1.0);
  asmtest::Add(c, -1.0, -1.0, -1.0);
  const auto ids = AllIds(c);
  const auto bounds = asmcore::ComputeBounds(c.data(), ids);
  for (double h : { 0.15, 0.5, 3.0 })
  {
    const asmcore::CellGrid grid =
      asmcore::BuildCellGrid(c.data(), ids, asmcore::GridSpec::Make(bounds, h));
    const asmcore::CellNeighborTable table = asmcore::BuildCellNeighbors(grid, UnevenTwoThreads());
    for (Index cell = 0; cell < grid.NumberOfCells(); ++cell)
    {
      std::int64_t ijk[3];
      grid.Spec.Unpack(grid.CellKey[cell], ijk);
      for (int k = 0; k < 27; ++k)
      {
        const std::int64_t n[3] = { ijk[0] + k % 3 - 1, ijk[1] + (k / 3) % 3 - 1,
          ijk[2] + k / 9 - 1 };
        Index expected = -1;
        if (n[0] >= 0 && n[1] >= 0 && n[2] >= 0 && n[0] < grid.Spec.Dims[0] &&
          n[1] < grid.Spec.Dims[1] && n[2] < grid.Spec.Dims[2])
        {
          const std::uint64_t key =
            (std::uint64_t(n[2]) << 42) | (std::uint64_t(n[1]) << 21) | std::uint64_t(n[0]);
          const auto it = std::find(grid.CellKey.begin(), grid.CellKey.end(), key);
          expected = it == grid.CellKey.end() ? -1 : static_cast<Index>(it - grid.CellKey.begin());
        }
        ASSERT_EQ(table.Of(cell)[k], expected) << "h " << h << " cell " << cell << " entry " << k;
      }
    }
  }
}

// GroupBy (the grid's and the members' counting sort) with several blocks:
// each group holds its items' values in increasing item order, whatever
// the thread count; items of negative key are left out.
TEST(FastPaths, GroupByIsAStableCountingSortOverBlocks)
{
  const Index n = 300000, keys = 5000; // 4 blocks of 75 000 items
  auto key = [](Index i) -> Index {
    std::uint64_t h = static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL;
    h ^= h >> 29;
    return h % 11 == 0 ? -1 : static_cast<Index>((h >> 7) % 5000);
  };
  auto value = [](Index i) { return 3 * i + 1; };
  std::vector<std::vector<Index>> expected(static_cast<std::size_t>(keys));
  for (Index i = 0; i < n; ++i)
  {
    if (key(i) >= 0)
    {
      expected[key(i)].push_back(value(i));
    }
  }
  for (const asmcore::Execution& execution : { asmcore::Execution(), UnevenTwoThreads() })
  {
    std::vector<Index> start, out;
    asmcore::GroupBy(n, keys, key, value, start, out, execution);
    ASSERT_EQ(start.size(), static_cast<std::size_t>(keys) + 1);
    ASSERT_EQ(start[0], 0);
    for (Index k = 0; k < keys; ++k)
    {
      ASSERT_EQ(std::vector<Index>(out.begin() + start[k], out.begin() + start[k + 1]), expected[k])
        << "group " << k;
    }
    EXPECT_EQ(static_cast<std::size_t>(start[keys]), out.size());
  }
}
