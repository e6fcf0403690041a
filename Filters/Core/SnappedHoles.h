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
 * leave the input points.
 *
 * The bound is a maximum over the whole cloud. For samples spread over
 * several processes (distributed runs) it is taken in steps, each process
 * on its own samples: the reaches (SnappedReaches) and the largest reach of
 * the samples that stay (FixedReach), whose maximum over the processes
 * starts the bound; the candidates reaching past it, with their centres
 * (SnapCandidates); the bound from every process's candidates, widest first
 * (SnapBound); and the moves (MoveSnappedSamples). BoundSnappedHoles is
 * those steps on one set of samples (computing only the centres it needs).
 */
#ifndef asm_core_SnappedHoles_h
#define asm_core_SnappedHoles_h

#include "Simplify.h"

#include <utility>
#include <vector>

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

/// A sample that may move: its squared reach from its position, the
/// squared radius of its cluster about its (approximate) minimax centre,
/// and that centre.
struct VTKASMFILTERS_EXPORT SnapCandidate
{
  Index Sample = -1;
  double Reach = 0.0;
  double Radius = 0.0;
  double Centre[3] = { 0, 0, 0 };
};

/// The squared reach of every sample's cluster from its position (samples
/// and clusters as in BoundSnappedHoles).
VTKASMFILTERS_EXPORT std::vector<double> SnappedReaches(Coordinates xyz,
  const std::vector<Index>& memberStart, const Index* members, const double* positions,
  const Execution& execution = {});

/// The largest of `reach` over the samples not flagged in `snapped` (0 for
/// none): where the bound starts.
VTKASMFILTERS_EXPORT double FixedReach(
  const std::vector<double>& reach, const std::vector<char>& snapped);

/// The snapped samples whose reach exceeds `start`, in sample order, each
/// with its centre and radius.
VTKASMFILTERS_EXPORT std::vector<SnapCandidate> SnapCandidates(Coordinates xyz,
  const std::vector<Index>& memberStart, const Index* members, const std::vector<char>& snapped,
  const std::vector<double>& reach, double start, const double* positions,
  const Execution& execution = {});

/// The bound (a squared reach) from its start and the candidates' (reach,
/// radius), widest first: each candidate that still reaches past the bound
/// raises it to its radius; the first that does not ends the scan.
VTKASMFILTERS_EXPORT double SnapBound(
  double start, const std::vector<std::pair<double, double>>& reachAndRadius);

/// Moves the candidates that reach past `limit` towards their centres, just
/// far enough.
VTKASMFILTERS_EXPORT void MoveSnappedSamples(Coordinates xyz, const std::vector<Index>& memberStart,
  const Index* members, const std::vector<SnapCandidate>& candidates, double limit,
  double* positions, const Execution& execution = {});
} // namespace asmcore

#endif
