// SPDX-License-Identifier: BSD-3-Clause
#include "Curvature.h"

#include "CellFrame.h"

#include <Eigen/Core>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
namespace
{
CurvatureEstimate NoEstimate(Index count)
{
  CurvatureEstimate e;
  e.MeanCurvature = std::numeric_limits<double>::quiet_NaN();
  e.SurfaceVariation = std::numeric_limits<double>::quiet_NaN();
  e.NumberOfNeighbors = static_cast<int>(count);
  return e;
}

bool Finite(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// Relative pivot below which the quadric's design matrix is rank-deficient.
constexpr double RankThreshold = 1e-6;
} // namespace

CurvatureEstimate EstimateCurvatureAt(const double* xyz, const Index* neighbors, Index count,
  const double p[3], const double orientNormal[3])
{
  if (count <= 0 || !Finite(p))
  {
    return NoEstimate(count);
  }
  CurvatureEstimate estimate;
  estimate.NumberOfNeighbors = static_cast<int>(count);

  // 1-2. PCA frame and oriented normal.
  const CellFrame frame = ComputeCellFrame(xyz, IdView(neighbors, static_cast<std::size_t>(count)));
  Eigen::Vector3d n = frame.Normal();
  if (orientNormal &&
    n.dot(Eigen::Vector3d(orientNormal[0], orientNormal[1], orientNormal[2])) < 0.0)
  {
    n = -n;
  }
  estimate.SurfaceVariation = frame.SurfaceVariation();
  for (int a = 0; a < 3; ++a)
  {
    estimate.Normal[a] = n[a];
  }
  if (count < 6)
  {
    return estimate; // plane
  }

  // 3. Local coordinates around the projection o of p onto the PCA plane.
  const Eigen::Vector3d pv(p[0], p[1], p[2]);
  const Eigen::Vector3d origin = pv - (pv - frame.Centroid).dot(n) * n;
  const Eigen::Vector3d e0 = frame.Axes.col(0);
  const Eigen::Vector3d e1 = frame.Axes.col(1);
  // Scratch kept per thread: the many small fits of a run allocate nothing.
  thread_local Eigen::Matrix<double, Eigen::Dynamic, 3> local;
  thread_local Eigen::Matrix<double, Eigen::Dynamic, 6> design;
  thread_local Eigen::ColPivHouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, 6>> qr;
  local.resize(count, 3);
  double radius2 = 0.0;
  for (Index i = 0; i < count; ++i)
  {
    const double* x = xyz + 3 * neighbors[i];
    const Eigen::Vector3d d = Eigen::Vector3d(x[0], x[1], x[2]) - origin;
    local(i, 0) = d.dot(e0);
    local(i, 1) = d.dot(e1);
    local(i, 2) = d.dot(n);
    radius2 += local(i, 0) * local(i, 0) + local(i, 1) * local(i, 1);
  }
  const double scale = std::sqrt(radius2 / static_cast<double>(count));
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    return estimate; // every neighbour projects onto o: plane
  }
  local /= scale;

  // 4. Least squares: w = a u^2 + b uv + c v^2 + d u + e v + f.
  design.resize(count, 6);
  for (Index i = 0; i < count; ++i)
  {
    const double u = local(i, 0);
    const double v = local(i, 1);
    design.row(i) << u * u, u * v, v * v, u, v, 1.0;
  }
  qr.setThreshold(RankThreshold);
  qr.compute(design);
  if (qr.rank() < 6)
  {
    return estimate; // ill-posed: plane
  }
  const Eigen::Matrix<double, 6, 1> coef = qr.solve(local.col(2));
  if (!coef.allFinite())
  {
    return estimate;
  }

  // 5. Mean curvature of the graph at (0, 0), in scaled units, then back to
  // 1 / length; negated so that bending away from n is positive.
  const double fu = coef[3];
  const double fv = coef[4];
  const double fuu = 2.0 * coef[0];
  const double fuv = coef[1];
  const double fvv = 2.0 * coef[2];
  const double g = 1.0 + fu * fu + fv * fv;
  const double h = ((1.0 + fv * fv) * fuu - 2.0 * fu * fv * fuv + (1.0 + fu * fu) * fvv) /
    (2.0 * g * std::sqrt(g));
  estimate.MeanCurvature = -h / scale;
  estimate.QuadricFit = true;
  return estimate;
}

std::vector<CurvatureEstimate> EstimateCurvature(Coordinates xyz, IdView ids,
  const Neighbors& tree, const double* queries, Index nQueries, const double* orientNormals, int k,
  const Execution& exec)
{
  std::vector<CurvatureEstimate> estimates(static_cast<std::size_t>(std::max<Index>(nQueries, 0)));
  if (nQueries <= 0)
  {
    return estimates;
  }
  if (k <= 0)
  {
    k = DefaultCurvatureNeighbors;
  }
  // Without normals, orient away from the centroid of the cloud (summed in
  // id order: deterministic).
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  if (!orientNormals && !ids.empty())
  {
    for (Index id : ids)
    {
      Eigen::Vector3d p;
      xyz.Get(id, p.data());
      centroid += p;
    }
    centroid /= static_cast<double>(ids.size());
  }

  auto body = [&](Index begin, Index end) {
    // Reused by the queries of this range. The neighbours' coordinates come
    // from the tree (the same numbers as the cloud's, widened for a float
    // cloud), side by side: no gather from a cloud in random order.
    std::vector<Index> neighbors;
    std::vector<double> sqDist;
    std::vector<double> local;
    std::vector<Index> localIds;
    for (Index i = begin; i < end; ++i)
    {
      const double* q = queries + 3 * i;
      tree.KNearest(q, k, neighbors, sqDist, local);
      double away[3];
      const double* orient = orientNormals ? orientNormals + 3 * i : away;
      for (int a = 0; a < 3; ++a)
      {
        away[a] = q[a] - centroid[a];
      }
      const auto count = static_cast<Index>(neighbors.size());
      for (auto j = static_cast<Index>(localIds.size()); j < count; ++j)
      {
        localIds.push_back(j);
      }
      estimates[static_cast<std::size_t>(i)] =
        EstimateCurvatureAt(local.data(), localIds.data(), count, q, orient);
    }
  };

  const Index batches = 20;
  for (Index batch = 0; batch < batches; ++batch)
  {
    const Index begin = nQueries * batch / batches;
    const Index end = nQueries * (batch + 1) / batches;
    exec.Run(begin, end, body);
    if (exec.Report(static_cast<double>(batch + 1) / static_cast<double>(batches)))
    {
      return {};
    }
  }
  return estimates;
}
} // namespace asmcore
