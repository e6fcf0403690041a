// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the curvature estimate (Core/Curvature): mean curvature on
// spheres, cylinders and planes, surface variation on a cube, fallbacks,
// determinism under parallel execution. A disabled benchmark measures the
// kd-tree and the estimate on a million-point sphere:
//   asm_tests --gtest_also_run_disabled_tests --gtest_filter='*Benchmark*'
#include "Core/Curvature.h"
#include "Core/Neighbors.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <numeric>
#include <random>
#include <thread>

using asmcore::CurvatureEstimate;
using asmcore::Index;
using asmtest::AllIds;
using asmtest::Cloud;

namespace
{

// An Execution that cuts each range into `threads` parts run on threads.
asmcore::Execution Threaded(int threads)
{
  asmcore::Execution exec;
  exec.For = [threads](Index begin, Index end, const std::function<void(Index, Index)>& body) {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
    {
      const Index b = begin + (end - begin) * t / threads;
      const Index e = begin + (end - begin) * (t + 1) / threads;
      if (b < e)
      {
        pool.emplace_back(body, b, e);
      }
    }
    for (auto& thread : pool)
    {
      thread.join();
    }
  };
  return exec;
}

// Estimates at the given queries of a cloud (all its points used).
std::vector<CurvatureEstimate> Estimate(const Cloud& c, const Cloud& queries, const Cloud* normals,
  int k = asmcore::DefaultCurvatureNeighbors, const asmcore::Execution& exec = asmcore::Execution())
{
  const auto ids = AllIds(c);
  const asmcore::Neighbors tree(c.data(), ids);
  return asmcore::EstimateCurvature(c.data(), ids, tree, queries.data(),
    static_cast<Index>(queries.size() / 3), normals ? normals->data() : nullptr, k, exec);
}

// Random points on the cylinder x^2 + y^2 = r^2, |z| <= 2r.
Cloud Cylinder(std::size_t n, double r, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  std::uniform_real_distribution<double> height(-2.0 * r, 2.0 * r);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double t = angle(rng);
    asmtest::Add(c, r * std::cos(t), r * std::sin(t), height(rng));
  }
  return c;
}

// The surface of the cube [-1, 1]^3, each face an n x n grid.
Cloud CubeSurface(int n)
{
  Cloud c;
  const Cloud face = asmtest::GridSurface(n, 1.0, [](double, double) { return 1.0; });
  for (int axis = 0; axis < 3; ++axis)
  {
    for (double side : { -1.0, 1.0 })
    {
      for (std::size_t i = 0; i < face.size(); i += 3)
      {
        double p[3];
        p[axis] = side;
        p[(axis + 1) % 3] = face[i];
        p[(axis + 2) % 3] = face[i + 1];
        asmtest::Add(c, p[0], p[1], p[2]);
      }
    }
  }
  return c;
}

// The first `count` points of a cloud as queries.
Cloud Head(const Cloud& c, std::size_t count)
{
  return Cloud(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(3 * count));
}
} // namespace

//------------------------------------------------------------------------------
TEST(Curvature, SphereMeanCurvatureIsOneOverRadius)
{
  for (double r : { 0.5, 1.0, 2.0 })
  {
    const double centre[3] = { 0.3, -1.0, 2.0 };
    const Cloud sphere = asmtest::Sphere(20000, r, 17, centre[0], centre[1], centre[2]);
    // Queries: 300 points of the cloud and 100 other points of the sphere.
    Cloud queries = Head(sphere, 300);
    const Cloud extra = asmtest::Sphere(100, r, 99, centre[0], centre[1], centre[2]);
    queries.insert(queries.end(), extra.begin(), extra.end());
    Cloud outward, inward;
    for (std::size_t i = 0; i < queries.size(); i += 3)
    {
      for (int a = 0; a < 3; ++a)
      {
        outward.push_back((queries[i + a] - centre[a]) / r);
        inward.push_back(-outward.back());
      }
    }
    const auto out = Estimate(sphere, queries, &outward);
    const auto in = Estimate(sphere, queries, &inward);
    const auto guessed = Estimate(sphere, queries, nullptr); // away from the centroid
    ASSERT_EQ(queries.size() / 3, out.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < out.size(); ++i)
    {
      ASSERT_TRUE(out[i].QuadricFit);
      EXPECT_NEAR(1.0 / r, out[i].MeanCurvature, 0.05 / r) << "r=" << r << " query " << i;
      EXPECT_NEAR(-1.0 / r, in[i].MeanCurvature, 0.05 / r) << "r=" << r << " query " << i;
      EXPECT_NEAR(1.0 / r, guessed[i].MeanCurvature, 0.05 / r) << "r=" << r << " query " << i;
      worst = std::max(worst, std::abs(out[i].MeanCurvature * r - 1.0));
      // The oriented normal is the outward radial direction.
      const double dot = out[i].Normal[0] * outward[3 * i] + out[i].Normal[1] * outward[3 * i + 1] +
        out[i].Normal[2] * outward[3 * i + 2];
      EXPECT_GT(dot, 0.99);
      EXPECT_GT(guessed[i].Normal[0] * outward[3 * i] + guessed[i].Normal[1] * outward[3 * i + 1] +
          guessed[i].Normal[2] * outward[3 * i + 2],
        0.99);
      EXPECT_EQ(20, out[i].NumberOfNeighbors);
      EXPECT_LT(out[i].SurfaceVariation, 0.01);
    }
    std::cout << "sphere r=" << r << ": max relative error of H " << worst << "\n";
  }
}

TEST(Curvature, OffCentreQueryUsesTheFullFormula)
{
  // The paraboloid z = (x^2 + y^2) / 2 around its apex: the PCA normal is z,
  // the quadric fits exactly, and at (x, y) the mean curvature w.r.t. -z is
  // (2 + s^2) / (2 (1 + s^2)^(3/2)) with s^2 = x^2 + y^2: the gradient terms
  // matter away from the apex (0.805 at s = 0.5, not 1).
  const Cloud bowl =
    asmtest::GridSurface(41, 1.0, [](double x, double y) { return 0.5 * (x * x + y * y); });
  const std::vector<Index> ids = AllIds(bowl);
  const double down[3] = { 0, 0, -1 };
  const double up[3] = { 0, 0, 1 };
  for (const auto& xy : { std::make_pair(0.0, 0.0), std::make_pair(0.5, 0.0),
         std::make_pair(0.3, -0.4), std::make_pair(-0.2, 0.7) })
  {
    const double s2 = xy.first * xy.first + xy.second * xy.second;
    const double expected = (2.0 + s2) / (2.0 * std::pow(1.0 + s2, 1.5));
    const double p[3] = { xy.first, xy.second, 0.5 * s2 };
    const double above[3] = { xy.first, xy.second, 0.5 * s2 + 0.3 }; // projects to p
    for (const double* q : { p, above })
    {
      const CurvatureEstimate e = asmcore::EstimateCurvatureAt(
        bowl.data(), ids.data(), static_cast<Index>(ids.size()), q, down);
      EXPECT_TRUE(e.QuadricFit);
      EXPECT_NEAR(expected, e.MeanCurvature, 1e-9) << "at " << xy.first << " " << xy.second;
      EXPECT_NEAR(-1.0, e.Normal[2], 1e-12);
    }
    const CurvatureEstimate flipped =
      asmcore::EstimateCurvatureAt(bowl.data(), ids.data(), static_cast<Index>(ids.size()), p, up);
    EXPECT_NEAR(-expected, flipped.MeanCurvature, 1e-9);
  }
}

TEST(Curvature, SkewQuadricNeedsTheCrossTerm)
{
  // z = x^2 / 2 + 0.3 xy + 0.2 y^2 on a grid symmetric about the origin: z is
  // the PCA normal, the quadric fits exactly, and fxy = 0.3, so the formula's
  // -2 fu fv fuv term counts wherever the gradient has two components (on
  // the rotationally symmetric bowl above, fuv = 0 in any in-plane frame).
  const auto f = [](double x, double y) { return 0.5 * x * x + 0.3 * x * y + 0.2 * y * y; };
  const Cloud skew = asmtest::GridSurface(41, 1.0, f);
  const std::vector<Index> ids = AllIds(skew);
  const double down[3] = { 0, 0, -1 };
  for (const auto& xy : { std::make_pair(0.0, 0.0), std::make_pair(0.5, 0.2),
         std::make_pair(-0.4, 0.6), std::make_pair(0.3, -0.5) })
  {
    const double x = xy.first, y = xy.second;
    const double fx = x + 0.3 * y, fy = 0.3 * x + 0.4 * y;
    const double fxx = 1.0, fxy = 0.3, fyy = 0.4;
    const double g = 1.0 + fx * fx + fy * fy;
    const double expected = ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy) /
      (2.0 * g * std::sqrt(g));
    const double p[3] = { x, y, f(x, y) };
    const CurvatureEstimate e = asmcore::EstimateCurvatureAt(
      skew.data(), ids.data(), static_cast<Index>(ids.size()), p, down);
    EXPECT_TRUE(e.QuadricFit);
    EXPECT_NEAR(expected, e.MeanCurvature, 1e-9) << "at " << x << " " << y;
  }
}

// The quadric fit's rank test is the QR's (a pivot below 1e-6 of the
// largest), taken on the normal equations' pivots squared: a neighbourhood
// 50 times longer than wide, on an exact shallow bowl, is still fitted
// (its v^2 column is about 5e-4 of the largest, 2.5e-7 squared), and to
// the exact curvature. A test on the unsquared pivots would fall back to
// the plane here.
TEST(Curvature, ElongatedNeighbourhoodsStillGetTheirQuadric)
{
  const double kappa = 0.01; // z = kappa (x^2 + y^2) / 2: mean curvature kappa at the apex
  Cloud strip;
  for (int i = -20; i <= 20; ++i)
  {
    for (int j = -2; j <= 2; ++j)
    {
      const double x = 0.05 * i, y = 0.01 * j;
      asmtest::Add(strip, x, y, 0.5 * kappa * (x * x + y * y));
    }
  }
  const std::vector<Index> ids = AllIds(strip);
  const double apex[3] = { 0.0, 0.0, 0.0 };
  const double down[3] = { 0, 0, -1 };
  const CurvatureEstimate e = asmcore::EstimateCurvatureAt(
    strip.data(), ids.data(), static_cast<Index>(ids.size()), apex, down);
  EXPECT_TRUE(e.QuadricFit);
  EXPECT_NEAR(kappa, e.MeanCurvature, 1e-6 * kappa);
  EXPECT_NEAR(-1.0, e.Normal[2], 1e-12);
}

TEST(Curvature, CylinderMeanCurvatureIsHalfOverRadius)
{
  for (double r : { 0.5, 1.0, 2.0 })
  {
    const Cloud cylinder = Cylinder(20000, r, 23);
    Cloud queries, outward;
    for (std::size_t i = 0; i < cylinder.size() && queries.size() < 3 * 300; i += 3)
    {
      if (std::abs(cylinder[i + 2]) < r) // away from the open ends
      {
        queries.insert(queries.end(), cylinder.begin() + i, cylinder.begin() + i + 3);
        asmtest::Add(outward, cylinder[i] / r, cylinder[i + 1] / r, 0.0);
      }
    }
    const auto out = Estimate(cylinder, queries, &outward);
    ASSERT_EQ(300u, out.size());
    for (std::size_t i = 0; i < out.size(); ++i)
    {
      EXPECT_NEAR(0.5 / r, out[i].MeanCurvature, 0.05 * 0.5 / r) << "r=" << r << " query " << i;
    }
  }
}

TEST(Curvature, PlaneHasZeroMeanCurvature)
{
  // A regular grid and random points of a tilted, shifted plane.
  const Eigen::Matrix3d rotation =
    Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(10.0, -3.0, 5.0);
  const Eigen::Vector3d normal = rotation.col(2);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Cloud random;
  for (int i = 0; i < 5000; ++i)
  {
    asmtest::Add(random, u(rng), u(rng), 0.0);
  }
  const Cloud grid = asmtest::GridSurface(61, 1.0, [](double, double) { return 0.0; });
  for (const Cloud& flat : { grid, random })
  {
    Cloud plane, queries, normals;
    for (std::size_t i = 0; i < flat.size(); i += 3)
    {
      const Eigen::Vector3d p =
        rotation * Eigen::Vector3d(flat[i], flat[i + 1], flat[i + 2]) + shift;
      asmtest::Add(plane, p[0], p[1], p[2]);
      if (i % 15 == 0)
      {
        asmtest::Add(queries, p[0], p[1], p[2]);
        asmtest::Add(normals, normal[0], normal[1], normal[2]);
      }
    }
    const auto estimates = Estimate(plane, queries, &normals);
    for (const CurvatureEstimate& e : estimates)
    {
      EXPECT_TRUE(e.QuadricFit);
      EXPECT_LT(std::abs(e.MeanCurvature), 1e-6);
      EXPECT_LT(e.SurfaceVariation, 1e-12);
      EXPECT_NEAR(1.0, Eigen::Vector3d(e.Normal[0], e.Normal[1], e.Normal[2]).dot(normal), 1e-9);
    }
  }
}

TEST(Curvature, SurfaceVariationPeaksOnCubeEdges)
{
  const Cloud cube = CubeSurface(41); // spacing 0.05
  Cloud queries;
  asmtest::Add(queries, 1.0, 1.0, 0.0); // edge midpoints
  asmtest::Add(queries, -1.0, 0.0, 1.0);
  asmtest::Add(queries, 1.0, 0.0, 0.0); // face centres
  asmtest::Add(queries, 0.0, 0.0, -1.0);
  const auto e = Estimate(cube, queries, nullptr); // outward: away from the centre
  ASSERT_EQ(4u, e.size());
  for (int edge = 0; edge < 2; ++edge)
  {
    EXPECT_GT(e[edge].SurfaceVariation, 0.02) << "edge " << edge;
    EXPECT_GT(e[edge].MeanCurvature, 0.0) << "a convex edge bends away from the outward normal";
    for (int face = 2; face < 4; ++face)
    {
      EXPECT_GT(e[edge].SurfaceVariation, 100.0 * e[face].SurfaceVariation);
    }
  }
  for (int face = 2; face < 4; ++face)
  {
    EXPECT_LT(e[face].SurfaceVariation, 1e-12) << "face " << face;
    EXPECT_LT(std::abs(e[face].MeanCurvature), 1e-6) << "face " << face;
  }
  std::cout << "cube: surface variation edge " << e[0].SurfaceVariation << ", face "
            << e[2].SurfaceVariation << "\n";
}

TEST(Curvature, FallsBackToPlaneWhenUnderdetermined)
{
  const Cloud sphere = asmtest::Sphere(2000, 1.0, 3);
  const auto few = Estimate(sphere, Head(sphere, 10), nullptr, 5); // k < 6
  for (const CurvatureEstimate& e : few)
  {
    EXPECT_FALSE(e.QuadricFit);
    EXPECT_EQ(0.0, e.MeanCurvature);
    EXPECT_EQ(5, e.NumberOfNeighbors);
    EXPECT_TRUE(std::isfinite(e.SurfaceVariation));
  }
  // Points on a line, and on two crossing lines: the quadric is not defined.
  Cloud line, cross;
  for (int i = -30; i <= 30; ++i)
  {
    asmtest::Add(line, 0.1 * i, 0.2 * i, -0.05 * i);
    asmtest::Add(cross, 0.1 * i, 0.0, 0.0);
    asmtest::Add(cross, 0.0, 0.1 * i, 0.0);
  }
  Cloud queries = Head(line, 3);
  asmtest::Add(queries, 0.0, 0.0, 0.0); // where the lines cross
  for (const Cloud& c : { line, cross })
  {
    for (const CurvatureEstimate& e : Estimate(c, queries, nullptr))
    {
      EXPECT_FALSE(e.QuadricFit);
      EXPECT_EQ(0.0, e.MeanCurvature);
      EXPECT_TRUE(std::isfinite(e.SurfaceVariation));
    }
  }
}

TEST(Curvature, NoEstimateWithoutNeighborsOrFiniteQuery)
{
  Cloud queries;
  asmtest::Add(queries, 0.0, 0.0, 0.0);
  asmtest::Add(queries, std::nan(""), 0.0, 0.0);
  const auto empty = Estimate(Cloud(), queries, nullptr);
  const auto sphere = Estimate(asmtest::Sphere(500, 1.0), queries, nullptr);
  ASSERT_EQ(2u, empty.size());
  EXPECT_TRUE(std::isnan(empty[0].MeanCurvature));
  EXPECT_TRUE(std::isnan(empty[0].SurfaceVariation));
  EXPECT_EQ(0, empty[0].NumberOfNeighbors);
  EXPECT_TRUE(std::isnan(sphere[1].MeanCurvature));
  EXPECT_TRUE(std::isfinite(sphere[0].MeanCurvature)); // the centre: still an estimate
  EXPECT_TRUE(Estimate(Cloud(), Cloud(), nullptr).empty());
}

TEST(Curvature, ParallelRunIsDeterministicAndAbortable)
{
  const Cloud sphere = asmtest::Sphere(30000, 1.5, 5);
  const Cloud queries = Head(sphere, 5000);
  const auto sequential = Estimate(sphere, queries, nullptr);
  const auto threaded = Estimate(sphere, queries, nullptr, 20, Threaded(3));
  ASSERT_EQ(sequential.size(), threaded.size());
  for (std::size_t i = 0; i < sequential.size(); ++i)
  {
    // Bit for bit: every query is computed the same way on any thread.
    const CurvatureEstimate& a = sequential[i];
    const CurvatureEstimate& b = threaded[i];
    EXPECT_EQ(0, std::memcmp(&a.MeanCurvature, &b.MeanCurvature, sizeof(double))) << i;
    EXPECT_EQ(0, std::memcmp(&a.SurfaceVariation, &b.SurfaceVariation, sizeof(double))) << i;
    EXPECT_EQ(0, std::memcmp(a.Normal, b.Normal, sizeof(a.Normal))) << i;
    EXPECT_EQ(a.NumberOfNeighbors, b.NumberOfNeighbors);
    EXPECT_EQ(a.QuadricFit, b.QuadricFit);
  }

  asmcore::Execution aborting;
  int reports = 0;
  aborting.Progress = [&reports](double fraction) {
    ++reports;
    EXPECT_GT(fraction, 0.0);
    return fraction >= 0.5;
  };
  EXPECT_TRUE(Estimate(sphere, queries, nullptr, 20, aborting).empty());
  EXPECT_EQ(10, reports);
}

TEST(CurvatureBenchmark, DISABLED_MillionPointSphere)
{
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  const Cloud sphere = asmtest::Sphere(1000000, 1.0, 1);
  const auto ids = AllIds(sphere);
  auto t0 = Clock::now();
  const asmcore::Neighbors tree(sphere.data(), ids);
  std::cout << "build, 1e6 points: " << seconds(t0) << " s\n";

  const Cloud queries = asmtest::Sphere(100000, 1.0, 2);
  const Index n = static_cast<Index>(queries.size() / 3);
  std::vector<Index> found;
  std::vector<double> d;
  Index checksum = 0;
  t0 = Clock::now();
  for (Index i = 0; i < n; ++i)
  {
    tree.KNearest(queries.data() + 3 * i, 20, found, d);
    checksum += found[0];
  }
  std::cout << "1e5 kNN queries, k=20, 1 thread: " << seconds(t0) << " s (" << checksum << ")\n";

  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  for (unsigned t : { 1u, threads })
  {
    const asmcore::Execution exec = t == 1 ? asmcore::Execution() : Threaded(static_cast<int>(t));
    t0 = Clock::now();
    const auto e =
      asmcore::EstimateCurvature(sphere.data(), ids, tree, queries.data(), n, nullptr, 20, exec);
    double mean = 0.0;
    for (const CurvatureEstimate& c : e)
    {
      mean += c.MeanCurvature / static_cast<double>(n);
    }
    std::cout << "1e5 curvature estimates, k=20, " << t << " thread(s): " << seconds(t0)
              << " s (mean H " << mean << ")\n";
    EXPECT_NEAR(1.0, mean, 0.01);
  }
}

// Six neighbours determine the quadric (six unknowns): a fit, not the
// plane; five are too few.
TEST(Curvature, SixNeighboursAreEnoughForTheQuadric)
{
  // The centre and a pentagon of radius 1 on the bowl z = (x^2 + y^2) / 2
  // (no conic passes through all six: the design has full rank).
  Cloud bowl;
  asmtest::Add(bowl, 0.0, 0.0, 0.0);
  for (int k = 0; k < 5; ++k)
  {
    const double angle = 0.4 * 3.141592653589793 * k;
    asmtest::Add(bowl, std::cos(angle), std::sin(angle), 0.5);
  }
  const std::vector<Index> ids = AllIds(bowl);
  const double p[3] = { 0, 0, 0 }, down[3] = { 0, 0, -1 };
  const CurvatureEstimate six = asmcore::EstimateCurvatureAt(bowl.data(), ids.data(), 6, p, down);
  EXPECT_TRUE(six.QuadricFit);
  EXPECT_NEAR(six.MeanCurvature, 1.0, 1e-9);
  const CurvatureEstimate five = asmcore::EstimateCurvatureAt(bowl.data(), ids.data(), 5, p, down);
  EXPECT_FALSE(five.QuadricFit);
  EXPECT_EQ(five.MeanCurvature, 0.0);
}
