// SPDX-License-Identifier: BSD-3-Clause
// vtkASMSimplify's distributed path (vtkASMDistributed.h) on one process: a
// vtkDummyController with AlwaysDistribute. Points flagged as duplicates of
// another process's points (vtkGhostType & DUPLICATEPOINT) are skipped: the
// output is that of the cloud without them, each point counted once.
#include "FilterHelpers.h"

#include "vtkDataSetAttributes.h"
#include "vtkDummyController.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

namespace
{
struct Output
{
  std::vector<std::array<double, 3>> Points; // sorted
  double Members = 0.0;                      // ClusterSize summed
};

Output Simplify(vtkPolyData* input, int mode)
{
  vtkNew<vtkDummyController> controller;
  vtkNew<vtkASMSimplify> asm_;
  asm_->SetController(controller);
  asm_->AlwaysDistributeOn();
  asm_->SetMode(mode);
  asm_->SetFillHoles(false); // (switched off in distributed runs, with a warning)
  asm_->SetTargetModeToNumberOfOutputPoints();
  asm_->SetNumberOfOutputPoints(400);
  asm_->SetInputData(input);
  asm_->Update();
  vtkPolyData* out = asm_->GetOutput();
  Output run;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    std::array<double, 3> p;
    out->GetPoint(i, p.data());
    run.Points.push_back(p);
  }
  std::sort(run.Points.begin(), run.Points.end());
  vtkDataArray* sizes = out->GetPointData()->GetArray("ClusterSize");
  EXPECT_NE(sizes, nullptr);
  for (vtkIdType i = 0; sizes && i < sizes->GetNumberOfTuples(); ++i)
  {
    run.Members += sizes->GetTuple1(i);
  }
  // The distributed path ran: it names each point's process.
  EXPECT_NE(out->GetPointData()->GetArray("vtkOriginalProcessIds"), nullptr);
  return run;
}
} // namespace

TEST(DistributedFilter, DuplicateGhostPointsAreSkipped)
{
  const asmtest::Cloud cloud = asmtest::Sphere(6000, 1.0, 3);
  vtkSmartPointer<vtkPolyData> clean = asmtest::ToPolyData(cloud);
  // The same points, then copies of every third one (shifted a little, so
  // that they would change the result if they were used), flagged as
  // duplicates owned by another process.
  asmtest::Cloud withCopies = cloud;
  for (std::size_t i = 0; i < cloud.size() / 3; i += 3)
  {
    withCopies.insert(withCopies.end(), { cloud[3 * i] + 1e-3, cloud[3 * i + 1], cloud[3 * i + 2] });
  }
  vtkSmartPointer<vtkPolyData> ghosted = asmtest::ToPolyData(withCopies);
  vtkNew<vtkUnsignedCharArray> ghosts;
  ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
  ghosts->SetNumberOfTuples(ghosted->GetNumberOfPoints());
  for (vtkIdType i = 0; i < ghosted->GetNumberOfPoints(); ++i)
  {
    ghosts->SetValue(i, i < clean->GetNumberOfPoints() ? 0 : vtkDataSetAttributes::DUPLICATEPOINT);
  }
  ghosted->GetPointData()->AddArray(ghosts);

  for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    const Output expected = Simplify(clean, mode);
    const Output run = Simplify(ghosted, mode);
    ASSERT_EQ(expected.Points.size(), 400u);
    EXPECT_EQ(expected.Members, 6000.0) << "mode " << mode;
    EXPECT_EQ(run.Members, 6000.0) << "mode " << mode << ": the duplicates are not members";
    EXPECT_EQ(run.Points, expected.Points) << "mode " << mode;
  }
}
