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

// The first k with the least d[k] < infinity (-1 if none), and that value in
// bestD: the loop `if (d[k] < bestD) { bestD = d[k]; best = k; }` from
// bestD = infinity, with four independent chains (shorter latency).
inline Index FirstMinimum(const double* d, Index n, double& bestD)
{
  double m[4] = { Infinity, Infinity, Infinity, Infinity };
  Index at[4] = { -1, -1, -1, -1 };
  Index k = 0;
  for (; k + 4 <= n; k += 4)
  {
    for (int j = 0; j < 4; ++j)
    {
      const bool less = d[k + j] < m[j];
      m[j] = less ? d[k + j] : m[j];
      at[j] = less ? k + j : at[j];
    }
  }
  for (int j = 0; k < n; ++k, ++j)
  {
    if (d[k] < m[j])
    {
      m[j] = d[k];
      at[j] = k;
    }
  }
  Index best = -1;
  bestD = Infinity;
  for (int j = 0; j < 4; ++j)
  {
    if (at[j] >= 0 && (m[j] < bestD || (m[j] == bestD && at[j] < best)))
    {
      bestD = m[j];
      best = at[j];
    }
  }
  return best;
}


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
    std::vector<double> sx, sy, sz, cx, cy, cz, dist;
    constexpr Index Block = 4;
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
      // The samples are copied to structure-of-arrays scratch so the
      // distances of one point to them are computed in vector lanes (same
      // formula, same rounding as SquaredDistance).
      const Index own = last - first;
      sx.resize(static_cast<std::size_t>(own));
      sy.resize(static_cast<std::size_t>(own));
      sz.resize(static_cast<std::size_t>(own));
      dist.resize(static_cast<std::size_t>(std::max<Index>(own, Block)));
      for (Index s = 0; s < own; ++s)
      {
        sx[s] = pos[3 * (first + s)];
        sy[s] = pos[3 * (first + s) + 1];
        sz[s] = pos[3 * (first + s) + 2];
      }
      double reach = 0.0;
      double box[6] = { Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity };
      for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
      {
        const double* p = xyz + 3 * grid.Order[i];
        const double px = p[0], py = p[1], pz = p[2];
        double* d = dist.data();
        for (Index s = 0; s < own; ++s)
        {
          const double dx = px - sx[s], dy = py - sy[s], dz = pz - sz[s];
          d[s] = dx * dx + dy * dy + dz * dz;
        }
        double bestD = Infinity;
        const Index local = FirstMinimum(d, own, bestD);
        const Index best = local < 0 ? -1 : first + local;
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
      // box, so it is at least the box gap away from a candidate. The result
      // is the least (distance, sample index) over the candidates: blocks of
      // candidates are evaluated whole (one past the first gap beyond the
      // current best distance cannot win), padded with far dummies.
      std::sort(candidates.begin(), candidates.end());
      const Index m = static_cast<Index>(candidates.size());
      const Index padded = (m + Block - 1) / Block * Block;
      cx.resize(static_cast<std::size_t>(padded));
      cy.resize(static_cast<std::size_t>(padded));
      cz.resize(static_cast<std::size_t>(padded));
      for (Index k = 0; k < padded; ++k)
      {
        const double* t = k < m ? pos + 3 * candidates[k].second : nullptr;
        cx[k] = t ? t[0] : Infinity;
        cy[k] = t ? t[1] : Infinity;
        cz[k] = t ? t[2] : Infinity;
      }
      for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
      {
        const double* p = xyz + 3 * grid.Order[i];
        const double px = p[0], py = p[1], pz = p[2];
        Index best = assign[i];
        double bestD = distance2[i];
        for (Index k0 = 0; k0 < m && !(candidates[k0].first > bestD); k0 += Block)
        {
          double* d = dist.data();
          for (Index k = 0; k < Block; ++k)
          {
            const double dx = px - cx[k0 + k], dy = py - cy[k0 + k], dz = pz - cz[k0 + k];
            d[k] = dx * dx + dy * dy + dz * dz;
          }
          const Index n = std::min(Block, m - k0);
          for (Index k = 0; k < n; ++k)
          {
            const Index s = candidates[k0 + k].second;
            if (d[k] < bestD || (d[k] == bestD && s < best))
            {
              bestD = d[k];
              best = s;
            }
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
  execution.Run(0, grid.NumberOfCells(), [&](Index b, Index e) {
    std::vector<double> sum;
    std::vector<Index> count;
    for (Index c = b; c < e; ++c)
    {
      const Index first = samples.Start[c], budget = samples.Start[c + 1] - first;
      if (budget == 0)
      {
        continue;
      }
      sum.assign(static_cast<std::size_t>(3 * budget), 0.0);
      count.assign(static_cast<std::size_t>(budget), 0);
      // Points assigned to c's samples lie in c's ring; fixed visiting order.
      const Index* ring = neighbors.Of(c);
      for (int k = 0; k < 27; ++k)
      {
        const Index nb = ring[k];
        if (nb < 0)
        {
          continue;
        }
        for (Index i = grid.CellStart[nb]; i < grid.CellStart[nb + 1]; ++i)
        {
          const Index s = assign[i] - first;
          if (s >= 0 && s < budget)
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
      for (Index s = 0; s < budget; ++s)
      {
        if (!samples.Fixed[first + s] && count[s] > 0)
        {
          for (int a = 0; a < 3; ++a)
          {
            next[3 * (first + s) + a] = sum[3 * s + a] / static_cast<double>(count[s]);
          }
        }
      }
    }
  });
  samples.Position.swap(next);
}
} // namespace asmcore
