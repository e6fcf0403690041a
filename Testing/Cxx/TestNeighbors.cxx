// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the kd-tree (Core/Neighbors): k nearest, nearest and radius
// queries against brute force, with duplicates, ties and degenerate clouds.
#include "Core/Neighbors.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <thread>
#include <utility>

using asmcore::Index;
using asmtest::Cloud;

namespace
{
using Ranked = std::vector<std::pair<double, Index>>;

// The `keep` first points of (c, ids) by (squared distance to p, id). The
// distance is evaluated exactly as the tree does, so ties compare equal.
Ranked BruteForce(const Cloud& c, asmcore::IdView ids, const double p[3],
  std::size_t keep = std::numeric_limits<std::size_t>::max())
{
  Ranked all;
  for (Index id : ids)
  {
    const double dx = c[3 * id] - p[0];
    const double dy = c[3 * id + 1] - p[1];
    const double dz = c[3 * id + 2] - p[2];
    all.emplace_back(dx * dx + dy * dy + dz * dz, id);
  }
  keep = std::min(keep, all.size());
  std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(keep), all.end());
  all.resize(keep);
  return all;
}

void ExpectSame(const Ranked& expected, asmcore::IdView ids, const std::vector<double>& sqDist,
  const std::string& what)
{
  ASSERT_EQ(expected.size(), ids.size()) << what;
  ASSERT_EQ(expected.size(), sqDist.size()) << what;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    ASSERT_EQ(expected[i].second, ids[i]) << what << " rank " << i;
    ASSERT_EQ(expected[i].first, sqDist[i]) << what << " rank " << i;
  }
}

// The coordinates an answer gives are those of its ids, side by side.
void ExpectCoordinates(const Cloud& c, const std::vector<Index>& ids,
  const std::vector<double>& xyz, const std::string& what)
{
  ASSERT_EQ(3 * ids.size(), xyz.size()) << what;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      ASSERT_EQ(c[3 * ids[i] + a], xyz[3 * i + a]) << what << " rank " << i;
    }
  }
}

// A test cloud: `unique` random points (uniform in [0, 1]^3, or on the
// integer lattice [0, 4]^3 when `lattice`, which makes many exact ties),
// plus `duplicates` copies of random earlier points. The ids used are a
// shuffled subset (every id but those = 3 mod 7), to check id mapping.
struct TestCloud
{
  Cloud Points;
  std::vector<Index> Ids;
};

TestCloud MakeCloud(std::size_t unique, std::size_t duplicates, bool lattice, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::uniform_int_distribution<int> cell(0, 4);
  TestCloud t;
  for (std::size_t i = 0; i < unique; ++i)
  {
    if (lattice)
    {
      asmtest::Add(t.Points, cell(rng), cell(rng), cell(rng));
    }
    else
    {
      asmtest::Add(t.Points, uniform(rng), uniform(rng), uniform(rng));
    }
  }
  for (std::size_t i = 0; i < duplicates && unique > 0; ++i)
  {
    const std::size_t from = std::uniform_int_distribution<std::size_t>(0, unique - 1)(rng);
    asmtest::Add(t.Points, t.Points[3 * from], t.Points[3 * from + 1], t.Points[3 * from + 2]);
  }
  for (Index id = 0; id < static_cast<Index>(t.Points.size() / 3); ++id)
  {
    if (id % 7 != 3)
    {
      t.Ids.push_back(id);
    }
  }
  std::shuffle(t.Ids.begin(), t.Ids.end(), rng);
  return t;
}

// Query positions: random ones around the cloud (some far outside), points
// of the cloud, and, for lattices, lattice and half-lattice points.
std::vector<std::array<double, 3>> MakeQueries(const TestCloud& t, bool lattice, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::vector<std::array<double, 3>> q;
  const double scale = lattice ? 4.0 : 1.0;
  std::uniform_real_distribution<double> around(-0.5 * scale, 1.5 * scale);
  for (int i = 0; i < 25; ++i)
  {
    q.push_back({ around(rng), around(rng), around(rng) });
  }
  q.push_back({ 100.0 * scale, -50.0 * scale, 3.0 });
  for (std::size_t i = 0; i < t.Ids.size() && i < 15; ++i)
  {
    const double* p = t.Points.data() + 3 * t.Ids[i];
    q.push_back({ p[0], p[1], p[2] });
  }
  if (lattice)
  {
    std::uniform_int_distribution<int> half(0, 8);
    for (int i = 0; i < 15; ++i)
    {
      q.push_back({ 0.5 * half(rng), 0.5 * half(rng), 0.5 * half(rng) });
    }
  }
  return q;
}
} // namespace

//------------------------------------------------------------------------------
TEST(Neighbors, EmptyCloudAnswersNothing)
{
  const double p[3] = { 0, 0, 0 };
  std::vector<Index> ids = { 42 };
  std::vector<double> d = { 1.0 };
  const asmcore::Neighbors unbuilt;
  const Cloud none;
  const asmcore::Neighbors built(none.data(), {});
  for (const asmcore::Neighbors* tree : { &unbuilt, &built })
  {
    EXPECT_TRUE(tree->Empty());
    tree->KNearest(p, 5, ids, d);
    EXPECT_TRUE(ids.empty());
    EXPECT_TRUE(d.empty());
    const asmcore::NearestPoint nearest = tree->Nearest(p);
    EXPECT_EQ(-1, nearest.Id);
    EXPECT_TRUE(std::isinf(nearest.Distance));
    ids = { 1 };
    tree->Radius(p, 10.0, ids);
    EXPECT_TRUE(ids.empty());
  }
}

TEST(Neighbors, KNearestMatchesBruteForce)
{
  unsigned seed = 11;
  for (bool lattice : { false, true })
  {
    for (std::size_t n : { 1, 2, 9, 60, 400, 3000 })
    {
      const TestCloud t = MakeCloud(n, n / 4 + (n > 1 ? 1 : 0), lattice, ++seed);
      const asmcore::Neighbors tree(t.Points.data(), t.Ids);
      const int size = static_cast<int>(t.Ids.size());
      ASSERT_EQ(size, tree.Size());
      std::vector<Index> ids;
      std::vector<double> d;
      for (const auto& q : MakeQueries(t, lattice, seed))
      {
        const Ranked all = BruteForce(t.Points, t.Ids, q.data());
        for (int k : { 1, 2, 5, 20, 32, 33, 100, size - 1, size, size + 7 })
        {
          if (k <= 0)
          {
            continue;
          }
          tree.KNearest(q.data(), k, ids, d);
          const Ranked expected(all.begin(), all.begin() + std::min(k, size));
          ExpectSame(expected, ids, d,
            "n=" + std::to_string(n) + " lattice=" + std::to_string(lattice) +
              " k=" + std::to_string(k));
        }
        const asmcore::NearestPoint nearest = tree.Nearest(q.data());
        ASSERT_EQ(all.front().second, nearest.Id);
        ASSERT_EQ(std::sqrt(all.front().first), nearest.Distance);
      }
    }
  }
}

TEST(Neighbors, RadiusMatchesBruteForce)
{
  unsigned seed = 101;
  for (bool lattice : { false, true })
  {
    for (std::size_t n : { 1, 50, 2000 })
    {
      const TestCloud t = MakeCloud(n, n / 3, lattice, ++seed);
      const asmcore::Neighbors tree(t.Points.data(), t.Ids);
      std::vector<Index> ids, ids2;
      std::vector<double> d;
      for (const auto& q : MakeQueries(t, lattice, seed))
      {
        const Ranked all = BruteForce(t.Points, t.Ids, q.data());
        const double unit = lattice ? 4.0 : 1.0;
        for (double r : { 0.0, 0.02, 0.1, 0.3, 1.0, 2.0 })
        {
          const double radius = r * unit;
          Ranked expected;
          for (const auto& e : all)
          {
            if (e.first <= radius * radius)
            {
              expected.push_back(e);
            }
          }
          tree.Radius(q.data(), radius, ids, d);
          ExpectSame(expected, ids, d, "n=" + std::to_string(n) + " r=" + std::to_string(radius));
          tree.Radius(q.data(), radius, ids2);
          ASSERT_EQ(ids, ids2);
        }
      }
    }
  }
}

// A float cloud (ids below 2^31) gets the compact layout, 16 bytes per
// point: it must answer exactly what the wide layout answers on the same
// numbers as doubles (the brute force included). Both give the points'
// coordinates on request: the cloud's numbers (the floats widened).
TEST(Neighbors, FloatCloudsGetTheCompactLayoutWithTheSameAnswers)
{
  unsigned seed = 301;
  for (bool lattice : { false, true })
  {
    for (std::size_t n : { 1, 60, 3000, 20000 })
    {
      TestCloud t = MakeCloud(n, n / 4, lattice, ++seed);
      std::vector<float> floats(t.Points.size());
      for (std::size_t i = 0; i < floats.size(); ++i)
      {
        floats[i] = static_cast<float>(t.Points[i] * 3.1);
        t.Points[i] = static_cast<double>(floats[i]); // the same numbers, widened
      }
      const asmcore::Neighbors compact(floats.data(), t.Ids);
      const asmcore::Neighbors wide(t.Points.data(), t.Ids);
      ASSERT_TRUE(compact.HasCompactLayout());
      ASSERT_FALSE(wide.HasCompactLayout());
      ASSERT_EQ(compact.Size(), wide.Size());
      std::vector<Index> ids, wideIds, withXyz;
      std::vector<double> d, wideD, xyz;
      // Both layouts: the same ids and distances with the coordinates as
      // without, and the coordinates of those ids.
      auto expectCoordinates = [&](auto query, const std::string& what) {
        for (const asmcore::Neighbors* tree : { &compact, &wide })
        {
          query(*tree, ids, d, nullptr);
          query(*tree, withXyz, wideD, &xyz);
          ASSERT_EQ(ids, withXyz) << what;
          ASSERT_EQ(d, wideD) << what;
          ExpectCoordinates(t.Points, ids, xyz, what);
        }
      };
      for (auto q : MakeQueries(t, lattice, seed))
      {
        for (double& x : q)
        {
          x *= 3.1;
        }
        const std::string what = "n=" + std::to_string(n) + " lattice=" + std::to_string(lattice);
        for (int k : { 1, 8, 33, static_cast<int>(t.Ids.size()) + 1 })
        {
          compact.KNearest(q.data(), k, ids, d);
          wide.KNearest(q.data(), k, wideIds, wideD);
          ExpectSame(BruteForce(t.Points, t.Ids, q.data(), static_cast<std::size_t>(k)), ids, d,
            what + " k=" + std::to_string(k));
          ASSERT_EQ(wideIds, ids) << what;
          ASSERT_EQ(wideD, d) << what;
          expectCoordinates(
            [&](const asmcore::Neighbors& tree, std::vector<Index>& i, std::vector<double>& sq,
              std::vector<double>* x) {
              x ? tree.KNearest(q.data(), k, i, sq, *x) : tree.KNearest(q.data(), k, i, sq);
            },
            what + " k=" + std::to_string(k) + " with coordinates");
        }
        const asmcore::NearestPoint a = compact.Nearest(q.data()), b = wide.Nearest(q.data());
        ASSERT_EQ(b.Id, a.Id) << what;
        ASSERT_EQ(b.Distance, a.Distance) << what;
        for (double r : { 0.05, 0.4, 3.0 })
        {
          compact.Radius(q.data(), r * (lattice ? 4.0 : 1.0), ids, d);
          wide.Radius(q.data(), r * (lattice ? 4.0 : 1.0), wideIds, wideD);
          ASSERT_EQ(wideIds, ids) << what << " r=" << r;
          ASSERT_EQ(wideD, d) << what << " r=" << r;
          const double radius = r * (lattice ? 4.0 : 1.0);
          expectCoordinates(
            [&](const asmcore::Neighbors& tree, std::vector<Index>& i, std::vector<double>& sq,
              std::vector<double>* x) {
              x ? tree.Radius(q.data(), radius, i, sq, *x) : tree.Radius(q.data(), radius, i, sq);
            },
            what + " r=" + std::to_string(r) + " with coordinates");
        }
      }
    }
  }
}

TEST(Neighbors, BadArgumentsGiveEmptyResults)
{
  const TestCloud t = MakeCloud(100, 0, false, 5);
  const asmcore::Neighbors tree(t.Points.data(), t.Ids);
  std::vector<Index> ids;
  std::vector<double> d;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double bad[3] = { 0.5, nan, 0.5 };
  const double good[3] = { 0.5, 0.5, 0.5 };
  tree.KNearest(bad, 3, ids, d);
  EXPECT_TRUE(ids.empty());
  std::vector<double> xyz;
  tree.KNearest(good, 3, ids, d, xyz); // (then the bad query must clear all three)
  tree.KNearest(bad, 3, ids, d, xyz);
  EXPECT_TRUE(ids.empty() && d.empty() && xyz.empty());
  tree.Radius(good, 1.0, ids, d, xyz);
  tree.Radius(bad, 1.0, ids, d, xyz);
  EXPECT_TRUE(ids.empty() && d.empty() && xyz.empty());
  tree.KNearest(good, 0, ids, d);
  EXPECT_TRUE(ids.empty());
  EXPECT_EQ(-1, tree.Nearest(bad).Id);
  tree.Radius(bad, 1.0, ids);
  EXPECT_TRUE(ids.empty());
  tree.Radius(good, -1.0, ids);
  EXPECT_TRUE(ids.empty());
  tree.Radius(good, nan, ids);
  EXPECT_TRUE(ids.empty());
}

TEST(Neighbors, MillionIdenticalPoints)
{
  const Index n = 1000000;
  Cloud c;
  c.reserve(3 * n + 300);
  for (Index i = 0; i < n; ++i)
  {
    asmtest::Add(c, 1.5, -2.0, 0.25);
  }
  std::vector<Index> all(n);
  std::iota(all.begin(), all.end(), Index(0));
  const asmcore::Neighbors tree(c.data(), all);
  ASSERT_EQ(n, tree.Size());

  std::vector<Index> ids;
  std::vector<double> d;
  std::vector<Index> first20(20);
  std::iota(first20.begin(), first20.end(), Index(0));
  const double at[3] = { 1.5, -2.0, 0.25 };
  const double away[3] = { 4.5, 2.0, 0.25 }; // distance 5
  for (const double* q : { at, away })
  {
    tree.KNearest(q, 20, ids, d);
    EXPECT_EQ(first20, ids); // ties: smallest ids
    EXPECT_EQ(std::vector<double>(20, q == at ? 0.0 : 25.0), d);
    EXPECT_EQ(0, tree.Nearest(q).Id);
    tree.KNearest(q, 1000, ids, d); // heap path
    ASSERT_EQ(1000u, ids.size());
    EXPECT_EQ(999, ids.back());
  }
  tree.Radius(at, 0.0, ids);
  EXPECT_EQ(all, ids);
  tree.Radius(away, 4.999, ids);
  EXPECT_TRUE(ids.empty());

  // The same heap of duplicates with 200 scattered points interleaved: the
  // tree must split around the pile and still break ties by id.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 200; ++i)
  {
    asmtest::Add(c, u(rng), u(rng), u(rng));
  }
  std::vector<Index> mixed(static_cast<std::size_t>(c.size() / 3));
  std::iota(mixed.begin(), mixed.end(), Index(0));
  std::shuffle(mixed.begin(), mixed.end(), rng);
  const asmcore::Neighbors tree2(c.data(), mixed);
  for (int i = 0; i < 6; ++i)
  {
    const double q[3] = { u(rng), u(rng), u(rng) };
    tree2.KNearest(q, 30, ids, d);
    ExpectSame(BruteForce(c, mixed, q, 30), ids, d, "mixed");
  }
  tree2.KNearest(at, 5, ids, d);
  EXPECT_EQ(std::vector<Index>({ 0, 1, 2, 3, 4 }), ids);

  // By position (the curvature's and the key point error's queries): the
  // ties at the k-th distance are a million points at one position, of
  // which only the k of smallest id can be taken; the search reads k of
  // each leaf of coincident points, not the million (a cloud of 200 000
  // identical points took 150 s to simplify with curvature, and its key
  // point error 160 s; 0.1 s now).
  std::vector<double> xyz;
  for (const asmcore::Neighbors* t : { &tree, &tree2 })
  {
    t->KNearestByPosition(at, 20, ids, d, xyz);
    EXPECT_EQ(first20, ids);
    EXPECT_EQ(std::vector<double>(20, 0.0), d);
    t->RadiusForKNearest(at, 0.0, 20, ids, d, xyz);
    ASSERT_GE(ids.size(), 20u);
    // (k of each leaf of the pile: one leaf, or about a hundred where the
    // scattered points cut the pile's range.)
    EXPECT_LE(ids.size(), t == &tree ? 20u : 10000u);
    EXPECT_EQ(first20, std::vector<Index>(ids.begin(), ids.begin() + 20));
    t->RadiusForKNearest(at, 10.0, 20, ids, d, xyz);
    EXPECT_LE(ids.size(), t == &tree ? 20u : 10200u);
  }
}

// Layouts that take the build off its common path (a grid of buckets that
// leaves about LeafSize points each): most points in a tiny cluster (the
// root splits at the median, then ranges too large for the spare array are
// permuted in place), points at exponentially shrinking spacings (a split
// after split peels few points: depth), flat and thin boxes, coordinates
// one ulp apart, a box a few denormals wide (too thin for a grid). Every answer must still be
// exact.
TEST(Neighbors, AdversarialLayoutsMatchBruteForce)
{
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::pair<std::string, Cloud>> layouts;
  {
    Cloud c; // 200 k points within 1e-6 of the origin, 2 k spread over [0, 10]^3
    for (int i = 0; i < 200000; ++i)
    {
      asmtest::Add(c, 1e-6 * u(rng), 1e-6 * u(rng), 1e-6 * u(rng));
    }
    for (int i = 0; i < 2000; ++i)
    {
      asmtest::Add(c, 10 * u(rng), 10 * u(rng), 10 * u(rng));
    }
    layouts.emplace_back("cluster", c);
  }
  {
    Cloud c; // x = 2^-i for i < 1000 (down to 2^-999), three points each
    for (int i = 0; i < 1000; ++i)
    {
      for (int copy = 0; copy < 3; ++copy)
      {
        asmtest::Add(c, std::ldexp(1.0, -i), copy, 0.0);
      }
    }
    layouts.emplace_back("exponential", c);
  }
  {
    Cloud c; // a plane, a line and a thin slab, overlapping
    for (int i = 0; i < 20000; ++i)
    {
      asmtest::Add(c, u(rng), u(rng), 0.5);
      asmtest::Add(c, u(rng), 0.5, 0.5);
      asmtest::Add(c, u(rng), u(rng), 0.5 + 1e-12 * u(rng));
    }
    layouts.emplace_back("flat", c);
  }
  {
    Cloud c; // coordinates one ulp apart, in piles
    const double x = 1e8, y = std::nextafter(x, 2e8);
    for (int i = 0; i < 5000; ++i)
    {
      asmtest::Add(c, i % 2 ? x : y, i % 3 ? x : y, i % 5 ? x : y);
    }
    layouts.emplace_back("ulp", c);
  }
  {
    Cloud c; // a box too thin to divide into cells: 0 and the smallest denormal
    const double tiny = std::numeric_limits<double>::denorm_min();
    for (int i = 0; i < 3000; ++i)
    {
      asmtest::Add(c, i % 2 ? 0.0 : tiny, i % 3 ? 0.0 : tiny, i % 7 ? 0.0 : 2 * tiny);
    }
    layouts.emplace_back("denormal", c);
  }
  std::vector<Index> ids;
  std::vector<double> d;
  for (const auto& [name, c] : layouts)
  {
    std::vector<Index> all(c.size() / 3);
    std::iota(all.begin(), all.end(), Index(0));
    std::shuffle(all.begin(), all.end(), rng);
    const asmcore::Neighbors tree(c.data(), all);
    ASSERT_EQ(static_cast<Index>(all.size()), tree.Size()) << name;
    std::vector<std::array<double, 3>> queries;
    for (int i = 0; i < 12; ++i)
    {
      const double* p = c.data() + 3 * all[static_cast<std::size_t>(i) * 997 % all.size()];
      queries.push_back({ p[0], p[1], p[2] });
      queries.push_back({ p[0] + 1e-7 * u(rng), p[1] - 1e-7 * u(rng), p[2] });
    }
    queries.push_back({ 5.0, 5.0, 5.0 });
    queries.push_back({ -1.0, 0.3, 2.0 });
    for (const auto& q : queries)
    {
      const Ranked expected = BruteForce(c, all, q.data(), 100);
      for (int k : { 1, 20, 100 })
      {
        tree.KNearest(q.data(), k, ids, d);
        ExpectSame(
          Ranked(expected.begin(), expected.begin() + k), ids, d, name + " k=" + std::to_string(k));
      }
      const double r = std::sqrt(expected[19].first);
      tree.Radius(q.data(), r, ids, d);
      Ranked within;
      for (const auto& e : BruteForce(c, all, q.data()))
      {
        if (e.first <= r * r)
        {
          within.push_back(e);
        }
      }
      ExpectSame(within, ids, d, name + " radius");
    }
  }
}

TEST(Neighbors, ConcurrentQueriesAgree)
{
  const TestCloud t = MakeCloud(20000, 100, false, 21);
  const asmcore::Neighbors tree(t.Points.data(), t.Ids);
  const std::size_t queries = 4000;
  const int k = 12;
  auto run = [&](std::size_t begin, std::size_t end, std::vector<Index>& out) {
    std::vector<Index> ids;
    std::vector<double> d;
    for (std::size_t i = begin; i < end; ++i)
    {
      const double* p = t.Points.data() + 3 * t.Ids[i];
      tree.KNearest(p, k, ids, d);
      std::copy(ids.begin(), ids.end(), out.begin() + static_cast<std::ptrdiff_t>(k * i));
    }
  };
  std::vector<Index> sequential(k * queries), threaded(k * queries);
  run(0, queries, sequential);
  std::vector<std::thread> pool;
  for (std::size_t w = 0; w < 4; ++w)
  {
    pool.emplace_back(run, queries * w / 4, queries * (w + 1) / 4, std::ref(threaded));
  }
  for (auto& thread : pool)
  {
    thread.join();
  }
  EXPECT_EQ(sequential, threaded);
}
