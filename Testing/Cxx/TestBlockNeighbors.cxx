// SPDX-License-Identifier: BSD-3-Clause
// ForEachKNearest (the metrics' k-nearest queries in blocks) gives, for every
// finite query, exactly what Neighbors::KNearestByPosition gives: the same ids
// in the same order with the same squared distances, ties by position then
// id included, whatever the order of the ids and the thread count.
#include "Core/BlockNeighbors.h"
#include "Core/Grid.h"
#include "Core/Neighbors.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <mutex>
#include <numeric>
#include <random>
#include <vector>

using asmcore::Index;
using asmtest::Cloud;

namespace
{
struct Answer
{
  int Visits = 0;
  std::vector<Index> Ids;
  std::vector<double> Sq;
};

std::vector<Answer> Visit(const Cloud& queries, asmcore::IdView ids, const Cloud& surface,
  const asmcore::Neighbors& tree, int k, const asmcore::Execution& execution)
{
  std::vector<Answer> answers(ids.size());
  std::mutex mutex;
  asmcore::ForEachKNearest(
    queries.data(), ids, tree, k,
    [&](const asmcore::KNearestAnswer& answer) {
      std::lock_guard<std::mutex> lock(mutex);
      Answer& a = answers[static_cast<std::size_t>(answer.Query)];
      ++a.Visits;
      const double* x = queries.data() + 3 * ids[static_cast<std::size_t>(answer.Query)];
      EXPECT_TRUE(std::equal(answer.Point, answer.Point + 3, x)) << "the query's own point";
      a.Ids = answer.Ids;
      a.Sq = answer.SqDist;
      for (std::size_t j = 0; j < a.Ids.size(); ++j)
      {
        const double* y = surface.data() + 3 * a.Ids[j];
        EXPECT_TRUE(std::equal(y, y + 3, answer.Xyz + 3 * j)) << "neighbour " << j << "'s point";
      }
    },
    execution);
  return answers;
}

// Every finite query visited once with the tree's own answer; the others
// never.
void ExpectTreeAnswers(const Cloud& queries, asmcore::IdView ids, const Cloud& surface,
  const asmcore::Neighbors& tree, int k, const std::vector<Answer>& answers)
{
  std::vector<Index> near;
  std::vector<double> sq;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    const double* p = queries.data() + 3 * ids[i];
    const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
    ASSERT_EQ(finite ? 1 : 0, answers[i].Visits) << "query " << i;
    if (!finite)
    {
      continue;
    }
    std::vector<double> xyz;
    tree.KNearestByPosition(p, k, near, sq, xyz);
    ASSERT_EQ(near, answers[i].Ids) << "query " << i;
    ASSERT_EQ(sq, answers[i].Sq) << "query " << i;
  }
}

// Every query of `queries` (ids 0, 1, ...) against a tree of `surface`, at
// each k: the tree's own answers.
void ExpectTreeAnswersAt(const Cloud& surface, const Cloud& queries, std::initializer_list<int> ks)
{
  const asmcore::Neighbors tree(surface.data(), asmtest::AllIds(surface));
  const auto ids = asmcore::IdView::Identity(queries.size() / 3);
  for (int k : ks)
  {
    ExpectTreeAnswers(queries, ids, surface, tree, k, Visit(queries, ids, surface, tree, k, {}));
  }
}

// A wavy sheet of `n` points and `m` queries near it (denser than the
// sheet, so that the queries are answered in blocks).
void Sheet(int n, int m, std::uint64_t seed, Cloud& surface, Cloud& queries)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto height = [](double x, double y) { return 0.2 * std::sin(3.0 * x) * std::cos(2.0 * y); };
  for (int i = 0; i < n; ++i)
  {
    const double x = u(rng), y = u(rng);
    asmtest::Add(surface, x, y, height(x, y) + 0.005 * u(rng));
  }
  for (int i = 0; i < m; ++i)
  {
    const double x = 1.1 * u(rng), y = 1.1 * u(rng);
    asmtest::Add(queries, x, y, height(x, y) + 0.02 * u(rng));
  }
}
} // namespace

TEST(BlockNeighbors, DenseQueriesGetTheTreeAnswers)
{
  Cloud surface, queries;
  Sheet(2000, 60000, 3, surface, queries);
  ExpectTreeAnswersAt(surface, queries, { 1, 3, 8, 20 });
}

TEST(BlockNeighbors, FewQueriesPerBlockGetTheTreeAnswers)
{
  // Four queries per surface point: about ten per block of one k-th
  // distance (k = 8), so the blocks are made wider.
  Cloud surface, queries;
  Sheet(4000, 16000, 11, surface, queries);
  ExpectTreeAnswersAt(surface, queries, { 8 });
}

TEST(BlockNeighbors, ListedIdsInAnyOrderAndNonFiniteQueries)
{
  Cloud surface, queries;
  Sheet(1500, 40000, 5, surface, queries);
  queries[3 * 17 + 1] = std::numeric_limits<double>::quiet_NaN();
  queries[3 * 901] = std::numeric_limits<double>::infinity();
  const asmcore::Neighbors tree(surface.data(), asmtest::AllIds(surface));
  // A shuffled subset (a copy of the points is searched) and a range
  // starting after 0 (searched in place).
  std::vector<Index> shuffled(queries.size() / 3);
  std::iota(shuffled.begin(), shuffled.end(), Index(0));
  std::mt19937_64 rng(8);
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  shuffled.resize(shuffled.size() - 1000);
  std::vector<Index> range(30000);
  std::iota(range.begin(), range.end(), Index(10));
  for (const std::vector<Index>* ids : { &shuffled, &range })
  {
    const auto serial = Visit(queries, *ids, surface, tree, 8, {});
    ExpectTreeAnswers(queries, *ids, surface, tree, 8, serial);
    const auto threaded = Visit(queries, *ids, surface, tree, 8, asmtest::UnevenTwoThreads());
    for (std::size_t i = 0; i < ids->size(); ++i)
    {
      ASSERT_EQ(serial[i].Ids, threaded[i].Ids) << i;
      ASSERT_EQ(serial[i].Sq, threaded[i].Sq) << i;
    }
  }
}

namespace
{
// A 20 x 20 lattice, each point three times (ids far apart), and queries on
// lattice points and between them: many equal distances.
void TiedLattice(Cloud& surface, Cloud& queries)
{
  for (int copy = 0; copy < 3; ++copy)
  {
    for (int i = 0; i < 20; ++i)
    {
      for (int j = 0; j < 20; ++j)
      {
        asmtest::Add(surface, 0.1 * i, 0.1 * j, 0.0);
      }
    }
  }
  for (int i = 0; i < 78; ++i)
  {
    for (int j = 0; j < 78; ++j)
    {
      asmtest::Add(queries, 0.025 * i, 0.025 * j, (i + j) % 3 == 0 ? 0.0 : 0.01);
    }
  }
}
} // namespace

TEST(BlockNeighbors, TiesAreBrokenByPositionAsInTheTree)
{
  Cloud surface, queries;
  TiedLattice(surface, queries);
  ExpectTreeAnswersAt(surface, queries, { 2, 5, 8 });
}

TEST(BlockNeighbors, TiedNeighboursDoNotDependOnTheIds)
{
  // The same lattice with its points in another order (a simplified cloud
  // gathered from a different number of processes): for every query, the
  // same neighbours' points in the same order, in blocks and one by one.
  Cloud surface, queries;
  TiedLattice(surface, queries);
  const Index n = static_cast<Index>(surface.size() / 3);
  std::vector<Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Index(0));
  std::mt19937_64 rng(21);
  std::shuffle(order.begin(), order.end(), rng);
  Cloud shuffled;
  for (Index id : order)
  {
    asmtest::Add(shuffled, surface[3 * id], surface[3 * id + 1], surface[3 * id + 2]);
  }
  const asmcore::Neighbors tree(surface.data(), asmtest::AllIds(surface));
  const asmcore::Neighbors other(shuffled.data(), asmtest::AllIds(shuffled));
  // All queries (in blocks), and every 40th (sparser than the lattice: one by one).
  std::vector<Index> sparse;
  for (Index i = 0; i < static_cast<Index>(queries.size() / 3); i += 40)
  {
    sparse.push_back(i);
  }
  const std::vector<Index> all = asmtest::AllIds(queries);
  for (const std::vector<Index>* ids : { &all, static_cast<const std::vector<Index>*>(&sparse) })
  {
    for (int k : { 3, 8 })
    {
      const auto a = Visit(queries, *ids, surface, tree, k, {});
      const auto b = Visit(queries, *ids, shuffled, other, k, {});
      int tied = 0;
      for (std::size_t i = 0; i < ids->size(); ++i)
      {
        ASSERT_EQ(a[i].Sq, b[i].Sq) << "query " << i;
        for (std::size_t j = 0; j < a[i].Ids.size(); ++j)
        {
          const double* x = surface.data() + 3 * a[i].Ids[j];
          const double* y = shuffled.data() + 3 * b[i].Ids[j];
          ASSERT_TRUE(std::equal(x, x + 3, y)) << "query " << i << ", neighbour " << j;
        }
        // (A choice among equally near points: the (k+1)-th as near as the k-th.)
        std::vector<Index> near;
        std::vector<double> sq;
        tree.KNearest(queries.data() + 3 * (*ids)[i], k + 1, near, sq);
        tied += sq[static_cast<std::size_t>(k)] == sq[static_cast<std::size_t>(k - 1)] ? 1 : 0;
      }
      EXPECT_GT(tied, static_cast<int>(ids->size() / 10)) << "(the lattice must give ties)";
    }
  }
}

TEST(BlockNeighbors, SmallSurfaces)
{
  Cloud surface, queries;
  Sheet(5, 3000, 9, surface, queries);
  // k at and beyond the surface's size: every point, sorted.
  ExpectTreeAnswersAt(surface, queries, { 4, 5, 9 });
  const asmcore::Neighbors tree(surface.data(), asmtest::AllIds(surface));
  const auto ids = asmcore::IdView::Identity(queries.size() / 3);
  // No visit: k <= 0, an empty surface.
  int none = 0;
  auto count = [&](const asmcore::KNearestAnswer&) { ++none; };
  asmcore::ForEachKNearest(queries.data(), ids, tree, 0, count);
  asmcore::ForEachKNearest(queries.data(), ids, asmcore::Neighbors(), 3, count);
  EXPECT_EQ(0, none);
}

TEST(BlockNeighbors, FarFromTheOriginAsTheTree)
{
  // Georeferenced coordinates: millimetre spacing 10^7 units from the origin,
  // where a coordinate's last place is about 2e-9 (the radii's slack must
  // cover the rounding of the differences).
  Cloud surface, queries;
  Sheet(2000, 30000, 13, surface, queries);
  for (Cloud* cloud : { &surface, &queries })
  {
    for (std::size_t i = 0; i < cloud->size(); ++i)
    {
      (*cloud)[i] = 1e7 * (i % 3 == 0 ? 1.0 : 2.0) + 1e-3 * (*cloud)[i];
    }
  }
  ExpectTreeAnswersAt(surface, queries, { 1, 8 });
}

TEST(BlockNeighbors, ExtentsNearTheLimitsOfDoubles)
{
  // A cloud 1e-303 across (its grid's edge would be subnormal, and a cell's
  // coordinate 0 * (1 / edge) a NaN), one whose extent overflows, and one
  // whose blocks' centroids overflow: the tree's answers all the same.
  for (const double scale : { 1e-305, 1e306, 2e307 })
  {
    Cloud surface, queries;
    Sheet(300, 3000, 17, surface, queries);
    for (Cloud* cloud : { &surface, &queries })
    {
      for (double& v : *cloud)
      {
        v *= scale;
      }
    }
    if (scale == 1e306)
    {
      asmtest::Add(queries, -1.7e308, 0.0, 0.0); // (the extent overflows)
      asmtest::Add(queries, 1.7e308, 0.0, 0.0);
    }
    ExpectTreeAnswersAt(surface, queries, { 1, 8 });
  }
  // The grid of such a cloud: a finite inverse edge, in range.
  asmcore::Bounds tiny;
  tiny.Valid = true;
  for (int a = 0; a < 3; ++a)
  {
    tiny.Min[a] = -2.3e-302;
    tiny.Max[a] = tiny.Min[a] + 2e-303;
  }
  const asmcore::GridSpec spec = asmcore::GridSpec::Make(tiny, 0.0);
  EXPECT_TRUE(std::isfinite(1.0 / spec.CellSize));
  EXPECT_LE(spec.Dims[0], asmcore::GridSpec::MaxDim);
}
