// SPDX-License-Identifier: BSD-3-Clause
#include "Lloyd.h"


#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();


} // namespace

void RelaxCell(Coordinates xyz, IdView points, const CellFrame& frame,
  const std::vector<Index>& exclude, Index firstSample, Index fixedCount, Index budget,
  int iterations, SampleSet& samples, CellScratch& scratch)
{
  const auto n = static_cast<Index>(points.size());
  const Index free = budget - fixedCount;
  if (free <= 0 || n <= 0)
  {
    return;
  }
  double* pos = samples.Position.data() + 3 * firstSample;
  if (iterations <= 0 || budget > LargeCellBudget)
  {
    // Median splits of the other points in the (v0, v1) plane.
    scratch.Local.resize(static_cast<std::size_t>(n));
    scratch.Subset.clear();
    for (Index i = 0; i < n; ++i)
    {
      double p[3];
      xyz.Get(points[i], p);
      scratch.Local[i] = frame.ToLocal(p);
      if (std::find(exclude.begin(), exclude.end(), points[i]) == exclude.end())
      {
        scratch.Subset.push_back(i);
      }
    }
    Clusters groups;
    SplitInPlane(scratch.Local, scratch.Subset.data(), scratch.Subset.data() + scratch.Subset.size(),
      free, groups);
    for (Index k = 0; k < groups.Size(); ++k)
    {
      const Eigen::Vector3d world =
        frame.Centroid + frame.Axes * Centroid(scratch.Local, groups.Begin(k), groups.End(k));
      std::copy(world.data(), world.data() + 3, pos + 3 * (fixedCount + k));
    }
    return;
  }
  // Farthest-point seeding from the fixed samples.
  scratch.Distance.assign(static_cast<std::size_t>(n), Infinity);
  auto lower = [&](const double* seed) {
    for (Index i = 0; i < n; ++i)
    {
      double p[3];
      xyz.Get(points[i], p);
      scratch.Distance[i] = std::min(scratch.Distance[i], SquaredDistance(p, seed));
    }
  };
  for (Index s = 0; s < fixedCount; ++s)
  {
    lower(pos + 3 * s);
  }
  for (Index s = fixedCount; s < budget; ++s)
  {
    Index pick = 0;
    if (s == 0)
    {
      // No key point: start from the point nearest the cell's centroid.
      const double centre[3] = { frame.Centroid[0], frame.Centroid[1], frame.Centroid[2] };
      double best = Infinity;
      for (Index i = 0; i < n; ++i)
      {
        double p[3];
        xyz.Get(points[i], p);
        const double d = SquaredDistance(p, centre);
        if (d < best)
        {
          best = d;
          pick = i;
        }
      }
    }
    else
    {
      for (Index i = 1; i < n; ++i)
      {
        if (scratch.Distance[i] > scratch.Distance[pick])
        {
          pick = i;
        }
      }
    }
    xyz.Get(points[pick], pos + 3 * s);
    lower(pos + 3 * s);
  }
  // Lloyd iterations inside the cell, fixed samples fixed.
  scratch.Label.resize(static_cast<std::size_t>(n));
  for (int it = 0; it < iterations; ++it)
  {
    scratch.Sum.assign(static_cast<std::size_t>(3 * budget), 0.0);
    scratch.Count.assign(static_cast<std::size_t>(budget), 0);
    for (Index i = 0; i < n; ++i)
    {
      double p[3];
      xyz.Get(points[i], p);
      Index best = 0;
      double bestD = SquaredDistance(p, pos);
      for (Index s = 1; s < budget; ++s)
      {
        const double d = SquaredDistance(p, pos + 3 * s);
        if (d < bestD)
        {
          bestD = d;
          best = s;
        }
      }
      ++scratch.Count[best];
      for (int a = 0; a < 3; ++a)
      {
        scratch.Sum[3 * best + a] += p[a];
      }
    }
    for (Index s = fixedCount; s < budget; ++s)
    {
      if (scratch.Count[s] > 0)
      {
        for (int a = 0; a < 3; ++a)
        {
          pos[3 * s + a] = scratch.Sum[3 * s + a] / static_cast<double>(scratch.Count[s]);
        }
      }
    }
  }
}

void MoveToCentroids(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const PointArray<SampleId>& assign, SampleSet& samples, const Execution& execution)
{
  // The points assigned to a cell's samples lie in its ring (the assignment
  // searches rings, which are symmetric). A chunk of cells scans the union
  // of its cells' rings once, in increasing cell order, which is each ring's
  // visiting order: every sample sums its points in the same order as a scan
  // of its own ring would. Only the chunk's own samples are written, and no
  // sample position is read: the positions are updated in place.
  execution.Run(0, grid.NumberOfCells(), [&](Index b, Index e) {
    const Index firstSample = samples.Start[b], lastSample = samples.Start[e];
    if (lastSample == firstSample)
    {
      return;
    }
    Index lo = std::numeric_limits<Index>::max(), hi = -1;
    for (Index c = b; c < e; ++c)
    {
      if (samples.Start[c + 1] == samples.Start[c])
      {
        continue;
      }
      for (int k = 0; k < 27; ++k)
      {
        const Index nb = neighbors.Of(c)[k];
        if (nb >= 0)
        {
          lo = std::min(lo, nb);
          hi = std::max(hi, nb);
        }
      }
    }
    std::vector<char> inRing(static_cast<std::size_t>(hi - lo + 1), 0);
    for (Index c = b; c < e; ++c)
    {
      if (samples.Start[c + 1] == samples.Start[c])
      {
        continue;
      }
      for (int k = 0; k < 27; ++k)
      {
        const Index nb = neighbors.Of(c)[k];
        if (nb >= 0)
        {
          inRing[nb - lo] = 1;
        }
      }
    }
    const Index owned = lastSample - firstSample;
    std::vector<double> sum(static_cast<std::size_t>(3 * owned), 0.0);
    std::vector<Index> count(static_cast<std::size_t>(owned), 0);
    for (Index nb = lo; nb <= hi; ++nb)
    {
      if (!inRing[nb - lo])
      {
        continue;
      }
      for (Index i = grid.CellStart[nb]; i < grid.CellStart[nb + 1]; ++i)
      {
        const Index s = assign[i] - firstSample;
        if (s >= 0 && s < owned)
        {
          double p[3];
          xyz.Get(grid.PointAt(i), p);
          ++count[s];
          for (int a = 0; a < 3; ++a)
          {
            sum[3 * s + a] += p[a];
          }
        }
      }
    }
    for (Index s = 0; s < owned; ++s)
    {
      if (!samples.Fixed[firstSample + s] && count[s] > 0)
      {
        for (int a = 0; a < 3; ++a)
        {
          samples.Position[3 * (firstSample + s) + a] = sum[3 * s + a] / static_cast<double>(count[s]);
        }
      }
    }
  });
}
} // namespace asmcore
