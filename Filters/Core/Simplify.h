// SPDX-License-Identifier: BSD-3-Clause
/**
 * The ASM driver (paper §3.2, §3.3, §3.5): grid hashing, per-cell PCA,
 * budgets (Eq. 4), key points with the error bound (Eq. 5), and the
 * combination with sampling, producing exactly N_s samples. The parameters,
 * the result, and the steps both modes share; the modes' pipelines are in
 * PaperSimplify.h and FeatureSimplify.h.
 */
#ifndef asm_core_Simplify_h
#define asm_core_Simplify_h

#include "Common.h"
#include "Grid.h"

#include <cfloat>

namespace asmcore
{
/// Cell weight w_c of Eq. 4.
enum class WeightMode
{
  Uniform,         ///< w_c = 1
  SurfaceVariation ///< w_c = 1 + CurvatureWeight * sigma_c / mean(sigma)
};

/// Which pipeline runs.
enum class SimplifyMode
{
  FeaturePreserving, ///< the literal pipeline with the fixes of FeatureSimplify.h (default)
  Paper              ///< the paper's pipeline read literally (ASM-spec.md, "Pipeline")
};

/// Parameters of one run; lengths in data units.
struct VTKASMFILTERS_EXPORT SimplifyParameters
{
  Index NumberOfSamples = 0;   ///< N_s; clamped to the number of points
  double CellSize = 0.0;       ///< grid cell edge; <= 0: automatic
  double SamplesPerCell = 8.0; ///< mean budget per non-empty cell aimed at by the automatic size
  double Alpha = 0.125;        ///< partition threshold, fraction of a cell's v2 extent
  double ErrorTolerance = 0.0; ///< bound on each key point's error; <= 0: off
  WeightMode Weight = WeightMode::Uniform;
  double CurvatureWeight = 1.0;           ///< k of the surface-variation weight
  std::uint64_t RandomSeed = 1;           ///< seed of the random choice among key points
  bool Snap = false;                      ///< samples are input points (nearest the centroid)
  double LinkFactor = 2.0;                ///< key-cluster link distance, in mean point spacings
  double CoordinateEpsilon = DBL_EPSILON; ///< relative precision of the input coordinates
  SimplifyMode Mode = SimplifyMode::FeaturePreserving;

  // Options of the feature-preserving mode (ignored in Paper mode); each one
  // switches one fix off (see FeatureSimplify.h).
  bool ValidateKeyPoints = true; ///< Lemma 2 across cell borders
  double KeyPointRadius = 0.7;   ///< Lemma 2 radius, fraction of the cell size, in (0, 1]
  double KeyPointProminence =
    0.05;                         ///< least prominence of a validated key, fraction of that radius
  bool InPlaneKeyPoints = true;   ///< extremes along +-v0/+-v1 are key points too
  bool ExtremeKeyPoints = true;   ///< a key sample is its extreme point, not the band centroid
  bool CoverEveryCell = true;     ///< every non-empty cell gets a sample when N_s allows
  double BudgetExponent = 0.5;    ///< gamma of N_c ~ w_c * n_c^gamma (the paper: 1)
  int LloydIterations = 4;        ///< inside a cell; 0: median splits of the non-key points
  int CrossCellIterations = 1;    ///< across cell borders, clamped to MaxCrossCellIterations
  double FeatureLinkFactor = 4.0; ///< key-cluster link distance, in mean point spacings
  bool InputPointSamples =
    true; ///< each sample is the input point nearest its cluster's centre (see BoundSnappedHoles)
  bool FillHoles = true; ///< bounded hole filling (global: GatherOverProcesses in distributed runs)
  double HoleFillFraction = 0.02; ///< at most this fraction of the samples is moved per round
  int HoleFillRounds =
    4; ///< rounds of hole filling, each followed by a Lloyd step (DefaultHoleFillRounds)
  /// Mean budget per non-empty cell aimed at by the automatic cell size in
  /// this mode (SamplesPerCell is the paper mode's); <= 0: SamplesPerCell.
  double FeatureSamplesPerCell = 4.0;
  /// k of the budget weight w_c = 1 + k * sigma_c / mean(sigma) (surface
  /// variation, unitless) when Weight is Uniform; 0: w_c = 1. With Weight =
  /// SurfaceVariation, CurvatureWeight is k as in Paper mode.
  double VariationBudget = 1.0;
  /// Ratio r = sigma_c / mean(sigma) past which the weight with
  /// VariationBudget grows as sqrt(VariationCap * r) instead of r, so that a
  /// few sharp cells (cusps, spikes) do not draw the samples of the smooth
  /// surface away; <= 0: no cap.
  double VariationCap = 4.0;
  /// A cell of two or more samples keeps at least one free (Lloyd) sample:
  /// at most N_c - 1 of its samples are key samples (one in a cell of one).
  bool ReserveFreeSample = true;
  /// Lloyd iterations across cell borders after the hole filling, before
  /// the final clusters (they tighten the clusters the hole filling moved).
  /// Local (InfluenceRingsOf): distributed runs take them with a wider halo.
  int FinalLloydIterations = 2;
  /// k of the final Lloyd iterations' weighted assignment: a point joins
  /// the sample s of least m_s |p - s|^2, m_s = 1 + k min(VariationCap,
  /// sigma_s / mean(sigma)), sigma_s the surface variation of s's plain
  /// (Euclidean) cluster before the iteration (the first iteration reuses
  /// the assignment the steps before left, the next ones assign again); the
  /// samples crowd towards creases and curved bands, which the per-cell
  /// budget alone spreads over its cell. The mean is over the whole cloud
  /// (SumOverProcesses in distributed runs). 0: Euclidean.
  double LloydVariationWeight = 0.75;
  /// Rounds of covering refinement (Covering.h) of the input-point samples
  /// (InputPointSamples or Snap); 0: the input point nearest the cluster's
  /// centre (the default: BoundSnappedHoles bounds the largest hole without
  /// moving every sample). Global: not for distributed runs.
  int CoveringRounds = 0;
  /// A point of a cell of fewer than 3 points (no PCA frame) that is the
  /// Lemma 2 extreme away from its neighbours within KeyPointRadius is a key
  /// point (a spike tip alone in its cell); needs ValidateKeyPoints and
  /// InPlaneKeyPoints.
  bool SparseCellKeyPoints = true;
  /// With InputPointSamples (not Snap): a sample whose cluster reaches
  /// farther from it than the largest hole the clusters would leave with
  /// their samples at (about) their minimax centres (key samples where they
  /// are) moves towards that centre, just far enough: snapping never makes
  /// the largest hole larger, and only those samples (at 20 %: 2-15 % on the scans) leave
  /// the input points. Global: a distributed driver sets it off and takes
  /// the bound over all processes after the run (SnappedHoles.h).
  bool BoundSnappedHoles = true;

  /// @name Distributed runs (vtkASMDistributed); all unset in a serial run.
  /// Every process calls Simplify on the points of the cells it owns plus a
  /// halo of neighbouring cells, with the agreed grid and budgets.
  ///@{
  const GridSpec* Grid = nullptr; ///< the grid to use instead of one fitted to the points
  /// The points' cells in that grid when the caller has grouped them already
  /// (a distributed run's points arrive in cell order): cell c holds the
  /// points ids[CellStart[c]] .. ids[CellStart[c + 1] - 1], in (key, id)
  /// order, as BuildCellGrid would group them; they are not grouped again.
  const CellGrid* Cells = nullptr;
  /// Budget N_c of the cell with this key, apportioned over all processes.
  /// Paper mode: -1 for halo cells (owned by another process: neighbours
  /// only, no samples, and their points join no sample here). Feature mode:
  /// see OutputCell. Replaces Eq. 4 on the local points; NumberOfSamples is
  /// then ignored.
  std::function<Index(std::uint64_t cellKey)> CellBudget;
  const double* CloudCentroid = nullptr; ///< centroid of the whole cloud (orients normals)
  /// Feature-preserving mode: CellBudget gives the TRUE budget of every cell
  /// passed (halo cells included, so that cross-cell steps see their real
  /// samples), and only the samples of the cells for which this returns true
  /// are output (with all their members, halo points included). Unset: all.
  std::function<bool(std::uint64_t cellKey)> OutputCell;
  /// Feature-preserving mode: replaces each value by its sum over all
  /// processes (collective). The final Lloyd iterations' variation weights
  /// (LloydVariationWeight) are relative to the mean over the samples of the
  /// whole cloud: each process sums its output cells' samples (ExactMean)
  /// and calls this once per iteration, CollectiveSumsOf(parameters) times
  /// in a run that is not cut short. Unset: the mean is over this run's
  /// output cells' samples (all of them without OutputCell).
  std::function<void(std::vector<long long>& values)> SumOverProcesses;
  /// Feature-preserving mode with FillHoles: replaces `values` by every
  /// process's `values`, concatenated in process order (collective; the
  /// number of calls depends on the data, the same on every process). The
  /// hole filling ranks the samples and points of the output cells and
  /// gathers the rankings and removal costs, so that every process makes
  /// the moves of a one-process run (HoleFilling.h). Unset: one process.
  std::function<void(std::vector<double>& values)> GatherOverProcesses;
  /// Feature-preserving mode: after every step that moves samples (the
  /// sampling inside the cells, each cross-cell Lloyd step, each
  /// hole-filling round, each final Lloyd iteration), called with this
  /// run's cells (keys ascending), their samples (cell c: [start[c],
  /// start[c + 1])) and the samples' positions: replaces the positions of
  /// the samples of cells that another process owns by that owner's
  /// (collective). A distributed driver then needs a halo of only
  /// InfluenceRingsPerStep rings (plus its margin) instead of
  /// InfluenceRingsOf. Unset: nothing is exchanged.
  std::function<void(const std::vector<std::uint64_t>& cellKeys, const std::vector<Index>& start,
    std::vector<double>& positions)>
    ShareSamples;
  ///@}
};

/// The number of samples a run of `total` valid points produces:
/// NumberOfSamples clamped to [0, total], or `total` (an upper bound) when
/// CellBudget gives the budgets (distributed runs).
VTKASMFILTERS_EXPORT Index SampleTarget(const SimplifyParameters& parameters, Index total);

/// The mean budget per non-empty cell the automatic cell size aims at:
/// SamplesPerCell in Paper mode, FeatureSamplesPerCell (when > 0) in the
/// feature-preserving mode; at least 1.
VTKASMFILTERS_EXPORT double SamplesPerCellOf(const SimplifyParameters& parameters);

/// The ratio sigma_c / mean(sigma) past which the budget weight grows as its
/// square root (SimplifyParameters::VariationCap): VariationCap in the
/// feature-preserving mode with VariationBudget (when > 0), else none
/// (infinity; the paper mode's weight is Eq. 4's, uncapped).
VTKASMFILTERS_EXPORT double VariationCapOf(const SimplifyParameters& parameters);

/// k of the budget weight w_c = 1 + k * sigma_c / mean(sigma): CurvatureWeight
/// with WeightMode::SurfaceVariation, else VariationBudget in the
/// feature-preserving mode, else 0 (w_c = 1).
VTKASMFILTERS_EXPORT double VariationWeightOf(const SimplifyParameters& parameters);

/// The shares w_c * n_c^exponent of Eq. 4 of cells holding `capacity` points
/// each, with surface variations `variation`, listed in ascending cell key
/// order (the order matters only to floating-point rounding of the mean).
VTKASMFILTERS_EXPORT std::vector<double> CellShares(const std::vector<Index>& capacity,
  const std::vector<double>& variation, const SimplifyParameters& parameters,
  double exponent = 1.0);

/// One output sample: a cluster of input points.
struct VTKASMFILTERS_EXPORT Sample
{
  double Position[3] = { 0, 0, 0 }; ///< cluster centroid, or the snapped input point
  double Normal[3] = { 0, 0, 1 };   ///< the cell's PCA normal, oriented
  Index Representative = -1;        ///< input point nearest the centroid
  Index MemberBegin = 0; ///< members are SimplifyResult::Members[MemberBegin, +ClusterSize)
  Index ClusterSize = 0;
  /// The first CoreSize members place the sample (centroid, representative);
  /// the others joined it as their nearest sample (points of cells or key
  /// clusters left without a sample of their own), so that the samples'
  /// members partition the input points.
  Index CoreSize = 0;
  double SurfaceVariation = 0.0; ///< of the sample's grid cell
  double KeyError = 0.0;         ///< key samples: distance to the extreme input point
  bool Key = false;              ///< the sample is a key point
};

struct VTKASMFILTERS_EXPORT SimplifyResult
{
  UnwrittenArray<Sample> Samples; ///< (grown by ResizeInParallel)
  PointArray<Index> Members;      ///< input point ids, grouped by sample: a partition of `ids`
  double CellSize = 0.0;
  Index NumberOfCells = 0; ///< non-empty grid cells
  Index NumberOfKeyPoints = 0;
  double AKPE = 0.0; ///< mean KeyError over key samples
  double MKPE = 0.0; ///< max KeyError over key samples
  /// Exact duplicates of the representatives: (Representative of a sample,
  /// another input point at exactly its position), sorted; empty when no
  /// representative has one. A group of duplicates holding several
  /// representatives is listed once, under the first of them (the others
  /// appear as its duplicates): at most one pair per input point. The core
  /// chooses among duplicates by id; these let a caller choose by the
  /// points' values instead (asmvtk::ChooseAmongDuplicates, which gives
  /// every sample of a group the same choice).
  std::vector<std::pair<Index, Index>> RepresentativeDuplicates;
  bool Aborted = false;
};

struct CellFrame;
struct CellGrid;

/// Budget shares of Eq. 4: w_c * n_c^exponent per non-empty cell of `grid`
/// (w_c from parameters.Weight and the mean surface variation of the
/// cloud; `frames` empty: every variation 0, so w_c = 1), and each cell's
/// capacity n_c.
VTKASMFILTERS_EXPORT std::vector<double> CellShares(const std::vector<CellFrame>& frames,
  const CellGrid& grid, const SimplifyParameters& parameters, double exponent,
  std::vector<Index>& capacity);

/// Step 1 of both modes, the grid: parameters.Cells when set (distributed
/// runs: a copy, with the ids as its order), else the points grouped in
/// parameters.Grid when set, else cells of edge parameters.CellSize when it is positive and
/// finite, else the automatic cell size for about target / SamplesPerCell
/// non-empty cells (BuildAutomaticCellGrid).
VTKASMFILTERS_EXPORT CellGrid BuildRunGrid(Coordinates xyz, IdView ids,
  const SimplifyParameters& parameters, Index target, const Execution& execution = {});

/// Fills NumberOfKeyPoints, AKPE and MKPE of `result` from its key samples.
VTKASMFILTERS_EXPORT void SummarizeKeyPoints(SimplifyResult& result);

/// Simplify the points xyz[3*id], id in `ids` (finite points), to exactly
/// min(NumberOfSamples, ids.size()) samples. `normals` (N x 3, may be empty)
/// orients the output normals; without it they point away from the cloud's
/// centroid. Samples are ordered by grid cell, then key samples first.
VTKASMFILTERS_EXPORT SimplifyResult Simplify(Coordinates xyz, IdView ids, NormalField normals,
  const SimplifyParameters& parameters, const Execution& execution = {});
} // namespace asmcore

#endif
