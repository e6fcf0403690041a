// SPDX-License-Identifier: BSD-3-Clause
/**
 * Measures of a simplification (paper §3.4 and the field's usual ones): key
 * point error (AKPE, MKPE: Eq. 1-3), nearest-neighbour distances in both
 * directions, the symmetric Hausdorff distance, and point-to-plane
 * distances to the other cloud's surface (a plane fitted to its k nearest
 * points). Works for any pair of clouds, whatever simplified them.
 */
#ifndef asm_core_Metrics_h
#define asm_core_Metrics_h

#include "Common.h"
#include "Grid.h"
#include "KeyPoints.h"

#include <Eigen/Core>

#include <cfloat>

namespace asmcore
{
class Neighbors;

/// How the distance between paired key points is measured.
enum class KeyPointDistance
{
  Euclidean, ///< |p - p'| (default)
  Squared    ///< |p - p'|^2: the paper's Eq. 3 read literally
};

/// Count, mean, root mean square and maximum of a list of distances.
struct VTKASMFILTERS_EXPORT DistanceSummary
{
  Index Count = 0;
  double Mean = 0.0;
  double RMS = 0.0;
  double Max = 0.0;
};

/// Summary of `d`, summed in order (deterministic).
VTKASMFILTERS_EXPORT DistanceSummary Summarize(const std::vector<double>& d);

/// The key points of a whole cloud (§3.2): the centroid of every key cluster
/// of every cell of `spec`, found with `rule`, ordered by cell.
VTKASMFILTERS_EXPORT std::vector<Eigen::Vector3d> CloudKeyPoints(const double* xyz, IdView ids,
  const GridSpec& spec, const KeyPointRule& rule, const Execution& execution = {});

/// For each point xyz[3*id], id in ids: the distance to its nearest point in
/// `target` (+infinity when `target` is empty).
VTKASMFILTERS_EXPORT std::vector<double> NearestDistances(
  const double* xyz, IdView ids, const Neighbors& target, const Execution& execution = {});

/// For each point xyz[3*id], id in ids: the distance to the plane fitted
/// (PCA) to its k nearest points of the cloud indexed by `surface`; the
/// distance to the nearest point when fewer than 3 points are found, or
/// when they span no plane (one position, or a line: their spread across
/// their longest axis within 1e-6 of the spread along it or within the
/// rounding of double coordinates).
VTKASMFILTERS_EXPORT std::vector<double> PointToPlaneDistances(
  const double* xyz, IdView ids, const Neighbors& surface, int k, const Execution& execution = {});

/// For each point xyz[3*id], id in ids, from its k nearest points of the
/// cloud indexed by `surface` (one query each): in `plane`
/// what PointToPlaneDistances gives, in `nearest` what NearestDistances
/// gives (either may be null; resized to ids.size()). The queries are made
/// in blocks of nearby points (ForEachKNearest, BlockNeighbors.h), whatever
/// the order of the points; each answer is the same as alone.
/// `surfaceEpsilon`: the relative precision of the surface's coordinates
/// (FLT_EPSILON for floats), whose roundings do not make a line a plane.
VTKASMFILTERS_EXPORT void SurfaceDistances(const double* xyz, IdView ids, const Neighbors& surface,
  int k, std::vector<double>* plane, std::vector<double>* nearest, const Execution& execution = {},
  double surfaceEpsilon = DBL_EPSILON);

/// Parameters of CompareClouds.
struct VTKASMFILTERS_EXPORT ComparisonOptions
{
  KeyPointRule Rule;           ///< the key point rule of the simplifier (Alpha, ...)
  double CellSize = 0.0;       ///< grid cell edge; <= 0: as the simplifier would choose it
  double SamplesPerCell = 8.0; ///< for the automatic cell size, from the simplified count
  KeyPointDistance Measure = KeyPointDistance::Euclidean;
  int PlaneNeighbors = 8; ///< k of the point-to-plane fits
  /// The relative precision of the clouds' coordinates, the coarser of the
  /// two (SurfaceDistances: neighbours on a line within it span no plane).
  double SurfaceEpsilon = DBL_EPSILON;
};

/// Everything measured between an original and a simplified cloud. Lengths
/// in data units; AKPE and MKPE squared with KeyPointDistance::Squared.
struct VTKASMFILTERS_EXPORT Comparison
{
  double CellSize = 0.0;
  Index OriginalKeyPoints = 0;
  Index SimplifiedKeyPoints = 0;
  double AKPE = 0.0;                    ///< Eq. 1 over the original key points
  double MKPE = 0.0;                    ///< Eq. 2
  double Diagonal = 0.0;                ///< of the original's bounding box
  DistanceSummary OriginalToSimplified; ///< nearest-neighbour distances
  DistanceSummary SimplifiedToOriginal;
  double Hausdorff = 0.0;              ///< symmetric: max of the two maxima
  DistanceSummary PointToPlane;        ///< original points to the simplified surface
  std::vector<double> SimplifiedError; ///< per simplified point: distance to the original surface
  bool Aborted = false;
};

/// Compare `original` (xyz[3*id], id in ids, indexed by `originalTree`) and
/// `simplified` (sxyz, sids), both finite and non-empty. Key points of both
/// clouds are found on one grid (covering both), each original key point is
/// paired with the nearest simplified key point.
VTKASMFILTERS_EXPORT Comparison CompareClouds(const double* xyz, IdView ids,
  const Neighbors& originalTree, const double* sxyz, const std::vector<Index>& sids,
  const ComparisonOptions& options, const Execution& execution = {});
} // namespace asmcore

#endif
