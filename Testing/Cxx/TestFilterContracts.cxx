// SPDX-License-Identifier: BSD-3-Clause
// Pipeline contracts of both filters: the inputs are left unmodified, and
// re-executing with changed parameters gives what a fresh filter gives.
#include "FilterHelpers.h"

#include "vtkASMFilterUtilities.h"
#include "vtkASMSimplify.h"
#include "vtkASMSimplifySteps.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkKeyPointError.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

using asmtest::Cloud;
using asmtest::ToPolyData;

namespace
{
// Content of an array as strings (exact, whatever the type).
void ExpectSameArray(vtkAbstractArray* a, vtkAbstractArray* b, const std::string& what)
{
  ASSERT_NE(a, nullptr) << what;
  ASSERT_NE(b, nullptr) << what;
  EXPECT_STREQ(a->GetClassName(), b->GetClassName()) << what;
  ASSERT_EQ(a->GetNumberOfComponents(), b->GetNumberOfComponents()) << what;
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples()) << what;
  auto* da = vtkDataArray::SafeDownCast(a);
  auto* db = vtkDataArray::SafeDownCast(b);
  const vtkIdType values = a->GetNumberOfValues();
  for (vtkIdType v = 0; v < values; ++v)
  {
    if (da && db)
    {
      const double x =
        da->GetComponent(v / a->GetNumberOfComponents(), v % a->GetNumberOfComponents());
      const double y =
        db->GetComponent(v / a->GetNumberOfComponents(), v % a->GetNumberOfComponents());
      ASSERT_TRUE(std::memcmp(&x, &y, sizeof(double)) == 0) << what << " value " << v;
    }
    else
    {
      ASSERT_EQ(a->GetVariantValue(v).ToString(), b->GetVariantValue(v).ToString())
        << what << " value " << v;
    }
  }
}

void ExpectSameFields(vtkFieldData* a, vtkFieldData* b, const std::string& what)
{
  ASSERT_EQ(a->GetNumberOfArrays(), b->GetNumberOfArrays()) << what;
  for (int i = 0; i < a->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* x = a->GetAbstractArray(i);
    const std::string name = x->GetName() ? x->GetName() : "";
    vtkAbstractArray* y = x->GetName() ? b->GetAbstractArray(x->GetName()) : b->GetAbstractArray(i);
    ExpectSameArray(x, y, what + " " + name);
  }
}

// Points, point data (with attribute roles), field data and vertices.
void ExpectSameData(vtkPointSet* a, vtkPointSet* b, const std::string& what)
{
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints()) << what;
  if (a->GetNumberOfPoints() > 0)
  {
    ExpectSameArray(a->GetPoints()->GetData(), b->GetPoints()->GetData(), what + " points");
  }
  ExpectSameFields(a->GetPointData(), b->GetPointData(), what + " point data");
  for (int attribute = 0; attribute < vtkDataSetAttributes::NUM_ATTRIBUTES; ++attribute)
  {
    vtkAbstractArray* x = a->GetPointData()->GetAbstractAttribute(attribute);
    vtkAbstractArray* y = b->GetPointData()->GetAbstractAttribute(attribute);
    ASSERT_EQ(x == nullptr, y == nullptr) << what << " attribute " << attribute;
    if (x && x->GetName())
    {
      EXPECT_STREQ(x->GetName(), y->GetName()) << what << " attribute " << attribute;
    }
  }
  ExpectSameFields(a->GetFieldData(), b->GetFieldData(), what + " field data");
  ASSERT_EQ(a->GetNumberOfCells(), b->GetNumberOfCells()) << what;
}

// A cloud with attributes of several kinds, normals and field data.
vtkSmartPointer<vtkPolyData> RichCloud(unsigned seed)
{
  const Cloud c = asmtest::Sphere(3000, 1.0, seed);
  auto input = ToPolyData(c, VTK_FLOAT);
  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  vtkNew<vtkIntArray> label;
  label->SetName("Label");
  vtkNew<vtkStringArray> name;
  name->SetName("Name");
  for (vtkIdType i = 0; i < n; ++i)
  {
    normals->InsertNextTuple(c.data() + 3 * i);
    rgb->InsertNextTuple3(i % 256, (i * 3) % 256, 7);
    label->InsertNextValue(static_cast<int>(i % 5));
    name->InsertNextValue(std::to_string(i));
  }
  input->GetPointData()->SetNormals(normals);
  input->GetPointData()->SetScalars(rgb);
  input->GetPointData()->AddArray(label);
  input->GetPointData()->AddArray(name);
  vtkNew<vtkStringArray> site;
  site->SetName("Site");
  site->InsertNextValue("lab");
  input->GetFieldData()->AddArray(site);
  return input;
}

using Setter = std::function<void(vtkASMSimplify*)>;

const std::vector<std::pair<std::string, Setter>>& Variants()
{
  static const std::vector<std::pair<std::string, Setter>> variants = {
    { "defaults", [](vtkASMSimplify*) {} },
    { "count",
      [](vtkASMSimplify* f) {
        f->SetTargetModeToNumberOfOutputPoints();
        f->SetNumberOfOutputPoints(333);
      } },
    { "snap+tolerance",
      [](vtkASMSimplify* f) {
        f->SetSnapToInputPoints(true);
        f->SetErrorTolerance(0.01);
      } },
    { "cell+alpha+seed",
      [](vtkASMSimplify* f) {
        f->SetCellSize(0.3);
        f->SetAlpha(0.3);
        f->SetRandomSeed(9);
      } },
    { "weight+double+nocurvature",
      [](vtkASMSimplify* f) {
        f->SetWeightMode(vtkASMSimplify::SURFACE_VARIATION_WEIGHT);
        f->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
        f->SetGenerateCurvature(false);
        f->SetOutputFraction(0.2);
      } },
  };
  return variants;
}
} // namespace

TEST(FilterContracts, ASMSimplifyLeavesItsInputUnmodified)
{
  for (const auto& variant : Variants())
  {
    auto input = RichCloud(3);
    vtkNew<vtkPolyData> copy;
    copy->DeepCopy(input);
    vtkNew<vtkASMSimplify> filter;
    variant.second(filter);
    filter->SetInputData(input);
    filter->Update();
    ASSERT_GT(filter->GetOutput()->GetNumberOfPoints(), 0) << variant.first;
    ExpectSameData(input, copy, "input after " + variant.first);
    // Changing the output does not reach the input either.
    filter->GetOutput()->GetPointData()->GetArray("Label")->SetComponent(0, 0, -5);
    ExpectSameData(input, copy, "input after editing the output, " + variant.first);
  }
}

TEST(FilterContracts, KeyPointErrorLeavesItsInputsUnmodified)
{
  auto original = RichCloud(3);
  vtkNew<vtkASMSimplify> simplify;
  simplify->SetInputData(original);
  simplify->Update();
  vtkNew<vtkPolyData> simplified;
  simplified->DeepCopy(simplify->GetOutput());
  vtkNew<vtkPolyData> originalCopy, simplifiedCopy;
  originalCopy->DeepCopy(original);
  simplifiedCopy->DeepCopy(simplified);
  vtkNew<vtkKeyPointError> error;
  error->SetInputData(0, original);
  error->SetInputData(1, simplified);
  error->Update();
  ASSERT_EQ(error->GetOutput(0)->GetNumberOfPoints(), simplified->GetNumberOfPoints());
  ExpectSameData(original, originalCopy, "original");
  ExpectSameData(simplified, simplifiedCopy, "simplified");
  // The output's new arrays are its own.
  EXPECT_EQ(simplified->GetPointData()->GetArray("Error"), nullptr);
  EXPECT_EQ(simplified->GetFieldData()->GetArray("HausdorffDistance"), nullptr);
}

TEST(FilterContracts, ReExecutionEqualsAFreshRun)
{
  auto input = RichCloud(5);
  const auto& variants = Variants();
  for (std::size_t a = 0; a < variants.size(); ++a)
  {
    const std::size_t b = (a + 1) % variants.size();
    // Run with A, then change to B and run again...
    vtkNew<vtkASMSimplify> reused;
    variants[a].second(reused);
    reused->SetInputData(input);
    reused->Update();
    vtkNew<vtkASMSimplify> defaults; // back to the defaults, then B
    reused->SetTargetMode(defaults->GetTargetMode());
    reused->SetOutputFraction(defaults->GetOutputFraction());
    reused->SetNumberOfOutputPoints(defaults->GetNumberOfOutputPoints());
    reused->SetSnapToInputPoints(defaults->GetSnapToInputPoints());
    reused->SetErrorTolerance(defaults->GetErrorTolerance());
    reused->SetCellSize(defaults->GetCellSize());
    reused->SetAlpha(defaults->GetAlpha());
    reused->SetRandomSeed(defaults->GetRandomSeed());
    reused->SetWeightMode(defaults->GetWeightMode());
    reused->SetOutputPointsPrecision(defaults->GetOutputPointsPrecision());
    reused->SetGenerateCurvature(defaults->GetGenerateCurvature());
    variants[b].second(reused);
    reused->Update();
    // ... and compare with a fresh filter run with B only.
    vtkNew<vtkASMSimplify> fresh;
    variants[b].second(fresh);
    fresh->SetInputData(input);
    fresh->Update();
    ExpectSameData(
      reused->GetOutput(), fresh->GetOutput(), variants[a].first + " then " + variants[b].first);
  }
  // A modified input (same object) re-executes too.
  vtkNew<vtkASMSimplify> filter;
  filter->SetInputData(input);
  filter->Update();
  double before[3];
  filter->GetOutput()->GetPoint(0, before);
  input->DeepCopy(RichCloud(6));
  input->Modified();
  filter->Update();
  double after[3];
  filter->GetOutput()->GetPoint(0, after);
  EXPECT_NE(before[0], after[0]);
  vtkNew<vtkASMSimplify> fresh;
  fresh->SetInputData(input);
  fresh->Update();
  ExpectSameData(filter->GetOutput(), fresh->GetOutput(), "after modifying the input");
}

TEST(FilterContracts, KeyPointErrorReExecutionEqualsAFreshRun)
{
  auto original = RichCloud(7);
  vtkNew<vtkASMSimplify> simplify;
  simplify->SetInputData(original);
  simplify->Update();
  vtkPolyData* simplified = simplify->GetOutput();

  vtkNew<vtkKeyPointError> reused;
  reused->SetInputData(0, original);
  reused->SetInputData(1, simplified);
  reused->Update();
  reused->SetAlpha(0.3);
  reused->SetCellSize(0.25);
  reused->SetDistanceMeasure(vtkKeyPointError::SQUARED_DISTANCE);
  reused->SetPlaneNeighbors(5);
  reused->Update();

  vtkNew<vtkKeyPointError> fresh;
  fresh->SetInputData(0, original);
  fresh->SetInputData(1, simplified);
  fresh->SetAlpha(0.3);
  fresh->SetCellSize(0.25);
  fresh->SetDistanceMeasure(vtkKeyPointError::SQUARED_DISTANCE);
  fresh->SetPlaneNeighbors(5);
  fresh->Update();
  ExpectSameData(reused->GetOutput(0), fresh->GetOutput(0), "port 0");
  vtkTable* x = vtkTable::SafeDownCast(reused->GetOutputDataObject(1));
  vtkTable* y = vtkTable::SafeDownCast(fresh->GetOutputDataObject(1));
  ASSERT_NE(x, nullptr);
  ASSERT_NE(y, nullptr);
  ExpectSameFields(x->GetRowData(), y->GetRowData(), "table");
}

// The threading tests (RunForEachThreading) run every threaded backend this
// VTK has, so they cover the one it uses by default (TBB in Debian's VTK 9.1,
// Sequential in ParaView 5.11's VTK 9.2).
TEST(FilterContracts, ThreadingTestsCoverTheDefaultBackend)
{
  const std::string backend = vtkSMPTools::GetBackend();
  const std::vector<std::string> threaded = asmtest::ThreadedSMPBackends();
  std::string list;
  for (const std::string& name : threaded)
  {
    list += " " + name;
  }
  RecordProperty("ThreadedBackends", list);
  std::cout << "vtkSMPTools backend " << backend << "; threaded backends:" << list << "\n";
  ASSERT_FALSE(threaded.empty());
  EXPECT_TRUE(backend == "Sequential" ||
    std::find(threaded.begin(), threaded.end(), backend) != threaded.end())
    << backend;
  const std::vector<asmtest::ThreadingRun> runs =
    asmtest::RunForEachThreading([]() { return std::vector<double>{ 1.0 }; });
  EXPECT_EQ(runs.size(), 2 * threaded.size());
  EXPECT_TRUE(asmtest::SameOutputs(runs));
  EXPECT_EQ(vtkSMPTools::GetBackend(), backend); // restored
}

// Small clouds run on the calling thread (MinimumPointsForThreads): the
// helpers the filter runs its loops through either hand the whole range to
// the calling thread or go through vtkSMPTools.
TEST(FilterContracts, SmallCloudsRunOnTheCallingThread)
{
  vtkNew<vtkASMSimplify> filter;
  EXPECT_EQ(filter->GetMinimumPointsForThreads(), -1); // automatic
  filter->SetMinimumPointsForThreads(-5);
  EXPECT_EQ(filter->GetMinimumPointsForThreads(), -1);
  filter->SetMinimumPointsForThreads(1234);
  EXPECT_EQ(asmvtk::MinimumPointsForThreads(filter->GetMinimumPointsForThreads()), 1234);
  vtkNew<vtkKeyPointError> error; // the same property, the same rule
  EXPECT_EQ(error->GetMinimumPointsForThreads(), -1);
  error->SetMinimumPointsForThreads(-7);
  EXPECT_EQ(error->GetMinimumPointsForThreads(), -1);

  asmtest::SMPScope restore;
  // Automatic: 50000 with STDThread (threads started anew in every loop), 0
  // with the backends that keep theirs.
  for (const std::string& backend : asmtest::ThreadedSMPBackends())
  {
    ASSERT_TRUE(vtkSMPTools::SetBackend(backend.c_str()));
    const vtkIdType automatic = backend == "STDThread" ? 50000 : 0;
    EXPECT_EQ(asmvtk::MinimumPointsForThreads(-1), automatic) << backend;
    EXPECT_EQ(asmvtk::DescribeMinimumPointsForThreads(-1),
      "-1 (automatic: " + std::to_string(automatic) + " with the " + backend + " backend)");
  }
  ASSERT_TRUE(vtkSMPTools::SetBackend("STDThread"));
  vtkSMPTools::Initialize(2);
  const std::thread::id caller = std::this_thread::get_id();
  for (bool threads : { false, true })
  {
    std::mutex lock;
    std::vector<std::pair<vtkIdType, vtkIdType>> ranges;
    bool otherThread = false;
    auto record = [&](vtkIdType b, vtkIdType e) {
      std::lock_guard<std::mutex> guard(lock);
      ranges.emplace_back(b, e);
      otherThread = otherThread || std::this_thread::get_id() != caller;
    };
    asmvtk::For(threads, 0, 100000, record);
    std::sort(ranges.begin(), ranges.end());
    ASSERT_FALSE(ranges.empty());
    EXPECT_EQ(ranges.front().first, 0);
    EXPECT_EQ(ranges.back().second, 100000);
    for (std::size_t k = 1; k < ranges.size(); ++k)
    {
      EXPECT_EQ(ranges[k].first, ranges[k - 1].second); // a partition of the range
    }
    if (!threads)
    {
      EXPECT_EQ(ranges.size(), 1u);
      EXPECT_FALSE(otherThread);
    }
    else
    {
      EXPECT_GT(ranges.size(), 1u); // vtkSMPTools cut it
    }
    const asmcore::Execution execution = asmvtk::SMPExecution(filter, 0.0, 1.0, threads);
    EXPECT_EQ(static_cast<bool>(execution.For), threads);
  }
  // With one vtkSMPTools thread the calling thread runs every loop itself
  // (VTK 9.2's STDThread backend would start a thread for it and wait).
  vtkSMPTools::Initialize(1);
  {
    std::vector<std::pair<vtkIdType, vtkIdType>> ranges;
    bool otherThread = false;
    asmvtk::For(true, 0, 100000, [&](vtkIdType b, vtkIdType e) {
      ranges.emplace_back(b, e);
      otherThread = otherThread || std::this_thread::get_id() != caller;
    });
    EXPECT_EQ(ranges, (std::vector<std::pair<vtkIdType, vtkIdType>>{ { 0, 100000 } }));
    EXPECT_FALSE(otherThread);
    EXPECT_FALSE(asmvtk::SMPExecution(filter, 0.0, 1.0, true).For);
  }
}

// The core's loops without a parallel For run on the calling thread in a
// few consecutive pieces (as vtkSMPTools cuts a loop for one thread), so
// that scratch kept per piece stays a fraction of the range.
TEST(FilterContracts, SequentialLoopsRunInPieces)
{
  const asmcore::Execution sequential;
  auto piecesOf = [&](asmcore::Index begin, asmcore::Index end) {
    std::vector<std::pair<asmcore::Index, asmcore::Index>> pieces;
    sequential.Run(
      begin, end, [&](asmcore::Index b, asmcore::Index e) { pieces.emplace_back(b, e); });
    return pieces;
  };
  using Pieces = std::vector<std::pair<asmcore::Index, asmcore::Index>>;
  EXPECT_EQ(piecesOf(10, 110), (Pieces{ { 10, 35 }, { 35, 60 }, { 60, 85 }, { 85, 110 } }));
  EXPECT_EQ(piecesOf(0, 3), (Pieces{ { 0, 1 }, { 1, 2 }, { 2, 3 } }));
  EXPECT_EQ(piecesOf(7, 14), (Pieces{ { 7, 8 }, { 8, 10 }, { 10, 12 }, { 12, 14 } }));
  EXPECT_TRUE(piecesOf(5, 5).empty());
}

// Every property of vtkASMSimplify that the core reads reaches it as set:
// each switch turned on alone turns on its own parameter only, and each
// value away from its default arrives as set (a property read from the
// wrong getter, or not passed on, shows).
TEST(FilterContracts, EveryPropertyReachesTheCore)
{
  struct Switch
  {
    void (vtkASMSimplify::*Set)(bool);
    bool asmcore::SimplifyParameters::*Field;
  };
  using P = asmcore::SimplifyParameters;
  const Switch switches[] = { { &vtkASMSimplify::SetValidateKeyPoints, &P::ValidateKeyPoints },
    { &vtkASMSimplify::SetInPlaneKeyPoints, &P::InPlaneKeyPoints },
    { &vtkASMSimplify::SetExtremeKeyPoints, &P::ExtremeKeyPoints },
    { &vtkASMSimplify::SetCoverEveryCell, &P::CoverEveryCell },
    { &vtkASMSimplify::SetInputPointSamples, &P::InputPointSamples },
    { &vtkASMSimplify::SetFillHoles, &P::FillHoles },
    { &vtkASMSimplify::SetReserveFreeSample, &P::ReserveFreeSample },
    { &vtkASMSimplify::SetSparseCellKeyPoints, &P::SparseCellKeyPoints },
    { &vtkASMSimplify::SetBoundSnappedHoles, &P::BoundSnappedHoles },
    { &vtkASMSimplify::SetSnapToInputPoints, &P::Snap } };
  vtkNew<vtkASMSimplify> f;
  for (const Switch& on : switches)
  {
    for (const Switch& s : switches)
    {
      (f.GetPointer()->*s.Set)(&s == &on);
    }
    const P p = asmvtk::CoreParameters(f, 123);
    for (const Switch& s : switches)
    {
      EXPECT_EQ(p.*s.Field, &s == &on)
        << "switch " << (&on - switches) << ", parameter " << (&s - switches);
    }
  }
  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    f->SetMode(mode);
    f->SetWeightMode(mode == vtkASMSimplify::PAPER ? vtkASMSimplify::UNIFORM_WEIGHT
                                                   : vtkASMSimplify::SURFACE_VARIATION_WEIGHT);
    f->SetCellSize(0.125);
    f->SetSamplesPerCell(3.5);
    f->SetCurvatureWeight(2.5);
    f->SetBudgetExponent(0.25);
    f->SetFeatureSamplesPerCell(1.75);
    f->SetVariationBudget(0.3);
    f->SetVariationCap(5.5);
    f->SetAlpha(0.2);
    f->SetErrorTolerance(0.01);
    f->SetRandomSeed(77);
    f->SetKeyPointRadius(0.45);
    f->SetKeyPointProminence(0.15);
    f->SetLloydIterations(7);
    f->SetCrossCellIterations(3);
    f->SetHoleFillFraction(0.2);
    f->SetFinalLloydIterations(5);
    f->SetLloydVariationWeight(1.25);
    f->SetCoveringRounds(3);
    const P p = asmvtk::CoreParameters(f, 123);
    EXPECT_EQ(p.Mode,
      mode == vtkASMSimplify::PAPER ? asmcore::SimplifyMode::Paper
                                    : asmcore::SimplifyMode::FeaturePreserving);
    EXPECT_EQ(p.Weight,
      mode == vtkASMSimplify::PAPER ? asmcore::WeightMode::Uniform
                                    : asmcore::WeightMode::SurfaceVariation);
    EXPECT_EQ(p.NumberOfSamples, 123);
    EXPECT_EQ(p.CellSize, 0.125);
    EXPECT_EQ(p.SamplesPerCell, 3.5);
    EXPECT_EQ(p.CurvatureWeight, 2.5);
    EXPECT_EQ(p.BudgetExponent, 0.25);
    EXPECT_EQ(p.FeatureSamplesPerCell, 1.75);
    EXPECT_EQ(p.VariationBudget, 0.3);
    EXPECT_EQ(p.VariationCap, 5.5);
    EXPECT_EQ(p.Alpha, 0.2);
    EXPECT_EQ(p.ErrorTolerance, 0.01);
    EXPECT_EQ(p.RandomSeed, 77u);
    EXPECT_EQ(p.KeyPointRadius, 0.45);
    EXPECT_EQ(p.KeyPointProminence, 0.15);
    EXPECT_EQ(p.LloydIterations, 7);
    EXPECT_EQ(p.CrossCellIterations, 3);
    EXPECT_EQ(p.HoleFillFraction, 0.2);
    EXPECT_EQ(p.FinalLloydIterations, 5);
    EXPECT_EQ(p.LloydVariationWeight, 1.25);
    EXPECT_EQ(p.CoveringRounds, 3);
  }
}
