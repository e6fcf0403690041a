// SPDX-License-Identifier: BSD-3-Clause
#include "Lloyd.h"

#include <Eigen/Eigenvalues>

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
    SplitInPlane(scratch.Local, scratch.Subset.data(),
      scratch.Subset.data() + scratch.Subset.size(), free, groups);
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

namespace
{
// Visits, for every chunk of owner cells [b, e), the points assigned to the
// chunk's samples. Those points lie in their owner cells' rings (every
// assignment, weighted or not, searches rings, which are symmetric), so the
// chunk scans the union of its cells' rings once, in increasing cell order,
// which is each ring's visiting order: every sample sees its points in the
// same order as a scan of its own ring would.
// begin(firstSample, owned) starts a chunk, visit(s - firstSample, slot)
// is called per point, end() finishes it.
template <typename Begin, typename Visit, typename End>
void ScanOwnedClusters(const CellGrid& grid, const CellNeighborTable& neighbors,
  const PointArray<SampleId>& assign, const SampleSet& samples, const Execution& execution,
  const Begin& begin, const Visit& visit, const End& end)
{
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
    auto state = begin(firstSample, owned);
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
          visit(state, s, grid.PointAt(i));
        }
      }
    }
    end(state, firstSample, owned);
  });
}
} // namespace

void MoveToCentroids(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const PointArray<SampleId>& assign, SampleSet& samples, const Execution& execution)
{
  // Only the chunk's own samples are written, and no sample position is
  // read: the positions are updated in place.
  struct Sums
  {
    std::vector<double> Sum;
    std::vector<Index> Count;
  };
  ScanOwnedClusters(
    grid, neighbors, assign, samples, execution,
    [](Index, Index owned) {
      return Sums{ std::vector<double>(static_cast<std::size_t>(3 * owned), 0.0),
        std::vector<Index>(static_cast<std::size_t>(owned), 0) };
    },
    [&](Sums& sums, Index s, Index point) {
      double p[3];
      xyz.Get(point, p);
      ++sums.Count[s];
      for (int a = 0; a < 3; ++a)
      {
        sums.Sum[3 * s + a] += p[a];
      }
    },
    [&](Sums& sums, Index firstSample, Index owned) {
      for (Index s = 0; s < owned; ++s)
      {
        if (!samples.Fixed[firstSample + s] && sums.Count[s] > 0)
        {
          for (int a = 0; a < 3; ++a)
          {
            samples.Position[3 * (firstSample + s) + a] =
              sums.Sum[3 * s + a] / static_cast<double>(sums.Count[s]);
          }
        }
      }
    });
}

std::vector<double> ClusterVariations(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const PointArray<SampleId>& assign, const SampleSet& samples,
  const Execution& execution)
{
  std::vector<double> variation(static_cast<std::size_t>(samples.Size()), 0.0);
  // Moments about the sample's position (near its points: no cancellation).
  struct Moments
  {
    Index First;
    std::vector<double> M; // per sample: count, sum d, sum d d^T (6)
  };
  ScanOwnedClusters(
    grid, neighbors, assign, samples, execution,
    [](Index firstSample, Index owned) {
      return Moments{ firstSample, std::vector<double>(static_cast<std::size_t>(10 * owned), 0.0) };
    },
    [&](Moments& m, Index s, Index point) {
      double p[3];
      xyz.Get(point, p);
      const double* o = samples.Position.data() + 3 * (m.First + s);
      const double d[3] = { p[0] - o[0], p[1] - o[1], p[2] - o[2] };
      double* q = m.M.data() + 10 * s;
      q[0] += 1.0;
      q[1] += d[0];
      q[2] += d[1];
      q[3] += d[2];
      q[4] += d[0] * d[0];
      q[5] += d[0] * d[1];
      q[6] += d[0] * d[2];
      q[7] += d[1] * d[1];
      q[8] += d[1] * d[2];
      q[9] += d[2] * d[2];
    },
    [&](Moments& m, Index firstSample, Index owned) {
      for (Index s = 0; s < owned; ++s)
      {
        const double* q = m.M.data() + 10 * s;
        const double n = q[0];
        if (n < 3.0)
        {
          continue;
        }
        const Eigen::Vector3d c(q[1] / n, q[2] / n, q[3] / n);
        Eigen::Matrix3d cov;
        cov << q[4] / n, q[5] / n, q[6] / n, q[5] / n, q[7] / n, q[8] / n, q[6] / n, q[8] / n,
          q[9] / n;
        cov -= c * c.transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
        solver.computeDirect(cov, Eigen::EigenvaluesOnly);
        const Eigen::Vector3d lambda = solver.eigenvalues().cwiseMax(0.0);
        const double trace = lambda.sum();
        variation[firstSample + s] = trace > 0.0 ? lambda[0] / trace : 0.0;
      }
    });
  return variation;
}

std::vector<double> VariationScales(
  const std::vector<double>& variation, double weight, double cap, double mean)
{
  std::vector<double> scale(variation.size(), 1.0);
  for (std::size_t s = 0; mean > 0.0 && s < variation.size(); ++s)
  {
    scale[s] = 1.0 + weight * std::min(cap, variation[s] / mean);
  }
  return scale;
}

std::vector<double> VariationScales(const std::vector<double>& variation, double weight, double cap)
{
  ExactMean mean;
  for (double v : variation)
  {
    mean.Add(v);
  }
  return VariationScales(variation, weight, cap, mean.Value());
}
} // namespace asmcore
