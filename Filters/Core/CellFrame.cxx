// SPDX-License-Identifier: BSD-3-Clause
#include "CellFrame.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace asmcore
{
namespace
{
// Flip v so that its component of largest magnitude is positive (ties: the
// first such component).
Eigen::Vector3d Canonical(const Eigen::Vector3d& v)
{
  Eigen::Index k = 0;
  for (Eigen::Index i = 1; i < 3; ++i)
  {
    if (std::abs(v[i]) > std::abs(v[k]) * (1.0 + 1e-12))
    {
      k = i;
    }
  }
  return v[k] < 0.0 ? Eigen::Vector3d(-v) : v;
}
} // namespace

double CellFrame::SurfaceVariation() const
{
  const double sum = this->Lambda.sum();
  return sum > 0.0 ? std::max(0.0, this->Lambda[2]) / sum : 0.0;
}

Eigen::Vector3d CellFrame::ToLocal(const double p[3]) const
{
  const Eigen::Vector3d d = Eigen::Vector3d(p[0], p[1], p[2]) - this->Centroid;
  return this->Axes.transpose() * d;
}

CellFrame ComputeCellFrame(Coordinates xyz, IdView ids, FrameSolver solverKind)
{
  const auto count = static_cast<Index>(ids.size());
  CellFrame frame;
  frame.Count = count;
  if (count <= 0)
  {
    return frame;
  }
  // Two passes (mean, then centred covariance) stay accurate far from the
  // origin, e.g. for georeferenced scans.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Index i = 0; i < count; ++i)
  {
    Eigen::Vector3d p;
    xyz.Get(ids[i], p.data());
    sum += p;
  }
  frame.Centroid = sum / static_cast<double>(count);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (Index i = 0; i < count; ++i)
  {
    Eigen::Vector3d p;
    xyz.Get(ids[i], p.data());
    const Eigen::Vector3d d = p - frame.Centroid;
    cov.noalias() += d * d.transpose();
  }
  cov /= static_cast<double>(count);
  if (!cov.allFinite())
  {
    return frame; // overflow on absurd coordinates: identity frame
  }

  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  if (solverKind == FrameSolver::ClosedForm)
  {
    solver.computeDirect(cov);
  }
  else
  {
    solver.compute(cov);
  }
  if (solver.info() != Eigen::Success)
  {
    return frame;
  }
  // Eigen sorts ascending: column 2 has the largest eigenvalue.
  const Eigen::Vector3d v0 = Canonical(solver.eigenvectors().col(2)).normalized();
  Eigen::Vector3d v1 = solver.eigenvectors().col(1);
  v1 = Canonical((v1 - v1.dot(v0) * v0).normalized());
  frame.Axes.col(0) = v0;
  frame.Axes.col(1) = v1;
  frame.Axes.col(2) = v0.cross(v1).normalized();
  for (int k = 0; k < 3; ++k)
  {
    frame.Lambda[k] = std::max(0.0, solver.eigenvalues()[2 - k]);
  }
  return frame;
}
} // namespace asmcore
