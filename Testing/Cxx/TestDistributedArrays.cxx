// SPDX-License-Identifier: BSD-3-Clause
// The point-data arrays of vtkASMSimplify's distributed path (one process:
// a vtkDummyController with AlwaysDistribute) against the serial path's:
// string, variant and bit arrays, which do not travel with the points, are
// read at the samples' representatives after the run and give what the
// serial path gives, in the input's order of arrays; an array with fewer
// tuples than points is dropped with a warning on both paths (never read
// past its end); among exact duplicates with the same numbers, the strings
// decide on both paths.
#include "FilterHelpers.h"

#include "vtkBitArray.h"
#include "vtkDummyController.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"
#include "vtkVariantArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <tuple>
#include <vector>

namespace
{
// The name, variant and bit of input point i.
std::string NameOf(vtkIdType i)
{
  return "point " + std::to_string(i);
}
// Variants of every kind, with values that a 6-digit text form would round.
vtkVariant VariantOf(vtkIdType i)
{
  switch (i % 7)
  {
    case 0:
      return vtkVariant("v" + std::to_string(i));
    case 1:
      return vtkVariant(static_cast<int>(i));
    case 2:
      return vtkVariant(1.0 / static_cast<double>(i + 1));
    case 3:
      return vtkVariant(static_cast<float>(i) / 7.0f);
    case 4:
      return vtkVariant((1ULL << 63) + static_cast<unsigned long long>(i));
    case 5:
      return vtkVariant(static_cast<char>('a' + i % 26));
    default:
      return vtkVariant(); // (empty)
  }
}
// The same type and exactly the same value.
bool SameVariant(const vtkVariant& a, const vtkVariant& b)
{
  if (a.IsValid() != b.IsValid() || a.GetType() != b.GetType())
  {
    return false;
  }
  if (!a.IsValid())
  {
    return true;
  }
  if (a.IsString())
  {
    return a.ToString() == b.ToString();
  }
  return a.IsFloat() || a.IsDouble()
    ? a.ToDouble() == b.ToDouble()
    : a.ToUnsignedLongLong() == b.ToUnsignedLongLong() && a.ToLongLong() == b.ToLongLong();
}
int BitOf(vtkIdType i)
{
  return i % 3 == 0 ? 1 : 0;
}

// A sphere with a string, a variant, a two-component bit and a
// two-component string array.
vtkSmartPointer<vtkPolyData> SphereWithArrays()
{
  vtkSmartPointer<vtkPolyData> input = asmtest::ToPolyData(asmtest::Sphere(6000, 1.0, 5));
  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkStringArray> names;
  names->SetName("Point name");
  vtkNew<vtkVariantArray> variants;
  variants->SetName("Variant");
  vtkNew<vtkBitArray> bits;
  bits->SetName("Bits");
  bits->SetNumberOfComponents(2);
  for (vtkIdType i = 0; i < n; ++i)
  {
    names->InsertNextValue(NameOf(i));
    variants->InsertNextValue(VariantOf(i));
    bits->InsertNextValue(BitOf(i));
    bits->InsertNextValue(1 - BitOf(i));
  }
  // (Numeric arrays in between: the output keeps the input's order.)
  vtkNew<vtkFloatArray> intensity;
  intensity->SetName("Intensity");
  vtkNew<vtkIntArray> label;
  label->SetName("Label");
  for (vtkIdType i = 0; i < n; ++i)
  {
    intensity->InsertNextValue(static_cast<float>(i % 100));
    label->InsertNextValue(static_cast<int>(i % 5));
  }
  input->GetPointData()->AddArray(names);
  input->GetPointData()->AddArray(intensity);
  input->GetPointData()->AddArray(variants);
  input->GetPointData()->AddArray(label);
  input->GetPointData()->AddArray(bits);
  // Two strings per point (before 2026-11-29 the serial path copied a
  // string array's values at the representatives' ids as value indices:
  // every tuple of a two-component array was wrong).
  vtkNew<vtkStringArray> pairs;
  pairs->SetName("Name pair");
  pairs->SetNumberOfComponents(2);
  for (vtkIdType i = 0; i < n; ++i)
  {
    pairs->InsertNextValue(NameOf(i));
    pairs->InsertNextValue("second of " + std::to_string(i));
  }
  input->GetPointData()->AddArray(pairs);
  return input;
}

// `input` simplified to 300 points, on the distributed path or not; warnings
// counted.
vtkSmartPointer<vtkPolyData> SimplifyTo300(
  vtkPolyData* input, int mode, bool distributed, int& warnings)
{
  asmtest::FilterRun run;
  vtkNew<vtkDummyController> controller;
  if (distributed)
  {
    run.Filter->SetController(controller);
    run.Filter->AlwaysDistributeOn();
  }
  run.Filter->SetMode(mode);
  run.Count(300);
  vtkSmartPointer<vtkPolyData> out = run.Execute(input);
  warnings = run.Messages->Warnings;
  EXPECT_EQ(run.Messages->Errors, 0);
  EXPECT_EQ(out->GetPointData()->GetArray("vtkOriginalProcessIds") != nullptr, distributed);
  return out;
}
} // namespace

TEST(DistributedArrays, StringVariantAndBitArraysTakeTheRepresentativesValues)
{
  const vtkSmartPointer<vtkPolyData> input = SphereWithArrays();
  for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    // (x, y, z, name) of every sample, sorted: serial and distributed runs.
    using Row = std::tuple<double, double, double, std::string>;
    std::vector<Row> rows[2];
    std::vector<std::string> arrayNames[2]; // (vtkOriginalProcessIds left out)
    for (bool distributed : { false, true })
    {
      const std::string what =
        "mode " + std::to_string(mode) + (distributed ? ", distributed" : "");
      int warnings = 0;
      vtkSmartPointer<vtkPolyData> out = SimplifyTo300(input, mode, distributed, warnings);
      EXPECT_EQ(warnings, 0) << what << ": every array is passed on";
      vtkPointData* pd = out->GetPointData();
      auto* ids = vtkIdTypeArray::SafeDownCast(pd->GetArray("vtkOriginalPointIds"));
      auto* names = vtkStringArray::SafeDownCast(pd->GetAbstractArray("Point name"));
      auto* variants = vtkVariantArray::SafeDownCast(pd->GetAbstractArray("Variant"));
      auto* bits = vtkBitArray::SafeDownCast(pd->GetAbstractArray("Bits"));
      auto* pairs = vtkStringArray::SafeDownCast(pd->GetAbstractArray("Name pair"));
      ASSERT_TRUE(ids && names && variants && bits && pairs) << what;
      ASSERT_EQ(pairs->GetNumberOfComponents(), 2) << what;
      ASSERT_EQ(pairs->GetNumberOfValues(), 600) << what;
      ASSERT_EQ(out->GetNumberOfPoints(), 300) << what;
      ASSERT_EQ(names->GetNumberOfValues(), 300) << what;
      ASSERT_EQ(bits->GetNumberOfComponents(), 2) << what;
      int wrong = 0;
      for (vtkIdType s = 0; s < 300; ++s)
      {
        // The representative's own values, whichever process holds it.
        const vtkIdType id = ids->GetValue(s);
        const vtkVariant v = variants->GetValue(s);
        wrong += names->GetValue(s) != NameOf(id) || !SameVariant(v, VariantOf(id)) ||
            bits->GetValue(2 * s) != BitOf(id) || bits->GetValue(2 * s + 1) != 1 - BitOf(id) ||
            pairs->GetValue(2 * s) != NameOf(id) ||
            pairs->GetValue(2 * s + 1) != "second of " + std::to_string(id)
          ? 1
          : 0;
        double p[3];
        out->GetPoint(s, p);
        rows[distributed].emplace_back(p[0], p[1], p[2], names->GetValue(s));
      }
      EXPECT_EQ(wrong, 0) << what;
      for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
      {
        const std::string name = pd->GetArrayName(a);
        if (name != "vtkOriginalProcessIds")
        {
          arrayNames[distributed].push_back(name);
        }
      }
      std::sort(rows[distributed].begin(), rows[distributed].end());
    }
    EXPECT_EQ(rows[1], rows[0]) << "mode " << mode << ": the distributed run gives the serial one";
    EXPECT_EQ(arrayNames[1], arrayNames[0]) << "mode " << mode << ": arrays in the same order";
    ASSERT_GE(arrayNames[0].size(), 6u);
    EXPECT_EQ(arrayNames[0][0], "Point name");
    EXPECT_EQ(arrayNames[0][4], "Bits");
    EXPECT_EQ(arrayNames[0][5], "Name pair");
  }
}

TEST(DistributedArrays, ArraysShorterThanThePointsAreDroppedOnBothPaths)
{
  vtkSmartPointer<vtkPolyData> input = asmtest::ToPolyData(asmtest::Sphere(6000, 1.0, 7));
  vtkNew<vtkFloatArray> shortArray; // (2 tuples for 6000 points)
  shortArray->SetName("Short");
  shortArray->SetNumberOfTuples(2);
  shortArray->SetValue(0, 1.0f);
  shortArray->SetValue(1, 2.0f);
  input->GetPointData()->AddArray(shortArray);
  vtkNew<vtkStringArray> shortNames;
  shortNames->SetName("Short names");
  shortNames->InsertNextValue("only one");
  input->GetPointData()->AddArray(shortNames);
  for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    for (bool distributed : { false, true })
    {
      const std::string what =
        "mode " + std::to_string(mode) + (distributed ? ", distributed" : "");
      int warnings = 0;
      vtkSmartPointer<vtkPolyData> out = SimplifyTo300(input, mode, distributed, warnings);
      EXPECT_EQ(out->GetNumberOfPoints(), 300) << what;
      EXPECT_EQ(out->GetPointData()->GetAbstractArray("Short"), nullptr) << what;
      EXPECT_EQ(out->GetPointData()->GetAbstractArray("Short names"), nullptr) << what;
      EXPECT_GE(warnings, 1) << what << ": the user is told";
    }
  }
}

TEST(DistributedArrays, AmongDuplicatesTheStringsDecideOnBothPaths)
{
  // Every point twice (ids i and i + n, as merged overlapping scans give),
  // with the same numbers on both copies and different strings: "z..." on
  // the first copy, "a..." on the second. A serial run stands for the copy
  // whose values come first, "a...": so must a distributed run, whose
  // strings do not travel with the points.
  const vtkSmartPointer<vtkPolyData> sphere = asmtest::ToPolyData(asmtest::Sphere(3000, 1.0, 9));
  const vtkIdType n = sphere->GetNumberOfPoints();
  vtkNew<vtkPoints> points;
  vtkNew<vtkStringArray> names;
  names->SetName("Point name");
  vtkNew<vtkIntArray> label;
  label->SetName("Label");
  vtkNew<vtkFloatArray> intensity;
  intensity->SetName("Intensity");
  for (int copy = 0; copy < 2; ++copy)
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      points->InsertNextPoint(sphere->GetPoint(i));
      names->InsertNextValue((copy == 0 ? "z" : "a") + std::to_string(i));
      label->InsertNextValue(static_cast<int>(i % 5));
      intensity->InsertNextValue(static_cast<float>(i % 7));
    }
  }
  vtkNew<vtkPolyData> input;
  input->SetPoints(points);
  input->GetPointData()->AddArray(label);
  input->GetPointData()->AddArray(names);
  input->GetPointData()->AddArray(intensity);
  for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    std::vector<std::pair<vtkIdType, std::string>> rows[2]; // (representative, name)
    for (bool distributed : { false, true })
    {
      const std::string what =
        "mode " + std::to_string(mode) + (distributed ? ", distributed" : "");
      int warnings = 0;
      vtkSmartPointer<vtkPolyData> out = SimplifyTo300(input, mode, distributed, warnings);
      EXPECT_EQ(warnings, 0) << what;
      vtkPointData* pd = out->GetPointData();
      auto* ids = vtkIdTypeArray::SafeDownCast(pd->GetArray("vtkOriginalPointIds"));
      auto* outNames = vtkStringArray::SafeDownCast(pd->GetAbstractArray("Point name"));
      ASSERT_TRUE(ids && outNames) << what;
      ASSERT_EQ(outNames->GetNumberOfValues(), 300) << what;
      int first = 0;
      for (vtkIdType s = 0; s < 300; ++s)
      {
        const vtkIdType id = ids->GetValue(s);
        first += outNames->GetValue(s)[0] == 'a' ? 1 : 0;
        EXPECT_EQ(outNames->GetValue(s), names->GetValue(id)) << what << ", sample " << s;
        rows[distributed].emplace_back(id, outNames->GetValue(s));
      }
      EXPECT_EQ(first, 300) << what << ": every sample stands for the copy named a...";
      std::sort(rows[distributed].begin(), rows[distributed].end());
    }
    EXPECT_EQ(rows[1], rows[0]) << "mode " << mode << ": the distributed run gives the serial one";
  }
}
