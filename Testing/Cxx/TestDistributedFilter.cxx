// SPDX-License-Identifier: BSD-3-Clause
// vtkASMSimplify's distributed path (vtkASMDistributed.h) on one process: a
// vtkDummyController with AlwaysDistribute. Points flagged as duplicates of
// another process's points (vtkGhostType & DUPLICATEPOINT) are skipped: the
// output is that of the cloud without them, each point counted once. And
// the canonical order of the redistributed points makes the output
// independent of the input order, bit for bit.
#include "FilterHelpers.h"

#include "vtkCallbackCommand.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkDummyController.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkSOADataArrayTemplate.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace
{
struct Output
{
  std::vector<std::array<double, 3>> Points; // sorted
  double Members = 0.0;                      // ClusterSize summed
};

// A filter that takes the distributed path on one process (every option at
// its default: Fill Holes gathers over the one process).
vtkSmartPointer<vtkASMSimplify> DistributedFilter(int mode)
{
  vtkNew<vtkDummyController> controller;
  auto filter = vtkSmartPointer<vtkASMSimplify>::New();
  filter->SetController(controller); // (the filter holds it)
  filter->AlwaysDistributeOn();
  filter->SetMode(mode);
  return filter;
}

// `input` simplified to `count` points on the distributed path.
vtkSmartPointer<vtkPolyData> SimplifyTo(vtkPolyData* input, int mode, vtkIdType count)
{
  vtkSmartPointer<vtkASMSimplify> asm_ = DistributedFilter(mode);
  asm_->SetTargetModeToNumberOfOutputPoints();
  asm_->SetNumberOfOutputPoints(count);
  asm_->SetInputData(input);
  asm_->Update();
  return asm_->GetOutput();
}

// The output's points with the first component of array `name`, as
// (x, y, z, value) rows, sorted (none when the array is missing).
std::vector<std::array<double, 4>> SortedRows(vtkPolyData* out, const char* name)
{
  std::vector<std::array<double, 4>> result;
  vtkDataArray* value = out->GetPointData()->GetArray(name);
  for (vtkIdType i = 0; value && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    result.push_back({ p[0], p[1], p[2], value->GetTuple1(i) });
  }
  std::sort(result.begin(), result.end());
  return result;
}

Output Simplify(vtkPolyData* input, int mode)
{
  vtkSmartPointer<vtkPolyData> out = SimplifyTo(input, mode, 400);
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
    withCopies.insert(
      withCopies.end(), { cloud[3 * i] + 1e-3, cloud[3 * i + 1], cloud[3 * i + 2] });
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

// The distributed path puts each process's points in a canonical order
// (cell, then x, y, z, then the arrays' bytes), so the output does not
// depend on the input order, to the last bit: here on a lattice in x (every
// cell holds many points of equal x, ordered by y and z) with a point array
// averaged over the clusters.
TEST(DistributedFilter, CanonicalOrderMakesTheOutputIndependentOfInputOrder)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = 20000;
  std::vector<std::array<double, 4>> rows(n); // x y z value
  for (auto& r : rows)
  {
    r = { std::floor(u(rng) * 40.0) / 40.0, u(rng), 0.2 * std::sin(6.0 * u(rng)), u(rng) };
  }
  auto makeInput = [](const std::vector<std::array<double, 4>>& rows) {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkDoubleArray> value;
    value->SetName("Value");
    for (const auto& r : rows)
    {
      points->InsertNextPoint(r[0], r[1], r[2]);
      value->InsertNextValue(r[3]);
    }
    auto pd = vtkSmartPointer<vtkPolyData>::New();
    pd->SetPoints(points);
    pd->GetPointData()->AddArray(value);
    return pd;
  };
  auto simplify = [](vtkPolyData* input, int mode) {
    return SortedRows(SimplifyTo(input, mode, 500), "Value");
  };
  vtkSmartPointer<vtkPolyData> forward = makeInput(rows);
  std::shuffle(rows.begin(), rows.end(), rng);
  vtkSmartPointer<vtkPolyData> shuffled = makeInput(rows);
  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    const auto a = simplify(forward, mode);
    const auto b = simplify(shuffled, mode);
    ASSERT_EQ(a.size(), 500u) << "mode " << mode;
    EXPECT_EQ(a, b) << "mode " << mode;
  }
}

// Every point scanned twice with a different label (merged scans): the
// label a sample takes is that of the duplicate whose values come first (5,
// not 256: by value, not by the values' bytes or the points' ids), on the
// serial and the distributed path, whichever copy comes first in the input,
// with and without snapping.
TEST(DistributedFilter, ExactDuplicatesGiveTheirFirstValuesWhateverTheOrder)
{
  const asmtest::Cloud unique = asmtest::Sphere(6000, 1.0, 11);
  auto makeInput = [&unique](int firstLabel, int secondLabel) {
    asmtest::Cloud twice = unique;
    twice.insert(twice.end(), unique.begin(), unique.end());
    vtkSmartPointer<vtkPolyData> pd = asmtest::ToPolyData(twice);
    vtkNew<vtkIntArray> label;
    label->SetName("Label");
    const vtkIdType n = static_cast<vtkIdType>(unique.size() / 3);
    label->SetNumberOfTuples(2 * n);
    for (vtkIdType i = 0; i < 2 * n; ++i)
    {
      label->SetValue(i, i < n ? firstLabel : secondLabel);
    }
    pd->GetPointData()->AddArray(label);
    return pd;
  };
  const vtkSmartPointer<vtkPolyData> inputs[2] = { makeInput(256, 5), makeInput(5, 256) };
  using Row = std::array<double, 4>; // x y z label
  auto rows = [](vtkPolyData* out) {
    EXPECT_NE(out->GetPointData()->GetArray("Label"), nullptr);
    return SortedRows(out, "Label");
  };
  for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    for (bool snap : { false, true })
    {
      std::vector<std::vector<Row>> runs;
      for (bool distributed : { false, true })
      {
        for (vtkPolyData* input : inputs)
        {
          vtkSmartPointer<vtkASMSimplify> asm_ =
            distributed ? DistributedFilter(mode) : vtkSmartPointer<vtkASMSimplify>::New();
          asm_->SetMode(mode);
          asm_->SetSnapToInputPoints(snap);
          asm_->SetTargetModeToNumberOfOutputPoints();
          asm_->SetNumberOfOutputPoints(300);
          asm_->SetInputData(input);
          asm_->Update();
          runs.push_back(rows(asm_->GetOutput()));
        }
      }
      const std::string what = "mode " + std::to_string(mode) + (snap ? ", snapped" : "");
      ASSERT_EQ(runs[0].size(), 300u) << what;
      const auto fives =
        std::count_if(runs[0].begin(), runs[0].end(), [](const Row& r) { return r[3] == 5.0; });
      EXPECT_EQ(fives, 300) << what;
      for (std::size_t r = 1; r < runs.size(); ++r)
      {
        EXPECT_EQ(runs[r], runs[0]) << what << ", run " << r << " (serial, serial swapped, "
                                    << "distributed, distributed swapped)";
      }
    }
  }
}

// A distributed run reports its progress in order (the preparation first,
// then the core from 0.2), up to 1.
TEST(DistributedFilter, ProgressIsMonotonic)
{
  const asmtest::Cloud cloud = asmtest::Sphere(20000, 1.0, 4);
  vtkSmartPointer<vtkPolyData> input = asmtest::ToPolyData(cloud);
  for (int mode : { vtkASMSimplify::FEATURE_PRESERVING, vtkASMSimplify::PAPER })
  {
    vtkSmartPointer<vtkASMSimplify> asm_ = DistributedFilter(mode);
    asm_->SetOutputFraction(0.05);
    asm_->SetInputData(input);
    std::vector<double> reported;
    vtkNew<vtkCallbackCommand> observer;
    observer->SetClientData(&reported);
    observer->SetCallback([](vtkObject*, unsigned long, void* client, void* data) {
      static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(data));
    });
    asm_->AddObserver(vtkCommand::ProgressEvent, observer);
    asm_->Update();
    ASSERT_GE(reported.size(), 3u) << "mode " << mode;
    EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end())) << "mode " << mode;
    EXPECT_EQ(reported.back(), 1.0) << "mode " << mode;
    EXPECT_NE(std::find(reported.begin(), reported.end(), 0.2), reported.end())
      << "mode " << mode << ": the preparation's end";
  }
}

// The distributed path's preparation (the boxes' histograms, the records
// written by blocks of points, the received points grouped and sorted cell
// by cell) runs on threads too: the output is the same, value for value and
// in the same order, at 1 and 2 threads. 200 000 points: several blocks.
TEST(DistributedFilter, SameOutputAtOneAndTwoThreads)
{
  const asmtest::Cloud cloud = asmtest::Sphere(200000, 1.0, 6);
  vtkSmartPointer<vtkPolyData> input = asmtest::ToPolyData(cloud);
  vtkNew<vtkDoubleArray> value;
  value->SetName("Value");
  value->SetNumberOfComponents(2);
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    value->InsertNextTuple2(cloud[3 * i] * 10.0 + cloud[3 * i + 1], static_cast<double>(i));
  }
  input->GetPointData()->AddArray(value);
  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    const std::vector<asmtest::ThreadingRun> runs = asmtest::RunForEachThreading([&]() {
      vtkSmartPointer<vtkASMSimplify> asm_ = DistributedFilter(mode);
      asm_->SetMinimumPointsForThreads(0);
      asm_->SetOutputFraction(0.02);
      asm_->SetInputData(input);
      asm_->Update();
      vtkPolyData* out = asm_->GetOutput();
      vtkDataArray* averaged = out->GetPointData()->GetArray("Value");
      std::vector<double> flat;
      EXPECT_NE(averaged, nullptr);
      for (vtkIdType i = 0; averaged && i < out->GetNumberOfPoints(); ++i)
      {
        double p[3];
        out->GetPoint(i, p);
        flat.insert(flat.end(), p, p + 3);
        flat.push_back(averaged->GetComponent(i, 0));
        flat.push_back(averaged->GetComponent(i, 1));
      }
      return flat;
    });
    ASSERT_FALSE(runs.empty());
    ASSERT_EQ(runs[0].Output.size(), 5u * 4000u) << "mode " << mode;
    EXPECT_TRUE(asmtest::SameOutputs(runs)) << "mode " << mode;
  }
}

// Arrays not laid out as one block of tuples (here a structure of arrays)
// are read through GetTuple: on the distributed path too, where a point
// kept by its own process is read from the input only when it is put in
// canonical order. The output is that of the same values in an ordinary
// array, with the ties of equal x that make records compared byte for byte.
TEST(DistributedFilter, StructureOfArraysGivesTheSameOutput)
{
  const asmtest::Cloud cloud = asmtest::Sphere(30000, 1.0, 4);
  asmtest::Cloud snapped = cloud;
  for (std::size_t i = 0; i < snapped.size(); i += 3)
  {
    snapped[i] = std::floor(snapped[i] * 64.0) / 64.0; // runs of equal x
  }
  vtkSmartPointer<vtkPolyData> plain = asmtest::ToPolyData(snapped);
  vtkSmartPointer<vtkPolyData> split = asmtest::ToPolyData(snapped);
  vtkNew<vtkFloatArray> aos;
  vtkNew<vtkSOADataArrayTemplate<float>> soa;
  aos->SetName("Colour");
  soa->SetName("Colour");
  aos->SetNumberOfComponents(3);
  soa->SetNumberOfComponents(3);
  const vtkIdType n = plain->GetNumberOfPoints();
  aos->SetNumberOfTuples(n);
  soa->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const float v = static_cast<float>(std::fmod(0.37 * static_cast<double>(i * (c + 1)), 1.0));
      aos->SetTypedComponent(i, c, v);
      soa->SetTypedComponent(i, c, v);
    }
  }
  plain->GetPointData()->AddArray(aos);
  split->GetPointData()->AddArray(soa);
  ASSERT_FALSE(soa->HasStandardMemoryLayout());
  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    vtkSmartPointer<vtkPolyData> a = SimplifyTo(plain, mode, 600);
    vtkSmartPointer<vtkPolyData> b = SimplifyTo(split, mode, 600);
    ASSERT_EQ(a->GetNumberOfPoints(), 600) << "mode " << mode;
    ASSERT_EQ(b->GetNumberOfPoints(), 600) << "mode " << mode;
    vtkDataArray* ca = a->GetPointData()->GetArray("Colour");
    vtkDataArray* cb = b->GetPointData()->GetArray("Colour");
    ASSERT_NE(ca, nullptr);
    ASSERT_NE(cb, nullptr);
    ASSERT_TRUE(asmtest::SamePoints(a, b)) << "mode " << mode;
    for (vtkIdType i = 0; i < 600; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_EQ(ca->GetComponent(i, c), cb->GetComponent(i, c))
          << "mode " << mode << " point " << i;
      }
    }
  }
}

// From 200 000 points the grid's size is searched twice: first on a
// subsample picked by coordinates (CellSizeSubsample), then on every point,
// starting from the first search's answer. The distributed path searches
// the same way, so it sizes the grid as the serial path does, and its output
// is the serial path's (up to the order of the sums within a cell).
TEST(DistributedFilter, LargeCloudsGetTheSerialGrid)
{
  const asmtest::Cloud cloud = asmtest::Sphere(250000, 1.0, 8);
  vtkSmartPointer<vtkPolyData> input = asmtest::ToPolyData(cloud);
  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    vtkNew<vtkASMSimplify> serial;
    serial->SetMode(mode);
    serial->SetTargetModeToNumberOfOutputPoints();
    serial->SetNumberOfOutputPoints(2500);
    serial->SetInputData(input);
    serial->Update();
    vtkSmartPointer<vtkPolyData> distributed = SimplifyTo(input, mode, 2500);
    const double size = asmtest::FieldValue(serial->GetOutput(), "CellSize");
    ASSERT_GT(size, 0.0) << "mode " << mode;
    EXPECT_NEAR(asmtest::FieldValue(distributed, "CellSize"), size, 1e-12 * size)
      << "mode " << mode;
    const auto a = SortedRows(serial->GetOutput(), "ClusterSize");
    const auto b = SortedRows(distributed, "ClusterSize");
    ASSERT_EQ(a.size(), 2500u) << "mode " << mode;
    ASSERT_EQ(b.size(), a.size()) << "mode " << mode;
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      for (int c = 0; c < 4; ++c)
      {
        worst = std::max(worst, std::abs(a[i][c] - b[i][c]));
      }
    }
    EXPECT_LE(worst, 1e-9) << "mode " << mode; // (the cloud's diagonal is 3.5)
  }
}

// Clouds of sparse cells (100 random points: nearly every cell too sparse
// for a sample of its own) take the automatic cell size's outlier-robust
// second search on the distributed path too: the serial cell size and
// points (before, such runs differed: 12 of 360 in a sweep's reproducer,
// float and double points; mpi.SparseCells checks the same over 3
// processes).
TEST(DistributedFilter, SparseCellsGetTheSerialCellSize)
{
  int runs = 0;
  for (unsigned seed = 0; seed < 15; ++seed)
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    asmtest::Cloud cube;
    for (int i = 0; i < 100; ++i)
    {
      asmtest::Add(cube, unit(rng), unit(rng), unit(rng));
    }
    vtkSmartPointer<vtkPolyData> input = asmtest::ToPolyData(cube);
    for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
    {
      for (const vtkIdType count : { 5, 12, 30 })
      {
        vtkNew<vtkASMSimplify> serial;
        serial->SetMode(mode);
        serial->SetTargetModeToNumberOfOutputPoints();
        serial->SetNumberOfOutputPoints(count);
        serial->SetInputData(input);
        serial->Update();
        vtkSmartPointer<vtkPolyData> distributed = SimplifyTo(input, mode, count);
        ASSERT_EQ(asmtest::FieldValue(distributed, "CellSize"),
          asmtest::FieldValue(serial->GetOutput(), "CellSize"))
          << "seed " << seed << ", mode " << mode << ", N_s " << count;
        ASSERT_EQ(
          SortedRows(distributed, "ClusterSize"), SortedRows(serial->GetOutput(), "ClusterSize"))
          << "seed " << seed << ", mode " << mode << ", N_s " << count;
        ++runs;
      }
    }
  }
  EXPECT_EQ(runs, 90);
}
