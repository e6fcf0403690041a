// SPDX-License-Identifier: BSD-3-Clause
// What a composite input's leaves carry into the merged cloud
// (vtkASMCompositeInput.h), and the arrays' information keys: global ids
// that every leaf has are kept; ghost flags that only some leaves have still
// skip the flagged points (in both filters, on both of vtkKeyPointError's
// ports); a leaf that is not a point set is named in a warning; an array's
// information keys (units, GUI hints) reach the output, as VTK's
// point-subsetting filters keep them.
#include "FilterHelpers.h"

#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationStringKey.h"
#include "vtkIntArray.h"
#include "vtkKeyPointError.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <string>

using namespace asmtest;

namespace
{
// Points [first, last) of `c` with "Label" (int: the index in the whole
// cloud) and, as the global ids, "GID" (the same, as vtkIdType).
vtkSmartPointer<vtkPolyData> Leaf(const Cloud& c, vtkIdType first, vtkIdType last)
{
  vtkSmartPointer<vtkPolyData> leaf =
    ToPolyData(Cloud(c.begin() + 3 * first, c.begin() + 3 * last));
  vtkNew<vtkIntArray> label;
  vtkNew<vtkIdTypeArray> gid;
  label->SetName("Label");
  gid->SetName("GID");
  for (vtkIdType i = first; i < last; ++i)
  {
    label->InsertNextValue(static_cast<int>(i));
    gid->InsertNextValue(i);
  }
  leaf->GetPointData()->AddArray(label);
  leaf->GetPointData()->SetGlobalIds(gid);
  return leaf;
}

// Flags every other point of `leaf` with `flag`.
void FlagEveryOther(vtkPolyData* leaf, unsigned char flag)
{
  vtkNew<vtkUnsignedCharArray> ghosts;
  ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
  ghosts->SetNumberOfTuples(leaf->GetNumberOfPoints());
  for (vtkIdType i = 0; i < leaf->GetNumberOfPoints(); ++i)
  {
    ghosts->SetValue(i, i % 2 ? flag : 0);
  }
  leaf->GetPointData()->AddArray(ghosts);
}

vtkSmartPointer<vtkMultiBlockDataSet> Blocks(vtkDataObject* a, vtkDataObject* b)
{
  auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, a);
  blocks->SetBlock(1, b);
  return blocks;
}

const Cloud Ball = Sphere(5000, 1.0, 11);
} // namespace

// Both leaves have GID as their global ids: the output has it, as its
// global ids, with the representative's value (before, the merge dropped it
// and warned that it was "not on every block").
TEST(CompositeLeaves, GlobalIdsOfEveryLeafAreKept)
{
  auto blocks = Blocks(Leaf(Ball, 0, 2000), Leaf(Ball, 2000, 5000));
  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    ObservedFilter<vtkASMSimplify> simplify;
    simplify.Filter->SetMode(mode);
    simplify.Filter->SetGenerateCurvature(false);
    simplify.Filter->SetInputData(blocks);
    simplify.Filter->Update();
    vtkPolyData* out = simplify.Filter->GetOutput();
    EXPECT_EQ(simplify.Messages->Warnings, 0) << simplify.Messages->LastMessage;
    ASSERT_GT(out->GetNumberOfPoints(), 0);
    vtkDataArray* gid = out->GetPointData()->GetGlobalIds();
    vtkDataArray* label = out->GetPointData()->GetArray("Label");
    ASSERT_NE(gid, nullptr) << mode;
    ASSERT_NE(label, nullptr);
    EXPECT_STREQ(gid->GetName(), "GID");
    for (vtkIdType s = 0; s < out->GetNumberOfPoints(); ++s)
    {
      ASSERT_EQ(gid->GetTuple1(s), label->GetTuple1(s)) << s;
    }
  }
  // vtkKeyPointError's simplified port passes its arrays on: GID too.
  ObservedFilter<vtkKeyPointError> error;
  error.Filter->SetInputData(0, ToPolyData(Ball));
  error.Filter->SetSimplifiedData(blocks);
  error.Filter->SetGenerateCurvature(false);
  error.Filter->Update();
  EXPECT_EQ(error.Messages->Warnings, 0) << error.Messages->LastMessage;
  ASSERT_NE(error.Filter->GetOutput()->GetPointData()->GetGlobalIds(), nullptr);
}

// Ghost flags given only where there are ghosts: leaf a has half of its
// 2000 points flagged as another piece's, leaf b has no flags. 10 % of the
// 1000 + 3000 unflagged points, none of them a flagged one (before, the
// flags were dropped with a warning: 500 samples, some flagged points).
TEST(CompositeLeaves, GhostFlagsOfSomeLeavesAreHonoured)
{
  vtkSmartPointer<vtkPolyData> a = Leaf(Ball, 0, 2000);
  FlagEveryOther(a, vtkDataSetAttributes::DUPLICATEPOINT);
  auto blocks = Blocks(a, Leaf(Ball, 2000, 5000));
  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    ObservedFilter<vtkASMSimplify> simplify;
    simplify.Filter->SetMode(mode);
    simplify.Filter->SetOutputFraction(0.1);
    simplify.Filter->SetInputData(blocks);
    simplify.Filter->Update();
    vtkPolyData* out = simplify.Filter->GetOutput();
    EXPECT_EQ(simplify.Messages->Warnings, 0) << simplify.Messages->LastMessage;
    ASSERT_EQ(out->GetNumberOfPoints(), 400) << mode;
    vtkDataArray* label = out->GetPointData()->GetArray("Label");
    ASSERT_NE(label, nullptr);
    for (vtkIdType s = 0; s < out->GetNumberOfPoints(); ++s)
    {
      const auto id = static_cast<vtkIdType>(label->GetTuple1(s));
      EXPECT_FALSE(id < 2000 && id % 2 == 1) << "sample " << s << " is flagged point " << id;
    }
  }
}

// vtkKeyPointError's original (port 0) as a composite: its hidden points
// (moved 1 up, out of the way) are skipped as in a vtkPointSet; before, the
// merge of the original's points dropped the flags: 10000 points measured
// instead of 5000, and a Hausdorff distance of 1.01.
TEST(CompositeLeaves, KeyPointErrorSkipsTheFlaggedPointsOfACompositeOriginal)
{
  Cloud moved = Ball;
  for (std::size_t i = 0; i < 2000; i += 2)
  {
    moved[3 * (i + 1) + 2] += 1.0; // the odd points of leaf a
  }
  vtkSmartPointer<vtkPolyData> a = Leaf(moved, 0, 2000);
  FlagEveryOther(a, vtkDataSetAttributes::HIDDENPOINT);
  vtkSmartPointer<vtkPolyData> b = Leaf(moved, 2000, 5000);
  vtkSmartPointer<vtkPolyData> whole = Leaf(moved, 0, 5000);
  FlagEveryOther(whole, 0); // (flags only in the first 2000 below)
  auto* flags = vtkUnsignedCharArray::SafeDownCast(
    whole->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
  for (vtkIdType i = 0; i < 5000; ++i)
  {
    flags->SetValue(i, i < 2000 && i % 2 ? vtkDataSetAttributes::HIDDENPOINT : 0);
  }
  const auto simplified = ToPolyData(Sphere(300, 1.0, 4));
  double hausdorff[2], count[2];
  for (const bool composite : { false, true })
  {
    ObservedFilter<vtkKeyPointError> error;
    if (composite)
    {
      error.Filter->SetInputData(0, Blocks(a, b));
    }
    else
    {
      error.Filter->SetInputData(0, whole);
    }
    error.Filter->SetSimplifiedData(simplified);
    error.Filter->SetGenerateCurvature(false);
    error.Filter->Update();
    vtkTable* figures = error.Filter->GetFiguresOutput();
    hausdorff[composite] =
      figures->GetColumnByName("HausdorffDistance")->GetVariantValue(0).ToDouble();
    count[composite] =
      figures->GetColumnByName("NumberOfOriginalPoints")->GetVariantValue(0).ToDouble();
  }
  EXPECT_EQ(count[0], 4000.0);
  EXPECT_EQ(count[1], 4000.0);
  EXPECT_EQ(hausdorff[0], hausdorff[1]);
  EXPECT_LT(hausdorff[1], 0.5);
}

// A leaf that is not a point set (an image) is left out with a warning that
// names it; the output is the point-set leaf's.
TEST(CompositeLeaves, ALeafThatIsNotAPointSetIsNamed)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(20, 20, 20);
  ObservedFilter<vtkASMSimplify> simplify;
  simplify.Filter->SetOutputFraction(0.1);
  simplify.Filter->SetInputData(Blocks(image, Leaf(Ball, 0, 5000)));
  simplify.Filter->Update();
  EXPECT_EQ(simplify.Filter->GetOutput()->GetNumberOfPoints(), 500);
  EXPECT_EQ(simplify.Messages->Warnings, 1);
  EXPECT_NE(simplify.Messages->LastMessage.find("block 1 (vtkImageData)"), std::string::npos)
    << simplify.Messages->LastMessage;

  ObservedFilter<vtkKeyPointError> error;
  error.Filter->SetInputData(0, Blocks(image, Leaf(Ball, 0, 5000)));
  error.Filter->SetSimplifiedData(simplify.Filter->GetOutput());
  error.Filter->Update();
  EXPECT_EQ(error.Messages->Warnings, 1);
  EXPECT_NE(error.Messages->LastMessage.find("(original, port 0)"), std::string::npos)
    << error.Messages->LastMessage;
}

// Information keys of the input arrays (here vtkDataArray::UNITS_LABEL and
// vtkAbstractArray::GUI_HIDE) reach the output arrays, from a point set and
// from a composite's leaves, in both modes and with snapping.
TEST(CompositeLeaves, ArrayInformationKeysAreKept)
{
  const auto tag = [](vtkPolyData* data) {
    vtkDataArray* label = data->GetPointData()->GetArray("Label");
    label->GetInformation()->Set(vtkDataArray::UNITS_LABEL(), "mm");
    label->GetInformation()->Set(vtkAbstractArray::GUI_HIDE(), 1);
  };
  vtkSmartPointer<vtkPolyData> single = Leaf(Ball, 0, 5000);
  tag(single);
  // An input array named as a generated one, with keys of its own: replaced,
  // its keys not kept.
  vtkNew<vtkIntArray> keyPoint;
  keyPoint->SetName("KeyPoint");
  keyPoint->SetNumberOfTuples(5000);
  keyPoint->Fill(0);
  keyPoint->GetInformation()->Set(vtkDataArray::UNITS_LABEL(), "none");
  single->GetPointData()->AddArray(keyPoint);
  vtkSmartPointer<vtkPolyData> a = Leaf(Ball, 0, 2000), b = Leaf(Ball, 2000, 5000);
  tag(a);
  // The keys of the second leaf only (the first's array has an information
  // object without keys, made by a range query).
  vtkSmartPointer<vtkPolyData> c = Leaf(Ball, 0, 2000), d = Leaf(Ball, 2000, 5000);
  tag(d);
  double range[2];
  c->GetPointData()->GetArray("Label")->GetRange(range);
  ASSERT_TRUE(c->GetPointData()->GetArray("Label")->HasInformation());
  vtkSmartPointer<vtkMultiBlockDataSet> composite = Blocks(a, b), secondOnly = Blocks(c, d);
  for (vtkDataObject* input :
    { static_cast<vtkDataObject*>(single.Get()), static_cast<vtkDataObject*>(composite.Get()),
      static_cast<vtkDataObject*>(secondOnly.Get()) })
  {
    for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
    {
      for (const bool snap : { false, true })
      {
        vtkNew<vtkASMSimplify> simplify;
        simplify->SetMode(mode);
        simplify->SetSnapToInputPoints(snap);
        simplify->SetInputData(input);
        simplify->Update();
        vtkDataArray* label = simplify->GetOutput()->GetPointData()->GetArray("Label");
        ASSERT_NE(label, nullptr);
        ASSERT_TRUE(label->HasInformation()) << mode << snap;
        const char* units = label->GetInformation()->Get(vtkDataArray::UNITS_LABEL());
        EXPECT_STREQ(units ? units : "(none)", "mm") << mode << snap;
        EXPECT_EQ(label->GetInformation()->Get(vtkAbstractArray::GUI_HIDE()), 1) << mode << snap;
        // The generated arrays are not given the input's keys.
        vtkDataArray* generated = simplify->GetOutput()->GetPointData()->GetArray("KeyPoint");
        EXPECT_FALSE(generated->HasInformation() &&
          generated->GetInformation()->Has(vtkDataArray::UNITS_LABEL()));
      }
    }
  }
}
