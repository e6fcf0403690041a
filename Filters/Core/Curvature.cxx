// SPDX-License-Identifier: BSD-3-Clause
#include "Curvature.h"

#include "CellFrame.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>

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

// Relative pivot below which the quadric's design matrix is rank-deficient
// (a pivot of its QR, |R_ii| / |R_00|; the LDLT of the normal equations
// has D_i = R_ii^2, so its pivots are compared with the square).
constexpr double RankThreshold = 1e-6;

// Whether the pivots D of a pivoted LDLT of A^T A (largest first, as the
// pivoting takes them) are all above RankThreshold of the largest, squared.
bool IsFullRank(const Eigen::Matrix<double, 6, 1>& d)
{
  const double largest = d.cwiseAbs().maxCoeff();
  const double floor = RankThreshold * RankThreshold * largest;
  return largest > 0.0 && std::isfinite(largest) && (d.array() > floor).all();
}
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
  const CellFrame frame = ComputeCellFrame(
    xyz, IdView(neighbors, static_cast<std::size_t>(count)), FrameSolver::ClosedForm);
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

  // 4. Least squares: w = a u^2 + b uv + c v^2 + d u + e v + f, through its
  // normal equations (A^T A) x = A^T w, A's rows r = (u^2, uv, v^2, u, v, 1):
  // in the scaled coordinates their entries are of order 1. A^T A holds the
  // 15 moments m_ij = sum u^i v^j (i + j <= 4), A^T w the 6 sums of w u^i v^j
  // (i + j <= 2), summed in scalars.
  double m10 = 0, m01 = 0, m20 = 0, m11 = 0, m02 = 0, m30 = 0, m21 = 0, m12 = 0, m03 = 0;
  double m40 = 0, m31 = 0, m22 = 0, m13 = 0, m04 = 0;
  double w00 = 0, w10 = 0, w01 = 0, w20 = 0, w11 = 0, w02 = 0;
  for (Index i = 0; i < count; ++i)
  {
    const double u = local(i, 0);
    const double v = local(i, 1);
    const double w = local(i, 2);
    const double uu = u * u, uv = u * v, vv = v * v;
    m10 += u;
    m01 += v;
    m20 += uu;
    m11 += uv;
    m02 += vv;
    m30 += uu * u;
    m21 += uu * v;
    m12 += u * vv;
    m03 += vv * v;
    m40 += uu * uu;
    m31 += uu * uv;
    m22 += uu * vv;
    m13 += uv * vv;
    m04 += vv * vv;
    w00 += w;
    w10 += w * u;
    w01 += w * v;
    w20 += w * uu;
    w11 += w * uv;
    w02 += w * vv;
  }
  Eigen::Matrix<double, 6, 6> normalMatrix;
  // (Rows and columns in the order of r; symmetric.)
  normalMatrix << m40, m31, m22, m30, m21, m20, //
    m31, m22, m13, m21, m12, m11,               //
    m22, m13, m04, m12, m03, m02,               //
    m30, m21, m12, m20, m11, m10,               //
    m21, m12, m03, m11, m02, m01,               //
    m20, m11, m02, m10, m01, static_cast<double>(count);
  Eigen::Matrix<double, 6, 1> rhs;
  rhs << w20, w11, w02, w10, w01, w00;
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(normalMatrix);
  if (ldlt.info() != Eigen::Success || !IsFullRank(ldlt.vectorD()))
  {
    return estimate; // ill-posed: plane
  }
  const Eigen::Matrix<double, 6, 1> coef = ldlt.solve(rhs);
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

std::vector<CurvatureEstimate> EstimateCurvature(Coordinates xyz, IdView ids, const Neighbors& tree,
  const double* queries, Index nQueries, const double* orientNormals, int k, const Execution& exec)
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
      tree.KNearestByPosition(q, k, neighbors, sqDist, local);
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
