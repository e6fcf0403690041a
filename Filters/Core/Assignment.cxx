// SPDX-License-Identifier: BSD-3-Clause
#include "Assignment.h"

#include "Neighbors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();

/// AssignToSamples for the points of a cell that owns many samples: a k-d
/// tree of the ring's samples (ties: lower index, as the brute-force search).
void AssignLargeCell(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, Index c, PointArray<SampleId>& assign, std::vector<Index>& ringSamples,
  const double* scale = nullptr)
{
  ringSamples.clear();
  for (int k = 0; k < 27; ++k)
  {
    const Index nb = neighbors.Of(c)[k];
    for (Index s = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && s < samples.Start[nb + 1]; ++s)
    {
      ringSamples.push_back(s);
    }
  }
  const double* pos = samples.Position.data();
  const Neighbors tree(pos, ringSamples);
  if (scale)
  {
    // Weighted (factors >= 1): the plain nearest sample s0 at d0 bounds the
    // answer's weighted distance by scale[s0] d0^2, so the answer lies within
    // d0 sqrt(scale[s0]) (widened against rounding); the least weighted
    // distance among those, ties: the lower index.
    std::vector<Index> near;
    for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
    {
      double p[3];
      xyz.Get(grid.PointAt(i), p);
      const NearestPoint nearest = tree.Nearest(p);
      Index best = -1;
      double bestD = Infinity;
      if (nearest.Id >= 0)
      {
        tree.Radius(p, nearest.Distance * std::sqrt(scale[nearest.Id]) * (1.0 + 1e-9), near);
        for (Index s : near)
        {
          const double d = scale[s] * SquaredDistance(p, pos + 3 * s);
          if (d < bestD || (d == bestD && s < best))
          {
            bestD = d;
            best = s;
          }
        }
      }
      assign[i] = static_cast<SampleId>(best);
    }
    return;
  }
  for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
  {
    const NearestPoint nearest = tree.Nearest(xyz.At(grid.PointAt(i)).data());
    assign[i] = static_cast<SampleId>(nearest.Id);
  }
}

// The two passes of AssignToSamples, comparing weighted(s, d^2) (a template,
// so that the plain passes carry no test of `scale`). With scale >= 1,
// scale * d^2 >= d^2 >= the squared box gap: the pruning of pass 2 holds as
// it is.
template <typename Weighted>
void AssignPasses(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, PointArray<SampleId>& assign, const Execution& execution,
  const double* scale, const Weighted& weighted)
{
  assign.resize(static_cast<std::size_t>(grid.NumberOfPoints()));
  const double* pos = samples.Position.data();
  execution.Run(0, grid.NumberOfCells(), [&](Index b, Index e) {
    std::vector<std::pair<double, Index>> candidates; // (squared gap to the box, sample)
    std::vector<Index> ringSamples;
    std::vector<double> cellD2; // pass 1's squared distances of the cell's points
    for (Index c = b; c < e; ++c)
    {
      const Index first = samples.Start[c], last = samples.Start[c + 1];
      if (last - first > LargeCellBudget)
      {
        AssignLargeCell(xyz, grid, neighbors, samples, c, assign, ringSamples, scale);
        continue;
      }
      // Pass 1: the nearest of the cell's own samples, and the farthest any
      // point of the cell is from it (the search radius for the others).
      double reach = 0.0;
      double box[6] = { Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity };
      cellD2.resize(static_cast<std::size_t>(grid.CellSizeOf(c)));
      for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
      {
        double p[3];
        xyz.Get(grid.PointAt(i), p);
        Index best = -1;
        double bestD = Infinity;
        for (Index s = first; s < last; ++s)
        {
          const double d = weighted(s, SquaredDistance(p, pos + 3 * s));
          if (d < bestD)
          {
            bestD = d;
            best = s;
          }
        }
        assign[i] = static_cast<SampleId>(best);
        cellD2[static_cast<std::size_t>(i - grid.CellStart[c])] = bestD;
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
      const CellRef* ring = neighbors.Of(c);
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
        double p[3];
        xyz.Get(grid.PointAt(i), p);
        Index best = assign[i];
        double bestD = cellD2[static_cast<std::size_t>(i - grid.CellStart[c])];
        for (const auto& candidate : candidates)
        {
          if (candidate.first > bestD)
          {
            break;
          }
          const Index s = candidate.second;
          const double d = weighted(s, SquaredDistance(p, pos + 3 * s));
          if (d < bestD || (d == bestD && s < best))
          {
            bestD = d;
            best = s;
          }
        }
        assign[i] = static_cast<SampleId>(best);
      }
    }
  });
}

} // namespace

void AssignToSamples(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, PointArray<SampleId>& assign, const Execution& execution,
  const double* scale)
{
  if (scale)
  {
    AssignPasses(xyz, grid, neighbors, samples, assign, execution, scale,
      [scale](Index s, double d2) { return scale[s] * d2; });
  }
  else
  {
    AssignPasses(xyz, grid, neighbors, samples, assign, execution, scale,
      [](Index, double d2) { return d2; });
  }
}

void UpdateAssignment(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, const std::vector<Index>& previous, const std::vector<char>& moved,
  PointArray<SampleId>& assign, const Execution& execution, Index previousCount)
{
  const Index count = samples.Size();
  const Index cells = grid.NumberOfCells();
  // Old slot -> new slot (-1: the sample left the set).
  std::vector<Index> renumber(static_cast<std::size_t>(previousCount < 0 ? count : previousCount), -1);
  for (Index s = 0; s < count; ++s)
  {
    if (previous[s] >= 0)
    {
      renumber[previous[s]] = s;
    }
  }
  const double* pos = samples.Position.data();
  execution.Run(0, cells, [&](Index b, Index e) {
    std::vector<Index> near; // the moved samples of the ring
    std::vector<Index> ringSamples;
    for (Index c = b; c < e; ++c)
    {
      if (samples.Start[c + 1] - samples.Start[c] > LargeCellBudget)
      {
        // A cell owning many samples searches them with a k-d tree, as
        // AssignToSamples does (the same answers, in O(log) per point).
        AssignLargeCell(xyz, grid, neighbors, samples, c, assign, ringSamples);
        continue;
      }
      const CellRef* ring = neighbors.Of(c);
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
        double p[3];
        xyz.Get(grid.PointAt(i), p);
        const Index before = assign[i] >= 0 ? renumber[assign[i]] : -1;
        Index best = before;
        // (Its sample, if it stayed, is where it was: the same distance.)
        double bestD = before < 0 ? Infinity : SquaredDistance(p, pos + 3 * before);
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
        assign[i] = static_cast<SampleId>(best);
      }
    }
  });
}
} // namespace asmcore
