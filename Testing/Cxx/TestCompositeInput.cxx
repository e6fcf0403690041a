// SPDX-License-Identifier: BSD-3-Clause
// Composite inputs (vtkASMCompositeInput.h): a vtkMultiBlockDataSet or a
// vtkPartitionedDataSet of point sets is ONE cloud for vtkASMSimplify and
// vtkKeyPointError, not one run per block: the output is one vtkPolyData of
// exactly N_s points, the points of the blocks merged in traversal order
// give the same samples, the arrays every block has are carried (the others
// dropped with a warning), and vtkOriginalBlockIds / vtkOriginalPointIds
// name the block and the point each sample's representative is.
#include "FilterHelpers.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkKeyPointError.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <vector>

namespace
{
// Points [first, last) of `c` as a block with a "Value" array (double) and a
// "Label" array (int: the point's index in the whole cloud).
vtkSmartPointer<vtkPolyData> Block(const asmtest::Cloud& c, vtkIdType first, vtkIdType last)
{
  asmtest::Cloud part(c.begin() + 3 * first, c.begin() + 3 * last);
  vtkSmartPointer<vtkPolyData> block = asmtest::ToPolyData(part);
  vtkNew<vtkDoubleArray> value;
  vtkNew<vtkIntArray> label;
  value->SetName("Value");
  label->SetName("Label");
  for (vtkIdType i = first; i < last; ++i)
  {
    value->InsertNextValue(c[3 * i] + 2.0 * c[3 * i + 2]);
    label->InsertNextValue(static_cast<int>(i));
  }
  block->GetPointData()->AddArray(value);
  block->GetPointData()->AddArray(label);
  return block;
}

vtkSmartPointer<vtkPolyData> SimplifyTo(
  vtkDataObject* input, int mode, vtkIdType count, int* warnings = nullptr)
{
  vtkNew<vtkASMSimplify> simplify;
  vtkNew<asmtest::MessageCounter> messages;
  simplify->AddObserver(vtkCommand::WarningEvent, messages);
  simplify->SetMode(mode);
  simplify->SetGenerateCurvature(false);
  simplify->SetTargetModeToNumberOfOutputPoints();
  simplify->SetNumberOfOutputPoints(count);
  simplify->SetInputData(input);
  simplify->Update();
  if (warnings)
  {
    *warnings = messages->Warnings;
  }
  return vtkPolyData::SafeDownCast(simplify->GetOutputDataObject(0));
}
} // namespace

TEST(CompositeInput, MultiBlockIsOneCloud)
{
  // Two overlapping halves of one sphere, an empty block, an image (not a
  // point set: left out), and a block whose extra array the others lack
  // (its other arrays in another order); the composite's field data.
  const asmtest::Cloud cloud = asmtest::Sphere(30000, 1.0, 5);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(5);
  blocks->SetBlock(0, Block(cloud, 0, 12000));
  vtkNew<vtkPolyData> empty; // (a points object without points, and no arrays)
  empty->SetPoints(vtkNew<vtkPoints>());
  blocks->SetBlock(1, empty);
  blocks->SetBlock(2, vtkSmartPointer<vtkImageData>::New());
  vtkSmartPointer<vtkPolyData> last = Block(cloud, 12000, 30000);
  // Its arrays listed in the other order ("Label" first).
  vtkSmartPointer<vtkDataArray> value = last->GetPointData()->GetArray("Value");
  last->GetPointData()->RemoveArray("Value");
  last->GetPointData()->AddArray(value);
  vtkNew<vtkDoubleArray> extra;
  extra->SetName("OnlyInOneBlock");
  extra->SetNumberOfTuples(18000);
  extra->Fill(1.0);
  last->GetPointData()->AddArray(extra);
  blocks->SetBlock(3, last);
  vtkNew<vtkIntArray> scanner; // the composite's own field data
  scanner->SetName("ScannerId");
  scanner->InsertNextValue(42);
  blocks->GetFieldData()->AddArray(scanner);
  // The same points in one polydata, in traversal order.
  vtkSmartPointer<vtkPolyData> whole = Block(cloud, 0, 30000);
  const unsigned lastFlatIndex = 4; // (flat indices: the root 0, block k k + 1)

  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    int warnings = 0;
    vtkSmartPointer<vtkPolyData> merged = SimplifyTo(blocks, mode, 700, &warnings);
    vtkSmartPointer<vtkPolyData> plain = SimplifyTo(whole, mode, 700);
    ASSERT_NE(merged, nullptr) << "mode " << mode << ": a vtkPolyData, not one output per block";
    ASSERT_EQ(merged->GetNumberOfPoints(), 700) << "mode " << mode;
    ASSERT_EQ(plain->GetNumberOfPoints(), 700);
    EXPECT_GE(warnings, 1) << "the array one block lacks is named";
    EXPECT_EQ(merged->GetPointData()->GetArray("OnlyInOneBlock"), nullptr);
    vtkDataArray* value = merged->GetPointData()->GetArray("Value");
    vtkDataArray* label = merged->GetPointData()->GetArray("Label");
    vtkDataArray* block = merged->GetPointData()->GetArray("vtkOriginalBlockIds");
    vtkDataArray* id = merged->GetPointData()->GetArray("vtkOriginalPointIds");
    ASSERT_TRUE(value && label && block && id) << "mode " << mode;
    EXPECT_EQ(merged->GetPointData()->GetArray("vtkASMLeafPointIds"), nullptr);
    ASSERT_NE(merged->GetFieldData()->GetArray("ScannerId"), nullptr) << "mode " << mode;
    EXPECT_EQ(merged->GetFieldData()->GetArray("ScannerId")->GetTuple1(0), 42.0);
    ASSERT_TRUE(asmtest::SamePoints(merged, plain)) << "mode " << mode;
    vtkDataArray* plainValue = plain->GetPointData()->GetArray("Value");
    for (vtkIdType s = 0; s < 700; ++s)
    {
      ASSERT_EQ(value->GetComponent(s, 0), plainValue->GetComponent(s, 0));
      // The representative, named by block and id, is the point Label names.
      const auto flat = static_cast<unsigned>(block->GetComponent(s, 0));
      const auto within = static_cast<vtkIdType>(id->GetComponent(s, 0));
      ASSERT_TRUE(flat == 1 || flat == lastFlatIndex) << flat;
      const vtkIdType offset = flat == 1 ? 0 : 12000;
      ASSERT_EQ(static_cast<vtkIdType>(label->GetComponent(s, 0)), offset + within)
        << "sample " << s;
    }
  }
}

TEST(CompositeInput, MixedPrecisionLeavesAreMergedInDoubles)
{
  // A double leaf and a float leaf, in either order: the merged cloud holds
  // doubles (the float leaf's values exactly), so the output follows the
  // double input, as one polydata of the same numbers does.
  const asmtest::Cloud cloud = asmtest::Sphere(8000, 1.0, 6);
  const asmtest::Cloud first(cloud.begin(), cloud.begin() + 3 * 4000);
  asmtest::Cloud second(cloud.begin() + 3 * 4000, cloud.end());
  for (double& v : second)
  {
    v = static_cast<float>(v); // what the float leaf holds
  }
  for (bool doubleFirst : { true, false })
  {
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(2);
    blocks->SetBlock(doubleFirst ? 0 : 1, asmtest::ToPolyData(first, VTK_DOUBLE));
    blocks->SetBlock(doubleFirst ? 1 : 0, asmtest::ToPolyData(second, VTK_FLOAT));
    asmtest::Cloud all = doubleFirst ? first : second;
    const asmtest::Cloud& rest = doubleFirst ? second : first;
    all.insert(all.end(), rest.begin(), rest.end());
    vtkSmartPointer<vtkPolyData> whole = asmtest::ToPolyData(all, VTK_DOUBLE);
    for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
    {
      vtkSmartPointer<vtkPolyData> merged = SimplifyTo(blocks, mode, 400);
      vtkSmartPointer<vtkPolyData> plain = SimplifyTo(whole, mode, 400);
      ASSERT_NE(merged, nullptr);
      ASSERT_EQ(merged->GetNumberOfPoints(), 400);
      EXPECT_EQ(merged->GetPoints()->GetDataType(), VTK_DOUBLE)
        << "double leaf first: " << doubleFirst << ", mode " << mode;
      EXPECT_TRUE(asmtest::SamePoints(merged, plain))
        << "double leaf first: " << doubleFirst << ", mode " << mode;
    }
  }
}

TEST(CompositeInput, PartitionsGiveTheRequestedCountAndTheSameError)
{
  const asmtest::Cloud cloud = asmtest::Sphere(20000, 1.0, 9);
  vtkNew<vtkPartitionedDataSet> parts;
  parts->SetNumberOfPartitions(3);
  parts->SetPartition(0, Block(cloud, 0, 5000));
  parts->SetPartition(1, Block(cloud, 5000, 14000));
  parts->SetPartition(2, Block(cloud, 14000, 20000));
  vtkSmartPointer<vtkPolyData> whole = Block(cloud, 0, 20000);
  vtkSmartPointer<vtkPolyData> simplified =
    SimplifyTo(parts, vtkASMSimplify::FEATURE_PRESERVING, 900);
  ASSERT_NE(simplified, nullptr);
  ASSERT_EQ(simplified->GetNumberOfPoints(), 900);

  // vtkKeyPointError: the partitioned original (and a partitioned
  // simplified cloud) measure as the merged ones.
  vtkNew<vtkPartitionedDataSet> simplifiedParts;
  simplifiedParts->SetNumberOfPartitions(2);
  simplifiedParts->SetPartition(0, simplified);
  simplifiedParts->SetPartition(1, vtkSmartPointer<vtkPolyData>::New());
  auto measure = [](vtkDataObject* original, vtkDataObject* reduced) {
    vtkNew<vtkKeyPointError> error;
    error->SetGenerateCurvature(false);
    error->SetInputData(0, original);
    error->SetInputData(1, reduced);
    error->Update();
    vtkPolyData* out = vtkPolyData::SafeDownCast(error->GetOutputDataObject(0));
    EXPECT_NE(out, nullptr);
    return out ? std::vector<double>{ asmtest::FieldValue(out, "MKPE"),
      asmtest::FieldValue(out, "AKPE"), asmtest::FieldValue(out, "HausdorffDistance"),
      static_cast<double>(out->GetNumberOfPoints()) }
               : std::vector<double>{};
  };
  const std::vector<double> expected = measure(whole, simplified);
  ASSERT_EQ(expected.size(), 4u);
  EXPECT_EQ(expected[3], 900.0);
  EXPECT_GT(expected[2], 0.0);
  EXPECT_EQ(measure(parts, simplified), expected);
  EXPECT_EQ(measure(parts, simplifiedParts), expected);

  // The output has the simplified composite's own field data. (VTK's
  // executive passes the first input's field data to the output before the
  // filter runs, so that of the original needs nothing; that of the second
  // input comes through the merged cloud.)
  vtkNew<vtkIntArray> scanner;
  scanner->SetName("ScannerId");
  scanner->InsertNextValue(42);
  simplifiedParts->GetFieldData()->AddArray(scanner);
  vtkNew<vtkKeyPointError> error;
  error->SetGenerateCurvature(false);
  error->SetInputData(0, parts);
  error->SetInputData(1, simplifiedParts);
  error->Update();
  vtkPolyData* out = vtkPolyData::SafeDownCast(error->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  ASSERT_NE(out->GetFieldData()->GetArray("ScannerId"), nullptr);
  EXPECT_EQ(out->GetFieldData()->GetArray("ScannerId")->GetTuple1(0), 42.0);
}

// A leaf's array with fewer values than the leaf's points is left out with
// a warning naming it (it is not copied past its end).
TEST(CompositeInput, AShortArrayInALeafIsDroppedWithAWarning)
{
  const asmtest::Cloud cloud = asmtest::Sphere(5000, 1.0, 6);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  vtkSmartPointer<vtkPolyData> first = Block(cloud, 0, 2000);
  vtkSmartPointer<vtkPolyData> second = Block(cloud, 2000, 5000);
  for (vtkPolyData* leaf : { first.GetPointer(), second.GetPointer() })
  {
    vtkNew<vtkDoubleArray> shortArray;
    shortArray->SetName("Short");
    shortArray->SetNumberOfTuples(leaf == first ? 10 : 3000); // short in the first leaf only
    shortArray->Fill(1.0);
    leaf->GetPointData()->AddArray(shortArray);
  }
  blocks->SetBlock(0, first);
  blocks->SetBlock(1, second);
  vtkNew<vtkASMSimplify> simplify;
  vtkNew<asmtest::MessageCounter> messages;
  simplify->AddObserver(vtkCommand::WarningEvent, messages);
  simplify->AddObserver(vtkCommand::ErrorEvent, messages);
  simplify->SetTargetModeToNumberOfOutputPoints();
  simplify->SetNumberOfOutputPoints(300);
  simplify->SetInputData(blocks);
  simplify->Update();
  vtkPolyData* out = vtkPolyData::SafeDownCast(simplify->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  EXPECT_EQ(out->GetNumberOfPoints(), 300);
  EXPECT_EQ(messages->Errors, 0) << messages->LastMessage;
  EXPECT_EQ(messages->Warnings, 1);
  EXPECT_NE(messages->LastMessage.find("Short"), std::string::npos) << messages->LastMessage;
  EXPECT_EQ(out->GetPointData()->GetArray("Short"), nullptr);
  ASSERT_NE(out->GetPointData()->GetArray("Value"), nullptr);
  ASSERT_NE(out->GetPointData()->GetArray("Label"), nullptr);

  // vtkKeyPointError takes a composite simplified cloud the same way, and
  // says so too (it dropped the array without a word).
  asmtest::ObservedFilter<vtkKeyPointError> error;
  error.Filter->SetInputData(0, asmtest::ToPolyData(cloud));
  error.Filter->SetInputData(1, blocks); // (as the simplified cloud: its arrays are kept)
  error.Filter->SetGenerateCurvature(false);
  error.Filter->Update();
  vtkPolyData* measured = error.Filter->GetOutput();
  EXPECT_EQ(measured->GetNumberOfPoints(), 5000);
  EXPECT_EQ(error.Messages->Errors, 0) << error.Messages->LastMessage;
  EXPECT_EQ(error.Messages->Warnings, 1) << error.Messages->LastMessage;
  EXPECT_NE(error.Messages->LastMessage.find("Short"), std::string::npos)
    << error.Messages->LastMessage;
  EXPECT_EQ(measured->GetPointData()->GetArray("Short"), nullptr);
  EXPECT_NE(measured->GetPointData()->GetArray("Label"), nullptr);
}

// A composite without points (empty blocks, an image) gets a warning and an
// empty output, as an empty point set does.
TEST(CompositeInput, NoPointsGiveAWarningAndAnEmptyOutput)
{
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, vtkSmartPointer<vtkPolyData>::New());
  blocks->SetBlock(1, vtkSmartPointer<vtkImageData>::New());
  int warnings = 0;
  vtkSmartPointer<vtkPolyData> out =
    SimplifyTo(blocks, vtkASMSimplify::FEATURE_PRESERVING, 10, &warnings);
  ASSERT_NE(out, nullptr);
  EXPECT_EQ(out->GetNumberOfPoints(), 0);
  EXPECT_EQ(warnings, 1);
}
