// SPDX-License-Identifier: BSD-3-Clause
/**
 * Covering refinement for the feature-preserving mode, when the samples are
 * input points (InputPointSamples): the largest hole of a sampling is the
 * input point farthest from every sample, and the input point nearest a
 * cluster's centre can sit on one side of its cluster (measured: the points
 * farthest from every sample are members of their own sample's cluster, on
 * the far side from an input point that is 1/3 to 1/2 of the hole away from
 * the cluster's centroid). One round: every point joins its nearest sample,
 * then every free sample moves to the member whose farthest member is
 * nearest (a discrete 1-centre of its cluster, among the members nearest the
 * cluster's centroid and the member it sits on). Neither step lengthens the
 * distance from a point to its sample, so the largest hole does not grow.
 *
 * Each sample reads its own members only (the points of its cell's ring),
 * and writes its own position: the result does not depend on the thread
 * count.
 */
#ifndef asm_core_Covering_h
#define asm_core_Covering_h

#include "Assignment.h"

namespace asmcore
{
/// Members of a cluster tried as its covering input point: this many nearest
/// its centroid, and the member the sample sits on.
constexpr int CoveringCandidates = 16;

/// One round of covering refinement (see above) of the free samples of
/// `samples`; `assign` is left holding the assignment the round started from
/// (AssignToSamples).
VTKASMFILTERS_EXPORT void RefineCovering(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, SampleSet& samples, PointArray<SampleId>& assign,
  const Execution& execution);
} // namespace asmcore

#endif
