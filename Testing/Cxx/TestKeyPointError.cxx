// SPDX-License-Identifier: BSD-3-Clause
// Tests of vtkKeyPointError, and of the curvature arrays of both filters.
#include "vtkKeyPointError.h"

#include "FilterHelpers.h"

#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

using namespace asmtest;

namespace
{
struct ErrorRun : ObservedFilter<vtkKeyPointError>
{
  vtkPolyData* Execute(vtkDataObject* original, vtkDataObject* simplified)
  {
    this->Filter->SetInputData(0, original);
    this->Filter->SetSimplifiedData(simplified);
    this->Filter->Update();
    return vtkPolyData::SafeDownCast(this->Filter->GetOutputDataObject(0));
  }
  double Figure(const char* name)
  {
    vtkTable* table = this->Filter->GetFiguresOutput();
    EXPECT_EQ(table, this->Filter->GetOutputDataObject(1));
    vtkAbstractArray* column = table ? table->GetColumnByName(name) : nullptr;
    return column ? column->GetVariantValue(0).ToDouble() : std::nan("");
  }
};

Cloud Shifted(const Cloud& c, double dx, double dy, double dz)
{
  Cloud s = c;
  for (std::size_t i = 0; i < s.size(); i += 3)
  {
    s[i] += dx;
    s[i + 1] += dy;
    s[i + 2] += dz;
  }
  return s;
}

double Median(vtkDataArray* a)
{
  std::vector<double> v;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    v.push_back(a->GetTuple1(i));
  }
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

const Cloud Bump = GridSurface(39, 1.0, [](double x, double y) { return -0.5 * (x * x + y * y); });
} // namespace

TEST(KeyPointError, IdenticalCloudsHaveNoError)
{
  auto cloud = ToPolyData(Bump);
  ErrorRun run;
  vtkPolyData* out = run.Execute(cloud, cloud);
  ASSERT_EQ(out->GetNumberOfPoints(), cloud->GetNumberOfPoints());
  EXPECT_TRUE(OneVertexPerPoint(out));
  EXPECT_GT(run.Figure("NumberOfOriginalKeyPoints"), 0.0);
  EXPECT_EQ(run.Figure("NumberOfOriginalKeyPoints"), run.Figure("NumberOfSimplifiedKeyPoints"));
  for (const char* name : { "AKPE", "MKPE", "HausdorffDistance", "MeanDistanceOriginalToSimplified",
         "MaxDistanceSimplifiedToOriginal" })
  {
    EXPECT_EQ(run.Figure(name), 0.0) << name;
  }
  EXPECT_EQ(FieldValue(out, "AKPE"), 0.0);
  EXPECT_EQ(run.Messages->Warnings + run.Messages->Errors, 0);
}

TEST(KeyPointError, AShiftedCloudIsAsFarAsTheShift)
{
  // One cell for both clouds: the key points shift with the cloud, so every
  // pair is exactly d apart.
  const double d = 0.01;
  auto original = ToPolyData(Bump);
  auto shifted = ToPolyData(Shifted(Bump, 0, 0, d));
  ErrorRun run;
  run.Filter->SetCellSize(10.0);
  vtkPolyData* out = run.Execute(original, shifted);
  EXPECT_NEAR(run.Figure("AKPE"), d, 1e-12);
  EXPECT_NEAR(run.Figure("MKPE"), d, 1e-12);
  EXPECT_NEAR(run.Figure("AKPERelative"), d / 3.0, 1e-9); // diagonal sqrt(2^2 + 2^2 + 1^2)
  // Vertical shift of a surface of small slope: NN distances at most d.
  EXPECT_LE(run.Figure("HausdorffDistance"), d + 1e-12);
  EXPECT_GT(run.Figure("HausdorffDistance"), 0.5 * d);
  EXPECT_GT(run.Figure("PointToPlaneMean"), 0.5 * d);
  EXPECT_LE(run.Figure("PointToPlaneMax"), d + 1e-9);
  vtkDataArray* error = out->GetPointData()->GetArray("Error");
  ASSERT_NE(error, nullptr);
  EXPECT_NEAR(Median(error), d, 0.2 * d);
  // The paper's Eq. 3 as printed: squared distances.
  ErrorRun squared;
  squared.Filter->SetCellSize(10.0);
  squared.Filter->SetDistanceMeasure(vtkKeyPointError::SQUARED_DISTANCE);
  squared.Execute(original, shifted);
  EXPECT_NEAR(squared.Figure("AKPE"), d * d, 1e-14);
  // Divided by the squared diagonal (9), the same unit.
  EXPECT_NEAR(squared.Figure("AKPERelative"), d * d / 9.0, 1e-15);
  EXPECT_NEAR(squared.Figure("MKPERelative"), d * d / 9.0, 1e-15);
  // The Hausdorff distance is a distance in both: divided by the diagonal.
  EXPECT_EQ(squared.Figure("HausdorffDistance"), run.Figure("HausdorffDistance"));
  EXPECT_NEAR(
    squared.Figure("HausdorffDistanceRelative"), run.Figure("HausdorffDistance") / 3.0, 1e-15);
}

// The warning about unrelated clouds: given for boxes apart, not for a
// flat cloud whose simplification's centroids leave its plane by a rounding
// (z = 0.1 gave 0.10000000000000003).
TEST(KeyPointError, OnlyBoxesApartAreUnrelated)
{
  ErrorRun apart;
  apart.Execute(ToPolyData(Bump), ToPolyData(Shifted(Bump, 0, 0, 10.0)));
  EXPECT_EQ(apart.Messages->Warnings, 1);
  EXPECT_NE(apart.Messages->LastMessage.find("do not overlap"), std::string::npos)
    << apart.Messages->LastMessage;
  Cloud flat;
  std::mt19937_64 rng(0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 50; ++i)
  {
    Add(flat, unit(rng), unit(rng), 0.1);
  }
  Cloud off; // a simplification's centroids, a rounding above the plane
  Add(off, 0.3, 0.4, std::nextafter(0.1, 1.0));
  Add(off, 0.7, 0.6, std::nextafter(std::nextafter(0.1, 1.0), 1.0));
  // (The flat cloud has no key point: that warning, and no other.)
  const auto onlyNoKeyPoints = [](const MessageCounter* m) {
    EXPECT_EQ(m->Warnings, 1) << m->LastMessage;
    EXPECT_NE(m->LastMessage.find("no key point"), std::string::npos) << m->LastMessage;
  };
  ErrorRun near;
  near.Execute(ToPolyData(flat), ToPolyData(off));
  onlyNoKeyPoints(near.Messages);
  // Far from the origin (5e6, UTM-like, in double), clouds 4 apart along x
  // (the bump is 2 wide): unrelated too. Before 2026-11-29 the slack was
  // 1e-6 of the largest coordinate, 5, and no warning came.
  ErrorRun far;
  far.Execute(ToPolyData(Shifted(Bump, 5e6, 5e6, 0)), ToPolyData(Shifted(Bump, 5e6 + 6.0, 5e6, 0)));
  EXPECT_EQ(far.Messages->Warnings, 1) << far.Messages->LastMessage;
  // ... and a rounding above the plane there is still no warning.
  Cloud farOff;
  Add(farOff, 5e6 + 0.3, 5e6 + 0.4, std::nextafter(0.1, 1.0));
  ErrorRun farNear;
  farNear.Execute(ToPolyData(Shifted(flat, 5e6, 5e6, 0)), ToPolyData(farOff));
  onlyNoKeyPoints(farNear.Messages);
}

TEST(KeyPointError, AKPEIsTheMeanAndMKPETheLargest)
{
  // Two equal bumps in cells of their own (cell size 5, the grid from
  // x = -1): the simplified cloud lifts the first by d1 and the second by
  // d2, so half the key point pairs are d1 apart and half d2.
  const double d1 = 0.01, d2 = 0.03;
  Cloud original = Bump, simplified = Shifted(Bump, 0, 0, d1);
  const Cloud far = Shifted(Bump, 10.0, 0, 0), farLifted = Shifted(Bump, 10.0, 0, d2);
  original.insert(original.end(), far.begin(), far.end());
  simplified.insert(simplified.end(), farLifted.begin(), farLifted.end());
  ErrorRun run;
  run.Filter->SetCellSize(5.0);
  run.Execute(ToPolyData(original), ToPolyData(simplified));
  EXPECT_NEAR(run.Figure("AKPE"), 0.5 * (d1 + d2), 1e-12);
  EXPECT_NEAR(run.Figure("MKPE"), d2, 1e-12);
}

TEST(KeyPointError, HausdorffTakesTheLargerDirection)
{
  // The simplified cloud holds every original point and one more, 5 above
  // the apex (0, 0, 0): original -> simplified is 0 everywhere, simplified
  // -> original reaches 5, and the symmetric Hausdorff distance is 5.
  Cloud simplified = Bump;
  Add(simplified, 0.0, 0.0, 5.0);
  ErrorRun run;
  run.Execute(ToPolyData(Bump), ToPolyData(simplified));
  EXPECT_EQ(run.Figure("MaxDistanceOriginalToSimplified"), 0.0);
  EXPECT_NEAR(run.Figure("MaxDistanceSimplifiedToOriginal"), 5.0, 1e-12);
  EXPECT_NEAR(run.Figure("HausdorffDistance"), 5.0, 1e-12);
}

// Points flagged in vtkGhostType as another piece's (DUPLICATEPOINT) or
// hidden (HIDDENPOINT) are not measured, in either cloud, as vtkASMSimplify
// does not simplify them (before 2026-11-29 they were: a piece's ghost
// layer inflated the Hausdorff distance).
TEST(KeyPointError, GhostAndHiddenPointsAreNotMeasured)
{
  for (const int flag : { static_cast<int>(vtkDataSetAttributes::DUPLICATEPOINT),
         static_cast<int>(vtkDataSetAttributes::HIDDENPOINT) })
  {
    // Both clouds: the bump, then 10 flagged points 5 above it.
    Cloud withFar = Bump;
    for (int i = 0; i < 10; ++i)
    {
      Add(withFar, 0.01 * i, 0.0, 5.0);
    }
    const vtkIdType n = static_cast<vtkIdType>(Bump.size() / 3);
    vtkSmartPointer<vtkPolyData> clouds[2] = { ToPolyData(withFar), ToPolyData(withFar) };
    for (auto& cloud : clouds)
    {
      vtkNew<vtkUnsignedCharArray> ghosts;
      ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
      ghosts->SetNumberOfTuples(n + 10);
      for (vtkIdType i = 0; i < n + 10; ++i)
      {
        ghosts->SetValue(i, i < n ? 0 : flag);
      }
      cloud->GetPointData()->AddArray(ghosts);
    }
    // The original with its flagged points against the bump alone, then the
    // bump against the simplified cloud with its flagged points.
    for (int flagged = 0; flagged < 2; ++flagged)
    {
      ErrorRun run;
      vtkSmartPointer<vtkPolyData> bump = ToPolyData(Bump);
      vtkPolyData* out = flagged == 0 ? run.Execute(clouds[0], bump) : run.Execute(bump, clouds[1]);
      const std::string what =
        "flag " + std::to_string(flag) + (flagged == 0 ? ", original" : ", simplified");
      EXPECT_EQ(run.Messages->Errors + run.Messages->Warnings, 0) << what;
      EXPECT_EQ(run.Figure("NumberOfOriginalPoints"), static_cast<double>(n)) << what;
      EXPECT_EQ(run.Figure("NumberOfSimplifiedPoints"), static_cast<double>(n)) << what;
      EXPECT_EQ(run.Figure("HausdorffDistance"), 0.0) << what;
      EXPECT_EQ(run.Figure("AKPE"), 0.0) << what;
      if (flagged == 1)
      {
        vtkDataArray* error = out->GetPointData()->GetArray("Error");
        ASSERT_EQ(error->GetNumberOfTuples(), n + 10) << what;
        EXPECT_TRUE(std::isnan(error->GetTuple1(n))) << what;
        EXPECT_FALSE(std::isnan(error->GetTuple1(0))) << what;
      }
    }
  }
}

TEST(KeyPointError, MeasuresAnASMSimplification)
{
  auto bunny = ReadPLY("bunny.ply");
  FilterRun asmRun;
  vtkPolyData* simplified = asmRun.Execute(bunny);
  ErrorRun run;
  vtkPolyData* out = run.Execute(bunny, simplified);
  ASSERT_EQ(out->GetNumberOfPoints(), 1797);
  auto* table = vtkTable::SafeDownCast(run.Filter->GetOutputDataObject(1));
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(table->GetNumberOfRows(), 1);
  EXPECT_GE(table->GetNumberOfColumns(), 20);
  const double akpe = run.Figure("AKPE"), mkpe = run.Figure("MKPE");
  EXPECT_GT(akpe, 0.0);
  EXPECT_GE(mkpe, akpe);
  EXPECT_EQ(FieldValue(out, "MKPE"), mkpe);
  EXPECT_GE(run.Figure("HausdorffDistance"), run.Figure("MaxDistanceOriginalToSimplified"));
  EXPECT_GE(
    run.Figure("RMSDistanceOriginalToSimplified"), run.Figure("MeanDistanceOriginalToSimplified"));
  EXPECT_LE(run.Figure("PointToPlaneMean"), run.Figure("MeanDistanceOriginalToSimplified"));
  // Centroids of 20-point clusters lie close to the bunny's surface (about
  // 15 cm across): well under a millimetre on average.
  EXPECT_LT(run.Figure("PointToPlaneMean"), 1e-3);
  // The simplifier's own arrays are carried through, with the error.
  for (const char* name : { "KeyPoint", "ClusterSize", "Normals", "Error", "MeanCurvature" })
  {
    EXPECT_NE(out->GetPointData()->GetArray(name), nullptr) << name;
  }
  EXPECT_EQ(run.Messages->Warnings + run.Messages->Errors, 0);
}

// Every figure, the per-point Error and the curvature arrays are the same
// with one and two threads (its grids, trees and queries run through
// vtkSMPTools), on a cloud large enough for the parallel counting sorts to
// cut it into several blocks.
TEST(KeyPointError, SameFiguresAtOneAndTwoThreads)
{
  auto sphere = ToPolyData(Sphere(200000, 1.0, 3));
  FilterRun asmRun;
  asmRun.Filter->SetOutputFraction(0.05);
  asmRun.Filter->SetGenerateCurvature(false);
  vtkSmartPointer<vtkPolyData> simplified = asmRun.Execute(sphere);
  const std::vector<ThreadingRun> runs = RunForEachThreading([&]() {
    ErrorRun run;
    vtkPolyData* out = run.Execute(sphere, simplified);
    auto* table = vtkTable::SafeDownCast(run.Filter->GetOutputDataObject(1));
    std::vector<double> flat;
    EXPECT_NE(table, nullptr);
    for (vtkIdType c = 0; table && c < table->GetNumberOfColumns(); ++c)
    {
      flat.push_back(table->GetColumn(c)->GetVariantValue(0).ToDouble());
    }
    for (const char* name : { "Error", "MeanCurvature", "SurfaceVariation" })
    {
      vtkDataArray* a = out->GetPointData()->GetArray(name);
      EXPECT_NE(a, nullptr) << name;
      for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i)
      {
        flat.push_back(a->GetTuple1(i));
      }
    }
    return flat;
  });
  ASSERT_FALSE(runs.empty());
  ASSERT_GT(runs[0].Output.size(), 3 * 10000u);
  EXPECT_TRUE(SameOutputs(runs));
}

// On gridded data many simplified points are equally near an original one;
// which of them make its plane goes by position, not by their order in the
// simplified cloud (an MPI run gathers them in an order that depends on the
// process count). A stepped lattice against a sub-lattice, given in two
// orders: the per-original-point figures are the same bit for bit, the
// others up to their summation order. (With ties by index, the
// point-to-plane mean differed by 4e-4 of itself.)
TEST(KeyPointError, FiguresDoNotDependOnTheOrderOfTheSimplifiedPoints)
{
  const Cloud original =
    GridSurface(61, 3.0, [](double x, double y) { return 0.1 * std::floor(x + y); });
  Cloud simplified;
  for (std::size_t i = 0; i < 61; i += 2)
  {
    for (std::size_t j = 0; j < 61; j += 2)
    {
      const std::size_t p = 3 * (61 * i + j);
      Add(simplified, original[p], original[p + 1], original[p + 2]);
    }
  }
  std::vector<std::size_t> order(simplified.size() / 3);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::mt19937_64 rng(4);
  std::shuffle(order.begin(), order.end(), rng);
  Cloud shuffled;
  for (std::size_t i : order)
  {
    Add(shuffled, simplified[3 * i], simplified[3 * i + 1], simplified[3 * i + 2]);
  }
  auto cloud = ToPolyData(original);
  ErrorRun a, b;
  a.Execute(cloud, ToPolyData(simplified));
  b.Execute(cloud, ToPolyData(shuffled));
  auto* ta = vtkTable::SafeDownCast(a.Filter->GetOutputDataObject(1));
  auto* tb = vtkTable::SafeDownCast(b.Filter->GetOutputDataObject(1));
  ASSERT_NE(ta, nullptr);
  ASSERT_NE(tb, nullptr);
  ASSERT_EQ(ta->GetNumberOfColumns(), tb->GetNumberOfColumns());
  EXPECT_GT(a.Figure("PointToPlaneMean"), 1e-3) << "(the steps must show in the planes)";
  for (const char* name : { "PointToPlaneMean", "PointToPlaneMax", "PointToPlaneRMS" })
  {
    EXPECT_EQ(a.Figure(name), b.Figure(name)) << name;
  }
  for (vtkIdType c = 0; c < ta->GetNumberOfColumns(); ++c)
  {
    const double x = ta->GetColumn(c)->GetVariantValue(0).ToDouble();
    const double y = tb->GetColumn(c)->GetVariantValue(0).ToDouble();
    EXPECT_NEAR(x, y, 1e-12 * std::max(1.0, std::abs(x))) << ta->GetColumnName(c);
  }
}

TEST(KeyPointError, BadInputs)
{
  auto sphere = ToPolyData(Sphere(2000, 1.0));
  {
    ErrorRun run; // empty simplified cloud: a warning (as vtkASMSimplify's), empty outputs
    EXPECT_EQ(run.Execute(sphere, vtkNew<vtkPolyData>())->GetNumberOfPoints(), 0);
    EXPECT_EQ(run.Messages->Errors, 0);
    EXPECT_EQ(run.Messages->Warnings, 1);
    auto* table = vtkTable::SafeDownCast(run.Filter->GetOutputDataObject(1));
    ASSERT_NE(table, nullptr);
    EXPECT_EQ(table->GetNumberOfRows(), 0);
  }
  {
    ErrorRun run; // the inputs swapped: a warning, figures still computed
    auto small = ToPolyData(Sphere(100, 1.0, 9));
    run.Execute(small, sphere);
    // (and one more: the 100 points in cells sized for 2000 hold no key point)
    EXPECT_EQ(run.Messages->Warnings, 2);
    EXPECT_EQ(run.Figure("NumberOfOriginalKeyPoints"), 0.0);
    EXPECT_GT(run.Figure("HausdorffDistance"), 0.0);
  }
  {
    ErrorRun run; // disjoint clouds: a warning, and the distance between them
    auto far = ToPolyData(Sphere(200, 1.0, 3, 100, 0, 0));
    run.Execute(sphere, far);
    EXPECT_EQ(run.Messages->Warnings, 1);
    EXPECT_GT(run.Figure("MeanDistanceSimplifiedToOriginal"), 97.0);
  }
  {
    ErrorRun run; // NaN points (the first and the last): skipped, their error is NaN
    Cloud c;
    Add(c, 0, std::nan(""), 0);
    const Cloud s = Sphere(200, 1.0, 5);
    c.insert(c.end(), s.begin(), s.end());
    Add(c, std::nan(""), 0, 0);
    vtkPolyData* out = run.Execute(sphere, ToPolyData(c));
    EXPECT_EQ(run.Messages->Warnings, 1);
    ASSERT_EQ(out->GetNumberOfPoints(), 202);
    vtkDataArray* error = out->GetPointData()->GetArray("Error");
    vtkDataArray* curvature = out->GetPointData()->GetArray("MeanCurvature");
    ASSERT_NE(curvature, nullptr);
    for (vtkIdType i = 0; i < 202; ++i)
    {
      const bool skipped = i == 0 || i == 201;
      EXPECT_EQ(std::isnan(error->GetTuple1(i)), skipped) << i;
      EXPECT_EQ(std::isnan(curvature->GetTuple1(i)), skipped) << i;
    }
    EXPECT_EQ(run.Figure("NumberOfSimplifiedPoints"), 200.0);
  }
  // A NaN parameter (the clamped setters let NaN through): an error naming
  // it and an empty output.
  using Setter = void (vtkKeyPointError::*)(double);
  const std::pair<const char*, Setter> parameters[] = { { "Alpha", &vtkKeyPointError::SetAlpha },
    { "CellSize", &vtkKeyPointError::SetCellSize },
    { "SamplesPerCell", &vtkKeyPointError::SetSamplesPerCell } };
  for (const auto& [name, set] : parameters)
  {
    ErrorRun run;
    (run.Filter.GetPointer()->*set)(std::nan(""));
    EXPECT_EQ(run.Execute(sphere, ToPolyData(Sphere(200, 1.0, 5)))->GetNumberOfPoints(), 0);
    EXPECT_EQ(run.Messages->Errors, 1) << name;
    EXPECT_NE(run.Messages->LastMessage.find(name), std::string::npos) << run.Messages->LastMessage;
  }
  // Float values in a double array: the figures of the float array (the
  // same key point rule: the coordinates' precision is a float's).
  const Cloud box = TurnedBox(20000);
  vtkSmartPointer<vtkPolyData> floats = ToPolyData(box, VTK_FLOAT);
  vtkSmartPointer<vtkPolyData> doubles = FloatsInDoubles(box);
  auto reduced = ToPolyData(Cloud(box.begin(), box.begin() + 3 * 1000));
  ErrorRun fromFloats, fromDoubles;
  fromFloats.Execute(floats, reduced);
  fromDoubles.Execute(doubles, reduced);
  EXPECT_EQ(fromFloats.Figure("NumberOfOriginalKeyPoints"),
    fromDoubles.Figure("NumberOfOriginalKeyPoints"));
  EXPECT_EQ(fromFloats.Figure("MKPE"), fromDoubles.Figure("MKPE"));
}

TEST(Curvature, ASMOutputOnASphereHasMeanCurvatureOneOverR)
{
  for (double r : { 0.5, 2.0 })
  {
    FilterRun run;
    run.Filter->SetOutputFraction(0.1);
    vtkPolyData* out = run.Execute(ToPolyData(Sphere(20000, r, 2)));
    vtkDataArray* h = out->GetPointData()->GetArray("MeanCurvature");
    ASSERT_NE(h, nullptr);
    EXPECT_NEAR(Median(h), 1.0 / r, 0.05 / r) << "outward normals: positive";
    EXPECT_EQ(out->GetPointData()->GetScalars(), h);
    ASSERT_NE(out->GetPointData()->GetArray("NeighborhoodSurfaceVariation"), nullptr);
  }
  // Off: no curvature arrays; the sample's cell's surface variation is the
  // active scalars instead.
  FilterRun off;
  off.Filter->GenerateCurvatureOff();
  vtkPolyData* out = off.Execute(ToPolyData(Sphere(2000, 1.0)));
  EXPECT_EQ(out->GetPointData()->GetArray("MeanCurvature"), nullptr);
  ASSERT_NE(out->GetPointData()->GetScalars(), nullptr);
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "SurfaceVariation");
}

TEST(Curvature, KeyPointErrorCurvatureFollowsTheSimplifiedNormals)
{
  // The simplified cloud's normals sign its mean curvature: outward on a
  // sphere of radius 2, +1/2; the same points with inward normals, -1/2;
  // without normals, away from the original's centroid: +1/2.
  auto sphere = ToPolyData(Sphere(20000, 2.0, 3));
  FilterRun simplify;
  simplify.Filter->SetOutputFraction(0.05);
  vtkPolyData* simplified = simplify.Execute(sphere);
  vtkDataArray* normals = simplified->GetPointData()->GetNormals();
  ASSERT_NE(normals, nullptr);
  vtkNew<vtkDoubleArray> inward;
  inward->SetName("Normals");
  inward->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    const double* v = normals->GetTuple3(i);
    inward->InsertNextTuple3(-v[0], -v[1], -v[2]);
  }
  for (int orientation : { 1, -1, 0 })
  {
    vtkNew<vtkPolyData> copy;
    copy->ShallowCopy(simplified);
    vtkNew<vtkPointData> pd;
    if (orientation != 0)
    {
      pd->SetNormals(orientation > 0 ? normals : static_cast<vtkDataArray*>(inward));
    }
    copy->GetPointData()->ShallowCopy(pd);
    ErrorRun error;
    vtkPolyData* measured = error.Execute(sphere, copy);
    vtkDataArray* h = measured->GetPointData()->GetArray("MeanCurvature");
    ASSERT_NE(h, nullptr);
    const double expected = orientation < 0 ? -0.5 : 0.5;
    EXPECT_NEAR(Median(h), expected, 0.025) << "orientation " << orientation;
    for (vtkIdType i = 0; i < h->GetNumberOfTuples(); ++i)
    {
      ASSERT_GT(h->GetTuple1(i) * expected, 0.0) << "orientation " << orientation << ", " << i;
    }
  }
}

TEST(Curvature, PlaneHasZeroMeanCurvatureInBothFilters)
{
  auto plane =
    ToPolyData(GridSurface(100, 1.0, [](double x, double y) { return 0.2 * x - 0.1 * y; }));
  FilterRun run;
  vtkPolyData* out = run.Execute(plane);
  vtkDataArray* h = out->GetPointData()->GetArray("MeanCurvature");
  ASSERT_NE(h, nullptr);
  for (vtkIdType i = 0; i < h->GetNumberOfTuples(); ++i)
  {
    EXPECT_NEAR(h->GetTuple1(i), 0.0, 1e-6);
  }
  ErrorRun error;
  vtkPolyData* measured = error.Execute(plane, out);
  vtkDataArray* he = measured->GetPointData()->GetArray("MeanCurvature");
  ASSERT_NE(he, nullptr);
  EXPECT_NEAR(Median(he), 0.0, 1e-6);
}
