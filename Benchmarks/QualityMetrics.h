// SPDX-License-Identifier: BSD-3-Clause
/**
 * The quality measures of asm_quality_benchmark, the same for every method.
 * All lengths are divided by the original cloud's bounding-box diagonal.
 *
 *  - PlaneMean, PlaneMax: point-to-plane distance from each ORIGINAL point to
 *    the simplified surface, the plane being fitted (PCA) to the
 *    PlaneNeighbors (8) simplified points nearest that original point
 *    (asmcore::PointToPlaneDistances); mean and maximum;
 *  - NNRms: nearest-neighbour distance RMS both ways,
 *    sqrt((mean d(o, S)^2 + mean d(s, O)^2) / 2) -- the two directions
 *    weigh the same whatever the counts;
 *  - Hole: the largest hole, max over original points o of d(o, S) (the
 *    one-sided Hausdorff distance original -> simplified);
 *  - TipMean, TipMax: over the known feature points f (synthetic shapes
 *    only), the distance d(f, S) to the nearest sample.
 */
#ifndef asm_QualityMetrics_h
#define asm_QualityMetrics_h

#include "Core/Neighbors.h"

#include <vector>

namespace asmbench
{
struct Quality
{
  double PlaneMean = 0.0;
  double PlaneMax = 0.0;
  double NNRms = 0.0;
  double Hole = 0.0;
  double TipMean = 0.0;
  double TipMax = 0.0;
  bool HasTips = false;
};

/// Each measure's median over `draws` (non-empty; e.g. the measures of
/// several draws of a random method), measure by measure (Median: the mean
/// of the two middle values for an even count).
Quality MedianQuality(const std::vector<Quality>& draws);

/// The original cloud, indexed once and measured against many simplifications.
class Reference
{
public:
  /// xyz: the original points; features: known feature points (may be empty).
  Reference(std::vector<double> xyz, std::vector<double> features);
  double Diagonal() const { return this->Diag; }

  /// Measures `simplified` (x y z of each sample; non-empty) against the original.
  Quality Measure(const std::vector<double>& simplified, int planeNeighbors = 8) const;

private:
  std::vector<double> Xyz;
  std::vector<asmcore::Index> Ids;
  std::vector<double> Features;
  asmcore::Neighbors Tree;
  double Diag = 0.0;
};
} // namespace asmbench

#endif
