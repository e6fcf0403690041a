// SPDX-License-Identifier: BSD-3-Clause
/**
 * The output of the feature-preserving mode (FeatureSimplify.h, phase 6),
 * in two steps: with the cell-ordered copy of the points, each sample's
 * final position and representative (PlaceOutputSamples); after the copy is
 * released, the samples with their normals (LayOutSamples). Before them,
 * the clusters' last repair (FillEmptyClusters). Private to
 * SimplifyFeaturePreserving (declared here for its tests).
 */
#ifndef asm_core_FeatureOutput_h
#define asm_core_FeatureOutput_h

#include "CellNeighbors.h"
#include "Grid.h"
#include "Lloyd.h"
#include "Simplify.h"

#include <vector>

namespace asmcore
{
namespace feature
{
// Per-sample facts besides the position.
struct VTKASMFILTERS_EXPORT SampleInfo
{
  Index Owner = -1; // grid cell whose frame gives the normal
  /// Key samples: the extreme input point (a slot); from the output's first
  /// step on, every sample's representative (an input point id).
  Index Point = -1;
  double KeyError = 0.0;
};

// What the output needs of a cell's frame.
struct VTKASMFILTERS_EXPORT CellSurface
{
  Eigen::Vector3d Normal;
  Eigen::Vector3d Centroid;
  double SurfaceVariation;
};

/// Per cell, whether its samples are output (SimplifyParameters::OutputCell,
/// a distributed run's own cells); empty without OutputCell (all are).
VTKASMFILTERS_EXPORT std::vector<char> OutputCells(
  const CellGrid& grid, const SimplifyParameters& parameters);

/// The clusters' last repair, before the output: every sample left without
/// members (count[s] == 0) takes the point nearest it, among the points of
/// its owner cell's ring (neighbors) that are unassigned or whose cluster
/// has two or more members, so that no cluster is emptied in turn (never a
/// key sample's extreme point, info[s].Point, from its cluster); samples
/// in index order, `assign` (by slot) and `count` updated. A sample whose
/// ring has no such point (N_s close to N) then takes the nearest such
/// point of the whole grid, so that no sample stays empty while there are
/// at least as many points as samples. With `output` (OutputCells, a
/// distributed run), only the output cells' samples do, and only points
/// that this process outputs (a member of an output cell's sample, or
/// unassigned in an output cell): a point taken there is one that no other
/// process outputs, and no point of another process's cluster is taken.
VTKASMFILTERS_EXPORT void FillEmptyClusters(Coordinates xyz, const CellGrid& grid,
  const CellNeighborTable& neighbors, const SampleSet& samples, const std::vector<SampleInfo>& info,
  PointArray<SampleId>& assign, std::vector<Index>& count,
  const std::vector<char>& output = std::vector<char>());

/// Output, step 1. P: the points in slot order (the cell-ordered copy);
/// members: each sample's members as slots, grouped by sample
/// (memberStart). Each sample's final position (into samples.Position): an
/// input point with InputPointSamples or Snap (the member nearest the
/// sample; ties by position, then id), else its cluster's centroid (key
/// samples stay on their extreme point); with BoundSnappedHoles, the
/// snapped samples whose cluster reaches past the largest hole minimax
/// centres would leave move towards that centre. Then the members and each
/// sample's representative (info[s].Point) become input point ids (idOf),
/// and `duplicates` lists the representatives' exact duplicates
/// (SimplifyResult::RepresentativeDuplicates).
VTKASMFILTERS_EXPORT void PlaceOutputSamples(Coordinates P, const CellGrid& grid,
  const SlotIds& idOf, const std::vector<Index>& memberStart, const SimplifyParameters& parameters,
  SampleSet& samples, std::vector<SampleInfo>& info, PointArray<Index>& members,
  std::vector<std::pair<Index, Index>>& duplicates, const Execution& execution);

/// Output, step 2 (result.Members holds input point ids): result.Samples from the samples'
/// positions, members and representatives, each with its owner cell's surface: the normal oriented
/// along the members' input normals (else away from the cloud's centroid),
/// the surface variation, the key flag and error.
VTKASMFILTERS_EXPORT void LayOutSamples(Coordinates xyz, IdView ids, NormalField normals,
  const std::vector<CellSurface>& surfaces, const std::vector<SampleInfo>& info,
  const SampleSet& samples, const std::vector<Index>& memberStart,
  const SimplifyParameters& parameters, SimplifyResult& result, const Execution& execution);

/// Distributed runs: only the samples of the cells this process outputs (its
/// own, SimplifyParameters::OutputCell), with their members; the others were
/// computed as context.
VTKASMFILTERS_EXPORT void KeepOutputCells(
  SimplifyResult& result, const std::vector<SampleInfo>& info, const std::vector<char>& output);
} // namespace feature
} // namespace asmcore

#endif
