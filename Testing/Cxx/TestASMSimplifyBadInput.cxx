// SPDX-License-Identifier: BSD-3-Clause
// vtkASMSimplify on bad input: a clear warning or error and a valid output,
// never a crash or a hang.
#include "vtkASMSimplify.h"

#include "FilterHelpers.h"

#include "vtkCommand.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

using namespace asmtest;

namespace
{
void ExpectFinite(vtkPolyData* out)
{
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const double* p = out->GetPoint(i);
    ASSERT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
  }
  ASSERT_TRUE(OneVertexPerPoint(out));
}
} // namespace

TEST(ASMSimplifyBadInput, EmptyInput)
{
  FilterRun run;
  EXPECT_EQ(run.Execute(vtkNew<vtkPolyData>())->GetNumberOfPoints(), 0);
  EXPECT_EQ(run.Messages->Warnings, 1);
  FilterRun withPoints;
  EXPECT_EQ(withPoints.Execute(ToPolyData({}))->GetNumberOfPoints(), 0);
  EXPECT_EQ(withPoints.Messages->Warnings, 1);
}

TEST(ASMSimplifyBadInput, OnePoint)
{
  auto input = ToPolyData({ 1, 2, 3 });
  FilterRun fraction; // 5 % of one point rounds to none
  EXPECT_EQ(fraction.Execute(input)->GetNumberOfPoints(), 0);
  EXPECT_EQ(fraction.Messages->Warnings, 1);
  FilterRun one;
  one.Count(1);
  vtkPolyData* out = one.Execute(input);
  ASSERT_EQ(out->GetNumberOfPoints(), 1);
  EXPECT_EQ(out->GetPoint(0)[2], 3.0);
  EXPECT_EQ(one.Messages->Warnings, 1) << "N_s >= N passes through with a warning";
}

TEST(ASMSimplifyBadInput, AllPointsIdentical)
{
  Cloud c;
  for (int i = 0; i < 1000; ++i)
  {
    asmtest::Add(c, 5, -2, 7);
  }
  FilterRun run;
  run.Count(10);
  vtkPolyData* out = run.Execute(ToPolyData(c));
  ASSERT_EQ(out->GetNumberOfPoints(), 10);
  ExpectFinite(out);
  for (vtkIdType i = 0; i < 10; ++i)
  {
    EXPECT_EQ(out->GetPoint(i)[0], 5.0);
    EXPECT_EQ(out->GetPoint(i)[1], -2.0);
    EXPECT_EQ(out->GetPoint(i)[2], 7.0);
  }
  EXPECT_EQ(run.Messages->Warnings + run.Messages->Errors, 0);
}

TEST(ASMSimplifyBadInput, CollinearPoints)
{
  Cloud c;
  for (int i = 0; i < 1000; ++i)
  {
    asmtest::Add(c, 1 + 2.0 * i, 2 + 1.0 * i, 3 - 0.5 * i);
  }
  FilterRun run;
  run.Count(50);
  vtkPolyData* out = run.Execute(ToPolyData(c));
  ASSERT_EQ(out->GetNumberOfPoints(), 50);
  ExpectFinite(out);
  for (vtkIdType i = 0; i < 50; ++i)
  {
    const double* p = out->GetPoint(i);
    const double t = (p[0] - 1) / 2.0;
    EXPECT_NEAR(p[1], 2 + t, 1e-9);
    EXPECT_NEAR(p[2], 3 - 0.5 * t, 1e-9);
  }
}

TEST(ASMSimplifyBadInput, NaNAndInfinitePointsAreSkipped)
{
  Cloud c = asmtest::Sphere(1000, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 10; ++i)
  {
    asmtest::Add(c, nan, 0, 0);
  }
  for (int i = 0; i < 5; ++i)
  {
    asmtest::Add(c, 0, -inf, inf);
  }
  // Doubles and floats (read in place), both modes, with the curvature
  // (its k-d tree over the finite points only).
  for (const int type : { VTK_DOUBLE, VTK_FLOAT })
  {
    for (const int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
    {
      const std::string what = std::string(type == VTK_FLOAT ? "float" : "double") +
        (mode == vtkASMSimplify::PAPER ? ", paper" : ", default");
      FilterRun run;
      run.Filter->SetOutputFraction(0.1);
      run.Filter->SetMode(mode);
      run.Filter->SetGenerateCurvature(true);
      vtkPolyData* out = run.Execute(ToPolyData(c, type));
      ASSERT_EQ(out->GetNumberOfPoints(), 100) << "10 % of the 1000 finite points, " << what;
      ExpectFinite(out);
      EXPECT_EQ(run.Messages->Warnings, 1) << what;
      EXPECT_EQ(out->GetFieldData()->GetArray("NumberOfSkippedPoints")->GetTuple1(0), 15.0) << what;
      auto* ids = out->GetPointData()->GetArray("vtkOriginalPointIds");
      for (vtkIdType i = 0; i < 100; ++i)
      {
        EXPECT_LT(ids->GetTuple1(i), 1000.0) << what;
      }
      auto* curvature = out->GetPointData()->GetArray("MeanCurvature");
      ASSERT_NE(curvature, nullptr) << what;
      for (vtkIdType i = 0; i < 100; ++i)
      {
        // A unit sphere: mean curvature about 1 in magnitude everywhere.
        EXPECT_NEAR(std::abs(curvature->GetTuple1(i)), 1.0, 0.3) << what << ", point " << i;
      }
    }
  }
  // Only non-finite points: an empty output.
  FilterRun none;
  none.Count(3);
  EXPECT_EQ(none.Execute(ToPolyData({ nan, nan, nan, inf, 0, 0 }))->GetNumberOfPoints(), 0);
}

TEST(ASMSimplifyBadInput, ZeroOutputPoints)
{
  FilterRun run;
  run.Count(0);
  EXPECT_EQ(run.Execute(ToPolyData(asmtest::Sphere(100, 1.0)))->GetNumberOfPoints(), 0);
  EXPECT_EQ(run.Messages->Warnings, 1);
}

TEST(ASMSimplifyBadInput, MoreOutputPointsThanInputPassesThrough)
{
  auto input = ToPolyData(asmtest::Sphere(500, 1.0));
  FilterRun run;
  run.Count(100000);
  vtkPolyData* out = run.Execute(input);
  ASSERT_EQ(out->GetNumberOfPoints(), 500);
  EXPECT_EQ(run.Messages->Warnings, 1);
  std::set<vtkIdType> ids;
  for (vtkIdType i = 0; i < 500; ++i)
  {
    const auto id =
      static_cast<vtkIdType>(out->GetPointData()->GetArray("vtkOriginalPointIds")->GetTuple1(i));
    ids.insert(id);
    EXPECT_EQ(out->GetPointData()->GetArray("ClusterSize")->GetTuple1(i), 1.0);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(out->GetPoint(i)[a], input->GetPoint(id)[a]);
    }
  }
  EXPECT_EQ(ids.size(), 500u);
}

TEST(ASMSimplifyBadInput, NegativeAndAbsurdParameters)
{
  auto input = ToPolyData(asmtest::Sphere(2000, 1.0));
  {
    FilterRun run; // clamped setters
    run.Filter->SetAlpha(-3);
    EXPECT_EQ(run.Filter->GetAlpha(), 0.0);
    run.Filter->SetOutputFraction(7);
    EXPECT_EQ(run.Filter->GetOutputFraction(), 1.0);
    run.Filter->SetNumberOfOutputPoints(-5);
    EXPECT_EQ(run.Filter->GetNumberOfOutputPoints(), 0);
    run.Filter->SetSamplesPerCell(-1);
    EXPECT_EQ(run.Filter->GetSamplesPerCell(), 1.0);
  }
  {
    FilterRun run; // negative cell size and tolerance: automatic size, no bound
    run.Filter->SetCellSize(-1);
    run.Filter->SetErrorTolerance(-1);
    run.Filter->SetAlpha(0.5);
    EXPECT_EQ(run.Execute(input)->GetNumberOfPoints(), 100);
    EXPECT_EQ(run.Messages->Warnings + run.Messages->Errors, 0);
  }
  {
    FilterRun run; // a cell size far too small is enlarged, with a warning
    run.Filter->SetCellSize(1e-300);
    EXPECT_EQ(run.Execute(input)->GetNumberOfPoints(), 100);
    EXPECT_EQ(run.Messages->Warnings, 1);
  }
  {
    FilterRun run; // huge sizes: one cell
    run.Filter->SetCellSize(1e300);
    run.Filter->SetSamplesPerCell(1e300);
    ExpectFinite(run.Execute(input));
    EXPECT_EQ(run.Filter->GetOutput()->GetNumberOfPoints(), 100);
  }
  {
    FilterRun run; // not a number: an error and an empty output
    run.Filter->SetErrorTolerance(std::nan(""));
    EXPECT_EQ(run.Execute(input)->GetNumberOfPoints(), 0);
    EXPECT_EQ(run.Messages->Errors, 1);
  }
  {
    FilterRun run;
    run.Filter->SetCellSize(std::numeric_limits<double>::infinity());
    EXPECT_EQ(run.Execute(input)->GetNumberOfPoints(), 0);
    EXPECT_EQ(run.Messages->Errors, 1);
  }
}

// Each floating-point property set to NaN or infinity (the clamped setters
// let NaN through): an error naming it and an empty output, in both modes.
TEST(ASMSimplifyBadInput, EveryNonFiniteParameterIsAnError)
{
  auto input = ToPolyData(asmtest::Sphere(2000, 1.0));
  using Setter = void (vtkASMSimplify::*)(double);
  const std::vector<std::pair<const char*, Setter>> properties = {
    { "OutputFraction", &vtkASMSimplify::SetOutputFraction },
    { "CellSize", &vtkASMSimplify::SetCellSize },
    { "SamplesPerCell", &vtkASMSimplify::SetSamplesPerCell },
    { "Alpha", &vtkASMSimplify::SetAlpha },
    { "ErrorTolerance", &vtkASMSimplify::SetErrorTolerance },
    { "CurvatureWeight", &vtkASMSimplify::SetCurvatureWeight },
    { "FeatureSamplesPerCell", &vtkASMSimplify::SetFeatureSamplesPerCell },
    { "VariationBudget", &vtkASMSimplify::SetVariationBudget },
    { "VariationCap", &vtkASMSimplify::SetVariationCap },
    { "KeyPointRadius", &vtkASMSimplify::SetKeyPointRadius },
    { "KeyPointProminence", &vtkASMSimplify::SetKeyPointProminence },
    { "BudgetExponent", &vtkASMSimplify::SetBudgetExponent },
    { "HoleFillFraction", &vtkASMSimplify::SetHoleFillFraction },
    { "LloydVariationWeight", &vtkASMSimplify::SetLloydVariationWeight },
  };
  for (const auto& [name, set] : properties)
  {
    for (const int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
    {
      FilterRun run;
      run.Filter->SetMode(mode);
      (run.Filter.GetPointer()->*set)(std::nan(""));
      EXPECT_EQ(run.Execute(input)->GetNumberOfPoints(), 0) << name << ", mode " << mode;
      EXPECT_EQ(run.Messages->Errors, 1) << name << ", mode " << mode;
      EXPECT_NE(run.Messages->LastMessage.find(name), std::string::npos)
        << run.Messages->LastMessage;
    }
  }
}

TEST(ASMSimplifyBadInput, MillionsOfPointsInOneCell)
{
  // Two million points in a 1 mm blob, one grid cell of 1 m.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1e-3);
  Cloud c;
  c.reserve(6000000);
  for (int i = 0; i < 2000000; ++i)
  {
    asmtest::Add(c, u(rng), u(rng), 0.1 * u(rng));
  }
  FilterRun run;
  run.Filter->SetCellSize(1.0);
  run.Count(1000);
  vtkPolyData* out = run.Execute(ToPolyData(c));
  EXPECT_EQ(out->GetNumberOfPoints(), 1000);
  ExpectFinite(out);
  EXPECT_EQ(out->GetFieldData()->GetArray("CellSize")->GetTuple1(0), 1.0);
}
