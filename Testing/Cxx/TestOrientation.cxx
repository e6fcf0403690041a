// SPDX-License-Identifier: BSD-3-Clause
// Orientation in vtkASMSimplify's output: the PCA normals agree with the
// input normals (whatever their array), and the sign of "MeanCurvature"
// follows the output normals (positive where the surface bends away from
// them).
#include "vtkASMSimplify.h"

#include "FilterHelpers.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSOADataArrayTemplate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace asmtest;

TEST(ASMSimplify, InputNormalsKeepTheirNameAndOrientThePCANormals)
{
  auto input = ReadPLY("kitten.ply"); // nx ny nz: an array called "Normals"
  ASSERT_NE(input->GetPointData()->GetNormals(), nullptr);
  FilterRun run;
  vtkPolyData* out = run.Execute(input);
  vtkPointData* pd = out->GetPointData();
  vtkDataArray* normals = pd->GetArray("Normals");
  vtkDataArray* pca = pd->GetArray("PCANormals");
  ASSERT_NE(normals, nullptr);
  ASSERT_NE(pca, nullptr);
  EXPECT_EQ(pd->GetNormals(), normals);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    normals->GetTuple(i, a);
    pca->GetTuple(i, b);
    EXPECT_GE(a[0] * b[0] + a[1] * b[1] + a[2] * b[2], 0.0) << i;
  }
}

// The input normals orient the PCA normals the same whatever their array
// (float or double, contiguous or not: read in place or copied), in both
// modes; flipped input normals flip them. A NaN normal (every 7 points) is
// skipped: the same output as a zero normal there, the cluster's other
// members deciding (a few samples, whose members' normals are nearly
// perpendicular to their cell's, turn with the sum).
TEST(ASMSimplify, InputNormalsOrientTheSameWhateverTheirArray)
{
  auto input = ReadPLY("kitten.ply");
  vtkDataArray* floats = input->GetPointData()->GetNormals();
  ASSERT_NE(vtkFloatArray::SafeDownCast(floats), nullptr);
  const vtkIdType n = floats->GetNumberOfTuples();
  vtkNew<vtkDoubleArray> doubles;
  vtkNew<vtkSOADataArrayTemplate<float>> split;
  vtkNew<vtkFloatArray> flipped;
  vtkNew<vtkFloatArray> holed;
  vtkNew<vtkFloatArray> zeroed;
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(doubles), static_cast<vtkDataArray*>(split),
         static_cast<vtkDataArray*>(flipped), static_cast<vtkDataArray*>(holed),
         static_cast<vtkDataArray*>(zeroed) })
  {
    a->SetName("Normals");
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(n);
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    double v[3];
    floats->GetTuple(i, v);
    doubles->SetTuple(i, v);
    split->SetTuple(i, v);
    flipped->SetTuple3(i, -v[0], -v[1], -v[2]);
    const double hole = std::nan("");
    i % 7 == 0 ? holed->SetTuple3(i, hole, hole, hole) : holed->SetTuple3(i, -v[0], -v[1], -v[2]);
    i % 7 == 0 ? zeroed->SetTuple3(i, 0, 0, 0) : zeroed->SetTuple3(i, -v[0], -v[1], -v[2]);
  }
  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    auto pcaNormals = [&](vtkDataArray* normals) {
      vtkNew<vtkPolyData> copy;
      copy->ShallowCopy(input);
      copy->GetPointData()->SetNormals(normals);
      FilterRun run;
      run.Filter->SetMode(mode);
      vtkPolyData* out = run.Execute(copy);
      std::vector<double> values;
      vtkDataArray* pca = out->GetPointData()->GetArray("PCANormals");
      for (vtkIdType i = 0; pca && i < pca->GetNumberOfTuples(); ++i)
      {
        for (int a = 0; a < 3; ++a)
        {
          values.push_back(pca->GetComponent(i, a));
        }
      }
      return values;
    };
    const std::vector<double> reference = pcaNormals(floats);
    ASSERT_FALSE(reference.empty());
    EXPECT_EQ(pcaNormals(doubles), reference) << mode;
    EXPECT_EQ(pcaNormals(split), reference) << mode;
    for (vtkDataArray* normals :
      { static_cast<vtkDataArray*>(flipped), static_cast<vtkDataArray*>(holed) })
    {
      const std::vector<double> inward = pcaNormals(normals);
      ASSERT_EQ(inward.size(), reference.size());
      std::size_t opposite = 0;
      for (std::size_t k = 0; k < reference.size(); k += 3)
      {
        opposite += reference[k] * inward[k] + reference[k + 1] * inward[k + 1] +
              reference[k + 2] * inward[k + 2] <
            0.0
          ? 1
          : 0;
      }
      if (normals == flipped)
      {
        EXPECT_EQ(opposite, reference.size() / 3) << mode;
      }
      else
      {
        EXPECT_GE(opposite, reference.size() / 3 * 95 / 100) << mode;
        EXPECT_EQ(inward, pcaNormals(zeroed)) << mode;
      }
    }
  }
}

TEST(ASMSimplify, MeanCurvatureSignFollowsTheSampleNormals)
{
  // A sphere of radius 2: with outward input normals (or none: away from
  // the cloud's centroid) the output normals point out and the mean
  // curvature is +1/2; with inward input normals both turn: -1/2.
  const double radius = 2.0;
  const Cloud c = Sphere(6000, radius, 4);
  for (int inputNormals : { 0, 1, -1 })
  {
    auto input = ToPolyData(c);
    if (inputNormals != 0)
    {
      vtkNew<vtkDoubleArray> normals;
      normals->SetName("InputNormals");
      normals->SetNumberOfComponents(3);
      for (std::size_t i = 0; i < c.size(); i += 3)
      {
        normals->InsertNextTuple3(inputNormals * c[i] / radius, inputNormals * c[i + 1] / radius,
          inputNormals * c[i + 2] / radius);
      }
      input->GetPointData()->SetNormals(normals);
    }
    for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
    {
      FilterRun run;
      run.Filter->SetMode(mode);
      run.Count(300);
      vtkPolyData* out = run.Execute(input);
      ASSERT_EQ(out->GetNumberOfPoints(), 300);
      vtkDataArray* normals = out->GetPointData()->GetArray("Normals");
      vtkDataArray* curvature = out->GetPointData()->GetArray("MeanCurvature");
      ASSERT_NE(normals, nullptr);
      ASSERT_NE(curvature, nullptr);
      const double sign = inputNormals < 0 ? -1.0 : 1.0;
      for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
      {
        double p[3], n[3];
        out->GetPoint(i, p);
        normals->GetTuple(i, n);
        EXPECT_GT(sign * (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]), 0.0) << mode << " " << i;
        EXPECT_NEAR(curvature->GetTuple1(i), sign / radius, 0.05)
          << "input normals " << inputNormals << ", mode " << mode << ", sample " << i;
      }
    }
  }
}
