// SPDX-License-Identifier: BSD-3-Clause
// Clouds whose points share few positions (README "Messy data"): many
// samples at one position stand for the same input point, chosen by value,
// and each keeps a cluster of its own.
#include "FilterHelpers.h"

#include "vtkASMSimplify.h"
#include "vtkDataArray.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

using asmtest::FilterRun;
using asmtest::ToPolyData;

// 3000 identical points labelled 3000 - id: the smallest label is the last
// point's. Half of them as samples, in both modes (the samples are listed
// once as a group, asmcore::ListDuplicatesOnce; before, each listed the
// whole group and a cloud of 200 000 identical points took 85 s): every
// sample stands for that last point, every cluster has a member, and the
// members are the whole cloud.
TEST(HostileInputs, ManySamplesAtOnePositionTakeTheFirstPointByValue)
{
  const vtkIdType n = 3000;
  asmtest::Cloud same;
  for (vtkIdType i = 0; i < n; ++i)
  {
    asmtest::Add(same, 0.25, 0.5, 0.75);
  }
  auto input = ToPolyData(same, VTK_FLOAT);
  vtkNew<vtkIntArray> label;
  label->SetName("Label");
  for (vtkIdType i = 0; i < n; ++i)
  {
    label->InsertNextValue(static_cast<int>(n - i));
  }
  input->GetPointData()->AddArray(label);
  for (const int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    for (const bool snap : { false, true })
    {
      SCOPED_TRACE("mode " + std::to_string(mode) + (snap ? ", snapped" : ""));
      FilterRun run;
      run.Filter->SetMode(mode);
      run.Filter->SetSnapToInputPoints(snap);
      run.Count(n / 2);
      vtkPolyData* out = run.Execute(input);
      ASSERT_EQ(out->GetNumberOfPoints(), n / 2);
      vtkDataArray* labels = out->GetPointData()->GetArray("Label");
      vtkDataArray* ids = out->GetPointData()->GetArray("vtkOriginalPointIds");
      vtkDataArray* sizes = out->GetPointData()->GetArray("ClusterSize");
      ASSERT_TRUE(labels && ids && sizes);
      double members = 0.0;
      for (vtkIdType s = 0; s < n / 2; ++s)
      {
        ASSERT_EQ(labels->GetTuple1(s), 1.0) << s;
        ASSERT_EQ(ids->GetTuple1(s), static_cast<double>(n - 1)) << s;
        ASSERT_GE(sizes->GetTuple1(s), 1.0) << s;
        members += sizes->GetTuple1(s);
      }
      EXPECT_EQ(members, static_cast<double>(n));
    }
  }
}
