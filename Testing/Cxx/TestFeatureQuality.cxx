// SPDX-License-Identifier: BSD-3-Clause
// Quality measurement of the modes against a voxel grid at the same count
// (disabled: prints figures, asserts nothing). Run with
//   ASM_QUALITY_DATA="/path/a.ply;/path/b.ply" ASM_QUALITY_FRACTION=0.05 \
//   asm_tests --gtest_also_run_disabled_tests --gtest_filter='*FeatureQuality*'
#include "Core/Grid.h"
#include "Core/Metrics.h"
#include "Core/Neighbors.h"
#include "Core/Simplify.h"

#include "FeatureShapes.h"
#include "FilterHelpers.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>

using asmcore::Index;
using namespace asmtest;

namespace
{
// vtkVoxelGrid's rule (the centroid of each occupied voxel), with the voxel
// size bisected until the count is within 1 % of the target.
Cloud VoxelGrid(const Cloud& c, Index target)
{
  const auto ids = AllIds(c);
  const auto bounds = asmcore::ComputeBounds(c.data(), ids);
  double lo = bounds.MaxExtent() * 1e-5, hi = bounds.MaxExtent();
  double h = hi;
  for (int it = 0; it < 60; ++it)
  {
    h = std::sqrt(lo * hi);
    const Index n = asmcore::CountOccupiedCells(c.data(), ids, asmcore::GridSpec::Make(bounds, h));
    if (std::abs(static_cast<double>(n - target)) <= 0.01 * static_cast<double>(target))
    {
      break;
    }
    (n > target ? lo : hi) = h;
  }
  const auto grid = asmcore::BuildCellGrid(c.data(), ids, asmcore::GridSpec::Make(bounds, h));
  Cloud out;
  for (Index k = 0; k < grid.NumberOfCells(); ++k)
  {
    double s[3] = { 0, 0, 0 };
    for (Index i = 0; i < grid.CellSizeOf(k); ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        s[a] += c[3 * grid.CellPoints(k)[i] + a];
      }
    }
    Add(out, s[0] / grid.CellSizeOf(k), s[1] / grid.CellSizeOf(k), s[2] / grid.CellSizeOf(k));
  }
  return out;
}

Cloud ASM(const Cloud& c, Index target, const std::function<void(asmcore::SimplifyParameters&)>& f)
{
  asmcore::SimplifyParameters p;
  p.NumberOfSamples = target;
  f(p);
  const auto r = asmcore::Simplify(c.data(), AllIds(c), nullptr, p);
  Cloud out;
  for (const auto& s : r.Samples)
  {
    Add(out, s.Position[0], s.Position[1], s.Position[2]);
  }
  return out;
}

void Score(const char* input, const char* method, const Cloud& original,
  const asmcore::Neighbors& tree, const Cloud& simplified,
  const std::vector<std::array<double, 3>>& features)
{
  asmcore::ComparisonOptions options;
  const auto cmp = asmcore::CompareClouds(
    original.data(), AllIds(original), tree, simplified.data(), AllIds(simplified), options);
  double tip = 0.0;
  for (const auto& f : features)
  {
    double best = 1e300;
    for (std::size_t i = 0; i < simplified.size(); i += 3)
    {
      best = std::min(
        best, std::hypot(simplified[i] - f[0], simplified[i + 1] - f[1], simplified[i + 2] - f[2]));
    }
    tip = std::max(tip, best);
  }
  const double d = cmp.Diagonal;
  std::printf("%-16s %-12s %7zu  p2p %.3e  nnO %.3e  nnS %.3e  nnRMS %.3e  hole %.3e  tip %.3e\n",
    input, method, simplified.size() / 3, cmp.PointToPlane.Mean / d,
    cmp.OriginalToSimplified.RMS / d, cmp.SimplifiedToOriginal.RMS / d,
    std::sqrt(0.5 *
      (cmp.OriginalToSimplified.RMS * cmp.OriginalToSimplified.RMS +
        cmp.SimplifiedToOriginal.RMS * cmp.SimplifiedToOriginal.RMS)) /
      d,
    cmp.OriginalToSimplified.Max / d, tip / d);
}
} // namespace

TEST(FeatureQuality, DISABLED_ModesAgainstAVoxelGrid)
{
  const char* env = std::getenv("ASM_QUALITY_FRACTION");
  const double fraction = env ? std::atof(env) : 0.05;
  std::vector<std::pair<std::string, Cloud>> inputs;
  std::vector<std::vector<std::array<double, 3>>> features;
  std::vector<std::string> files = { DataFile("bunny.ply"), DataFile("fandisk.ply"),
    DataFile("kitten.ply"), DataFile("laurana.ply") };
  if (const char* extra = std::getenv("ASM_QUALITY_DATA"))
  {
    std::stringstream ss(extra);
    std::string f;
    while (std::getline(ss, f, ';'))
    {
      files.push_back(f);
    }
  }
  for (const auto& f : files)
  {
    vtkNew<vtkPLYReader> reader;
    reader->SetFileName(f.c_str());
    reader->Update();
    vtkPolyData* pd = reader->GetOutput();
    Cloud c;
    for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
    {
      double p[3];
      pd->GetPoint(i, p);
      Add(c, p[0], p[1], p[2]);
    }
    inputs.emplace_back(f.substr(f.rfind('/') + 1), c);
    features.emplace_back();
  }
  const Shape cone = Cone(100000), box = Box(100000);
  inputs.emplace_back("cone", cone.Points);
  features.push_back(cone.Features);
  inputs.emplace_back("box", box.Points);
  features.push_back(box.Features);
  const std::vector<std::pair<const char*, std::function<void(asmcore::SimplifyParameters&)>>>
    methods = {
      { "paper", [](auto& p) { p.Mode = asmcore::SimplifyMode::Paper; } },
      { "feature", [](auto&) {} },
      { "nofill", [](auto& p) { p.FillHoles = false; } },
      { "x2 fill3",
        [](auto& p) {
          p.CrossCellIterations = 2;
          p.HoleFillRounds = 3;
        } },
    };
  for (std::size_t k = 0; k < inputs.size(); ++k)
  {
    const Cloud& c = inputs[k].second;
    const Index target = std::llround(fraction * static_cast<double>(c.size() / 3));
    const asmcore::Neighbors tree(c.data(), AllIds(c));
    Score(inputs[k].first.c_str(), "voxelgrid", c, tree, VoxelGrid(c, target), features[k]);
    for (const auto& m : methods)
    {
      Score(inputs[k].first.c_str(), m.first, c, tree, ASM(c, target, m.second), features[k]);
    }
  }
}

TEST(FeatureQuality, DISABLED_TimeFourMillionPoints)
{
  // A wavy closed surface: 4 M points on a sphere with ripples, one thread.
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0.0, 1.0);
  const std::size_t n = 4000000;
  Cloud c;
  c.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    double v[3] = { g(rng), g(rng), g(rng) };
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double r = 1.0 + 0.05 * std::sin(8 * v[0] / l) * std::cos(6 * v[1] / l);
    Add(c, r * v[0] / l, r * v[1] / l, r * v[2] / l);
  }
  const auto ids = AllIds(c);
  const std::vector<std::pair<const char*, std::function<void(asmcore::SimplifyParameters&)>>>
    methods = { { "paper", [](auto& p) { p.Mode = asmcore::SimplifyMode::Paper; } },
      { "feature", [](auto&) {} }, { "nofill", [](auto& p) { p.FillHoles = false; } } };
  const char* only = std::getenv("ASM_TIME_ONLY");
  for (const auto& m : methods)
  {
    if (only && std::string(only) != m.first)
    {
      continue;
    }
    asmcore::SimplifyParameters p;
    p.NumberOfSamples = static_cast<Index>(0.05 * n);
    m.second(p);
    std::vector<double> times;
    for (int repeat = 0; repeat < (only ? 1 : 3); ++repeat)
    {
      const auto t0 = std::chrono::steady_clock::now();
      const auto r = asmcore::Simplify(c.data(), ids, nullptr, p);
      times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      EXPECT_EQ(r.Samples.size(), static_cast<std::size_t>(p.NumberOfSamples));
    }
    std::sort(times.begin(), times.end());
    std::printf("%-14s median %.3f s  %.2f M points/s\n", m.first, times[times.size() / 2],
      n / times[times.size() / 2] / 1e6);
  }
}
