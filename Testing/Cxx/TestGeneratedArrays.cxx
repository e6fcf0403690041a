// SPDX-License-Identifier: BSD-3-Clause
// The arrays vtkASMSimplify generates against the input's own: an input
// array of a generated name (an earlier run's) is replaced by this run's;
// the origin arrays that paired with the replaced vtkOriginalPointIds go;
// input normals keep their name and attribute, the PCA normals stand beside
// them or become the normals; global and pedigree ids are labels.
#include "FilterHelpers.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using asmtest::FilterRun;
using asmtest::ToPolyData;

namespace
{
template <typename ArrayT>
void AddConstant(vtkPolyData* pd, const char* name, double value)
{
  vtkNew<ArrayT> a;
  a->SetName(name);
  a->SetNumberOfTuples(pd->GetNumberOfPoints());
  a->Fill(value);
  pd->GetPointData()->AddArray(a);
}
} // namespace

TEST(GeneratedArrays, AnEarlierRunsArraysAreReplaced)
{
  // A unit sphere carrying arrays of the generated names with values no run
  // gives (as an earlier run's output would carry its own).
  const vtkIdType n = 3000;
  for (const int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    vtkSmartPointer<vtkPolyData> input = ToPolyData(asmtest::Sphere(n, 1.0, 21));
    AddConstant<vtkDoubleArray>(input, "KeyPoint", 5.0);
    AddConstant<vtkDoubleArray>(input, "ClusterSize", 77.0);
    AddConstant<vtkFloatArray>(input, "SurfaceVariation", -1.0);
    AddConstant<vtkDoubleArray>(input, "MeanCurvature", 123.0);
    AddConstant<vtkFloatArray>(input, "NeighborhoodSurfaceVariation", -1.0);
    AddConstant<vtkIntArray>(input, "vtkOriginalPointIds", 5000.0);
    AddConstant<vtkIdTypeArray>(input, "vtkOriginalBlockIds", 9.0);
    AddConstant<vtkIdTypeArray>(input, "vtkOriginalProcessIds", 3.0);
    FilterRun run;
    run.Filter->SetMode(mode);
    run.Count(200);
    vtkPolyData* out = run.Execute(input);
    ASSERT_EQ(out->GetNumberOfPoints(), 200);
    vtkPointData* pd = out->GetPointData();
    double clustered = 0.0;
    for (vtkIdType s = 0; s < 200; ++s)
    {
      const double key = pd->GetArray("KeyPoint")->GetTuple1(s);
      EXPECT_TRUE(key == 0.0 || key == 1.0) << key;
      clustered += pd->GetArray("ClusterSize")->GetTuple1(s);
      const double variation = pd->GetArray("SurfaceVariation")->GetTuple1(s);
      EXPECT_GE(variation, 0.0);
      EXPECT_LE(variation, 1.0 / 3.0);
      EXPECT_NEAR(std::abs(pd->GetArray("MeanCurvature")->GetTuple1(s)), 1.0, 0.3);
      EXPECT_GE(pd->GetArray("NeighborhoodSurfaceVariation")->GetTuple1(s), 0.0);
      EXPECT_LT(pd->GetArray("vtkOriginalPointIds")->GetTuple1(s), static_cast<double>(n));
    }
    EXPECT_EQ(clustered, static_cast<double>(n)) << "mode " << mode;
    EXPECT_EQ(pd->GetArray("vtkOriginalBlockIds"), nullptr) << "mode " << mode;
    EXPECT_EQ(pd->GetArray("vtkOriginalProcessIds"), nullptr) << "mode " << mode;
  }
}

TEST(GeneratedArrays, AChainsOriginArraysArePairs)
{
  // Two blocks simplified, then simplified again: the second output's
  // vtkOriginalPointIds are ids into the first output, and no block ids of
  // the first run are left to be read with them.
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, ToPolyData(asmtest::Sphere(2000, 1.0, 3)));
  blocks->SetBlock(1, ToPolyData(asmtest::Sphere(2000, 2.0, 4)));
  FilterRun first;
  first.Count(600);
  vtkNew<vtkPolyData> once;
  once->ShallowCopy(first.Execute(blocks));
  ASSERT_NE(once->GetPointData()->GetArray("vtkOriginalBlockIds"), nullptr);
  FilterRun second;
  second.Count(100);
  vtkPolyData* twice = second.Execute(once);
  ASSERT_EQ(twice->GetNumberOfPoints(), 100);
  EXPECT_EQ(twice->GetPointData()->GetArray("vtkOriginalBlockIds"), nullptr);
  vtkDataArray* ids = twice->GetPointData()->GetArray("vtkOriginalPointIds");
  ASSERT_NE(ids, nullptr);
  for (vtkIdType s = 0; s < 100; ++s)
  {
    EXPECT_LT(ids->GetTuple1(s), 600.0);
  }
}

TEST(GeneratedArrays, NormalsKeepTheirNameAndRole)
{
  // An array named "Normals" that is not the normals attribute: carried
  // under its name; the PCA normals ("PCANormals") are the output's normals.
  // Input normals under another name: they stay the normals, and the PCA
  // normals are "Normals" beside them.
  for (const bool attribute : { false, true })
  {
    vtkSmartPointer<vtkPolyData> input = ToPolyData(asmtest::Sphere(2000, 1.0, 5));
    vtkNew<vtkFloatArray> normals;
    normals->SetName(attribute ? "N" : "Normals");
    normals->SetNumberOfComponents(3);
    for (vtkIdType i = 0; i < 2000; ++i)
    {
      normals->InsertNextTuple(input->GetPoint(i)); // outward, unit
    }
    if (attribute)
    {
      input->GetPointData()->SetNormals(normals);
    }
    else
    {
      input->GetPointData()->AddArray(normals);
    }
    FilterRun run;
    run.Count(150);
    vtkPolyData* out = run.Execute(input);
    vtkPointData* pd = out->GetPointData();
    ASSERT_NE(pd->GetNormals(), nullptr) << "attribute " << attribute;
    EXPECT_STREQ(pd->GetNormals()->GetName(), attribute ? "N" : "PCANormals");
    EXPECT_NE(pd->GetArray(attribute ? "Normals" : "PCANormals"), nullptr);
    EXPECT_NE(pd->GetArray(attribute ? "N" : "Normals"), nullptr);
  }
}

TEST(GeneratedArrays, GlobalAndPedigreeIdsAreLabels)
{
  // Floating-point ids, as a reader may give them: each sample takes its
  // representative's id (an id of the input), never a mean of ids.
  vtkSmartPointer<vtkPolyData> input = ToPolyData(asmtest::Sphere(3000, 1.0, 8));
  vtkNew<vtkDoubleArray> pedigree;
  pedigree->SetName("Pedigree");
  vtkNew<vtkFloatArray> global;
  global->SetName("Global");
  for (vtkIdType i = 0; i < 3000; ++i)
  {
    pedigree->InsertNextValue(10.0 * static_cast<double>(i));
    global->InsertNextValue(static_cast<float>(20 * i));
  }
  input->GetPointData()->SetPedigreeIds(pedigree);
  input->GetPointData()->SetGlobalIds(global);
  ASSERT_EQ(input->GetPointData()->GetPedigreeIds(), pedigree.GetPointer());
  ASSERT_EQ(input->GetPointData()->GetGlobalIds(), global.GetPointer());
  for (const int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    FilterRun run;
    run.Filter->SetMode(mode);
    run.Count(200);
    vtkPointData* pd = run.Execute(input)->GetPointData();
    vtkDataArray* ids = pd->GetArray("vtkOriginalPointIds");
    ASSERT_NE(pd->GetPedigreeIds(), nullptr);
    ASSERT_NE(pd->GetGlobalIds(), nullptr);
    for (vtkIdType s = 0; s < 200; ++s)
    {
      const double id = ids->GetTuple1(s);
      ASSERT_EQ(pd->GetArray("Pedigree")->GetTuple1(s), 10.0 * id) << "mode " << mode;
      ASSERT_EQ(pd->GetArray("Global")->GetTuple1(s), 20.0 * id) << "mode " << mode;
    }
  }
}
