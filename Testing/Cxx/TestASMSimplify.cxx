// SPDX-License-Identifier: BSD-3-Clause
// Tests of the vtkASMSimplify filter: counts, arrays, threads, progress,
// abort, real scans.
#include "vtkASMSimplify.h"

#include "FilterHelpers.h"

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

using namespace asmtest;

//------------------------------------------------------------------------------
TEST(ASMSimplify, ExactCountOnRealScans)
{
  for (const char* name : { "bunny.ply", "fandisk.ply", "kitten.ply", "laurana.ply" })
  {
    auto input = ReadPLY(name);
    const vtkIdType n = input->GetNumberOfPoints();
    ASSERT_GT(n, 0) << name;
    for (double fraction : { 0.001, 0.01, 0.05, 0.2, 0.5, 0.9 })
    {
      FilterRun run;
      run.Filter->SetOutputFraction(fraction);
      vtkPolyData* out = run.Execute(input);
      EXPECT_EQ(out->GetNumberOfPoints(), std::llround(fraction * n)) << name << " " << fraction;
      EXPECT_TRUE(OneVertexPerPoint(out));
      EXPECT_EQ(run.Messages->Warnings + run.Messages->Errors, 0);
    }
    for (vtkIdType target : { vtkIdType(1), vtkIdType(2), vtkIdType(17), vtkIdType(1000), n - 1 })
    {
      FilterRun run;
      run.Filter->SetTargetModeToNumberOfOutputPoints();
      run.Filter->SetNumberOfOutputPoints(target);
      EXPECT_EQ(run.Execute(input)->GetNumberOfPoints(), target) << name << " " << target;
    }
  }
}

TEST(ASMSimplify, BunnyAtFivePercentWithArraysAndFieldData)
{
  auto input = ReadPLY("bunny.ply");
  FilterRun run;
  run.Filter->SetModeToPaper(); // key points are band centroids: AKPE > 0
  vtkPolyData* out = run.Execute(input);
  ASSERT_EQ(out->GetNumberOfPoints(), 1797); // round(0.05 * 35947)
  vtkPointData* pd = out->GetPointData();
  for (const char* name :
    { "Normals", "KeyPoint", "ClusterSize", "SurfaceVariation", "vtkOriginalPointIds" })
  {
    ASSERT_NE(pd->GetArray(name), nullptr) << name;
    EXPECT_EQ(pd->GetArray(name)->GetNumberOfTuples(), 1797) << name;
  }
  EXPECT_EQ(pd->GetNormals(), pd->GetArray("Normals"));
  // Clusters partition (part of) the input: sizes add up to at most N.
  auto* sizes = vtkIdTypeArray::SafeDownCast(pd->GetArray("ClusterSize"));
  vtkIdType total = 0, keys = 0;
  auto* key = vtkUnsignedCharArray::SafeDownCast(pd->GetArray("KeyPoint"));
  for (vtkIdType i = 0; i < 1797; ++i)
  {
    EXPECT_GE(sizes->GetValue(i), 1);
    total += sizes->GetValue(i);
    keys += key->GetValue(i);
    const double sv = pd->GetArray("SurfaceVariation")->GetTuple1(i);
    EXPECT_GE(sv, 0.0);
    EXPECT_LE(sv, 1.0 / 3.0 + 1e-12);
  }
  EXPECT_LE(total, 35947);
  EXPECT_GT(total, 35947 / 2);
  EXPECT_GT(keys, 0);
  EXPECT_EQ(keys, static_cast<vtkIdType>(FieldValue(out, "NumberOfKeyPoints")));
  const double akpe = FieldValue(out, "AKPE"), mkpe = FieldValue(out, "MKPE");
  EXPECT_GT(akpe, 0.0);
  EXPECT_GE(mkpe, akpe);
  EXPECT_GT(FieldValue(out, "CellSize"), 0.0);
  EXPECT_EQ(FieldValue(out, "NumberOfSkippedPoints"), 0.0);
  // Float input, float output by default; double on request.
  EXPECT_EQ(out->GetPoints()->GetDataType(), VTK_FLOAT);
  run.Filter->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  run.Filter->Update();
  EXPECT_EQ(run.Filter->GetOutput()->GetPoints()->GetDataType(), VTK_DOUBLE);
}

TEST(ASMSimplify, ErrorToleranceBoundsMKPEOnTheBunny)
{
  // The paper mode: its key points are key cluster centroids, with an error
  // to bound (the default mode puts them on their extreme points: MKPE 0).
  auto input = ReadPLY("bunny.ply");
  auto paper = [](FilterRun& run) { run.Filter->SetMode(vtkASMSimplify::PAPER); };
  FilterRun loose;
  paper(loose);
  const double mkpe = FieldValue(loose.Execute(input), "MKPE");
  ASSERT_GT(mkpe, 0.0);
  for (double factor : { 0.5, 0.1 })
  {
    FilterRun bounded;
    paper(bounded);
    bounded.Filter->SetErrorTolerance(factor * mkpe);
    vtkPolyData* out = bounded.Execute(input);
    EXPECT_EQ(out->GetNumberOfPoints(), 1797);
    EXPECT_LE(FieldValue(out, "MKPE"), factor * mkpe);
  }
  // The bound holds for snapped key points too.
  FilterRun snapped;
  paper(snapped);
  snapped.Filter->SnapToInputPointsOn();
  snapped.Filter->SetErrorTolerance(0.2 * mkpe);
  EXPECT_LE(FieldValue(snapped.Execute(input), "MKPE"), 0.2 * mkpe);
  // Relative to the bounding-box diagonal: the same as the absolute bound
  // e * diagonal, and not the same as e itself.
  double b[6];
  input->GetBounds(b);
  const double diagonal = std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  const double e = 0.01;
  auto boundedMKPE = [&](double tolerance, bool relativeToDiagonal) {
    FilterRun run;
    paper(run);
    run.Filter->SetErrorTolerance(tolerance);
    run.Filter->SetRelativeErrorTolerance(relativeToDiagonal);
    return FieldValue(run.Execute(input), "MKPE");
  };
  const double relative = boundedMKPE(e, true);
  EXPECT_LE(relative, e * diagonal * (1 + 1e-6));
  EXPECT_NEAR(relative, boundedMKPE(e * diagonal, false), 1e-9 * mkpe);
  EXPECT_NE(relative, boundedMKPE(e, false));
}

TEST(ASMSimplify, AveragesInputArraysOverClusters)
{
  // Arrays equal to functions of the coordinates: their cluster means are
  // known from the output point (the cluster centroid).
  Cloud c = asmtest::Sphere(6000, 1.0, 3);
  auto input = ToPolyData(c);
  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> xyz;
  xyz->SetName("Position");
  xyz->SetNumberOfComponents(3);
  xyz->SetComponentName(0, "X");
  vtkNew<vtkIntArray> constant;
  constant->SetName("Label");
  vtkNew<vtkFloatArray> normals;
  normals->SetName("InputNormals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkStringArray> names;
  names->SetName("Name");
  vtkNew<vtkUnsignedCharArray> unnamed;
  unnamed->SetNumberOfComponents(2);
  for (vtkIdType i = 0; i < n; ++i)
  {
    xyz->InsertNextTuple(c.data() + 3 * i);
    constant->InsertNextValue(7);
    normals->InsertNextTuple(c.data() + 3 * i); // unit sphere: normal = position
    names->InsertNextValue("p" + std::to_string(i));
    unnamed->InsertNextTuple2(i % 2 ? 10 : 20, 3);
  }
  input->GetPointData()->AddArray(xyz);
  input->GetPointData()->AddArray(constant);
  input->GetPointData()->SetNormals(normals);
  input->GetPointData()->AddArray(names);
  input->GetPointData()->AddArray(unnamed);

  FilterRun run;
  run.Filter->SetModeToPaper(); // samples are cluster centroids (see TestFeaturePreserving)
  run.Filter->SetOutputFraction(0.1);
  vtkPolyData* out = run.Execute(input);
  ASSERT_EQ(out->GetNumberOfPoints(), 600);
  vtkPointData* pd = out->GetPointData();
  auto* position = vtkDoubleArray::SafeDownCast(pd->GetArray("Position"));
  ASSERT_NE(position, nullptr);
  EXPECT_STREQ(position->GetComponentName(0), "X");
  auto* label = vtkIntArray::SafeDownCast(pd->GetArray("Label"));
  ASSERT_NE(label, nullptr);
  auto* outNormals = vtkFloatArray::SafeDownCast(pd->GetArray("InputNormals"));
  ASSERT_NE(outNormals, nullptr);
  EXPECT_EQ(pd->GetNormals(), outNormals) << "the input's normals stay the active normals";
  auto* pca = pd->GetArray("Normals");
  ASSERT_NE(pca, nullptr);
  auto* outNames = vtkStringArray::SafeDownCast(pd->GetAbstractArray("Name"));
  ASSERT_NE(outNames, nullptr);
  auto* ids = vtkIdTypeArray::SafeDownCast(pd->GetArray("vtkOriginalPointIds"));
  ASSERT_NE(ids, nullptr);
  bool foundUnnamed = false;
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    foundUnnamed |= pd->GetArray(a) && !pd->GetArray(a)->GetName() &&
      pd->GetArray(a)->GetNumberOfComponents() == 2;
  }
  EXPECT_TRUE(foundUnnamed) << "unnamed arrays are carried too";
  for (vtkIdType i = 0; i < 600; ++i)
  {
    double p[3], mean[3], nrm[3], pcaN[3];
    out->GetPoint(i, p);
    position->GetTuple(i, mean);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(mean[a], p[a], 1e-12);
    }
    EXPECT_EQ(label->GetValue(i), 7);
    outNormals->GetTuple(i, nrm);
    EXPECT_NEAR(std::hypot(nrm[0], nrm[1], nrm[2]), 1.0, 1e-6)
      << "averaged normals are renormalised";
    pca->GetTuple(i, pcaN);
    EXPECT_GT(pcaN[0] * nrm[0] + pcaN[1] * nrm[1] + pcaN[2] * nrm[2], 0.0)
      << "PCA normals agree with the input normals";
    // The representative's string.
    EXPECT_EQ(outNames->GetValue(i), "p" + std::to_string(ids->GetValue(i)));
  }
}

TEST(ASMSimplify, SnapToInputPointsKeepsMeasuredPoints)
{
  auto input = ReadPLY("laurana.ply"); // with RGB colours
  FilterRun run;
  run.Filter->SnapToInputPointsOn();
  vtkPolyData* out = run.Execute(input);
  ASSERT_EQ(out->GetNumberOfPoints(), std::llround(0.05 * input->GetNumberOfPoints()));
  auto* ids = vtkIdTypeArray::SafeDownCast(out->GetPointData()->GetArray("vtkOriginalPointIds"));
  ASSERT_NE(ids, nullptr);
  vtkDataArray* inColors = input->GetPointData()->GetScalars();
  ASSERT_NE(inColors, nullptr);
  vtkDataArray* outColors = out->GetPointData()->GetArray(inColors->GetName());
  ASSERT_NE(outColors, nullptr);
  std::set<vtkIdType> distinct;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const vtkIdType id = ids->GetValue(i);
    distinct.insert(id);
    double p[3], q[3];
    out->GetPoint(i, p);
    input->GetPoint(id, q);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(p[a], q[a]);
      EXPECT_EQ(outColors->GetComponent(i, a), inColors->GetComponent(id, a));
    }
  }
  EXPECT_EQ(static_cast<vtkIdType>(distinct.size()), out->GetNumberOfPoints());
}

TEST(ASMSimplify, SameOutputAtOneAndTwoThreads)
{
  auto input = ReadPLY("bunny.ply");
  const std::vector<ThreadingRun> runs = RunForEachThreading([&]() {
    FilterRun run;
    run.Filter->SetOutputFraction(0.05);
    run.Filter->SetErrorTolerance(1e-4);
    run.Filter->SetMinimumPointsForThreads(0); // the bunny is small: threads anyway
    vtkPolyData* out = run.Execute(input);
    std::vector<double> flat;
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      double p[3];
      out->GetPoint(i, p);
      flat.insert(flat.end(), p, p + 3);
      flat.push_back(out->GetPointData()->GetArray("vtkOriginalPointIds")->GetTuple1(i));
      flat.push_back(out->GetPointData()->GetArray("KeyPoint")->GetTuple1(i));
    }
    flat.push_back(FieldValue(out, "AKPE"));
    return flat;
  });
  EXPECT_TRUE(SameOutputs(runs));
}

TEST(ASMSimplify, SameSeedSameOutputOtherSeedOtherChoice)
{
  auto input = ReadPLY("fandisk.ply");
  auto run = [&](int seed) {
    FilterRun r;
    r.Filter->SetModeToPaper(); // the random choice among key points is the paper's
    r.Filter->SetOutputFraction(0.01);
    r.Filter->SetRandomSeed(seed);
    vtkPolyData* out = r.Execute(input);
    std::vector<double> ids;
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      ids.push_back(out->GetPointData()->GetArray("vtkOriginalPointIds")->GetTuple1(i));
    }
    return ids;
  };
  EXPECT_EQ(run(1), run(1));
  EXPECT_NE(run(1), run(2)) << "at 1 % many cells have more key points than budget";
}

TEST(ASMSimplify, ReportsProgressAndHonoursAbort)
{
  auto input = ReadPLY("bunny.ply");
  struct Progress : public vtkCommand
  {
    static Progress* New() { return new Progress; }
    void Execute(vtkObject* caller, unsigned long, void* data) override
    {
      this->Values.push_back(*static_cast<double*>(data));
      if (this->AbortAt >= 0 && this->Values.back() >= this->AbortAt)
      {
        static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      }
    }
    std::vector<double> Values;
    double AbortAt = -1;
  };
  {
    FilterRun run;
    vtkNew<Progress> progress;
    run.Filter->AddObserver(vtkCommand::ProgressEvent, progress);
    EXPECT_EQ(run.Execute(input)->GetNumberOfPoints(), 1797);
    EXPECT_GE(progress->Values.size(), 10u);
    EXPECT_TRUE(std::is_sorted(progress->Values.begin(), progress->Values.end()));
    EXPECT_EQ(progress->Values.back(), 1.0);
    EXPECT_GE(std::count_if(progress->Values.begin(), progress->Values.end(),
                [](double v) { return v > 0.5 && v < 1.0; }),
      5);
  }
  {
    FilterRun run;
    vtkNew<Progress> progress;
    progress->AbortAt = 0.5;
    run.Filter->AddObserver(vtkCommand::ProgressEvent, progress);
    EXPECT_EQ(run.Execute(input)->GetNumberOfPoints(), 0);
    // The run stops at the first report past the abort request.
    const auto late = std::count_if(progress->Values.begin(), progress->Values.end(),
      [](double v) { return v > 0.5 && v < 1.0; });
    EXPECT_LE(late, 1);
    // The abort stops that run only: the next one (after a change) completes.
    run.Filter->RemoveObservers(vtkCommand::ProgressEvent);
    run.Filter->SetRandomSeed(2);
    run.Filter->Update();
    EXPECT_EQ(run.Filter->GetOutput()->GetNumberOfPoints(), 1797);
  }
}

TEST(ASMSimplify, AcceptsUnstructuredGridsAndDoublePoints)
{
  Cloud c = asmtest::Sphere(3000, 2.0);
  auto poly = ToPolyData(c, VTK_DOUBLE);
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(poly->GetPoints());
  FilterRun run;
  run.Filter->SetTargetModeToNumberOfOutputPoints();
  run.Filter->SetNumberOfOutputPoints(123);
  vtkPolyData* out = run.Execute(grid);
  EXPECT_EQ(out->GetNumberOfPoints(), 123);
  EXPECT_EQ(out->GetPoints()->GetDataType(), VTK_DOUBLE);
  EXPECT_TRUE(OneVertexPerPoint(out));
  run.Filter->SetOutputPointsPrecision(vtkAlgorithm::SINGLE_PRECISION);
  run.Filter->Update();
  EXPECT_EQ(run.Filter->GetOutput()->GetPoints()->GetDataType(), VTK_FLOAT);
}

TEST(ASMSimplify, FlatFloatPlaneHasNoKeyPoints)
{
  // A tilted plane stored in float: rounding must not create key points.
  Cloud c =
    asmtest::GridSurface(150, 50.0, [](double x, double y) { return 0.3 * x + 0.7 * y + 100.0; });
  FilterRun run;
  vtkPolyData* out = run.Execute(ToPolyData(c, VTK_FLOAT));
  ASSERT_EQ(out->GetNumberOfPoints(), std::llround(0.05 * 150 * 150));
  EXPECT_EQ(FieldValue(out, "NumberOfKeyPoints"), 0.0);
}

TEST(ASMSimplify, SurfaceVariationWeightMovesSamplesToCurvedParts)
{
  // A flat square with a sphere cap on it: the adaptive weight gives the
  // curved cells more samples than the uniform one.
  Cloud c = asmtest::GridSurface(200, 2.0, [](double, double) { return 0.0; });
  const Cloud ball = asmtest::Sphere(8000, 0.5, 4, 0, 0, 1.0);
  c.insert(c.end(), ball.begin(), ball.end());
  auto input = ToPolyData(c);
  auto onBall = [&](vtkASMSimplify* f) {
    vtkPolyData* out = f->GetOutput();
    int count = 0;
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      count += out->GetPoint(i)[2] > 0.25;
    }
    return count;
  };
  FilterRun uniform, adaptive;
  uniform.Execute(input);
  adaptive.Filter->SetWeightModeToSurfaceVariation();
  adaptive.Filter->SetCurvatureWeight(4.0);
  adaptive.Execute(input);
  EXPECT_EQ(adaptive.Filter->GetOutput()->GetNumberOfPoints(),
    uniform.Filter->GetOutput()->GetNumberOfPoints());
  EXPECT_GT(onBall(adaptive.Filter), onBall(uniform.Filter) * 5 / 4);
}
