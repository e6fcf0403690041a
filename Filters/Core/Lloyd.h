// SPDX-License-Identifier: BSD-3-Clause
/**
 * Spatially connected middle clusters for the feature-preserving mode: the
 * samples of a cell are seeded by farthest-point sampling from its key points
 * and relaxed by a few Lloyd (k-means) iterations with the key samples fixed,
 * first inside the cell, then across cell borders (each point goes to the
 * nearest sample owned by its own or a neighbouring cell). A Lloyd cluster is
 * the part of the cloud nearest one sample, a convex region cut out of the
 * surface: it does not break into pieces the way median splits of a band with
 * holes do, and its centroid stays on the surface.
 *
 * Every sample belongs to one grid cell (its owner). Each step looks at one
 * ring of cells only and writes per-cell or per-point slots, so the result
 * does not depend on the thread count.
 */
#ifndef asm_core_Lloyd_h
#define asm_core_Lloyd_h

#include "CellFrame.h"
#include "CellNeighbors.h"
#include "ExactMean.h"
#include "KeyPoints.h"

#include <algorithm>
#include <cmath>

namespace asmcore
{
/// |a - b|^2 for two 3-vectors.
inline double SquaredDistance(const double* a, const double* b)
{
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

/// Whether squared distances a and b differ by rounding only (the centroid
/// of two points is as far from both, whatever the summation order), so that
/// the choice between them is made on positions instead (PositionBefore).
inline bool NearlyEqual(double a, double b)
{
  return a == b ||
    (std::isfinite(a) && std::isfinite(b) && std::abs(a - b) <= 1e-12 * std::max(a, b));
}

/// A cell owning more samples than this is handled with O(n log b) steps
/// (median-split seeds, a k-d tree of the samples for the assignment)
/// instead of O(n b) ones, which matters with a large explicit CellSize.
constexpr Index LargeCellBudget = 64;

/// The samples of a run, grouped by owner cell.
struct VTKASMFILTERS_EXPORT SampleSet
{
  std::vector<double> Position; ///< 3 per sample
  std::vector<char> Fixed;      ///< key samples do not move
  std::vector<Index> Start;     ///< cell c owns samples [Start[c], Start[c+1])
  Index Size() const { return static_cast<Index>(this->Fixed.size()); }
};

/// Place the free samples of a cell whose points are xyz[points[i]] (sample
/// slots firstSample + fixedCount .. firstSample + budget; the fixed ones
/// are already written) by farthest-point seeding from the fixed samples and
/// `iterations` Lloyd iterations inside the cell. With iterations == 0 or
/// budget > LargeCellBudget, the free samples are instead the centroids of
/// median splits in the (v0, v1) plane of the cell's points other than
/// `exclude` (the literal reading's middle clustering). Scratch vectors are
/// reused.
struct VTKASMFILTERS_EXPORT CellScratch
{
  std::vector<double> Distance;
  std::vector<Index> Label;
  std::vector<double> Sum;
  std::vector<Index> Count;
  std::vector<Index> Subset;
  LocalPoints Local;
};
VTKASMFILTERS_EXPORT void RelaxCell(Coordinates xyz, IdView points, const CellFrame& frame,
  const std::vector<Index>& exclude, Index firstSample, Index fixedCount, Index budget,
  int iterations, SampleSet& samples, CellScratch& scratch);

/// One Lloyd step across cell borders: every free sample moves to the
/// centroid of the points assigned to it (unchanged when it has none).
VTKASMFILTERS_EXPORT void MoveToCentroids(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const PointArray<SampleId>& assign, SampleSet& samples,
  const Execution& execution);

/// The surface variation lambda_0 / (lambda_0 + lambda_1 + lambda_2) of
/// every sample's cluster (the points assigned to it; 0 for fewer than 3
/// points), per sample.
VTKASMFILTERS_EXPORT std::vector<double> ClusterVariations(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const PointArray<SampleId>& assign, const SampleSet& samples,
  const Execution& execution);

/// The factors of a variation-weighted assignment (AssignToSamples' scale):
/// per sample 1 + weight * min(cap, variation[s] / mean); all 1 when the
/// mean is 0 (or not positive).
VTKASMFILTERS_EXPORT std::vector<double> VariationScales(
  const std::vector<double>& variation, double weight, double cap, double mean);

/// The same with the mean of `variation` (an ExactMean).
VTKASMFILTERS_EXPORT std::vector<double> VariationScales(
  const std::vector<double>& variation, double weight, double cap);

} // namespace asmcore

#endif
