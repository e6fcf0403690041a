// SPDX-License-Identifier: BSD-3-Clause
#include "vtkASMDistributedMetrics.h"

#include "Core/CellSize.h"
#include "Core/Neighbors.h"

#include "vtkNew.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmvtk
{
namespace
{
// Count, sum, sum of squares and maximum of distances, reduced over the
// processes into a summary.
asmcore::DistanceSummary Reduce(const Communication& comm, const std::vector<double>& d)
{
  std::vector<double> sums = { static_cast<double>(d.size()), 0.0, 0.0 };
  double max = 0.0;
  for (double v : d)
  {
    sums[1] += v;
    sums[2] += v * v;
    max = std::max(max, v);
  }
  comm.Sum(sums);
  asmcore::DistanceSummary s;
  s.Count = static_cast<Index>(sums[0]);
  s.Max = comm.Max(max);
  if (s.Count > 0)
  {
    s.Mean = sums[1] / sums[0];
    s.RMS = std::sqrt(sums[2] / sums[0]);
  }
  return s;
}

std::vector<Index> Iota(std::size_t n)
{
  std::vector<Index> ids(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    ids[i] = static_cast<Index>(i);
  }
  return ids;
}

std::vector<double> Flatten(const std::vector<Eigen::Vector3d>& points)
{
  std::vector<double> flat;
  flat.reserve(3 * points.size());
  for (const auto& p : points)
  {
    flat.insert(flat.end(), { p[0], p[1], p[2] });
  }
  return flat;
}
} // namespace

DistributedComparison CompareDistributed(const Communication& comm, const double* xyz,
  asmcore::IdView ids, const double* sxyz, const std::vector<Index>& sids, const double* snormals,
  const asmcore::ComparisonOptions& options, int curvatureNeighbors,
  const asmcore::Execution& threads)
{
  asmcore::Execution execution;
  execution.For = threads.For; // (no progress: see the header)
  DistributedComparison out;
  asmcore::Comparison& result = out.Figures;

  // The simplified cloud, whole, on every process (and its normals).
  std::vector<double> mine, myNormals;
  for (std::size_t i = 0; i < sids.size(); ++i)
  {
    mine.insert(mine.end(), sxyz + 3 * sids[i], sxyz + 3 * sids[i] + 3);
    if (snormals)
    {
      myNormals.insert(myNormals.end(), snormals + 3 * i, snormals + 3 * i + 3);
    }
  }
  Index offset = 0;
  const std::vector<double> all = comm.AllGather(mine, &offset);
  const bool haveNormals =
    comm.Max(snormals || sids.empty() ? 0.0 : 1.0) == 0.0 && comm.Max(snormals ? 1.0 : 0.0) > 0.0;
  const std::vector<double> allNormals =
    haveNormals ? comm.AllGather(myNormals) : std::vector<double>();
  const std::vector<Index> allIds = Iota(all.size() / 3);
  out.SimplifiedPoints = static_cast<Index>(allIds.size());
  out.OriginalPoints = comm.Sum(static_cast<Index>(ids.size()));
  if (out.OriginalPoints == 0 || out.SimplifiedPoints == 0)
  {
    return out;
  }

  // One grid over both clouds, sized as the simplifier would size it.
  const asmcore::Bounds original = comm.Union(asmcore::ComputeBounds(xyz, ids, execution));
  asmcore::Bounds both = original;
  const asmcore::Bounds simplified = asmcore::ComputeBounds(all.data(), allIds, execution);
  for (int a = 0; a < 3; ++a)
  {
    both.Min[a] = std::min(both.Min[a], simplified.Min[a]);
    both.Max[a] = std::max(both.Max[a], simplified.Max[a]);
  }
  result.Diagonal = original.Diagonal();
  double cellSize = options.CellSize;
  if (!(cellSize > 0.0) || !std::isfinite(cellSize))
  {
    // (As the serial comparison: the original's points over both boxes.)
    cellSize = AutomaticCellSize(comm, xyz, ids, both, comm.Sum(static_cast<Index>(ids.size())),
      static_cast<double>(allIds.size()) / std::max(1.0, options.SamplesPerCell), execution);
  }
  const asmcore::GridSpec spec = asmcore::GridSpec::Make(both, cellSize);
  result.CellSize = spec.CellSize;

  // The original points by cell owner, with the halo (coordinates only).
  const asmcore::CellPartition partition = MakeCellPartition(comm, spec, xyz, ids);
  vtkNew<vtkPolyData> bare;
  const LocalCloud cloud = Redistribute(comm, bare, xyz, ids, partition, HaloRings);
  std::vector<Index> owned;
  for (std::size_t i = 0; i < cloud.Owned.size(); ++i)
  {
    if (cloud.Owned[i])
    {
      owned.push_back(static_cast<Index>(i));
    }
  }
  const double* oxyz = cloud.Xyz.data();

  // Key point error: the owned cells' key points against every simplified one.
  asmcore::KeyPointRule rule = options.Rule;
  rule.ErrorTolerance = 0.0;
  rule.Snap = false;
  const auto originalKeys = asmcore::CloudKeyPoints(oxyz, owned, spec, rule, execution);
  const auto simplifiedKeys = asmcore::CloudKeyPoints(all.data(), allIds, spec, rule, execution);
  result.OriginalKeyPoints = comm.Sum(static_cast<Index>(originalKeys.size()));
  result.SimplifiedKeyPoints = static_cast<Index>(simplifiedKeys.size());
  const std::vector<double> keyXyz = Flatten(originalKeys);
  const std::vector<double> simplifiedKeyXyz = Flatten(simplifiedKeys);
  const asmcore::Neighbors simplifiedTree(all.data(), allIds, execution);
  const asmcore::Neighbors simplifiedKeyTree(simplifiedKeyXyz.data(), Iota(simplifiedKeys.size()));
  std::vector<double> keyErrors = asmcore::NearestDistances(keyXyz.data(),
    Iota(originalKeys.size()), simplifiedKeys.empty() ? simplifiedTree : simplifiedKeyTree);
  if (options.Measure == asmcore::KeyPointDistance::Squared)
  {
    for (double& e : keyErrors)
    {
      e *= e;
    }
  }
  const asmcore::DistanceSummary keys = Reduce(comm, keyErrors);
  result.AKPE = keys.Mean;
  result.MKPE = keys.Max;

  // The owned original points against the whole simplified cloud.
  {
    std::vector<double> nearest, plane;
    asmcore::SurfaceDistances(oxyz, owned, simplifiedTree, options.PlaneNeighbors, &plane, &nearest,
      execution, options.SurfaceEpsilon);
    result.OriginalToSimplified = Reduce(comm, nearest);
    result.PointToPlane = Reduce(comm, plane);
  }

  // Each simplified point measured by the owner of its cell (owned + halo
  // original points), then summed: one contributor per point.
  std::vector<Index> mineToMeasure;
  for (Index j : allIds)
  {
    if (partition.OwnerOfPoint(all.data() + 3 * j) == comm.Rank())
    {
      mineToMeasure.push_back(j);
    }
  }
  const asmcore::Neighbors localTree(oxyz, cloud.Ids(), execution);
  std::vector<double> nearest, plane;
  asmcore::SurfaceDistances(all.data(), mineToMeasure, localTree, options.PlaneNeighbors, &plane,
    &nearest, execution, options.SurfaceEpsilon);
  const std::size_t n = allIds.size();
  const int fields = curvatureNeighbors > 0 ? 4 : 2;
  std::vector<double> perPoint(fields * n, 0.0);
  for (std::size_t m = 0; m < mineToMeasure.size(); ++m)
  {
    perPoint[mineToMeasure[m]] = nearest[m];
    perPoint[n + mineToMeasure[m]] = plane[m];
  }
  if (curvatureNeighbors > 0)
  {
    // Signed by the simplified normals, or else away from the centroid of
    // the whole original cloud, as a serial run signs them (this process's
    // points, owned and halo, have another centroid).
    double centroid[3] = { 0.0, 0.0, 0.0 };
    if (!haveNormals)
    {
      GlobalCentroid(comm, xyz, ids, out.OriginalPoints, centroid);
    }
    std::vector<double> queries, orient;
    for (Index j : mineToMeasure)
    {
      const double* q = all.data() + 3 * j;
      queries.insert(queries.end(), q, q + 3);
      if (haveNormals)
      {
        orient.insert(orient.end(), allNormals.data() + 3 * j, allNormals.data() + 3 * j + 3);
      }
      else
      {
        orient.insert(orient.end(), { q[0] - centroid[0], q[1] - centroid[1], q[2] - centroid[2] });
      }
    }
    const auto estimates = asmcore::EstimateCurvature(oxyz, cloud.Ids(), localTree, queries.data(),
      static_cast<Index>(mineToMeasure.size()), orient.data(), curvatureNeighbors, execution);
    for (std::size_t m = 0; m < estimates.size(); ++m)
    {
      perPoint[2 * n + mineToMeasure[m]] = estimates[m].MeanCurvature;
      perPoint[3 * n + mineToMeasure[m]] = estimates[m].SurfaceVariation;
    }
  }
  comm.Sum(perPoint);
  result.SimplifiedToOriginal =
    asmcore::Summarize(std::vector<double>(perPoint.begin(), perPoint.begin() + n));
  result.Hausdorff = std::max(result.OriginalToSimplified.Max, result.SimplifiedToOriginal.Max);

  // This process's simplified points.
  result.SimplifiedError.resize(sids.size());
  if (curvatureNeighbors > 0)
  {
    out.Curvature.resize(sids.size());
  }
  for (std::size_t i = 0; i < sids.size(); ++i)
  {
    const std::size_t j = static_cast<std::size_t>(offset / 3) + i; // offset counts doubles
    result.SimplifiedError[i] = perPoint[n + j];
    if (curvatureNeighbors > 0)
    {
      out.Curvature[i].MeanCurvature = perPoint[2 * n + j];
      out.Curvature[i].SurfaceVariation = perPoint[3 * n + j];
    }
  }
  return out;
}
} // namespace asmvtk
