// SPDX-License-Identifier: BSD-3-Clause
/**
 * Per-cell PCA (paper §3.2 steps i-iv): centroid, covariance and eigenframe
 * of the points of one grid cell.
 */
#ifndef asm_core_CellFrame_h
#define asm_core_CellFrame_h

#include "Common.h"

#include <Eigen/Core>

namespace asmcore
{
/// The PCA frame of a set of points.
struct VTKASMFILTERS_EXPORT CellFrame
{
  Eigen::Vector3d Centroid = Eigen::Vector3d::Zero();
  /// Columns v0, v1, v2: unit eigenvectors of the covariance, for eigenvalues
  /// in descending order; right-handed (v2 = v0 x v1); v2 ~ the normal.
  Eigen::Matrix3d Axes = Eigen::Matrix3d::Identity();
  /// lambda0 >= lambda1 >= lambda2 >= 0 (covariance divided by n).
  Eigen::Vector3d Lambda = Eigen::Vector3d::Zero();
  Index Count = 0;

  /// lambda2 / (lambda0 + lambda1 + lambda2), in [0, 1/3]; 0 when degenerate.
  double SurfaceVariation() const;
  Eigen::Vector3d Normal() const { return this->Axes.col(2); }
  /// Coordinates of p in the frame (origin at the centroid).
  Eigen::Vector3d ToLocal(const double p[3]) const;
};

/// How the covariance's eigenpairs are found.
enum class FrameSolver
{
  Iterative, ///< Eigen's QR iteration: accurate to the last bits (the cells' frames)
  ClosedForm ///< Eigen's closed form (computeDirect): about 3x faster, axes within ~1e-12
};

/// The PCA frame of the points xyz[ids[i]], i < ids.size(). The eigenvector
/// signs are fixed (largest component of v0 and v1 positive) so the frame
/// does not depend on the eigen solver's choices. Coincident or collinear
/// points give a valid frame with zero eigenvalues.
VTKASMFILTERS_EXPORT CellFrame ComputeCellFrame(
  Coordinates xyz, IdView ids, FrameSolver solver = FrameSolver::Iterative);
} // namespace asmcore

#endif
