/**
 * @class   vtkASMSimplify
 * @brief   simplify a point cloud to exactly N_s points with the Adaptive
 *          Simplification Method (ASM) of Yu & Wong (ICME 2006)
 *
 * vtkASMSimplify takes any vtkPointSet (polydata with or without cells,
 * unstructured grid, ...; float or double points) and returns a vtkPolyData
 * holding exactly N_s points, one vertex cell each. The method (paper §3.2,
 * §3.3 and §3.5):
 *
 * 1. hash the points into a uniform grid of cubic cells (edge CellSize, or
 *    chosen automatically so that a non-empty cell receives about
 *    SamplesPerCell output points on average; FeatureSamplesPerCell in
 *    FEATURE_PRESERVING mode when it is > 0);
 * 2. give every non-empty cell c a budget N_c proportional to w_c * n_c
 *    (paper Eq. 4), rounded with the largest-remainder method so that the
 *    budgets add up to N_s exactly; w_c = 1 (uniform density) by default, or
 *    driven by the cell's surface variation (adaptive density);
 * 3. in each cell, compute the PCA frame (v0, v1, v2; v2 ~ normal), split the
 *    points into a top, middle and bottom band along v2 with the partition
 *    threshold Alpha, and cluster the top and bottom bands separately in the
 *    (v0, v1) plane: each separate cluster's centroid is a key point;
 * 4. keep all key points and fill the rest of the cell's budget by clustering
 *    the middle band in the (v0, v1) plane, or, when the budget is smaller than
 *    the number of key points, keep a random subset of them (RandomSeed);
 * 5. when ErrorTolerance > 0, shrink Alpha in a cell (paper Eq. 5, translation
 *    invariant form alpha_new = alpha * eps / MKPE_c) until every key point of
 *    the cell lies within the tolerance of the extreme input point it stands
 *    for.
 *
 * Output arrays: every input point-data array, same class, name and
 * attribute role, aggregated over each sample's cluster: float and double
 * arrays averaged (NaN and infinite values ignored, the normals attribute
 * renormalised);
 * integer, id, bit, string and other categorical arrays take the value of the
 * representative point (see "vtkOriginalPointIds"; among exact duplicates, the one whose values
 * come first), never an average; with SnapToInputPoints on, every array takes the snapped input
 * point's values; "Normals" (float; the cell's PCA normal, oriented to agree with the input normals
 * when there are some, else away from the cloud's centroid; named "PCANormals"
 * if the input already has an array called "Normals"); "KeyPoint" (1 for
 * key-point samples, else 0); "ClusterSize" (input points the sample stands
 * for); "SurfaceVariation" (lambda2 / (lambda0 + lambda1 + lambda2) of the
 * sample's grid cell); "vtkOriginalPointIds" (id of the input point the
 * sample stands for: PAPER, the member nearest the cluster centroid;
 * FEATURE_PRESERVING, a key sample's extreme point, else the member nearest
 * the sample, its own input point with InputPointSamples); with GenerateCurvature (default on),
 * "MeanCurvature" and "NeighborhoodSurfaceVariation" from the input points
 * around each sample (see vtkKeyPointError for measuring a simplification). Field data: "AKPE" and
 * "MKPE" (mean and maximum distance, in data units, between each key point placed and the extreme
 * input point it stands for), "NumberOfKeyPoints", "CellSize", "NumberOfSkippedPoints" (non-finite
 * input points ignored).
 *
 * Composite input (a vtkMultiBlockDataSet of scans, the vtkPartitionedDataSet
 * of a partitioned file, ...): the vtkPointSet leaves are ONE cloud, not one
 * run each: N_s is the size of the whole output (a vtkPolyData), and
 * overlapping leaves are thinned together. The point arrays that every leaf
 * with points has (same name, type and components, a value for each point)
 * are carried, the others dropped with a warning; "vtkOriginalBlockIds" (the leaf's flat index) and
 * "vtkOriginalPointIds" (the id in that leaf) name each sample's
 * representative.
 *
 * Messy input: points with NaN or infinite coordinates are skipped with a
 * warning (counted in "NumberOfSkippedPoints"; OutputFraction is taken of the
 * finite points); points flagged in vtkGhostType as another piece's
 * (DUPLICATEPOINT) or hidden (HIDDENPOINT) are skipped without a word (not
 * this input's points); duplicates, far outliers, georeferenced float coordinates,
 * very dense cells and very anisotropic bounds give exactly N_s points (see
 * the README, "Messy data"). Coordinates beyond 1e100 in magnitude, or all
 * below 1e-100 (but not all 0), are an error with an empty output: their
 * squared distances would overflow or underflow (asmcore::CoordinateRange).
 * The input's field data is carried to the output.
 * The input is never modified.
 *
 * Modes. The steps above are the paper read literally (Mode PAPER, kept
 * exactly to reproduce the paper). Measured against the usual downsamplers,
 * that reading loses on every quality measure (see docs/ASM-spec.md, "What
 * the literal reading measures, and what fixes it"), so the default Mode is
 * FEATURE_PRESERVING, which keeps steps 1-5 and adds, each switchable on its
 * own: key points validated by the paper's Lemma 2 across cell borders
 * (ValidateKeyPoints, KeyPointRadius, KeyPointProminence: where the grid
 * cuts a smooth surface is not a feature); extremes along +-v0/+-v1 and the
 * frame diagonals as key points (InPlaneKeyPoints: spike tips, corners),
 * also in cells too sparse for a
 * frame (SparseCellKeyPoints); a key point placed on its extreme
 * input point (ExtremeKeyPoints); one sample per non-empty cell first and a
 * budget N_c ~ w_c * n_c^BudgetExponent (CoverEveryCell, BudgetExponent);
 * connected middle clusters by Lloyd iterations with the key samples fixed,
 * inside each cell and then across cell borders (LloydIterations,
 * CrossCellIterations); samples placed on input points (InputPointSamples);
 * a bounded hole-filling pass (FillHoles, HoleFillFraction); finer cells
 * (FeatureSamplesPerCell) whose budget follows the surface variation
 * (VariationBudget, capped by VariationCap); a free sample in every cell of
 * two or more (ReserveFreeSample); Lloyd iterations across cells after the
 * hole filling (FinalLloydIterations); a bound on the largest hole that snapping to input
 * points may leave (BoundSnappedHoles); and, off by default, rounds that
 * move input-point samples to cover their clusters (CoveringRounds). In this
 * mode a cluster is the set of input points nearest a sample, the count is
 * still exactly N_s, and AKPE/MKPE are 0 when the key points sit on their
 * extreme points. These feature-preserving options are ignored in PAPER mode
 * (the paper's own parameters, Alpha, SamplesPerCell, WeightMode,
 * RandomSeed, ..., apply to it).
 *
 * The output is deterministic: the same input, parameters and RandomSeed give
 * the same points in the same order whatever the number of threads.
 *
 * Parallel (MPI) runs, e.g. pvbatch --mpi or a pvserver with several
 * processes: the points of all processes are simplified as one cloud,
 * however they are split (one global grid, one owner process per grid cell,
 * points redistributed to the owners with a halo of neighbouring cells, one
 * budget of exactly N_s over all processes, global AKPE/MKPE); each process
 * outputs the samples of the cells it owns, with "vtkOriginalProcessIds"
 * next to "vtkOriginalPointIds". Both modes run distributed; 1, 2, 3...
 * processes give the same points (up to floating-point summation order). A
 * run on one process takes the distributed path when mpiexec (or another
 * MPI launcher) started it, or with AlwaysDistribute. In FEATURE_PRESERVING
 * mode, FillHoles gathers its rankings and removal costs over all processes
 * (every process makes the moves of a serial run), the halo cells' samples
 * are exchanged after every step (weighted FinalLloydIterations widen the
 * halo to 6 cell rings), and BoundSnappedHoles runs over all processes. The
 * serial path gives the same points too, and the same point-data arrays in
 * the same order (string, variant and bit arrays are read at the
 * representatives after the run). An array that some process
 * with points lacks, has with another type or number of components, or
 * with fewer tuples than points is dropped with a warning. Known
 * differences (found by a differential sweep, 2026-11-28): with far fewer
 * samples than non-empty cells (a small CellSize, far outliers), points of
 * cells without a sample within a process's halo can be left out of every
 * cluster (ClusterSize sums to less than N) or join another sample than in
 * a serial run; exact duplicates with different values can be grouped
 * differently (the same positions and counts, other averages); the normal
 * of a cloud that fits in one cell can have the other sign; at N_s close
 * to N, a sample with no point to take nearby takes one among its own
 * process's output (each point still in one cluster), not the cloud's.
 * Design and limits: vtkASMDistributed.h.
 * Without MPI (a desktop or builtin ParaView session, plain VTK) nothing
 * changes.
 *
 * @sa vtkVoxelGrid vtkMaskPoints vtkPCACurvatureEstimation
 */

#ifndef vtkASMSimplify_h
#define vtkASMSimplify_h

#include "vtkASMFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class vtkMultiProcessController;

class VTKASMFILTERS_EXPORT vtkASMSimplify : public vtkPolyDataAlgorithm
{
public:
  static vtkASMSimplify* New();
  vtkTypeMacro(vtkASMSimplify, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// How the requested output size N_s is given.
  enum TargetModes
  {
    OUTPUT_FRACTION = 0,        ///< N_s = round(OutputFraction * N)
    NUMBER_OF_OUTPUT_POINTS = 1 ///< N_s = NumberOfOutputPoints
  };

  /// Which pipeline runs.
  enum Modes
  {
    FEATURE_PRESERVING = 0, ///< the paper's pipeline with the measured fixes (default)
    PAPER = 1               ///< the paper's pipeline read literally, to reproduce the paper
  };

  /// How the per-cell weight w_c of Eq. 4 is chosen.
  enum WeightModes
  {
    UNIFORM_WEIGHT = 0,          ///< w_c = 1 (PAPER); FEATURE_PRESERVING: VariationBudget's
    SURFACE_VARIATION_WEIGHT = 1 ///< w_c = 1 + CurvatureWeight * sigma_c / mean(sigma)
  };

  ///@{
  /**
   * FEATURE_PRESERVING (default) or PAPER. PAPER runs the paper's pipeline
   * exactly as read in docs/ASM-spec.md (steps 1-5 above); FEATURE_PRESERVING
   * adds the fixes below, each of which can be switched off on its own. The
   * feature-preserving options below the Mode, ValidateKeyPoints to
   * BoundSnappedHoles, are ignored in PAPER mode; the parameters from
   * TargetMode on apply to it (SamplesPerCell and RandomSeed to it alone, as
   * they say). FEATURE_PRESERVING
   * keeps at most 2^31 - 1 output points and non-empty grid cells (an error
   * above that).
   */
  vtkSetClampMacro(Mode, int, FEATURE_PRESERVING, PAPER);
  vtkGetMacro(Mode, int);
  void SetModeToFeaturePreserving() { this->SetMode(FEATURE_PRESERVING); }
  void SetModeToPaper() { this->SetMode(PAPER); }
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: keep a key point only when it is the extreme along its
   * direction among all input points within KeyPointRadius, neighbouring
   * cells included (the paper's Lemma 2 across cell borders: where the grid
   * cuts a smooth surface is not a feature); default on.
   */
  vtkSetMacro(ValidateKeyPoints, bool);
  vtkGetMacro(ValidateKeyPoints, bool);
  vtkBooleanMacro(ValidateKeyPoints, bool);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: radius of the Lemma 2 test, as a fraction of the cell
   * size, in [0.01, 1]; default 0.7 (a wider test keeps fewer, more
   * significant key points: isolated pairs of points in a scan no longer
   * hold a sample each at their extremes).
   */
  vtkSetClampMacro(KeyPointRadius, double, 0.01, 1.0);
  vtkGetMacro(KeyPointRadius, double);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: least prominence of a validated key point (its height
   * along its direction above the mean of the points within KeyPointRadius),
   * as a fraction of that radius, in [0, 1]; default 0.05. Drops scanner
   * noise and the tangent points of smooth curved patches.
   */
  vtkSetClampMacro(KeyPointProminence, double, 0.0, 1.0);
  vtkGetMacro(KeyPointProminence, double);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: the extremes of a cell along +-v0 and +-v1 are key
   * point candidates too (spike tips, scan borders), and so are the extremes
   * along the eight diagonals +-v0 +-v1 +-v2 (corners); default on.
   */
  vtkSetMacro(InPlaneKeyPoints, bool);
  vtkGetMacro(InPlaneKeyPoints, bool);
  vtkBooleanMacro(InPlaneKeyPoints, bool);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: a key sample is the extreme input point of its key
   * cluster instead of the cluster's centroid (which lands mid-crease at a
   * corner); default on.
   */
  vtkSetMacro(ExtremeKeyPoints, bool);
  vtkGetMacro(ExtremeKeyPoints, bool);
  vtkBooleanMacro(ExtremeKeyPoints, bool);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: every non-empty cell gets at least one sample when
   * N_s is at least the number of non-empty cells (else the cells of largest
   * budget share get one each); default on.
   */
  vtkSetMacro(CoverEveryCell, bool);
  vtkGetMacro(CoverEveryCell, bool);
  vtkBooleanMacro(CoverEveryCell, bool);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: exponent gamma of the budget N_c ~ w_c * n_c^gamma
   * (dimensionless, in [0, 1]; the paper's Eq. 4 is gamma = 1); default 0.5,
   * which keeps overlapping scans from taking most of the samples.
   */
  vtkSetClampMacro(BudgetExponent, double, 0.0, 1.0);
  vtkGetMacro(BudgetExponent, double);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: Lloyd (k-means) iterations placing the non-key
   * samples inside a cell, key samples fixed (iterations, in [0, 20]); 0
   * uses the paper's median splits instead; default 4.
   */
  vtkSetClampMacro(LloydIterations, int, 0, 20);
  vtkGetMacro(LloydIterations, int);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: Lloyd iterations across cell borders after the
   * in-cell ones (iterations, in [0, 4]); default 1.
   */
  vtkSetClampMacro(CrossCellIterations, int, 0, 4);
  vtkGetMacro(CrossCellIterations, int);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: each sample is the input point nearest its cluster's
   * centre (a measured point on the surface, not a centroid inside its
   * curvature); the input arrays are still averaged over the cluster unless
   * SnapToInputPoints is on; default on. With BoundSnappedHoles, a few
   * samples move off their input point (SnapToInputPoints: none does).
   */
  vtkSetMacro(InputPointSamples, bool);
  vtkGetMacro(InputPointSamples, bool);
  vtkBooleanMacro(InputPointSamples, bool);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: a bounded hole-filling pass (up to four rounds, each
   * followed by a Lloyd step) that moves the samples whose removal costs least
   * (at most HoleFillFraction of them per round) to the input points farthest
   * from every sample; default on. Global: a distributed run (several
   * processes, or AlwaysDistribute) gathers the rankings of samples and
   * points and the removal costs over the processes, so that it makes the
   * moves of a serial run (and exchanges its halo cells' samples after each
   * round). It is
   * about 45 % of the mode's time: off, the mode runs about 1.8 times as
   * fast, with larger holes (README, "Faster settings of the default mode").
   */
  vtkSetMacro(FillHoles, bool);
  vtkGetMacro(FillHoles, bool);
  vtkBooleanMacro(FillHoles, bool);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: largest fraction of the samples the hole filling
   * moves per round, in [0, 0.5]; default 0.02.
   */
  vtkSetClampMacro(HoleFillFraction, double, 0.0, 0.5);
  vtkGetMacro(HoleFillFraction, double);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: mean number of output samples per non-empty grid
   * cell aimed at by the automatic cell size in this mode (SamplesPerCell is
   * PAPER mode's; 0: SamplesPerCell), clamped to >= 0; default 4. Finer
   * cells let the budget follow the surface variation (VariationBudget) more
   * closely.
   */
  vtkSetClampMacro(FeatureSamplesPerCell, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(FeatureSamplesPerCell, double);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: k of the budget weight w_c = 1 + k * sigma_c /
   * mean(sigma), sigma the cell's surface variation (unitless, >= 0; 0: the
   * same weight for every cell): bent and creased cells get more samples;
   * default 1. With WeightMode SURFACE_VARIATION_WEIGHT, CurvatureWeight is
   * k instead.
   */
  vtkSetClampMacro(VariationBudget, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(VariationBudget, double);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: the ratio r = sigma_c / mean(sigma) past which the
   * VariationBudget weight grows as sqrt(VariationCap * r) instead of r
   * (unitless, >= 0; 0: no cap), so that a few cusps or spikes do not draw
   * the samples of the smooth surface away; default 4. The
   * SURFACE_VARIATION_WEIGHT budget weight is not capped; the final Lloyd
   * iterations' weights (LloydVariationWeight) count min(VariationCap, r)
   * with either WeightMode.
   */
  vtkSetClampMacro(VariationCap, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(VariationCap, double);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: a cell of two or more samples keeps at least one
   * free (Lloyd) sample, so that at most N_c - 1 of its samples are key
   * samples (a cell of one sample may still make it a key sample); default
   * on. Off: key samples may take a cell's whole budget.
   */
  vtkSetMacro(ReserveFreeSample, bool);
  vtkGetMacro(ReserveFreeSample, bool);
  vtkBooleanMacro(ReserveFreeSample, bool);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: Lloyd iterations across cell borders after the hole
   * filling, before the final clusters (iterations, in [0, 8]); they tighten
   * the clusters that the hole filling moved; default 2. Local: a
   * distributed run exchanges its halo cells' samples after each one, and
   * weighted ones (LloydVariationWeight) need a halo of 6 cell rings
   * instead of 4.
   */
  vtkSetClampMacro(FinalLloydIterations, int, 0, 8);
  vtkGetMacro(FinalLloydIterations, int);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING: weight k of the final Lloyd iterations'
   * (FinalLloydIterations) variation-weighted assignment: a point joins the
   * sample s that minimises m_s |p - s|^2, with m_s = 1 + k min(VariationCap,
   * sigma_s / mean(sigma)), sigma_s the surface variation of the sample's
   * plain cluster before the iteration (k unitless, >= 0). Samples of
   * creased or curved clusters take smaller clusters, so the samples crowd
   * towards creases and curved bands (lower point-to-plane error there)
   * instead of spreading evenly over their cell's ring; one more
   * nearest-sample pass, about 7 % of the mode's time. 0: plain Lloyd
   * iterations. Default 0.75. The mean is over the whole cloud, in
   * distributed runs too (summed over the processes).
   */
  vtkSetClampMacro(LloydVariationWeight, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(LloydVariationWeight, double);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING, with InputPointSamples or SnapToInputPoints: rounds
   * of covering refinement, in [0, 8]; default 0. A round moves every
   * non-key sample to the member of its cluster whose farthest member is
   * nearest (instead of the member nearest the cluster's centre), then
   * re-forms the clusters. 0: the input point nearest the centre, which
   * keeps the clusters tightest; with BoundSnappedHoles on, the rounds
   * gain nothing on the largest hole (quality benchmark). Local (a sample
   * moves within its own cluster): distributed runs take it too.
   */
  vtkSetClampMacro(CoveringRounds, int, 0, 8);
  vtkGetMacro(CoveringRounds, int);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING, with ValidateKeyPoints and InPlaneKeyPoints: in a
   * cell of fewer than 3
   * points (too few for a PCA frame), a point that is the Lemma 2 extreme
   * along the direction away from the centroid of its neighbours within
   * KeyPointRadius (and stands out by KeyPointProminence) is a key point: a
   * spike tip alone in its cell; default on.
   */
  vtkSetMacro(SparseCellKeyPoints, bool);
  vtkGetMacro(SparseCellKeyPoints, bool);
  vtkBooleanMacro(SparseCellKeyPoints, bool);
  ///@}

  ///@{
  /**
   * FEATURE_PRESERVING, with InputPointSamples (not SnapToInputPoints): the
   * largest hole is bounded by what minimax centres would leave. A sample
   * whose cluster reaches farther from its input point than the largest
   * hole the clusters would leave with their samples at (about) their
   * minimax centres (key samples where they are) moves from its input point
   * towards that centre, just far enough to reach no farther; default on.
   * Only those samples (at 20 %: 2-15 % on the bundled and shared scans)
   * leave the input points; their vtkOriginalPointIds is still the input
   * point they left. The bound is the largest hole of the whole cloud:
   * distributed runs take it over all processes.
   */
  vtkSetMacro(BoundSnappedHoles, bool);
  vtkGetMacro(BoundSnappedHoles, bool);
  vtkBooleanMacro(BoundSnappedHoles, bool);
  ///@}

  ///@{
  /**
   * Whether N_s comes from OutputFraction (default) or NumberOfOutputPoints.
   */
  vtkSetClampMacro(TargetMode, int, OUTPUT_FRACTION, NUMBER_OF_OUTPUT_POINTS);
  vtkGetMacro(TargetMode, int);
  void SetTargetModeToOutputFraction() { this->SetTargetMode(OUTPUT_FRACTION); }
  void SetTargetModeToNumberOfOutputPoints() { this->SetTargetMode(NUMBER_OF_OUTPUT_POINTS); }
  ///@}

  ///@{
  /**
   * Fraction of the (finite) input points to keep, in [0, 1]; default 0.05.
   * Used when TargetMode is OUTPUT_FRACTION.
   */
  vtkSetClampMacro(OutputFraction, double, 0.0, 1.0);
  vtkGetMacro(OutputFraction, double);
  ///@}

  ///@{
  /**
   * Exact number of output points N_s (>= 0); default 1000. Used when
   * TargetMode is NUMBER_OF_OUTPUT_POINTS. N_s >= N keeps every input point, one
   * sample each (N_s = N, with a warning): the output is the input's points in
   * the grid's cell order, not the input itself; among exact duplicates the
   * non-averaged arrays take the tuple chosen by value, as at any N_s.
   */
  vtkSetClampMacro(NumberOfOutputPoints, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(NumberOfOutputPoints, vtkIdType);
  ///@}

  ///@{
  /**
   * Edge length of the grid cells, in data units; <= 0 (default) chooses it
   * automatically from the mean number of samples per non-empty cell: in
   * FEATURE_PRESERVING mode FeatureSamplesPerCell when it is > 0, else (and
   * in PAPER mode) SamplesPerCell.
   */
  vtkSetMacro(CellSize, double);
  vtkGetMacro(CellSize, double);
  ///@}

  ///@{
  /**
   * Mean number of output samples per non-empty grid cell aimed at by the
   * automatic cell size (points per cell, >= 1); default 8. PAPER mode; the
   * default mode uses FeatureSamplesPerCell when it is > 0.
   */
  vtkSetClampMacro(SamplesPerCell, double, 1.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SamplesPerCell, double);
  ///@}

  ///@{
  /**
   * Partition threshold alpha of §3.2, as a fraction of the cell's extent
   * along v2, in [0, 0.5]; default 1/8.
   */
  vtkSetClampMacro(Alpha, double, 0.0, 0.5);
  vtkGetMacro(Alpha, double);
  ///@}

  ///@{
  /**
   * Error tolerance epsilon on the maximum key point error (MKPE), in data
   * units (or a fraction of the bounding-box diagonal when
   * RelativeErrorTolerance is on); <= 0 (default) turns the bound off.
   */
  vtkSetMacro(ErrorTolerance, double);
  vtkGetMacro(ErrorTolerance, double);
  ///@}

  ///@{
  /**
   * When on, ErrorTolerance is a fraction of the input bounding-box diagonal
   * instead of a length; default off.
   */
  vtkSetMacro(RelativeErrorTolerance, bool);
  vtkGetMacro(RelativeErrorTolerance, bool);
  vtkBooleanMacro(RelativeErrorTolerance, bool);
  ///@}

  ///@{
  /**
   * Cell weight w_c of Eq. 4: UNIFORM_WEIGHT (default) or
   * SURFACE_VARIATION_WEIGHT (more samples where the surface bends).
   */
  vtkSetClampMacro(WeightMode, int, UNIFORM_WEIGHT, SURFACE_VARIATION_WEIGHT);
  vtkGetMacro(WeightMode, int);
  void SetWeightModeToUniform() { this->SetWeightMode(UNIFORM_WEIGHT); }
  void SetWeightModeToSurfaceVariation() { this->SetWeightMode(SURFACE_VARIATION_WEIGHT); }
  ///@}

  ///@{
  /**
   * Strength k of the adaptive weight w_c = 1 + k * sigma_c / mean(sigma)
   * (dimensionless, >= 0); default 1. Used with SURFACE_VARIATION_WEIGHT.
   */
  vtkSetClampMacro(CurvatureWeight, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(CurvatureWeight, double);
  ///@}

  ///@{
  /**
   * PAPER mode: seed of the random choice among key points when a cell's
   * budget is smaller than its number of key points (§3.3); default 1.
   * FEATURE_PRESERVING makes no random choice (the most prominent key points
   * first) and ignores it.
   */
  vtkSetMacro(RandomSeed, int);
  vtkGetMacro(RandomSeed, int);
  ///@}

  ///@{
  /**
   * When on, each sample is the input point nearest its cluster centroid
   * (a measured point, with that point's attribute values) instead of the
   * centroid itself; default off.
   */
  vtkSetMacro(SnapToInputPoints, bool);
  vtkGetMacro(SnapToInputPoints, bool);
  vtkBooleanMacro(SnapToInputPoints, bool);
  ///@}

  ///@{
  /**
   * When on (default), add "MeanCurvature" (1/length, positive where the
   * surface bends away from the output normal) and
   * "NeighborhoodSurfaceVariation" at each output point, estimated from its
   * CurvatureNeighbors nearest input points (a quadric fit in their PCA frame).
   */
  vtkSetMacro(GenerateCurvature, bool);
  vtkGetMacro(GenerateCurvature, bool);
  vtkBooleanMacro(GenerateCurvature, bool);
  ///@}

  ///@{
  /**
   * Neighbourhood size of the curvature estimates (points, >= 6); default 20.
   */
  vtkSetClampMacro(CurvatureNeighbors, int, 6, 1000);
  vtkGetMacro(CurvatureNeighbors, int);
  ///@}

  ///@{
  /**
   * Precision of the output points (vtkAlgorithm::DesiredOutputPrecision);
   * default DEFAULT_PRECISION, which follows the input. SINGLE_PRECISION
   * for double coordinates beyond a float's normal range (above 3.4e38, or
   * all below 1.2e-38) gives double points with a warning, not infinite or
   * zero ones.
   */
  vtkSetClampMacro(OutputPointsPrecision, int, SINGLE_PRECISION, DEFAULT_PRECISION);
  vtkGetMacro(OutputPointsPrecision, int);
  ///@}

  ///@{
  /**
   * Inputs with fewer points than this (per process) are simplified on the
   * calling thread alone; larger ones run their loops through vtkSMPTools.
   * In points; 0: always through vtkSMPTools; default -1: automatic, 50000
   * with vtkSMPTools' STDThread backend and 0 with the others (TBB, OpenMP).
   * VTK 9.1-9.2's STDThread backend starts its threads anew in every
   * parallel loop (about 0.1 ms each, a few hundred loops per run in
   * FEATURE_PRESERVING mode), which costs a small cloud more than a second
   * thread gains: measured on 2 cores, 2 threads were slower below about
   * 50 k points. TBB keeps its threads between loops: with Debian's VTK 9.1
   * on 2 cores, 2 threads were faster on every bundled scan, from 5.2 k points up (36 k points:
   * 0.019 s against 0.028). When vtkSMPTools has one thread (Sequential
   * backend, or vtkSMPTools::Initialize(1)) every input runs on the calling
   * thread. The output is the same either way.
   */
  vtkSetClampMacro(MinimumPointsForThreads, vtkIdType, -1, VTK_ID_MAX);
  vtkGetMacro(MinimumPointsForThreads, vtkIdType);
  ///@}

  ///@{
  /**
   * The processes of a parallel run; default the global controller. With an
   * MPI controller (pvbatch --mpi, pvserver) the points of all processes are
   * simplified together, as one cloud, whatever the split: one grid, one
   * owner per cell, one budget adding up to N_s over the processes; each
   * process outputs the samples of the cells it owns. Without MPI (null or
   * dummy controller) the filter works on its input alone.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * With several processes, or one process started by an MPI launcher
   * (mpiexec -n 1 pvbatch --mpi), the run is always distributed. When on, any
   * run with a controller is distributed too (a cell's points taken in
   * coordinate order instead of input order), so that it
   * gives the same points as 2, 3... processes; default off: a desktop or
   * builtin session (or no controller) runs the serial algorithm,
   * unchanged. Per-cell results do not depend on the order of the points,
   * so the serial path gives the same points as 2, 3... processes already.
   */
  vtkSetMacro(AlwaysDistribute, bool);
  vtkGetMacro(AlwaysDistribute, bool);
  vtkBooleanMacro(AlwaysDistribute, bool);
  ///@}

protected:
  vtkASMSimplify();
  ~vtkASMSimplify() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Reports non-finite parameters; false stops the run with an empty output.
  bool CheckParameters();

  int Mode = FEATURE_PRESERVING;
  bool ValidateKeyPoints = true;
  double KeyPointRadius = 0.7;
  double KeyPointProminence = 0.05;
  bool InPlaneKeyPoints = true;
  bool ExtremeKeyPoints = true;
  bool CoverEveryCell = true;
  double BudgetExponent = 0.5;
  int LloydIterations = 4;
  int CrossCellIterations = 1;
  bool InputPointSamples = true;
  bool FillHoles = true;
  double HoleFillFraction = 0.02;
  double FeatureSamplesPerCell = 4.0;
  double VariationBudget = 1.0;
  double VariationCap = 4.0;
  bool ReserveFreeSample = true;
  int FinalLloydIterations = 2;
  double LloydVariationWeight = 0.75;
  int CoveringRounds = 0;
  bool SparseCellKeyPoints = true;
  bool BoundSnappedHoles = true;
  int TargetMode = OUTPUT_FRACTION;
  double OutputFraction = 0.05;
  vtkIdType NumberOfOutputPoints = 1000;
  double CellSize = 0.0;
  double SamplesPerCell = 8.0;
  double Alpha = 0.125;
  double ErrorTolerance = 0.0;
  bool RelativeErrorTolerance = false;
  int WeightMode = UNIFORM_WEIGHT;
  double CurvatureWeight = 1.0;
  int RandomSeed = 1;
  bool SnapToInputPoints = false;
  bool GenerateCurvature = true;
  int CurvatureNeighbors = 20;
  int OutputPointsPrecision = DEFAULT_PRECISION;
  vtkIdType MinimumPointsForThreads = -1;
  vtkMultiProcessController* Controller = nullptr;
  bool AlwaysDistribute = false;

private:
  vtkASMSimplify(const vtkASMSimplify&) = delete;
  void operator=(const vtkASMSimplify&) = delete;
};

#endif
