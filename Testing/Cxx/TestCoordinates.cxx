// SPDX-License-Identifier: BSD-3-Clause
// Messy coordinates (README "Messy data"): georeferenced float clouds far
// from the origin, float values in double arrays and double relief below a
// float's rounding, integer and split (SOA) arrays, squares that overflow.
// The same output for the same values, whatever array holds them, and each
// array's own precision.
#include "FeatureShapes.h"
#include "FilterHelpers.h"

#include "vtkASMSimplify.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkKeyPointError.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSOADataArrayTemplate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using asmtest::Cloud;
using asmtest::ExpectAllFinite;
using asmtest::FieldValue;
using asmtest::FilterRun;
using asmtest::SphereDeviation;
using asmtest::ToPolyData;

// Double coordinates keep a double's precision: a relief far below a float's
// rounding at their magnitude (1e-3 at 1e5) still gives key points.
TEST(HostileInputs, DoubleCoordinatesKeepReliefBelowAFloatsRounding)
{
  Cloud c;
  for (int i = 0; i < 40; ++i)
  {
    for (int j = 0; j < 40; ++j)
    {
      const double bump = i == 20 && j == 20 ? 1e-3 : 0.0;
      asmtest::Add(c, 1e5 + i, 1e5 + j, 1e5 + bump);
    }
  }
  FilterRun run;
  run.Filter->SetModeToPaper();
  run.Count(160);
  vtkPolyData* out = run.Execute(ToPolyData(c));
  ASSERT_EQ(out->GetNumberOfPoints(), 160);
  EXPECT_GE(FieldValue(out, "NumberOfKeyPoints"), 1.0);
  FilterRun flat; // the same without the bump: an exact plane, no key points
  flat.Filter->SetModeToPaper();
  flat.Count(160);
  c[3 * (20 * 40 + 20) + 2] = 1e5;
  EXPECT_EQ(FieldValue(flat.Execute(ToPolyData(c)), "NumberOfKeyPoints"), 0.0);
}

TEST(HostileInputs, GeoreferencedFloatCloudFarFromTheOrigin)
{
  // A 500 m sphere 1e7 m from the origin, in float (UTM-like): coordinates
  // are rounded to 1 m there. The result must be as sensible as at the
  // origin: exact count, points and key points on the surface (within the
  // input's rounding), key points still found, no loss of precision beyond
  // the input's own.
  const double radius = 500.0;
  const double far[3] = { 1.0e7, 1.0e7, 100.0 };
  const double origin[3] = { 0, 0, 0 };
  const Cloud atOrigin = asmtest::Sphere(50000, radius, 21);
  Cloud shifted = atOrigin;
  for (std::size_t i = 0; i < shifted.size(); ++i)
  {
    shifted[i] += far[i % 3];
  }
  FilterRun reference;
  reference.Count(1000);
  vtkPolyData* ref = reference.Execute(ToPolyData(atOrigin, VTK_FLOAT));
  const double referenceKeys = FieldValue(ref, "NumberOfKeyPoints");

  FilterRun run;
  run.Count(1000);
  vtkPolyData* out = run.Execute(ToPolyData(shifted, VTK_FLOAT));
  ASSERT_EQ(out->GetNumberOfPoints(), 1000);
  ExpectAllFinite(out);
  EXPECT_EQ(out->GetPoints()->GetDataType(), VTK_FLOAT);
  // The centroids' sagitta at the origin; far away, + 1 m input rounding
  // + 1 m output rounding.
  const double sagitta = SphereDeviation(ref, origin, radius, false);
  EXPECT_LT(sagitta, 5.0);
  EXPECT_LT(SphereDeviation(out, far, radius, false), sagitta + 2.0);
  EXPECT_LT(SphereDeviation(out, far, radius, true), sagitta + 2.0);
  // (A smooth sphere: at the origin the default mode finds no key points
  // (since FeatureSamplesPerCell 4 and VariationBudget), and far away the
  // 1 m rounding must not take them away where there are some.)
  EXPECT_GE(FieldValue(out, "NumberOfKeyPoints"), 0.5 * referenceKeys);
  EXPECT_LT(FieldValue(out, "MKPE"), 0.1 * radius);
  EXPECT_NEAR(
    FieldValue(out, "CellSize"), FieldValue(ref, "CellSize"), 0.25 * FieldValue(ref, "CellSize"));

  // Double output points keep the computed positions (no float rounding).
  FilterRun precise;
  precise.Count(1000);
  precise.Filter->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  vtkPolyData* fine = precise.Execute(ToPolyData(shifted, VTK_FLOAT));
  EXPECT_EQ(fine->GetPoints()->GetDataType(), VTK_DOUBLE);
  EXPECT_LT(SphereDeviation(fine, far, radius, false), sagitta + 1.0);
}

// Float coordinates in a double array (an upstream filter that converts its
// points, such as vtkRedistributeDataSetFilter, gives them) carry a float's
// rounding: the same output as the float array, so flat faces rounded to
// float get no key points either way.
TEST(HostileInputs, FloatValuesInADoubleArrayGiveTheFloatResult)
{
  // A box, turned so that its flat faces' float rounding is off the plane,
  // and a few NaN points; as floats, and as those floats in a double array.
  asmtest::Cloud c = asmtest::TurnedBox(20000);
  for (int i = 0; i < 5; ++i)
  {
    asmtest::Add(c, std::nan(""), 0.0, 0.0);
  }
  vtkSmartPointer<vtkPolyData> floats = ToPolyData(c, VTK_FLOAT);
  vtkSmartPointer<vtkPolyData> doubles = asmtest::FloatsInDoubles(c);
  ASSERT_NE(doubles->GetPoint(1)[0], c[3]) << "rounded to float";
  for (const int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    vtkSmartPointer<vtkPolyData> outputs[2];
    for (vtkPolyData* input : { floats.GetPointer(), doubles.GetPointer() })
    {
      FilterRun run;
      run.Filter->SetMode(mode);
      run.Filter->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
      run.Count(1000);
      vtkSmartPointer<vtkPolyData>& out = outputs[input == doubles.GetPointer()];
      out = vtkSmartPointer<vtkPolyData>::New();
      out->ShallowCopy(run.Execute(input));
    }
    ASSERT_EQ(outputs[0]->GetNumberOfPoints(), 1000);
    EXPECT_TRUE(asmtest::SamePoints(outputs[0], outputs[1])) << "mode " << mode;
    EXPECT_EQ(
      FieldValue(outputs[0], "NumberOfKeyPoints"), FieldValue(outputs[1], "NumberOfKeyPoints"))
      << "mode " << mode;
  }
}

namespace
{
// A unit sphere of n points, every coordinate times `scale`.
Cloud SphereTimes(std::size_t n, double scale)
{
  Cloud c = asmtest::Sphere(n, 1.0, 5);
  for (double& v : c)
  {
    v *= scale;
  }
  return c;
}

// A sphere of radius 2^k (a power of two: the scaled coordinates are exact).
vtkSmartPointer<vtkPolyData> ScaledSphere(int k)
{
  Cloud c = asmtest::Sphere(3000, 1.0, 5);
  for (double& v : c)
  {
    v = std::ldexp(v, k);
  }
  return ToPolyData(c);
}
} // namespace

// Clouds scaled by a power of two within asmcore::CoordinateRange: the
// default mode's output is the unscaled one's, scaled, bit for bit
// (coordinates, key points, curvature); the paper mode's random choices
// hash the coordinates' bits, so it gets another draw of the same quality.
// The key point error's figures scale with the cloud.
TEST(HostileInputs, PowerOfTwoScalingsGiveTheScaledOutput)
{
  const auto one = ScaledSphere(0);
  for (const bool paper : { false, true })
  {
    FilterRun reference;
    reference.Count(150);
    if (paper)
    {
      reference.Filter->SetModeToPaper();
    }
    vtkPolyData* expected = reference.Execute(one);
    const double keys = FieldValue(expected, "NumberOfKeyPoints");
    ASSERT_GT(keys, 0);
    vtkNew<vtkKeyPointError> referenceError;
    referenceError->SetInputData(0, one);
    referenceError->SetInputData(1, expected);
    referenceError->Update();
    const double mkpe = FieldValue(referenceError->GetOutput(), "MKPERelative");
    const double planeMean = FieldValue(referenceError->GetOutput(), "PointToPlaneMeanRelative");
    for (const int k : { -330, -100, 100, 330 }) // 2^330 = 2.2e99
    {
      SCOPED_TRACE((paper ? "paper, k = " : "default, k = ") + std::to_string(k));
      FilterRun run;
      run.Count(150);
      if (paper)
      {
        run.Filter->SetModeToPaper();
      }
      const auto scaled = ScaledSphere(k);
      vtkPolyData* out = run.Execute(scaled);
      ASSERT_EQ(out->GetNumberOfPoints(), 150);
      EXPECT_EQ(run.Messages->Errors + run.Messages->Warnings, 0);
      auto* h = out->GetPointData()->GetArray("MeanCurvature");
      auto* hExpected = expected->GetPointData()->GetArray("MeanCurvature");
      auto* key = out->GetPointData()->GetArray("KeyPoint");
      auto* keyExpected = expected->GetPointData()->GetArray("KeyPoint");
      const double centre[3] = { 0, 0, 0 };
      if (!paper)
      {
        for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
        {
          double p[3], q[3];
          out->GetPoint(i, p);
          expected->GetPoint(i, q);
          for (int a = 0; a < 3; ++a)
          {
            ASSERT_EQ(p[a], std::ldexp(q[a], k)) << i;
          }
          ASSERT_EQ(h->GetTuple1(i), std::ldexp(hExpected->GetTuple1(i), -k)) << i;
          ASSERT_EQ(key->GetTuple1(i), keyExpected->GetTuple1(i)) << i;
        }
      }
      else
      {
        EXPECT_GT(FieldValue(out, "NumberOfKeyPoints"), keys / 2);
        EXPECT_LT(std::ldexp(SphereDeviation(out, centre, std::ldexp(1.0, k), false), -k), 0.05);
        for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
        {
          ASSERT_NEAR(std::ldexp(h->GetTuple1(i), k), 1.0, 0.05) << i;
        }
      }
      vtkNew<vtkKeyPointError> error;
      error->SetInputData(0, scaled);
      error->SetInputData(1, out);
      error->Update();
      vtkPolyData* measured = error->GetOutput();
      ASSERT_EQ(measured->GetNumberOfPoints(), 150);
      const double tolerance = paper ? 0.5 : 1e-12;
      EXPECT_NEAR(FieldValue(measured, "MKPERelative"), mkpe, tolerance * mkpe);
      EXPECT_NEAR(
        FieldValue(measured, "PointToPlaneMeanRelative"), planeMean, tolerance * planeMean);
      EXPECT_NEAR(FieldValue(measured, "BoundingBoxDiagonal"),
        std::ldexp(FieldValue(referenceError->GetOutput(), "BoundingBoxDiagonal"), k),
        std::ldexp(1e-12, k));
    }
  }
}

// Beyond asmcore::CoordinateRange the squared distances overflow or
// underflow (a sphere of radius 1e160 gave no key points and NaN
// curvatures, one at +-8e307 non-finite points in the paper mode): both
// filters say so and output nothing, whichever port holds the cloud.
TEST(HostileInputs, CoordinatesBeyondTheSquaresRangeAreAnError)
{
  for (const double scale : { 8e307, 1e160, 2e100, 5e-101, 1e-200, 1e-310 })
  {
    SCOPED_TRACE(scale);
    const Cloud c = SphereTimes(3000, scale);
    const auto far = ToPolyData(c);
    for (const bool paper : { false, true })
    {
      FilterRun run;
      run.Count(150);
      if (paper)
      {
        run.Filter->SetModeToPaper();
      }
      EXPECT_EQ(run.Execute(far)->GetNumberOfPoints(), 0);
      EXPECT_EQ(run.Messages->Errors, 1);
      EXPECT_NE(run.Messages->LastMessage.find("within [1e-100, 1e100]"), std::string::npos)
        << run.Messages->LastMessage;
    }
    // The key point error, with the out-of-range cloud on either port.
    Cloud unit = asmtest::Sphere(300, 1.0, 5);
    const auto near = ToPolyData(unit);
    for (const int port : { 0, 1 })
    {
      asmtest::ObservedFilter<vtkKeyPointError> error;
      error.Filter->SetInputData(port, far);
      error.Filter->SetInputData(1 - port, near);
      error.Filter->Update();
      EXPECT_EQ(error.Filter->GetOutput()->GetNumberOfPoints(), 0);
      EXPECT_EQ(error.Messages->Errors, 1);
      EXPECT_NE(
        error.Messages->LastMessage.find(port == 0 ? "original (port 0)" : "simplified (port 1)"),
        std::string::npos)
        << error.Messages->LastMessage;
    }
  }
  // At the origin, and at the range's ends: in range.
  for (const double scale : { 0.0, 9e99 / std::sqrt(3.0), 1.01e-100 })
  {
    SCOPED_TRACE(scale);
    const Cloud c = SphereTimes(3000, scale);
    FilterRun run;
    run.Count(150);
    EXPECT_EQ(run.Execute(ToPolyData(c))->GetNumberOfPoints(), 150);
    EXPECT_EQ(run.Messages->Errors, 0);
  }
}

// Single-precision output of double coordinates beyond a float's normal
// range: double points and a warning (they were all infinite at 1e50, all
// zero at 1e-60); within it, floats as asked.
TEST(HostileInputs, SinglePrecisionOutputBeyondAFloatsRangeStaysDouble)
{
  for (const double scale : { 1e50, 1e-60, 1.0 })
  {
    SCOPED_TRACE(scale);
    const Cloud c = SphereTimes(2000, scale);
    FilterRun run;
    run.Count(100);
    run.Filter->SetOutputPointsPrecision(vtkAlgorithm::SINGLE_PRECISION);
    vtkPolyData* out = run.Execute(ToPolyData(c));
    ASSERT_EQ(out->GetNumberOfPoints(), 100);
    const bool beyond = scale != 1.0;
    EXPECT_EQ(out->GetPoints()->GetDataType(), beyond ? VTK_DOUBLE : VTK_FLOAT);
    EXPECT_EQ(run.Messages->Warnings, beyond ? 1 : 0) << run.Messages->LastMessage;
    const double centre[3] = { 0, 0, 0 };
    EXPECT_LT(SphereDeviation(out, centre, scale, false) / scale, 0.05);
  }
}

// Points held as integers or in a split (structure-of-arrays) layout are
// converted to doubles block by block: the same output as the same
// coordinates in an ordinary double array (more points than one block).
TEST(HostileInputs, IntegerAndSplitPointArraysGiveTheDoubleResult)
{
  const Cloud c = asmtest::Sphere(100000, 1000.0, 5); // radius 1000: integers keep the shape
  const vtkIdType n = static_cast<vtkIdType>(c.size() / 3);
  vtkNew<vtkDoubleArray> doubles;
  vtkNew<vtkIntArray> integers;
  vtkNew<vtkSOADataArrayTemplate<double>> split;
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(doubles),
         static_cast<vtkDataArray*>(integers), static_cast<vtkDataArray*>(split) })
  {
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(n);
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double rounded[3] = { std::round(c[3 * i]), std::round(c[3 * i + 1]),
      std::round(c[3 * i + 2]) };
    doubles->SetTuple(i, rounded);
    integers->SetTuple(i, rounded);
    split->SetTuple(i, rounded);
  }
  auto simplified = [&](vtkDataArray* coordinates) {
    vtkNew<vtkPoints> points;
    points->SetData(coordinates);
    vtkNew<vtkPolyData> input;
    input->SetPoints(points);
    FilterRun run;
    run.Filter->SetOutputFraction(0.05);
    run.Filter->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
    vtkPolyData* out = run.Execute(input);
    std::vector<double> xyz(static_cast<std::size_t>(3 * out->GetNumberOfPoints()));
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      out->GetPoint(i, xyz.data() + 3 * i);
    }
    return xyz;
  };
  const std::vector<double> reference = simplified(doubles);
  ASSERT_EQ(reference.size(), 3u * 5000u);
  EXPECT_EQ(simplified(integers), reference);
  EXPECT_EQ(simplified(split), reference);
}
