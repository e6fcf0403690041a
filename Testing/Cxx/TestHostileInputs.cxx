// SPDX-License-Identifier: BSD-3-Clause
// Messy scan data (README "Messy data"): NaN holes, exact duplicates, far
// outliers, one very dense cell, 64-bit ids, extremely anisotropic bounds,
// short arrays, another piece's ghost points. Each gives exactly N_s sensible
// points. (Messy coordinates: TestCoordinates.cxx.)
#include "FeatureShapes.h"
#include "FilterHelpers.h"

#include "Core/Simplify.h"
#include "vtkASMSimplify.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkKeyPointError.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSOADataArrayTemplate.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <type_traits>

using asmtest::Cloud;
using asmtest::ExpectAllFinite;
using asmtest::FieldValue;
using asmtest::FilterRun;
using asmtest::SphereDeviation;
using asmtest::ToPolyData;

TEST(HostileInputs, NaNAndInfinitePointsAreSkippedWarnedAndCounted)
{
  // A depth camera's holes: 20 % of the points NaN or infinite, in any
  // coordinate, with attributes on every point.
  Cloud c = asmtest::Sphere(5000, 1.0, 11);
  const double bad[] = { std::nan(""), std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity() };
  for (int i = 0; i < 5000; i += 5)
  {
    c[3 * i + (i / 5) % 3] = bad[(i / 15) % 3];
  }
  auto input = ToPolyData(c, VTK_FLOAT);
  vtkNew<vtkFloatArray> intensity;
  intensity->SetName("Intensity");
  for (int i = 0; i < 5000; ++i)
  {
    intensity->InsertNextValue(static_cast<float>(i % 100));
  }
  input->GetPointData()->AddArray(intensity);

  FilterRun run;
  run.Count(400);
  vtkPolyData* out = run.Execute(input);
  ASSERT_EQ(out->GetNumberOfPoints(), 400);
  ExpectAllFinite(out);
  EXPECT_EQ(FieldValue(out, "NumberOfSkippedPoints"), 1000.0);
  EXPECT_GE(run.Messages->Warnings, 1);
  EXPECT_EQ(run.Messages->Errors, 0);
  auto* ids = out->GetPointData()->GetArray("vtkOriginalPointIds");
  auto* outIntensity = out->GetPointData()->GetArray("Intensity");
  ASSERT_NE(outIntensity, nullptr);
  for (vtkIdType i = 0; i < 400; ++i)
  {
    const auto id = static_cast<vtkIdType>(ids->GetTuple1(i));
    EXPECT_NE(id % 5, 0) << "a skipped point never represents a sample";
    EXPECT_TRUE(std::isfinite(outIntensity->GetTuple1(i)));
  }

  // The fraction is taken of the finite points.
  FilterRun fraction;
  fraction.Filter->SetOutputFraction(0.1);
  EXPECT_EQ(fraction.Execute(input)->GetNumberOfPoints(), 400);

  // vtkKeyPointError skips them too (their Error is NaN).
  asmtest::ObservedFilter<vtkKeyPointError> error;
  error.Filter->SetInputData(0, input);
  error.Filter->SetInputData(1, input);
  error.Filter->SetGenerateCurvature(false);
  error.Filter->Update();
  EXPECT_EQ(error.Messages->Errors, 0);
  EXPECT_GE(error.Messages->Warnings, 1);
  EXPECT_EQ(FieldValue(error.Filter->GetOutput(), "HausdorffDistance"), 0.0);
}

// One bad point alone (the first, one inside, the last; in x, y or z) is
// skipped too: the finite points are then all but one, not all.
TEST(HostileInputs, ASingleNonFinitePointIsSkipped)
{
  const Cloud sphere = asmtest::Sphere(3000, 1.0, 11);
  for (const int at : { 0, 1500, 2999 })
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      Cloud c = sphere;
      c[3 * at + axis] = std::nan("");
      FilterRun run;
      run.Count(300);
      vtkPolyData* out = run.Execute(ToPolyData(c, VTK_FLOAT));
      ASSERT_EQ(out->GetNumberOfPoints(), 300) << at << " " << axis;
      ExpectAllFinite(out);
      EXPECT_EQ(FieldValue(out, "NumberOfSkippedPoints"), 1.0) << at << " " << axis;
      auto* ids = out->GetPointData()->GetArray("vtkOriginalPointIds");
      for (vtkIdType i = 0; i < 300; ++i)
      {
        EXPECT_NE(static_cast<int>(ids->GetTuple1(i)), at) << "the skipped point represents none";
      }
    }
  }
}

TEST(HostileInputs, HalfOfThePointsExactDuplicates)
{
  // Every point scanned twice (merged scans): 50 % exact duplicates.
  const Cloud unique = asmtest::Sphere(10000, 1.0, 5);
  Cloud c = unique;
  c.insert(c.end(), unique.begin(), unique.end());
  const double centre[3] = { 0, 0, 0 };
  for (bool snap : { false, true })
  {
    FilterRun run;
    run.Count(500);
    run.Filter->SetSnapToInputPoints(snap);
    vtkPolyData* out = run.Execute(ToPolyData(c));
    ASSERT_EQ(out->GetNumberOfPoints(), 500);
    ExpectAllFinite(out);
    auto* sizes = out->GetPointData()->GetArray("ClusterSize");
    double total = 0.0;
    std::set<std::vector<double>> distinct;
    for (vtkIdType i = 0; i < 500; ++i)
    {
      total += sizes->GetTuple1(i);
      double p[3];
      out->GetPoint(i, p);
      distinct.insert({ p[0], p[1], p[2] });
    }
    EXPECT_EQ(total, 20000.0) << "every input point is in exactly one cluster";
    EXPECT_EQ(distinct.size(), 500u) << "no sample is spent twice on one position";
    EXPECT_LT(SphereDeviation(out, centre, 1.0, false), 0.05);
  }
}

// A piece of a partitioned dataset with its ghost points (another piece's,
// flagged DUPLICATEPOINT in vtkGhostType): they are not simplified here, in a
// serial run as in an MPI run; nor are hidden (blanked, HIDDENPOINT) points
// (before 2026-11-29 they were, and samples standing for them were output
// flagged hidden). A ghost array shorter than the points is not read (it is
// dropped with a warning, as any short array).
TEST(HostileInputs, AnotherPiecesGhostPointsAreNotSimplified)
{
  const asmtest::Cloud sphere = asmtest::Sphere(3000, 1.0, 17);
  asmtest::Cloud c = sphere;
  const asmtest::Cloud halo = asmtest::Sphere(300, 1.02, 18); // the ghosts
  c.insert(c.end(), halo.begin(), halo.end());
  for (const int flag : { static_cast<int>(vtkDataSetAttributes::DUPLICATEPOINT),
         static_cast<int>(vtkDataSetAttributes::HIDDENPOINT), 0 })
  {
    const bool shortGhosts = flag == 0; // (flagged DUPLICATEPOINT, short)
    vtkSmartPointer<vtkPolyData> input = ToPolyData(c);
    vtkNew<vtkUnsignedCharArray> ghosts;
    ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
    ghosts->SetNumberOfTuples(shortGhosts ? 1 : 3300);
    for (vtkIdType i = 0; i < ghosts->GetNumberOfTuples(); ++i)
    {
      ghosts->SetValue(
        i, i < 3000 ? 0 : (shortGhosts ? vtkDataSetAttributes::DUPLICATEPOINT : flag));
    }
    input->GetPointData()->AddArray(ghosts);
    vtkNew<vtkIntArray> piece;
    piece->SetName("Piece");
    for (vtkIdType i = 0; i < 3300; ++i)
    {
      piece->InsertNextValue(i < 3000 ? 0 : 1);
    }
    input->GetPointData()->AddArray(piece);
    for (const int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
    {
      FilterRun run;
      run.Filter->SetMode(mode);
      run.Filter->SetOutputFraction(0.1);
      vtkPolyData* out = run.Execute(input);
      const std::string what = (shortGhosts ? std::string("short ghost array")
                                            : "ghosts flagged " + std::to_string(flag)) +
        ", mode " + std::to_string(mode);
      ASSERT_EQ(out->GetNumberOfPoints(), shortGhosts ? 330 : 300) << what;
      EXPECT_EQ(run.Messages->Warnings, shortGhosts ? 1 : 0) << what;
      vtkDataArray* pieces = out->GetPointData()->GetArray("Piece");
      double fromGhosts = 0.0;
      for (vtkIdType s = 0; s < out->GetNumberOfPoints(); ++s)
      {
        fromGhosts += pieces->GetTuple1(s);
      }
      if (shortGhosts)
      {
        EXPECT_GT(fromGhosts, 0.0) << what;
      }
      else
      {
        EXPECT_EQ(fromGhosts, 0.0) << what;
        EXPECT_EQ(out->GetPointData()->GetArray("ClusterSize")->GetRange()[0] >= 1.0, true);
        vtkDataArray* flags = out->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName());
        ASSERT_NE(flags, nullptr) << what;
        EXPECT_EQ(flags->GetRange()[1], 0.0) << what << ": no sample is flagged";
      }
    }
  }
}

TEST(HostileInputs, OnePercentFarOutliers)
{
  // 1 % of the points scattered up to 1 km from a 1 m sphere: the sphere
  // must still get nearly all of the samples, and the automatic cell size
  // must follow the sphere, not the outliers' bounding box.
  Cloud c = asmtest::Sphere(20000, 1.0, 8);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1000.0, 1000.0);
  for (int i = 0; i < 200; ++i)
  {
    asmtest::Add(c, u(rng), u(rng), u(rng));
  }
  FilterRun clean;
  clean.Count(1000);
  clean.Filter->SetModeToPaper();
  const double cleanCell =
    FieldValue(clean.Execute(ToPolyData(asmtest::Sphere(20000, 1.0, 8))), "CellSize");

  // The default feature-preserving mode gives every non-empty cell a sample
  // first (CoverEveryCell), so each isolated outlier keeps one.
  FilterRun covering;
  covering.Count(1000);
  vtkPolyData* covered = covering.Execute(ToPolyData(c));
  ASSERT_EQ(covered->GetNumberOfPoints(), 1000);
  ExpectAllFinite(covered);

  FilterRun run;
  // Proportional budgets (Eq. 4): the paper's mode. The feature-preserving
  // default gives every outlier's cell a sample on purpose (CoverEveryCell).
  run.Filter->SetModeToPaper();
  run.Count(1000);
  vtkPolyData* out = run.Execute(ToPolyData(c));
  ASSERT_EQ(out->GetNumberOfPoints(), 1000);
  ExpectAllFinite(out);
  int onSphere = 0;
  for (vtkIdType i = 0; i < 1000; ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    onSphere += std::abs(std::hypot(p[0], p[1], p[2]) - 1.0) < 0.05;
  }
  // An outlier's cell has a share of 1000 / 20200 of a sample: below the
  // largest remainders, so the sphere keeps every sample.
  EXPECT_EQ(onSphere, 1000) << "outliers get at most their share (1 %) of the samples";
  EXPECT_LT(FieldValue(out, "CellSize"), 2.0 * cleanCell);
}

TEST(HostileInputs, FiveMillionPointsInOneCell)
{
  // One dense grid cell of 5 M points (a 1 mm blob in a 1 m cell): linear
  // or n log n work only, no recursion depth growing with n.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1e-3);
  const int n = 5000000;
  Cloud c;
  c.reserve(3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
  {
    asmtest::Add(c, u(rng), u(rng), 0.05 * u(rng) * u(rng) * 1e3);
  }
  FilterRun run;
  run.Filter->SetCellSize(1.0);
  run.Filter->SetGenerateCurvature(false);
  run.Count(2000);
  vtkPolyData* out = run.Execute(ToPolyData(c, VTK_FLOAT));
  ASSERT_EQ(out->GetNumberOfPoints(), 2000);
  ExpectAllFinite(out);
  EXPECT_EQ(FieldValue(out, "CellSize"), 1.0);
  double total = 0.0;
  auto* sizes = out->GetPointData()->GetArray("ClusterSize");
  for (vtkIdType i = 0; i < 2000; ++i)
  {
    total += sizes->GetTuple1(i);
  }
  EXPECT_EQ(total, static_cast<double>(n));
}

// Ids are 64-bit from the VTK arrays through the core and back.
static_assert(sizeof(asmcore::Index) == 8 && std::is_signed<asmcore::Index>::value,
  "asmcore::Index must be a signed 64-bit type");
static_assert(sizeof(vtkIdType) == 8, "VTK must be built with 64-bit ids (VTK_USE_64BIT_IDS)");
static_assert(std::is_same<decltype(asmcore::Sample::Representative), asmcore::Index>::value &&
    std::is_same<decltype(asmcore::Sample::MemberBegin), asmcore::Index>::value &&
    std::is_same<decltype(asmcore::Sample::ClusterSize), asmcore::Index>::value &&
    std::is_same<decltype(asmcore::SimplifyParameters::NumberOfSamples), asmcore::Index>::value &&
    std::is_same<asmcore::Index, asmcore::PointArray<asmcore::Index>::value_type>::value &&
    std::is_same<asmcore::PointArray<asmcore::Index>,
      decltype(asmcore::SimplifyResult::Members)>::value,
  "the core's ids and counts are 64-bit");
static_assert(std::is_same<decltype(std::declval<vtkASMSimplify&>().GetNumberOfOutputPoints()),
                vtkIdType>::value,
  "NumberOfOutputPoints is a vtkIdType");

TEST(HostileInputs, PointIdsBeyondTwoToThe31)
{
  // The core sees point ids 2^31 + k without 2^31 points in memory: the
  // coordinate pointer is based so that xyz + 3 * id lands in a small buffer.
  const asmcore::Index first = (asmcore::Index(1) << 31) + 12345;
  const Cloud c = asmtest::Sphere(3000, 1.0, 2);
  const std::uintptr_t base = reinterpret_cast<std::uintptr_t>(c.data()) -
    static_cast<std::uintptr_t>(first) * 3 * sizeof(double);
  const auto* xyz = reinterpret_cast<const double*>(base);
  std::vector<asmcore::Index> ids;
  for (asmcore::Index i = 0; i < 3000; ++i)
  {
    ids.push_back(first + i);
  }
  asmcore::SimplifyParameters parameters;
  parameters.NumberOfSamples = 150;
  parameters.Snap = true;
  const asmcore::SimplifyResult r = asmcore::Simplify(xyz, ids, nullptr, parameters);
  ASSERT_EQ(r.Samples.size(), 150u);
  std::vector<char> seen(3000, 0);
  for (asmcore::Index id : r.Members)
  {
    ASSERT_GE(id, first);
    ASSERT_LT(id, first + 3000);
    ASSERT_FALSE(seen[id - first]);
    seen[id - first] = 1;
  }
  for (const asmcore::Sample& s : r.Samples)
  {
    ASSERT_GE(s.Representative, first);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(s.Position[a], c[3 * (s.Representative - first) + a]);
    }
  }

  // The filter's id arrays are vtkIdTypeArray (64-bit).
  FilterRun run;
  run.Count(100);
  vtkPolyData* out = run.Execute(ToPolyData(c));
  EXPECT_NE(
    vtkIdTypeArray::SafeDownCast(out->GetPointData()->GetArray("vtkOriginalPointIds")), nullptr);
  EXPECT_NE(vtkIdTypeArray::SafeDownCast(out->GetPointData()->GetArray("ClusterSize")), nullptr);
}

TEST(HostileInputs, OneKilometreByOneMillimetreStrip)
{
  // Extremely anisotropic bounds: 1 km x 1 mm (x 10 um of relief). Exact
  // count, a grid following the long axis, points spread along the strip.
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Cloud c;
  for (int i = 0; i < 100000; ++i)
  {
    const double x = 1000.0 * u(rng);
    asmtest::Add(c, x, 1e-3 * u(rng), 1e-5 * std::sin(x));
  }
  for (bool snap : { false, true })
  {
    FilterRun run;
    run.Count(5000);
    run.Filter->SetSnapToInputPoints(snap);
    vtkPolyData* out = run.Execute(ToPolyData(c));
    ASSERT_EQ(out->GetNumberOfPoints(), 5000);
    ExpectAllFinite(out);
    const double cell = FieldValue(out, "CellSize");
    EXPECT_GT(cell, 0.01) << "cells are not sized by the 1 mm side";
    EXPECT_LT(cell, 100.0);
    // Every 10 m of the strip gets samples.
    std::vector<int> perBin(100, 0);
    double bounds[6];
    out->GetBounds(bounds);
    EXPECT_GE(bounds[0], 0.0);
    EXPECT_LE(bounds[1], 1000.0);
    EXPECT_GE(bounds[2], 0.0);
    EXPECT_LE(bounds[3], 1e-3);
    for (vtkIdType i = 0; i < 5000; ++i)
    {
      double p[3];
      out->GetPoint(i, p);
      ++perBin[std::min(99, static_cast<int>(p[0] / 10.0))];
    }
    EXPECT_GT(*std::min_element(perBin.begin(), perBin.end()), 20);
  }
  // A cell size far below the short side is enlarged (2^21 cells per axis),
  // with a warning, not a memory blow-up.
  FilterRun tiny;
  tiny.Count(5000);
  tiny.Filter->SetCellSize(1e-9);
  vtkPolyData* out = tiny.Execute(ToPolyData(c));
  EXPECT_EQ(out->GetNumberOfPoints(), 5000);
  EXPECT_GE(tiny.Messages->Warnings, 1);
  EXPECT_GT(FieldValue(out, "CellSize"), 0.99 * 1000.0 / (1 << 21));
}

TEST(HostileInputs, ArraysShorterThanThePointsAreDroppedWithAWarning)
{
  // A malformed dataset: point-data arrays (normals included) with fewer
  // tuples than points must not be read past their end.
  auto input = ToPolyData(asmtest::Sphere(2000, 1.0, 9));
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(10);
  normals->FillValue(1.0f);
  input->GetPointData()->SetNormals(normals);
  vtkNew<vtkUnsignedCharArray> flags;
  flags->SetName("Flags");
  flags->SetNumberOfTuples(1999);
  flags->FillValue(1);
  input->GetPointData()->AddArray(flags);
  vtkNew<vtkFloatArray> good;
  good->SetName("Good");
  good->SetNumberOfTuples(2000);
  good->FillValue(2.0f);
  input->GetPointData()->AddArray(good);

  FilterRun run;
  run.Count(100);
  vtkPolyData* out = run.Execute(input);
  ASSERT_EQ(out->GetNumberOfPoints(), 100);
  EXPECT_EQ(run.Messages->Warnings, 2);
  EXPECT_EQ(out->GetPointData()->GetArray("Flags"), nullptr);
  ASSERT_NE(out->GetPointData()->GetArray("Good"), nullptr);
  EXPECT_EQ(out->GetPointData()->GetArray("Good")->GetTuple1(99), 2.0);
  ASSERT_NE(out->GetPointData()->GetNormals(), nullptr) << "the PCA normals take their place";
  EXPECT_EQ(out->GetPointData()->GetNormals()->GetNumberOfTuples(), 100);

  // vtkKeyPointError with such a simplified cloud.
  auto simplified = ToPolyData(asmtest::Sphere(100, 1.0, 10));
  simplified->GetPointData()->SetNormals(normals);
  vtkNew<vtkKeyPointError> error;
  error->SetInputData(0, input);
  error->SetInputData(1, simplified);
  error->Update();
  EXPECT_EQ(error->GetOutput(0)->GetNumberOfPoints(), 100);
}

// A short array is left out of the choice among exact duplicates too (it
// was read past its end there, and decided the choice by what lay beyond).
TEST(HostileInputs, ShortArraysDoNotDecideAmongDuplicates)
{
  const asmtest::Cloud once = asmtest::Sphere(2000, 1.0, 12);
  asmtest::Cloud twice = once;
  twice.insert(twice.end(), once.begin(), once.end());
  auto input = ToPolyData(twice);
  vtkNew<vtkDoubleArray> shortArray; // first: compared first, were it compared
  shortArray->SetName("Short");
  shortArray->InsertNextValue(1.0);
  input->GetPointData()->AddArray(shortArray);
  vtkNew<vtkIntArray> label; // 1 on the first copy, 0 on the second: 0 comes first
  label->SetName("Label");
  for (vtkIdType i = 0; i < 4000; ++i)
  {
    label->InsertNextValue(i < 2000 ? 1 : 0);
  }
  input->GetPointData()->AddArray(label);
  for (const int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    FilterRun run;
    run.Filter->SetMode(mode);
    run.Filter->SetSnapToInputPoints(true);
    run.Count(150);
    vtkPolyData* out = run.Execute(input);
    ASSERT_EQ(out->GetNumberOfPoints(), 150);
    EXPECT_EQ(out->GetPointData()->GetArray("Short"), nullptr);
    vtkDataArray* labels = out->GetPointData()->GetArray("Label");
    for (vtkIdType s = 0; s < 150; ++s)
    {
      EXPECT_EQ(labels->GetTuple1(s), 0.0) << "mode " << mode << ", sample " << s;
    }
  }
}
