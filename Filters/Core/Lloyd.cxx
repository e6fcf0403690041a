// SPDX-License-Identifier: BSD-3-Clause
#include "Lloyd.h"

#include "Neighbors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace asmcore
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();


} // namespace

void RelaxCell(const double* xyz, const Index* points, Index n, const CellFrame& frame,
  const std::vector<Index>& exclude, Index firstSample, Index fixedCount, Index budget,
  int iterations, SampleSet& samples, CellScratch& scratch)
{
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
      scratch.Local[i] = frame.ToLocal(xyz + 3 * points[i]);
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
      scratch.Distance[i] = std::min(scratch.Distance[i], SquaredDistance(xyz + 3 * points[i], seed));
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
        const double d = SquaredDistance(xyz + 3 * points[i], centre);
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
    std::copy(xyz + 3 * points[pick], xyz + 3 * points[pick] + 3, pos + 3 * s);
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
      const double* p = xyz + 3 * points[i];
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

void AssignToSamples(const double* xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, std::vector<Index>& assign, std::vector<double>& distance2,
  const Execution& execution)
{
  assign.resize(grid.Order.size());
  distance2.resize(grid.Order.size());
  const double* pos = samples.Position.data();
  execution.Run(0, grid.NumberOfCells(), [&](Index b, Index e) {
    std::vector<std::pair<double, Index>> candidates; // (squared gap to the box, sample)
    std::vector<Index> ringSamples;
    for (Index c = b; c < e; ++c)
    {
      const Index first = samples.Start[c], last = samples.Start[c + 1];
      if (last - first > LargeCellBudget)
      {
        // Many samples: a k-d tree of the ring's samples (ties: lower index).
        ringSamples.clear();
        for (int k = 0; k < 27; ++k)
        {
          const Index nb = neighbors.Of(c)[k];
          for (Index s = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && s < samples.Start[nb + 1]; ++s)
          {
            ringSamples.push_back(s);
          }
        }
        const Neighbors tree(pos, ringSamples);
        for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
        {
          const double* p = xyz + 3 * grid.Order[i];
          const NearestPoint nearest = tree.Nearest(p);
          assign[i] = nearest.Id;
          distance2[i] = nearest.Id >= 0 ? SquaredDistance(p, pos + 3 * nearest.Id) : Infinity;
        }
        continue;
      }
      // Pass 1: the nearest of the cell's own samples, and the farthest any
      // point of the cell is from it (the search radius for the others).
      double reach = 0.0;
      double box[6] = { Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity };
      for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
      {
        const double* p = xyz + 3 * grid.Order[i];
        Index best = -1;
        double bestD = Infinity;
        for (Index s = first; s < last; ++s)
        {
          const double d = SquaredDistance(p, pos + 3 * s);
          if (d < bestD)
          {
            bestD = d;
            best = s;
          }
        }
        assign[i] = best;
        distance2[i] = bestD;
        reach = std::max(reach, bestD);
        for (int a = 0; a < 3; ++a)
        {
          box[a] = std::min(box[a], p[a]);
          box[3 + a] = std::max(box[3 + a], p[a]);
        }
      }
      // The neighbours' samples that can be nearer for some point of c:
      // within `reach` of the box of c's points.
      candidates.clear();
      const Index* ring = neighbors.Of(c);
      const double r = std::sqrt(reach);
      for (int k = 0; k < 27; ++k)
      {
        const Index nb = ring[k];
        if (k == 13 || nb < 0)
        {
          continue;
        }
        for (Index s = samples.Start[nb]; s < samples.Start[nb + 1]; ++s)
        {
          const double* t = pos + 3 * s;
          double g2 = 0.0;
          for (int a = 0; a < 3; ++a)
          {
            const double g = t[a] < box[a] ? box[a] - t[a] : (t[a] > box[3 + a] ? t[a] - box[3 + a] : 0.0);
            g2 += g * g;
          }
          if (!(g2 > reach) || !std::isfinite(r))
          {
            candidates.emplace_back(g2, s);
          }
        }
      }
      if (candidates.empty())
      {
        continue;
      }
      // Pass 2: those candidates, nearest the box first; a point lies in the
      // box, so it is at least the box gap away from a candidate (ties: the
      // lower sample index).
      std::sort(candidates.begin(), candidates.end());
      for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
      {
        const double* p = xyz + 3 * grid.Order[i];
        Index best = assign[i];
        double bestD = distance2[i];
        for (const auto& candidate : candidates)
        {
          if (candidate.first > bestD)
          {
            break;
          }
          const Index s = candidate.second;
          const double d = SquaredDistance(p, pos + 3 * s);
          if (d < bestD || (d == bestD && s < best))
          {
            bestD = d;
            best = s;
          }
        }
        assign[i] = best;
        distance2[i] = bestD;
      }
    }
  });
}

void UpdateAssignment(const double* xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, const std::vector<Index>& previous, const std::vector<char>& moved,
  std::vector<Index>& assign, std::vector<double>& distance2, const Execution& execution)
{
  const Index count = samples.Size();
  const Index cells = grid.NumberOfCells();
  for (Index c = 0; c < cells; ++c)
  {
    if (samples.Start[c + 1] - samples.Start[c] > LargeCellBudget)
    {
      // Such cells search with a k-d tree: search everything again.
      AssignToSamples(xyz, grid, neighbors, samples, assign, distance2, execution);
      return;
    }
  }
  std::vector<Index> renumber(static_cast<std::size_t>(count));
  for (Index s = 0; s < count; ++s)
  {
    renumber[previous[s]] = s;
  }
  const double* pos = samples.Position.data();
  execution.Run(0, cells, [&](Index b, Index e) {
    std::vector<Index> near; // the moved samples of the ring
    for (Index c = b; c < e; ++c)
    {
      const Index* ring = neighbors.Of(c);
      near.clear();
      for (int k = 0; k < 27; ++k)
      {
        const Index nb = ring[k];
        for (Index s = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && s < samples.Start[nb + 1]; ++s)
        {
          if (moved[s])
          {
            near.push_back(s);
          }
        }
      }
      for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
      {
        const double* p = xyz + 3 * grid.Order[i];
        const Index before = assign[i] >= 0 ? renumber[assign[i]] : -1;
        Index best = before;
        double bestD = distance2[i];
        auto consider = [&](Index s) {
          const double d = SquaredDistance(p, pos + 3 * s);
          if (d < bestD || (d == bestD && s < best))
          {
            bestD = d;
            best = s;
          }
        };
        if (before < 0 || moved[before])
        {
          // Its sample left (or it had none): the whole ring again.
          best = -1;
          bestD = Infinity;
          for (int k = 0; k < 27; ++k)
          {
            const Index nb = ring[k];
            for (Index s = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && s < samples.Start[nb + 1]; ++s)
            {
              consider(s);
            }
          }
        }
        else
        {
          // Its sample stayed: only a moved sample can now be nearer.
          for (Index s : near)
          {
            consider(s);
          }
        }
        assign[i] = best;
        distance2[i] = bestD;
      }
    }
  });
}

void MoveToCentroids(const double* xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const std::vector<Index>& assign, SampleSet& samples, const Execution& execution)
{
  std::vector<double> next(samples.Position);
  // The points assigned to a cell's samples lie in its ring (the assignment
  // searches rings, which are symmetric). A chunk of cells scans the union
  // of its cells' rings once, in increasing cell order, which is each ring's
  // visiting order: every sample sums its points in the same order as a scan
  // of its own ring would.
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
          const double* p = xyz + 3 * grid.Order[i];
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
          next[3 * (firstSample + s) + a] = sum[3 * s + a] / static_cast<double>(count[s]);
        }
      }
    }
  });
  samples.Position.swap(next);
}
} // namespace asmcore
