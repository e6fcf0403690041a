// SPDX-License-Identifier: BSD-3-Clause
// Crowded clouds (README "Messy data"): points that share few positions,
// and N_s close to N. Many samples at one position stand for the same
// input point, chosen by value; every sample keeps a cluster of its own.
#include "FilterHelpers.h"

#include "vtkASMSimplify.h"
#include "vtkDataArray.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <set>
#include <string>

using asmtest::FilterRun;
using asmtest::ToPolyData;

namespace
{
// An output's clusters: their members in all, the smallest, the distinct
// positions of their samples.
struct Clusters
{
  double Members = 0.0;
  double Smallest = 0.0;
  std::set<std::array<double, 3>> Positions;
};

Clusters ClustersOf(vtkPolyData* out)
{
  Clusters clusters;
  vtkDataArray* sizes = out->GetPointData()->GetArray("ClusterSize");
  clusters.Smallest = out->GetNumberOfPoints() > 0 ? sizes->GetRange()[0] : 0.0;
  for (vtkIdType s = 0; s < out->GetNumberOfPoints(); ++s)
  {
    clusters.Members += sizes->GetTuple1(s);
    std::array<double, 3> p;
    out->GetPoint(s, p.data());
    clusters.Positions.insert(p);
  }
  return clusters;
}
} // namespace

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

// N_s close to N: every sample stands for points of its own. A sample whose
// ring had no point to give (every neighbour a one-point cluster) stayed
// empty and was output on another sample's point (ClusterSize 0, one
// position twice: room-scan1 at 50 % had 11); it now takes the nearest
// point that can be given anywhere (feature::FillEmptyClusters). With
// N_s = N the output is the input's points (the warning says they are
// passed through), also with the key point options off.
TEST(HostileInputs, EverySampleHasPointsOfItsOwnUpToNsEqualsN)
{
  const vtkIdType n = 200;
  int cases = 0;
  for (unsigned seed = 0; seed < 12; ++seed)
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    asmtest::Cloud cube;
    for (vtkIdType i = 0; i < n; ++i)
    {
      asmtest::Add(cube, unit(rng), unit(rng), unit(rng));
    }
    auto input = ToPolyData(cube);
    std::set<std::array<double, 3>> inputPoints;
    for (vtkIdType i = 0; i < n; ++i)
    {
      std::array<double, 3> p;
      input->GetPoint(i, p.data());
      inputPoints.insert(p);
    }
    for (const vtkIdType count : { 160, 180, 190, 195, 200 })
    {
      for (const bool keyOptions : { true, false })
      {
        SCOPED_TRACE("seed " + std::to_string(seed) + ", N_s " + std::to_string(count) +
          (keyOptions ? "" : ", key point options off"));
        FilterRun run;
        run.Count(count);
        run.Filter->SetValidateKeyPoints(keyOptions);
        run.Filter->SetExtremeKeyPoints(keyOptions);
        vtkPolyData* out = run.Execute(input);
        ASSERT_EQ(out->GetNumberOfPoints(), count);
        const Clusters clusters = ClustersOf(out);
        EXPECT_GE(clusters.Smallest, 1.0);
        EXPECT_EQ(clusters.Members, static_cast<double>(n));
        EXPECT_EQ(clusters.Positions.size(), static_cast<std::size_t>(count));
        if (count == n)
        {
          EXPECT_EQ(clusters.Positions, inputPoints);
        }
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 120);
}

// A key sample stands for its extreme point (ExtremeKeyPoints): the repair
// of empty clusters took that point from the key sample's cluster when the
// cluster had another member, and the sample that took it snapped onto it,
// so one position was output twice and another input position was missing
// (half the points crowded into a corner, N_s = N / 2: 99 positions for
// 100 samples). Every sample now has a position of its own, at any N_s.
TEST(HostileInputs, KeySamplesKeepTheirExtremePoints)
{
  const vtkIdType n = 200;
  int twice = 0, cases = 0;
  for (unsigned seed = 0; seed < 16; ++seed)
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    asmtest::Cloud crowded;
    for (vtkIdType i = 0; i < n; ++i)
    {
      const double scale = i < n / 2 ? 0.1 : 1.0;
      asmtest::Add(crowded, scale * unit(rng), scale * unit(rng), scale * unit(rng));
    }
    auto input = ToPolyData(crowded);
    for (vtkIdType count = 20; count < n; count += 7)
    {
      FilterRun run;
      run.Count(count);
      vtkPolyData* out = run.Execute(input);
      ASSERT_EQ(out->GetNumberOfPoints(), count);
      const Clusters clusters = ClustersOf(out);
      EXPECT_EQ(clusters.Members, static_cast<double>(n)) << "seed " << seed << ", N_s " << count;
      twice += static_cast<int>(count - static_cast<vtkIdType>(clusters.Positions.size()));
      ++cases;
    }
  }
  EXPECT_EQ(cases, 16 * 26);
  EXPECT_EQ(twice, 0);
}
