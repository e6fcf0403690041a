// SPDX-License-Identifier: BSD-3-Clause
// No lost data: every point-data array type reaches the output of
// vtkASMSimplify (and of vtkKeyPointError's port 0), floating arrays
// averaged, integer and categorical arrays taken from the representative
// point; vtkOriginalPointIds maps back to real input points; field data is
// carried.
#include "FilterHelpers.h"

#include "Core/Simplify.h"
#include "vtkBitArray.h"
#include "vtkCharArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkKeyPointError.h"
#include "vtkLongArray.h"
#include "vtkLongLongArray.h"
#include "vtkPointData.h"
#include "vtkShortArray.h"
#include "vtkSignedCharArray.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedIntArray.h"
#include "vtkUnsignedLongArray.h"
#include "vtkUnsignedLongLongArray.h"
#include "vtkUnsignedShortArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using asmtest::Cloud;
using asmtest::FieldValue;
using asmtest::FilterRun;
using asmtest::ToPolyData;

namespace
{
// The integer value of component c of point i: distinct between
// neighbours, within the range of every type (0 .. 99).
double Label(vtkIdType i, int c)
{
  return static_cast<double>((i * 37 + c * 11) % 100);
}

template <typename ArrayT>
vtkSmartPointer<ArrayT> LabelArray(const char* name, int components, vtkIdType n)
{
  auto a = vtkSmartPointer<ArrayT>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      a->SetComponent(i, c, Label(i, c));
    }
  }
  return a;
}

// A sphere with one array of every type.
vtkSmartPointer<vtkPolyData> CloudWithEveryArrayType(int pointType = VTK_DOUBLE)
{
  const Cloud c = asmtest::Sphere(4000, 1.0, 13);
  auto input = ToPolyData(c, pointType);
  const vtkIdType n = input->GetNumberOfPoints();
  vtkPointData* pd = input->GetPointData();
  pd->AddArray(LabelArray<vtkCharArray>("char", 1, n));
  pd->AddArray(LabelArray<vtkSignedCharArray>("int8", 1, n));
  pd->AddArray(LabelArray<vtkUnsignedCharArray>("uint8", 4, n)); // e.g. RGBA
  pd->AddArray(LabelArray<vtkShortArray>("int16", 1, n));
  pd->AddArray(LabelArray<vtkUnsignedShortArray>("uint16", 2, n));
  pd->AddArray(LabelArray<vtkIntArray>("int32", 1, n));
  pd->AddArray(LabelArray<vtkUnsignedIntArray>("uint32", 1, n));
  pd->AddArray(LabelArray<vtkLongArray>("long", 1, n));
  pd->AddArray(LabelArray<vtkUnsignedLongArray>("ulong", 1, n));
  pd->AddArray(LabelArray<vtkLongLongArray>("int64", 3, n));
  pd->AddArray(LabelArray<vtkUnsignedLongLongArray>("uint64", 1, n));
  pd->AddArray(LabelArray<vtkIdTypeArray>("ids", 1, n));
  pd->AddArray(LabelArray<vtkIntArray>(nullptr, 1, n)); // unnamed
  auto bits = vtkSmartPointer<vtkBitArray>::New();
  bits->SetName("bits");
  bits->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    bits->SetValue(i, static_cast<int>(Label(i, 0)) % 2);
  }
  pd->AddArray(bits);
  auto strings = vtkSmartPointer<vtkStringArray>::New();
  strings->SetName("strings");
  for (vtkIdType i = 0; i < n; ++i)
  {
    strings->InsertNextValue("p" + std::to_string(i));
  }
  pd->AddArray(strings);
  // Floating arrays: functions of the coordinates, so their means are known.
  auto xyzD = vtkSmartPointer<vtkDoubleArray>::New();
  xyzD->SetName("xyz64");
  xyzD->SetNumberOfComponents(3);
  auto xF = vtkSmartPointer<vtkFloatArray>::New();
  xF->SetName("x32");
  auto unnamedF = vtkSmartPointer<vtkFloatArray>::New();
  unnamedF->SetNumberOfComponents(2);
  for (vtkIdType i = 0; i < n; ++i)
  {
    xyzD->InsertNextTuple(c.data() + 3 * i);
    xF->InsertNextValue(static_cast<float>(c[3 * i]));
    unnamedF->InsertNextTuple2(c[3 * i + 1], c[3 * i + 2]);
  }
  pd->AddArray(xyzD);
  pd->AddArray(xF);
  pd->AddArray(unnamedF);
  pd->SetActiveScalars("int32");
  return input;
}

const char* const IntegerArrays[] = { "char", "int8", "uint8", "int16", "uint16", "int32", "uint32",
  "long", "ulong", "int64", "uint64", "ids" };
} // namespace

TEST(NoLostData, EveryArrayTypeIsCarried)
{
  for (int variant = 0; variant < 4; ++variant)
  {
    const bool snap = variant % 2 == 1;
    const bool paper = variant < 2; // centroid positions: means are checkable
    auto input = CloudWithEveryArrayType();
    vtkPointData* inPD = input->GetPointData();
    FilterRun run;
    run.Filter->SetModeToPaper(); // samples are cluster centroids: array means = positions
    run.Count(300);
    run.Filter->SetSnapToInputPoints(snap);
    run.Filter->SetGenerateCurvature(false);
    run.Filter->SetMode(paper ? vtkASMSimplify::PAPER : vtkASMSimplify::FEATURE_PRESERVING);
    vtkPolyData* out = run.Execute(input);
    ASSERT_EQ(out->GetNumberOfPoints(), 300);
    vtkPointData* outPD = out->GetPointData();
    auto* originalIds = vtkIdTypeArray::SafeDownCast(outPD->GetArray("vtkOriginalPointIds"));
    ASSERT_NE(originalIds, nullptr);

    // Same class, components and tuple count for every input array, named
    // or not; the active scalars stay active.
    int unnamedIn = 0, unnamedOut = 0;
    for (int a = 0; a < inPD->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* in = inPD->GetAbstractArray(a);
      if (!in->GetName())
      {
        ++unnamedIn;
        continue;
      }
      vtkAbstractArray* o = outPD->GetAbstractArray(in->GetName());
      ASSERT_NE(o, nullptr) << in->GetName();
      EXPECT_STREQ(o->GetClassName(), in->GetClassName()) << in->GetName();
      EXPECT_EQ(o->GetNumberOfComponents(), in->GetNumberOfComponents()) << in->GetName();
      EXPECT_EQ(o->GetNumberOfTuples(), 300) << in->GetName();
    }
    for (int a = 0; a < outPD->GetNumberOfArrays(); ++a)
    {
      unnamedOut += outPD->GetAbstractArray(a)->GetName() == nullptr;
    }
    EXPECT_EQ(unnamedOut, unnamedIn);
    ASSERT_NE(outPD->GetScalars(), nullptr);
    EXPECT_STREQ(outPD->GetScalars()->GetName(), "int32");

    for (vtkIdType s = 0; s < 300; ++s)
    {
      const vtkIdType id = originalIds->GetValue(s);
      ASSERT_GE(id, 0);
      ASSERT_LT(id, input->GetNumberOfPoints());
      // Integer arrays: the representative's tuple, never an average.
      for (const char* name : IntegerArrays)
      {
        vtkDataArray* o = outPD->GetArray(name);
        for (int c = 0; c < o->GetNumberOfComponents(); ++c)
        {
          ASSERT_EQ(o->GetComponent(s, c), Label(id, c)) << name << " sample " << s;
        }
      }
      EXPECT_EQ(outPD->GetArray("bits")->GetComponent(s, 0), static_cast<int>(Label(id, 0)) % 2);
      EXPECT_EQ(vtkStringArray::SafeDownCast(outPD->GetAbstractArray("strings"))->GetValue(s),
        "p" + std::to_string(id));
      // Floating arrays: the cluster mean (= the position, for coordinates),
      // or the snapped point's value.
      double p[3], mean[3], in[3];
      out->GetPoint(s, p);
      outPD->GetArray("xyz64")->GetTuple(s, mean);
      input->GetPoint(id, in);
      for (int k = 0; k < 3; ++k)
      {
        if (paper && !snap)
        {
          EXPECT_NEAR(mean[k], p[k], 1e-12);
        }
        if (snap)
        {
          EXPECT_EQ(p[k], in[k]) << "snapped points are the input point at vtkOriginalPointIds";
        }
      }
      if (paper || snap)
      {
        EXPECT_NEAR(outPD->GetArray("x32")->GetTuple1(s), snap ? in[0] : p[0], 1e-6);
      }
    }
  }
}

TEST(NoLostData, OriginalPointIdIsAClusterMember)
{
  // In the core: each sample's representative is one of its members, the
  // one nearest the centroid.
  const Cloud c = asmtest::Sphere(3000, 1.0, 4);
  const std::vector<asmcore::Index> ids = asmtest::AllIds(c);
  asmcore::SimplifyParameters parameters;
  parameters.NumberOfSamples = 200;
  const asmcore::SimplifyResult r = asmcore::Simplify(c.data(), ids, nullptr, parameters);
  ASSERT_EQ(r.Samples.size(), 200u);
  for (const asmcore::Sample& s : r.Samples)
  {
    const auto* first = r.Members.data() + s.MemberBegin;
    const auto* last = first + s.ClusterSize;
    ASSERT_NE(std::find(first, last, s.Representative), last);
    const auto dist = [&](asmcore::Index id) {
      return std::hypot(
        c[3 * id] - s.Position[0], c[3 * id + 1] - s.Position[1], c[3 * id + 2] - s.Position[2]);
    };
    for (const auto* m = first; m != last; ++m)
    {
      EXPECT_LE(dist(s.Representative), dist(*m) + 1e-12);
    }
  }
}

TEST(NoLostData, FloatMeansIgnoreNaNAndInfiniteValues)
{
  // A NaN or infinite attribute value (a missing reading, a sensor's "no
  // return") does not poison its cluster.
  const Cloud c = asmtest::Sphere(2000, 1.0, 6);
  auto input = ToPolyData(c);
  vtkNew<vtkDoubleArray> reading;
  reading->SetName("Reading");
  const double inf = std::numeric_limits<double>::infinity();
  const double missing[3] = { std::nan(""), inf, -inf };
  for (vtkIdType i = 0; i < 2000; ++i)
  {
    reading->InsertNextValue(i % 3 == 0 ? missing[(i / 3) % 3] : 5.0);
  }
  input->GetPointData()->AddArray(reading);
  FilterRun run;
  run.Count(100);
  run.Filter->SetGenerateCurvature(false);
  vtkPolyData* out = run.Execute(input);
  vtkDataArray* o = out->GetPointData()->GetArray("Reading");
  auto* sizes = out->GetPointData()->GetArray("ClusterSize");
  for (vtkIdType s = 0; s < 100; ++s)
  {
    if (sizes->GetTuple1(s) >= 3)
    {
      EXPECT_EQ(o->GetTuple1(s), 5.0) << s;
    }
  }
}

// Exact duplicates with different values: a sample takes the values of the
// copy whose values come first, array by array, the numeric ones first (as
// a distributed run compares them; the first array ties here), then the
// string arrays, component by component, by value: strings in byte order,
// NaN after every number. Snapped, so that every array, the floating ones
// too, is taken from the representative; each case with the copies in both
// input orders.
TEST(NoLostData, ExactDuplicatesGiveTheValuesThatComeFirst)
{
  const Cloud unique = asmtest::Sphere(3000, 1.0, 13);
  const vtkIdType n = static_cast<vtkIdType>(unique.size() / 3);
  Cloud twice = unique;
  twice.insert(twice.end(), unique.begin(), unique.end());
  // Per copy: a tie (the same in both), a string, a pair of doubles whose
  // first component ties and whose second is NaN in one copy.
  struct Copy
  {
    const char* Name;
    double Second;
  };
  auto makeInput = [&](const Copy& a, const Copy& b) {
    vtkSmartPointer<vtkPolyData> pd = ToPolyData(twice);
    vtkNew<vtkIntArray> tie;
    tie->SetName("Tie");
    vtkNew<vtkStringArray> names;
    names->SetName("Name");
    vtkNew<vtkDoubleArray> pairs;
    pairs->SetName("Pair");
    pairs->SetNumberOfComponents(2);
    for (vtkIdType i = 0; i < 2 * n; ++i)
    {
      const Copy& c = i < n ? a : b;
      tie->InsertNextValue(7);
      names->InsertNextValue(c.Name);
      pairs->InsertNextTuple2(0.5, c.Second);
    }
    pd->GetPointData()->AddArray(tie);
    pd->GetPointData()->AddArray(names);
    pd->GetPointData()->AddArray(pairs);
    return pd;
  };
  // The copy expected second, then the one expected: the numbers decide
  // (the NaN comes after 1.0), though the string array comes before them in
  // the input, or, when they tie, the strings ("a" before "b").
  const Copy cases[3][2] = { { { "a", std::nan("") }, { "b", 1.0 } },
    { { "a", std::nan("") }, { "a", 1.0 } }, { { "b", 1.0 }, { "a", 1.0 } } };
  for (const auto& pair : cases)
  {
    const Copy& expected = pair[1];
    for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
    {
      for (bool swapped : { false, true })
      {
        FilterRun run;
        run.Count(200);
        run.Filter->SetMode(mode);
        run.Filter->SetSnapToInputPoints(true);
        vtkPolyData* out =
          run.Execute(swapped ? makeInput(pair[1], pair[0]) : makeInput(pair[0], pair[1]));
        ASSERT_EQ(out->GetNumberOfPoints(), 200);
        auto* names = vtkStringArray::SafeDownCast(out->GetPointData()->GetAbstractArray("Name"));
        vtkDataArray* pairs = out->GetPointData()->GetArray("Pair");
        ASSERT_NE(names, nullptr);
        ASSERT_NE(pairs, nullptr);
        int same = 0;
        for (vtkIdType i = 0; i < 200; ++i)
        {
          const double second = pairs->GetComponent(i, 1);
          same += names->GetValue(i) == expected.Name &&
              (std::isnan(second) ? std::isnan(expected.Second) : second == expected.Second)
            ? 1
            : 0;
        }
        EXPECT_EQ(same, 200) << "expected " << expected.Name << ", " << expected.Second << "; mode "
                             << mode << (swapped ? ", swapped" : "");
      }
    }
  }
  // Copies with the same values: the first copy (the lower id) represents.
  for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    for (bool snap : { false, true })
    {
      FilterRun run;
      run.Count(200);
      run.Filter->SetMode(mode);
      run.Filter->SetSnapToInputPoints(snap);
      vtkPolyData* out = run.Execute(makeInput({ "a", 1.0 }, { "a", 1.0 }));
      vtkDataArray* ids = out->GetPointData()->GetArray("vtkOriginalPointIds");
      ASSERT_NE(ids, nullptr);
      for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
      {
        ASSERT_LT(ids->GetTuple1(i), n) << "sample " << i << ", mode " << mode;
      }
    }
  }
  // Snapped, with floating-point arrays only (none taken from the
  // representative otherwise): the values decide too, NaN after 1.0.
  for (bool swapped : { false, true })
  {
    vtkSmartPointer<vtkPolyData> input = swapped ? makeInput({ "a", 1.0 }, { "a", std::nan("") })
                                                 : makeInput({ "a", std::nan("") }, { "a", 1.0 });
    input->GetPointData()->RemoveArray("Tie");
    input->GetPointData()->RemoveArray("Name");
    FilterRun run;
    run.Count(200);
    run.Filter->SetSnapToInputPoints(true);
    vtkPolyData* out = run.Execute(input);
    vtkDataArray* pairs = out->GetPointData()->GetArray("Pair");
    ASSERT_NE(pairs, nullptr);
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      ASSERT_EQ(pairs->GetComponent(i, 1), 1.0) << "sample " << i << (swapped ? ", swapped" : "");
    }
  }
}

TEST(NoLostData, FieldDataIsCarriedAndOurFiguresAdded)
{
  auto input = ToPolyData(asmtest::Sphere(2000, 1.0, 1));
  vtkNew<vtkStringArray> site;
  site->SetName("Site");
  site->InsertNextValue("north quarry");
  vtkNew<vtkIntArray> scanner;
  scanner->SetName("ScannerId");
  scanner->InsertNextValue(42);
  vtkNew<vtkDoubleArray> stale;
  stale->SetName("MKPE"); // e.g. from an earlier simplification
  stale->InsertNextValue(-1.0);
  input->GetFieldData()->AddArray(site);
  input->GetFieldData()->AddArray(scanner);
  input->GetFieldData()->AddArray(stale);

  FilterRun run;
  run.Count(100);
  vtkPolyData* out = run.Execute(input);
  vtkFieldData* fd = out->GetFieldData();
  auto* outSite = vtkStringArray::SafeDownCast(fd->GetAbstractArray("Site"));
  ASSERT_NE(outSite, nullptr);
  EXPECT_EQ(outSite->GetValue(0), "north quarry");
  ASSERT_NE(fd->GetArray("ScannerId"), nullptr);
  EXPECT_EQ(fd->GetArray("ScannerId")->GetTuple1(0), 42.0);
  EXPECT_GE(FieldValue(out, "MKPE"), 0.0) << "our figure replaces the stale one";
  EXPECT_EQ(FieldValue(out, "NumberOfSkippedPoints"), 0.0);
  int mkpeArrays = 0;
  for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
  {
    mkpeArrays += std::string(fd->GetAbstractArray(a)->GetName()) == "MKPE";
  }
  EXPECT_EQ(mkpeArrays, 1);
  EXPECT_EQ(input->GetFieldData()->GetArray("MKPE")->GetTuple1(0), -1.0) << "input untouched";
}

TEST(NoLostData, KeyPointErrorCarriesTheSimplifiedCloudsArrays)
{
  auto original = CloudWithEveryArrayType();
  FilterRun run;
  run.Count(300);
  run.Filter->SetGenerateCurvature(false);
  vtkPolyData* simplified = run.Execute(original);
  vtkNew<vtkIntArray> tag;
  tag->SetName("Tag");
  tag->InsertNextValue(3);
  simplified->GetFieldData()->AddArray(tag);

  vtkNew<vtkKeyPointError> error;
  error->SetInputData(0, original);
  error->SetInputData(1, simplified);
  error->SetGenerateCurvature(false);
  error->Update();
  vtkPolyData* out = error->GetOutput(0);
  ASSERT_EQ(out->GetNumberOfPoints(), 300);
  vtkPointData* inPD = simplified->GetPointData();
  for (int a = 0; a < inPD->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* in = inPD->GetAbstractArray(a);
    if (!in->GetName())
    {
      continue;
    }
    vtkAbstractArray* o = out->GetPointData()->GetAbstractArray(in->GetName());
    ASSERT_NE(o, nullptr) << in->GetName();
    EXPECT_STREQ(o->GetClassName(), in->GetClassName());
    for (vtkIdType t = 0; t < 300; ++t)
    {
      ASSERT_EQ(o->GetVariantValue(t * o->GetNumberOfComponents()).ToString(),
        in->GetVariantValue(t * in->GetNumberOfComponents()).ToString())
        << in->GetName();
    }
  }
  ASSERT_NE(out->GetFieldData()->GetArray("Tag"), nullptr);
  EXPECT_GE(FieldValue(out, "MKPE"), 0.0);
}

// Every attribute role of the input is kept on its array (texture
// coordinates, tensors, global and pedigree ids too, not only the scalars,
// vectors and normals), in both modes.
TEST(NoLostData, EveryAttributeRoleIsKept)
{
  auto input = ToPolyData(asmtest::Sphere(3000, 1.0, 7));
  const vtkIdType n = input->GetNumberOfPoints();
  vtkPointData* pd = input->GetPointData();
  auto tuples = [n](vtkDataArray* a, const char* name, int components) {
    a->SetName(name);
    a->SetNumberOfComponents(components);
    a->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      for (int c = 0; c < components; ++c)
      {
        a->SetComponent(i, c, static_cast<double>(i % 50 + c));
      }
    }
  };
  vtkNew<vtkFloatArray> scalars, vectors, tcoords;
  vtkNew<vtkDoubleArray> tensors;
  vtkNew<vtkIdTypeArray> globalIds, pedigreeIds;
  tuples(scalars, "S", 1);
  tuples(vectors, "V", 3);
  tuples(tcoords, "T", 2);
  tuples(tensors, "Tensor", 9);
  tuples(globalIds, "G", 1);
  for (vtkIdType i = 0; i < n; ++i)
  {
    globalIds->SetValue(i, i); // (global ids are unique)
  }
  tuples(pedigreeIds, "P", 1);
  pd->SetScalars(scalars);
  pd->SetVectors(vectors);
  pd->SetTCoords(tcoords);
  pd->SetTensors(tensors);
  pd->SetGlobalIds(globalIds);
  pd->SetPedigreeIds(pedigreeIds);
  for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    FilterRun run;
    run.Count(200);
    run.Filter->SetMode(mode);
    vtkPointData* out = run.Execute(input)->GetPointData();
    for (int role = 0; role < vtkDataSetAttributes::NUM_ATTRIBUTES; ++role)
    {
      vtkAbstractArray* in = pd->GetAbstractAttribute(role);
      if (!in || role == vtkDataSetAttributes::NORMALS)
      {
        continue;
      }
      vtkAbstractArray* o = out->GetAbstractAttribute(role);
      ASSERT_NE(o, nullptr) << vtkDataSetAttributes::GetAttributeTypeAsString(role) << ", mode "
                            << mode;
      EXPECT_STREQ(o->GetName(), in->GetName()) << mode;
      EXPECT_EQ(o->GetNumberOfTuples(), 200) << mode;
    }
  }
}

// A point given twice, once with z = +0 and once with z = -0, is one point
// given twice (the two compare equal): the values decide between the copies
// ("a" before "b"), whichever copy the grid meets first.
TEST(NoLostData, SignedZeroCopiesAreExactDuplicates)
{
  Cloud plane;
  for (int copy = 0; copy < 2; ++copy)
  {
    for (int i = 0; i < 60; ++i)
    {
      for (int j = 0; j < 60; ++j)
      {
        asmtest::Add(plane, i / 59.0, j / 59.0, copy == 0 ? 0.0 : -0.0);
      }
    }
  }
  auto input = ToPolyData(plane);
  vtkNew<vtkStringArray> names;
  names->SetName("Name");
  for (vtkIdType i = 0; i < 7200; ++i)
  {
    names->InsertNextValue(i < 3600 ? "b" : "a");
  }
  input->GetPointData()->AddArray(names);
  for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    FilterRun run;
    run.Count(200);
    run.Filter->SetMode(mode);
    run.Filter->SetSnapToInputPoints(true);
    vtkPolyData* out = run.Execute(input);
    auto* outNames = vtkStringArray::SafeDownCast(out->GetPointData()->GetAbstractArray("Name"));
    ASSERT_NE(outNames, nullptr);
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      ASSERT_EQ(outNames->GetValue(i), "a") << "sample " << i << ", mode " << mode;
    }
  }
}
