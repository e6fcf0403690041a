// SPDX-License-Identifier: BSD-3-Clause
/**
 * vtkKeyPointError in distributed (MPI) runs: the figures of the whole
 * original and simplified clouds, whatever their split over the processes.
 * Private (not wrapped, not installed); the communication is in
 * vtkASMDistributed.h.
 *
 * The simplified cloud (small) is gathered on every process. The original
 * is redistributed by grid cell as in vtkASMSimplify (one grid covering
 * both clouds, sized from the original's distinct cells, boxes of cells, a halo of
 * HaloRings cells), so each original key point is found once, by its cell's
 * owner, against all the simplified key points; nearest-neighbour and
 * point-to-plane distances of the original points use the whole simplified
 * cloud. Measures at a simplified point (its distance to the original,
 * "Error", curvature) are computed by the owner of its cell from the owned
 * and halo original points, then summed over the processes (one contributor
 * each). Sums, counts and maxima are reduced, so the figures equal the
 * serial ones up to floating-point summation order, provided the k nearest
 * original points of a simplified point lie within HaloRings cells of it.
 */
#ifndef vtkASMDistributedMetrics_h
#define vtkASMDistributedMetrics_h

#include "Core/Curvature.h"
#include "Core/Metrics.h"
#include "vtkASMDistributed.h"

namespace asmvtk
{
/// The comparison of a distributed run, and the per-point measures of this
/// process's simplified points (in the order of `sids`).
struct DistributedComparison
{
  asmcore::Comparison Figures;
  Index OriginalPoints = 0;                          ///< over all processes
  Index SimplifiedPoints = 0;                        ///< over all processes
  std::vector<asmcore::CurvatureEstimate> Curvature; ///< when requested
};

/// Collective. `snormals` (sids order x 3, may be null on every process)
/// orients the curvature; curvatureNeighbors <= 0: no curvature. The
/// process's own loops run on `threads` (its For only: a progress report
/// that aborts one process would leave the others waiting in a collective).
DistributedComparison CompareDistributed(const Communication& comm, const double* xyz,
  asmcore::IdView ids, const double* sxyz, const std::vector<Index>& sids, const double* snormals,
  const asmcore::ComparisonOptions& options, int curvatureNeighbors,
  const asmcore::Execution& threads = {});
} // namespace asmvtk

#endif
