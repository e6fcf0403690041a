// SPDX-License-Identifier: BSD-3-Clause
/**
 * The bound on the holes that snapping to input points leaves
 * (SimplifyParameters::BoundSnappedHoles, feature-preserving mode).
 *
 * The largest hole of a simplification is the farthest any input point is
 * from its sample. A sample placed on an input point (InputPointSamples) may
 * sit to one side of its cluster, and then its cluster reaches farther than
 * it would from the cluster's minimax centre (the centre of the smallest
 * ball holding it). The bound is the largest hole the clusters would leave
 * with their samples at (about) their minimax centres, the other samples
 * (key points, centroids) where they are; the samples whose cluster reaches
 * past it move from their input point towards their centre, just far enough.
 * So snapping never makes the largest hole larger, and only those samples
 * leave the input points. Global (the bound is a maximum over the cloud),
 * so not for distributed runs.
 */
#ifndef asm_core_SnappedHoles_h
#define asm_core_SnappedHoles_h

#include "Simplify.h"

namespace asmcore
{
/// An approximate minimax centre of the points xyz[first[m]], m in
/// [0, n): 64 Badoiu-Clarkson steps from `start` towards the farthest point,
/// the best centre seen kept (in `centre`). Returns its squared radius (the
/// squared distance to the farthest point), at least the exact one's.
VTKASMFILTERS_EXPORT double MinimaxCentre(
  Coordinates xyz, const Index* first, Index n, const double start[3], double centre[3]);

/// Moves the samples flagged in `snapped` (input-point samples that may
/// leave their point) whose cluster reaches past the bound towards their
/// minimax centre, just far enough (see above). Sample s (of snapped.size())
/// is at positions[3 s, 3 s + 3) and its cluster is the points xyz[m] for m
/// in members[memberStart[s], memberStart[s + 1]). Clusters are taken widest
/// first, so that only those need a centre; the result does not depend on
/// the thread count.
VTKASMFILTERS_EXPORT void BoundSnappedHoles(Coordinates xyz, const std::vector<Index>& memberStart,
  const Index* members, const std::vector<char>& snapped, double* positions,
  const Execution& execution = {});
} // namespace asmcore

#endif
