// SPDX-License-Identifier: BSD-3-Clause
/**
 * Per-point curvature estimates, for colouring a cloud as in the paper's
 * figures (mean curvature) and for the surface variation.
 *
 * For a query position p and its neighbourhood N(p), the k points of the
 * original cloud nearest p (found with a Neighbors tree):
 *  1. PCA of N(p) (ComputeCellFrame, closed-form eigen solver: the
 *     estimates agree with the iterative solver's to about 1e-13 relative):
 *     centroid c, axes v0, v1, v2 and
 *     eigenvalues lambda0 >= lambda1 >= lambda2; the surface variation is
 *     lambda2 / (lambda0 + lambda1 + lambda2), in [0, 1/3].
 *  2. The normal n = +-v2, oriented to agree with a given normal at p (or,
 *     without one, to point away from the centroid of the whole cloud).
 *  3. Local coordinates (u, v, w) = ((x - o).v0, (x - o).v1, (x - o).n)
 *     with origin o = p - ((p - c).n) n, the projection of p onto the PCA
 *     plane, divided by the RMS radius of N(p) around o in that plane for
 *     conditioning (the curvature is scaled back).
 *  4. Least-squares fit of the quadric w = a u^2 + b uv + c v^2 + d u + e v + f
 *     (its 6x6 normal equations, from 21 moment sums, solved by a pivoted
 *     LDLT: the scaled coordinates keep them well conditioned, and the
 *     coefficients agree with a QR of the design matrix to about 1e-13
 *     relative). With fewer than 6 neighbours, or a rank-deficient design
 *     (a pivot of the LDLT below (1e-6)^2 of the largest, i.e. a QR pivot
 *     below 1e-6 of the largest; e.g. neighbours on a line or on two
 *     lines), the surface is taken to be the PCA plane: curvature 0.
 *  5. The mean curvature of the graph w = f(u, v) at (0, 0), i.e. at the
 *     point of the fitted surface above the projection o of p, with the full
 *     formula (gradient terms included, so a tilted fit is handled):
 *        H_graph = ((1 + fv^2) fuu - 2 fu fv fuv + (1 + fu^2) fvv)
 *                  / (2 (1 + fu^2 + fv^2)^(3/2)),
 *     fu = d, fv = e, fuu = 2a, fuv = b, fvv = 2c.
 *
 * Sign convention: MeanCurvature = -H_graph, i.e. it is POSITIVE where the
 * surface bends away from the oriented normal n (convex seen from the side
 * n points to). A sphere of radius r gives +1/r with outward normals and
 * -1/r with inward ones; a cylinder of radius r gives +-1/(2r); a plane 0.
 * Units are 1/length; the estimate is invariant to translating, rotating
 * or uniformly scaling the cloud (up to the 1/scale of a curvature).
 */
#ifndef asm_core_Curvature_h
#define asm_core_Curvature_h

#include "Common.h"
#include "Neighbors.h"

namespace asmcore
{
/// Default neighbourhood size. The quadric has 6 unknowns; 20 neighbours
/// over-determine it more than three times, which averages sampling noise,
/// while keeping the neighbourhood local (a radius of about 2.5 point
/// spacings on a uniformly sampled surface), so that the quadric model
/// of the surface holds and sharp features are not blurred over a large
/// area. 20 is also a usual neighbourhood size for PCA normals and the
/// surface variation.
constexpr int DefaultCurvatureNeighbors = 20;

/// Curvature at one query position.
struct VTKASMFILTERS_EXPORT CurvatureEstimate
{
  double MeanCurvature = 0.0;     ///< see the sign convention above; NaN: no estimate
  double SurfaceVariation = 0.0;  ///< lambda2 / (lambda0 + lambda1 + lambda2); NaN: no estimate
  double Normal[3] = { 0, 0, 0 }; ///< unit oriented PCA normal n; 0 0 0: no estimate
  int NumberOfNeighbors = 0;      ///< size of the neighbourhood used
  bool QuadricFit = false;        ///< false: plane fallback (MeanCurvature 0) or no estimate
};

/// The estimate for one position p, given its neighbourhood (ids into xyz)
/// and the normal to orient n by (must not be perpendicular to the PCA
/// normal for the sign to be meaningful). No neighbours: NaN estimate.
VTKASMFILTERS_EXPORT CurvatureEstimate EstimateCurvatureAt(const double* xyz,
  const Index* neighbors, Index count, const double p[3], const double orientNormal[3]);

/// The estimates at nQueries positions queries[3*i] (not necessarily points
/// of the cloud), each from its k nearest points in `tree`, which must have
/// been built over (xyz, ids); k <= 0 means DefaultCurvatureNeighbors.
/// orientNormals: nullptr, or nQueries x 3
/// normals that the output normals are oriented to agree with; nullptr:
/// each normal points away from the centroid of the points `ids` (right for
/// closed, roughly convex shapes; pass normals otherwise).
///
/// Runs the queries through exec.Run: each query writes only its own slot,
/// so the result does not depend on how the range is cut. Reports progress
/// in 20 batches; if exec.Report asks to abort, returns an empty vector.
/// A non-finite query, or an empty tree, gives a NaN estimate.
/// Cost: O(nQueries (log N + k log k + k)) after the tree.
VTKASMFILTERS_EXPORT std::vector<CurvatureEstimate> EstimateCurvature(Coordinates xyz, IdView ids,
  const Neighbors& tree, const double* queries, Index nQueries, const double* orientNormals, int k,
  const Execution& exec);
} // namespace asmcore

#endif
