// SPDX-License-Identifier: BSD-3-Clause
// Tests of the feature-preserving mode (the default): grid cuts are not key
// points, tips and corners are kept, no cell is left empty, clusters are
// connected, and every fix can be switched off on its own.
#include "Core/Budget.h"
#include "Core/FeatureSimplify.h"
#include "Core/Simplify.h"

#include "FeatureShapes.h"
#include "FilterHelpers.h"

#include "vtkDoubleArray.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

using asmcore::Index;
using namespace asmtest;

namespace
{
double NearestSample(const asmcore::SimplifyResult& r, const std::array<double, 3>& x)
{
  double best = 1e300;
  for (const auto& s : r.Samples)
  {
    best =
      std::min(best, std::hypot(s.Position[0] - x[0], s.Position[1] - x[1], s.Position[2] - x[2]));
  }
  return best;
}

// Whether the members of sample s are connected when points closer than
// `link` are linked.
bool Connected(
  const Cloud& c, const asmcore::SimplifyResult& r, const asmcore::Sample& s, double link)
{
  const Index* m = r.Members.data() + s.MemberBegin;
  std::vector<char> seen(static_cast<std::size_t>(s.ClusterSize), 0);
  std::vector<Index> stack = { 0 };
  seen[0] = 1;
  Index reached = 1;
  while (!stack.empty())
  {
    const Index a = stack.back();
    stack.pop_back();
    for (Index b = 0; b < s.ClusterSize; ++b)
    {
      const double* p = c.data() + 3 * m[a];
      const double* q = c.data() + 3 * m[b];
      if (!seen[b] && std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) <= link)
      {
        seen[b] = 1;
        ++reached;
        stack.push_back(b);
      }
    }
  }
  return reached == s.ClusterSize;
}
} // namespace

//------------------------------------------------------------------------------
TEST(FeaturePreserving, TiltedPlaneCutByTheGridHasNoKeyPoints)
{
  const Shape plane = TiltedPlane(40000);
  // The literal reading takes every cell's highest and lowest points.
  const auto paper =
    SimplifyWith(plane.Points, 2000, [](auto& p) { p.Mode = asmcore::SimplifyMode::Paper; });
  EXPECT_GT(paper.NumberOfKeyPoints, 200);
  // Default: none inside; only at the plane's outer border (a scan border
  // is a real extreme along the in-plane axes).
  const auto r = SimplifyWith(plane.Points, 2000);
  ASSERT_EQ(r.Samples.size(), 2000u);
  for (const auto& s : r.Samples)
  {
    if (s.Key)
    {
      const double border = std::min(1.0 - std::abs(s.Position[0]), 1.0 - std::abs(s.Position[1]));
      EXPECT_LT(border, r.CellSize) << s.Position[0] << " " << s.Position[1];
    }
  }
  // Without the in-plane extremes: no key point at all.
  const auto noBorder =
    SimplifyWith(plane.Points, 2000, [](auto& p) { p.InPlaneKeyPoints = false; });
  EXPECT_EQ(noBorder.NumberOfKeyPoints, 0);
  // Without the Lemma 2 check the grid cuts come back.
  const auto unchecked =
    SimplifyWith(plane.Points, 2000, [](auto& p) { p.ValidateKeyPoints = false; });
  EXPECT_GT(unchecked.NumberOfKeyPoints, 200);
}

TEST(FeaturePreserving, ConeApexAndBoxCornersAreKept)
{
  // The apex and the corners are input points (as a CAD sampling would
  // have them); the literal reading keeps band centroids, which miss them.
  for (Index target : { 200, 1000, 4000 })
  {
    const Shape cone = Cone(40000);
    const auto r = SimplifyWith(cone.Points, target);
    EXPECT_LE(NearestSample(r, cone.Features[0]), cone.Spacing(40000)) << target;
    const Shape box = Box(40000);
    const auto b = SimplifyWith(box.Points, target);
    for (const auto& corner : box.Features)
    {
      EXPECT_LE(NearestSample(b, corner), box.Spacing(40000))
        << target << " corner " << corner[0] << " " << corner[1] << " " << corner[2];
    }
  }
}

TEST(FeaturePreserving, SparseCellsAreNotLeftEmpty)
{
  Cloud c = GridSurface(150, 1.0, [](double, double) { return 0.0; });
  const double lonely[5][3] = { { -1, -1, 1 }, { 1, -1, 1.2 }, { 0, 1, 0.8 }, { 0.5, 0.5, -1 },
    { -0.7, 0.2, 1.5 } };
  for (const auto& p : lonely)
  {
    Add(c, p[0], p[1], p[2]);
  }
  const Index target = 1000; // about 125 cells, far more than 5
  for (bool cover : { true, false })
  {
    const auto r = SimplifyWith(c, target, [&](auto& p) {
      p.CoverEveryCell = cover;
      p.BudgetExponent = 1.0;
    });
    ASSERT_EQ(static_cast<Index>(r.Samples.size()), target);
    int covered = 0;
    for (const auto& p : lonely)
    {
      covered += NearestSample(r, { p[0], p[1], p[2] }) < 1e-12 ? 1 : 0;
    }
    EXPECT_EQ(covered, cover ? 5 : 0) << "cover " << cover;
  }
  // The budget itself: one per cell first, exact in total.
  const std::vector<Index> capacity = { 1000, 1, 2, 500, 1 };
  const std::vector<double> share = { 1000, 1, 2, 500, 1 };
  const auto budget = asmcore::ApportionWithCoverage(share, capacity, 20, true);
  EXPECT_EQ(std::accumulate(budget.begin(), budget.end(), Index(0)), 20);
  for (std::size_t i = 0; i < budget.size(); ++i)
  {
    EXPECT_GE(budget[i], 1) << i;
    EXPECT_LE(budget[i], capacity[i]) << i;
  }
  const auto few = asmcore::ApportionWithCoverage(share, capacity, 2, true);
  EXPECT_EQ(few, (std::vector<Index>{ 1, 0, 0, 1, 0 })) << "too few: the largest shares";
}

TEST(FeaturePreserving, MiddleClustersAreConnected)
{
  const int n = 150;
  const double spacing = 2.0 / (n - 1);
  const Cloud c = GridSurface(
    n, 1.0, [](double x, double y) { return 0.15 * std::sin(3 * x) * std::cos(2 * y); });
  for (Index target : { 300, 1200 })
  {
    const auto r = SimplifyWith(c, target);
    ASSERT_EQ(static_cast<Index>(r.Samples.size()), target);
    Index members = 0;
    for (const auto& s : r.Samples)
    {
      ASSERT_GE(s.ClusterSize, 1);
      members += s.ClusterSize;
      EXPECT_TRUE(Connected(c, r, s, 1.5 * spacing))
        << "sample at " << s.Position[0] << " " << s.Position[1];
    }
    EXPECT_EQ(members, n * n) << "the clusters partition the points";
  }
}

TEST(FeaturePreserving, ExactCountAndMembersInEveryConfiguration)
{
  const Shape box = Box(20000);
  const std::vector<std::function<void(asmcore::SimplifyParameters&)>> configurations = {
    [](auto&) {}, [](auto& p) { p.ValidateKeyPoints = false; },
    [](auto& p) { p.InPlaneKeyPoints = false; }, [](auto& p) { p.ExtremeKeyPoints = false; },
    [](auto& p) { p.CoverEveryCell = false; }, [](auto& p) { p.BudgetExponent = 1.0; },
    [](auto& p) { p.LloydIterations = 0; }, [](auto& p) { p.CrossCellIterations = 0; },
    [](auto& p) { p.FillHoles = false; }, [](auto& p) { p.Snap = true; },
    [](auto& p) { p.InputPointSamples = false; },
    [](auto& p) { p.Mode = asmcore::SimplifyMode::Paper; },
    [](auto& p) { p.FeatureSamplesPerCell = 8.0; }, [](auto& p) { p.VariationBudget = 0.0; },
    [](auto& p) { p.CoveringRounds = 2; }, [](auto& p) { p.SparseCellKeyPoints = false; },
    [](auto& p) { p.BoundSnappedHoles = false; }, [](auto& p) { p.VariationCap = 0.0; },
    [](auto& p) { p.ReserveFreeSample = false; }, [](auto& p) { p.FinalLloydIterations = 0; }
  };
  for (std::size_t k = 0; k < configurations.size(); ++k)
  {
    for (Index target : { 1, 7, 100, 1000, 5000, 19999, 20000 })
    {
      const auto r = SimplifyWith(box.Points, target, configurations[k]);
      ASSERT_EQ(static_cast<Index>(r.Samples.size()), target) << "configuration " << k;
      Index members = 0;
      for (const auto& s : r.Samples)
      {
        members += s.ClusterSize;
        EXPECT_GE(s.Representative, 0);
      }
      EXPECT_LE(members, 20000);
      EXPECT_GE(members, target) << "configuration " << k << " target " << target;
    }
  }
  EXPECT_LE(asmcore::InfluenceRingsOf(asmcore::SimplifyParameters()), asmcore::InfluenceRings);
}

//------------------------------------------------------------------------------
namespace
{
std::vector<double> Flatten(vtkPolyData* out)
{
  std::vector<double> flat;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    flat.insert(flat.end(), p, p + 3);
    flat.push_back(out->GetPointData()->GetArray("vtkOriginalPointIds")->GetTuple1(i));
    flat.push_back(out->GetPointData()->GetArray("ClusterSize")->GetTuple1(i));
  }
  return flat;
}
} // namespace

TEST(FeaturePreserving, EachOptionSwitchesOnItsOwnAndThreadsDoNotMatter)
{
  auto input = ReadPLY("fandisk.ply");
  const vtkIdType n = input->GetNumberOfPoints();
  const std::vector<std::pair<const char*, std::function<void(vtkASMSimplify*)>>> options = {
    { "default", [](vtkASMSimplify*) {} },
    { "ValidateKeyPointsOff", [](vtkASMSimplify* f) { f->ValidateKeyPointsOff(); } },
    { "KeyPointRadius", [](vtkASMSimplify* f) { f->SetKeyPointRadius(0.25); } },
    { "KeyPointProminence", [](vtkASMSimplify* f) { f->SetKeyPointProminence(0.5); } },
    { "InPlaneKeyPointsOff", [](vtkASMSimplify* f) { f->InPlaneKeyPointsOff(); } },
    { "ExtremeKeyPointsOff", [](vtkASMSimplify* f) { f->ExtremeKeyPointsOff(); } },
    { "CoverEveryCellOff", [](vtkASMSimplify* f) { f->CoverEveryCellOff(); } },
    { "BudgetExponent", [](vtkASMSimplify* f) { f->SetBudgetExponent(1.0); } },
    { "LloydIterations", [](vtkASMSimplify* f) { f->SetLloydIterations(0); } },
    { "CrossCellIterations", [](vtkASMSimplify* f) { f->SetCrossCellIterations(0); } },
    { "InputPointSamplesOff", [](vtkASMSimplify* f) { f->InputPointSamplesOff(); } },
    { "FillHolesOff", [](vtkASMSimplify* f) { f->FillHolesOff(); } },
    { "HoleFillFraction", [](vtkASMSimplify* f) { f->SetHoleFillFraction(0.1); } },
    { "FeatureSamplesPerCell", [](vtkASMSimplify* f) { f->SetFeatureSamplesPerCell(8.0); } },
    { "VariationBudget", [](vtkASMSimplify* f) { f->SetVariationBudget(0.0); } },
    { "CoveringRounds", [](vtkASMSimplify* f) { f->SetCoveringRounds(2); } },
    { "BoundSnappedHolesOff", [](vtkASMSimplify* f) { f->BoundSnappedHolesOff(); } },
    { "VariationCap", [](vtkASMSimplify* f) { f->SetVariationCap(2.0); } },
    { "FinalLloydIterations", [](vtkASMSimplify* f) { f->SetFinalLloydIterations(0); } },
    { "LloydVariationWeight", [](vtkASMSimplify* f) { f->SetLloydVariationWeight(0.0); } },
    // (SparseCellKeyPoints changes nothing on the fandisk: no tip alone in a
    // cell; see FeatureCoverage.TipAloneInASparseCellIsAKeyPoint.)
    // (Nor ReserveFreeSample at 5 %: no cell's key points fill its budget;
    // see FeatureCoverage.ReserveFreeSampleKeepsANonKeySampleInACell.)
    { "Paper", [](vtkASMSimplify* f) { f->SetModeToPaper(); } }
  };
  std::vector<std::vector<double>> results;
  for (const auto& option : options)
  {
    const std::vector<ThreadingRun> runs = RunForEachThreading([&]() {
      FilterRun run;
      run.Filter->SetOutputFraction(0.05);
      run.Filter->GenerateCurvatureOff();
      run.Filter->SetMinimumPointsForThreads(0); // a small input: threads anyway
      option.second(run.Filter);
      vtkPolyData* out = run.Execute(input);
      EXPECT_EQ(out->GetNumberOfPoints(), std::llround(0.05 * n)) << option.first;
      EXPECT_EQ(run.Messages->Warnings + run.Messages->Errors, 0) << option.first;
      return Flatten(out);
    });
    EXPECT_TRUE(SameOutputs(runs)) << option.first;
    ASSERT_FALSE(runs.empty());
    for (std::size_t k = 0; k < results.size(); ++k)
    {
      EXPECT_NE(results[k], runs[0].Output) << option.first << " changes nothing";
    }
    results.push_back(runs[0].Output);
  }
}

TEST(FeaturePreserving, DefaultModeIsFeaturePreserving)
{
  // The filter's defaults are the core's.
  vtkNew<vtkASMSimplify> filter;
  const asmcore::SimplifyParameters core;
  EXPECT_EQ(filter->GetMode(), vtkASMSimplify::FEATURE_PRESERVING);
  EXPECT_EQ(core.Mode, asmcore::SimplifyMode::FeaturePreserving);
  EXPECT_EQ(filter->GetValidateKeyPoints(), core.ValidateKeyPoints);
  EXPECT_EQ(filter->GetKeyPointRadius(), core.KeyPointRadius);
  EXPECT_EQ(filter->GetKeyPointProminence(), core.KeyPointProminence);
  EXPECT_EQ(filter->GetInPlaneKeyPoints(), core.InPlaneKeyPoints);
  EXPECT_EQ(filter->GetExtremeKeyPoints(), core.ExtremeKeyPoints);
  EXPECT_EQ(filter->GetCoverEveryCell(), core.CoverEveryCell);
  EXPECT_EQ(filter->GetBudgetExponent(), core.BudgetExponent);
  EXPECT_EQ(filter->GetLloydIterations(), core.LloydIterations);
  EXPECT_EQ(filter->GetCrossCellIterations(), core.CrossCellIterations);
  EXPECT_EQ(filter->GetInputPointSamples(), core.InputPointSamples);
  EXPECT_EQ(filter->GetFillHoles(), core.FillHoles);
  EXPECT_EQ(filter->GetHoleFillFraction(), core.HoleFillFraction);
  EXPECT_EQ(filter->GetFeatureSamplesPerCell(), core.FeatureSamplesPerCell);
  EXPECT_EQ(filter->GetVariationBudget(), core.VariationBudget);
  EXPECT_EQ(filter->GetCoveringRounds(), core.CoveringRounds);
  EXPECT_EQ(filter->GetSparseCellKeyPoints(), core.SparseCellKeyPoints);
  EXPECT_EQ(filter->GetBoundSnappedHoles(), core.BoundSnappedHoles);
  EXPECT_EQ(filter->GetVariationCap(), core.VariationCap);
  EXPECT_EQ(filter->GetReserveFreeSample(), core.ReserveFreeSample);
  EXPECT_EQ(filter->GetFinalLloydIterations(), core.FinalLloydIterations);
  EXPECT_TRUE(filter->GetValidateKeyPoints());
  EXPECT_EQ(filter->GetBudgetExponent(), 0.5);
  filter->SetModeToPaper();
  EXPECT_EQ(filter->GetMode(), vtkASMSimplify::PAPER);
}

TEST(FeaturePreserving, PropagatesAttributes)
{
  // Arrays equal to the coordinates: averaged over each cluster. With
  // InputPointSamples off a sample is its cluster's centroid, so the
  // averaged array equals the output point; by default the output point is
  // the representative input point and the array still holds the mean.
  const Cloud c = asmtest::Sphere(6000, 1.0, 3);
  auto input = ToPolyData(c);
  vtkNew<vtkDoubleArray> position;
  position->SetName("Position");
  position->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    position->InsertNextTuple(c.data() + 3 * i);
  }
  input->GetPointData()->AddArray(position);
  for (bool inputPoints : { false, true })
  {
    FilterRun run;
    run.Filter->SetInputPointSamples(inputPoints);
    run.Filter->BoundSnappedHolesOff(); // every sample an input point (see FeatureCoverage)
    run.Filter->GenerateCurvatureOff();
    run.Filter->SetOutputFraction(0.1);
    vtkPolyData* out = run.Execute(input);
    ASSERT_EQ(out->GetNumberOfPoints(), 600);
    auto* mean = out->GetPointData()->GetArray("Position");
    auto* ids = out->GetPointData()->GetArray("vtkOriginalPointIds");
    auto* keys = out->GetPointData()->GetArray("KeyPoint");
    ASSERT_NE(mean, nullptr);
    for (vtkIdType i = 0; i < 600; ++i)
    {
      double p[3], m[3], r[3];
      out->GetPoint(i, p);
      mean->GetTuple(i, m);
      input->GetPoint(static_cast<vtkIdType>(ids->GetTuple1(i)), r);
      for (int a = 0; a < 3; ++a)
      {
        if (inputPoints || keys->GetTuple1(i) > 0)
        {
          EXPECT_NEAR(p[a], r[a], 1e-12) << "an input point";
        }
        else
        {
          EXPECT_NEAR(p[a], m[a], 1e-12) << "the cluster centroid";
        }
        EXPECT_NEAR(m[a], p[a], 0.2) << "the cluster mean is near the sample";
      }
    }
  }
}
