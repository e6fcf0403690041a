// SPDX-License-Identifier: BSD-3-Clause
// AssignToSamples, the default mode's nearest-sample passes, against a brute
// force search: every point joins the sample of least (weighted) squared
// distance among those owned by its cell and the neighbouring cells, ties
// going to the lower sample index, plain and weighted, with one thread and
// with two. On an integer lattice the ties are exact and everywhere, so the
// pruning and the blocks of four candidates must not change which of
// equally near samples wins. And one round of RefineCovering, which starts
// with such a pass: it never lets a cluster's covering radius grow.
#include "Core/Assignment.h"
#include "Core/CellNeighbors.h"
#include "Core/Covering.h"
#include "Core/FeatureOutput.h"
#include "Core/Grid.h"
#include "Core/Lloyd.h"

#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using asmcore::Index;
using asmtest::Cloud;

namespace
{
// Samples on points of each cell: cell c owns c % 5 of them (none to four,
// so that some rings are thin), spread over the cell's points.
asmcore::SampleSet SamplesOnPoints(const Cloud& c, const asmcore::CellGrid& grid)
{
  asmcore::SampleSet samples;
  const Index cells = grid.NumberOfCells();
  samples.Start.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (Index cell = 0; cell < cells; ++cell)
  {
    const Index n = std::min<Index>(cell % 5, grid.CellSizeOf(cell));
    for (Index k = 0; k < n; ++k)
    {
      const double* p = c.data() + 3 * grid.CellPoints(cell)[k * grid.CellSizeOf(cell) / n];
      samples.Position.insert(samples.Position.end(), p, p + 3);
      samples.Fixed.push_back(0);
    }
    samples.Start[cell + 1] = samples.Start[cell] + n;
  }
  return samples;
}

// The brute force answer for slot i of cell `cell`, and whether another
// sample of the ring is exactly as near.
std::pair<Index, bool> NearestInRing(const Cloud& c, const asmcore::CellGrid& grid,
  const asmcore::CellNeighborTable& neighbors, const asmcore::SampleSet& samples, Index cell,
  Index i, const double* scale)
{
  const double* p = c.data() + 3 * grid.PointAt(i);
  Index best = -1;
  double bestD = std::numeric_limits<double>::infinity();
  bool tie = false;
  for (int k = 0; k < 27; ++k)
  {
    const Index nb = neighbors.Of(cell)[k];
    for (Index s = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && s < samples.Start[nb + 1]; ++s)
    {
      double d = asmcore::SquaredDistance(p, samples.Position.data() + 3 * s);
      if (scale)
      {
        d *= scale[s];
      }
      if (d < bestD || (d == bestD && s < best))
      {
        tie = d == bestD;
        bestD = d;
        best = s;
      }
      else if (d == bestD)
      {
        tie = true;
      }
    }
  }
  return { best, tie };
}

// Every point's assignment, plain and weighted, with one and two threads,
// is the brute force answer; returns the number of points with a tie.
Index ExpectNearestRingSamples(const Cloud& c, double h)
{
  const asmtest::GriddedCloud gridded = asmtest::Gridded(c, h);
  const asmcore::CellGrid& grid = gridded.Grid;
  const asmcore::SampleSet samples = SamplesOnPoints(c, grid);
  // Weights 1, 1.5 and 2: exact products, so weighted ties stay exact.
  std::vector<double> scale(static_cast<std::size_t>(samples.Size()));
  for (Index s = 0; s < samples.Size(); ++s)
  {
    scale[s] = 1.0 + 0.5 * static_cast<double>(s % 3);
  }
  Index ties = 0;
  const double* const plain = nullptr;
  const double* const weighted = scale.data();
  for (const double* weights : { plain, weighted })
  {
    asmcore::PointArray<asmcore::SampleId> serial, threaded;
    asmcore::AssignToSamples(c.data(), grid, gridded.Neighbors, samples, serial, {}, weights);
    asmcore::AssignToSamples(
      c.data(), grid, gridded.Neighbors, samples, threaded, asmtest::UnevenTwoThreads(), weights);
    EXPECT_EQ(serial, threaded);
    for (Index cell = 0; cell < grid.NumberOfCells(); ++cell)
    {
      for (Index i = grid.CellStart[cell]; i < grid.CellStart[cell + 1]; ++i)
      {
        const auto expected = NearestInRing(c, grid, gridded.Neighbors, samples, cell, i, weights);
        EXPECT_EQ(expected.first, serial[i]) << "slot " << i << (weights ? " (weighted)" : "");
        if (expected.first != serial[i])
        {
          return ties; // (one message is enough)
        }
        ties += expected.second ? 1 : 0;
      }
    }
  }
  return ties;
}
} // namespace

TEST(Assignment, NearestRingSampleOnALatticeWithTies)
{
  // A 40 x 40 integer lattice on two levels (z = (i + j) % 2) in cells of
  // about 4 x 4 points: samples on lattice points, many points exactly
  // between two or four of them.
  Cloud c;
  for (int i = 0; i < 40; ++i)
  {
    for (int j = 0; j < 40; ++j)
    {
      asmtest::Add(c, i, j, (i + j) % 2);
    }
  }
  const Index ties = ExpectNearestRingSamples(c, 4.0);
  EXPECT_GT(ties, 300) << "(the lattice must give equally near samples)";
}

TEST(Assignment, NearestRingSampleOnASphere)
{
  const Cloud c = asmtest::Sphere(20000, 1.0, 5);
  ExpectNearestRingSamples(c, 0.2);
}

TEST(Covering, ARoundKeepsTheMemberItSitsOnWhenNoCandidateCoversBetter)
{
  // One cell, one sample: a dense blob of 100 points around the origin and a
  // sparse line of 10 points out to x = 2. The members nearest the centroid
  // (x ~ 0.1) are the blob's, each 1.8 or more from the line's end; the
  // line's point at x = 1 covers every member within 1.1. A sample sitting
  // there must stay (the round tries the member it sits on too), and one
  // sitting at the blob's far side must move to a better member.
  Cloud c;
  for (int i = 0; i < 10; ++i)
  {
    for (int j = 0; j < 10; ++j)
    {
      asmtest::Add(c, -0.1 + 0.02 * i, -0.1 + 0.02 * j, 0.0);
    }
  }
  for (int k = 1; k <= 10; ++k)
  {
    asmtest::Add(c, 0.2 * k, 0.0, 0.0);
  }
  const asmtest::GriddedCloud gridded = asmtest::Gridded(c, 10.0);
  ASSERT_EQ(gridded.Grid.NumberOfCells(), 1);
  // The covering radius of a sample at p: its farthest member (all points).
  auto radius = [&](const double* p) {
    double r = 0.0;
    for (std::size_t i = 0; i < c.size(); i += 3)
    {
      r = std::max(r, asmcore::SquaredDistance(p, c.data() + i));
    }
    return std::sqrt(r);
  };
  for (const double startX : { 1.0, -0.1 })
  {
    asmcore::SampleSet samples;
    samples.Start = { 0, 1 };
    samples.Position = { startX, startX < 0.0 ? -0.1 : 0.0, 0.0 };
    samples.Fixed = { 0 };
    const double before = radius(samples.Position.data());
    asmcore::PointArray<asmcore::SampleId> assign;
    asmcore::RefineCovering(c.data(), gridded.Grid, gridded.Neighbors, samples, assign, {});
    const double after = radius(samples.Position.data());
    EXPECT_LE(after, before) << "from x = " << startX;
    if (startX > 0.0)
    {
      EXPECT_EQ(samples.Position, std::vector<double>({ 1.0, 0.0, 0.0 }));
    }
    else
    {
      EXPECT_LT(after, before - 0.1);
    }
  }
}

// The clusters' last repair: an empty sample takes the nearest point of its
// ring that is unassigned or whose cluster has two or more members (never
// the last member of another cluster); with none left, it stays empty.
TEST(FillEmptyClusters, TakesOnlyPointsThatLeaveNoClusterEmpty)
{
  // Points on the x axis; cells of 2: p0, p1, p2, p4 in one cell, p3 in a
  // cell outside its ring.
  Cloud c;
  for (double x : { 0.0, 1.0, 1.1, 9.0, 1.5 })
  {
    asmtest::Add(c, x, 0.0, 0.0);
  }
  const auto ids = asmtest::AllIds(c);
  const asmcore::CellGrid grid = asmcore::BuildCellGrid(
    c.data(), ids, asmcore::GridSpec::Make(asmcore::ComputeBounds(c.data(), ids), 2.0));
  ASSERT_EQ(grid.NumberOfCells(), 2);
  const asmcore::CellNeighborTable neighbors = asmcore::BuildCellNeighbors(grid);
  // Samples 0-4 owned by the first cell, 5 by the second.
  asmcore::SampleSet samples;
  samples.Position = { 0.0, 0, 0, 1.05, 0, 0, -0.2, 0, 0, 0.5, 0, 0, 0.2, 0, 0, 9.0, 0, 0 };
  samples.Fixed.assign(6, 0);
  samples.Start = { 0, 5, 6 };
  std::vector<asmcore::feature::SampleInfo> info(6);
  for (Index s = 0; s < 6; ++s)
  {
    info[s].Owner = s < 5 ? 0 : 1;
  }
  // p0 -> 0, p1 and p2 -> 1, p3 -> 5, p4 unassigned; assign is by slot.
  const std::vector<asmcore::SampleId> byPoint = { 0, 1, 1, 5, -1 };
  asmcore::PointArray<asmcore::SampleId> assign(5);
  for (Index i = 0; i < 5; ++i)
  {
    assign[i] = byPoint[grid.PointAt(i)];
  }
  std::vector<Index> count = { 1, 2, 0, 0, 0, 1 };
  asmcore::feature::FillEmptyClusters(c.data(), grid, neighbors, samples, info, assign, count);
  // Sample 2 (at -0.2) takes p1, not p0 (nearer, but sample 0's only
  // member); sample 3 (at 0.5) then takes the unassigned p4, as every
  // cluster around has one member; sample 4 finds nothing to take.
  EXPECT_EQ(count, (std::vector<Index>{ 1, 1, 1, 1, 0, 1 }));
  const std::vector<asmcore::SampleId> expected = { 0, 2, 1, 5, 3 };
  for (Index i = 0; i < 5; ++i)
  {
    EXPECT_EQ(assign[i], expected[grid.PointAt(i)]) << "point " << grid.PointAt(i);
  }
}
