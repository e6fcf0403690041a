// SPDX-License-Identifier: BSD-3-Clause
/**
 * The feature-preserving mode of the ASM driver (ASM-spec.md, "What the
 * literal reading measures, and what fixes it"). Phases, each a separate
 * step of SimplifyFeaturePreserving so that a distributed driver can hook in
 * between them:
 *
 *  1. grid: hash the points (automatic or given cell size, as in Paper mode,
 *     the automatic one for FeatureSamplesPerCell samples per cell);
 *  2. per-cell analysis: PCA frame, key points (FeatureKeyPoints.h) — the
 *     extremes along +-v2 of the band clusters (link distance
 *     FeatureLinkFactor spacings) and, with InPlaneKeyPoints, along +-v0/+-v1,
 *     kept only when they are Lemma 2 extremes among the points within
 *     KeyPointRadius * h, neighbouring cells included (ValidateKeyPoints);
 *     a key sample sits on its extreme point (ExtremeKeyPoints);
 *  3. budget: N_c ~ w_c * n_c^BudgetExponent (from the cell's own points and
 *     the global mean of the weight; w_c = 1 + VariationBudget * r, r =
 *     sigma_c / mean(sigma), counted as sqrt(VariationCap * r) past
 *     VariationCap), with one sample per non-empty cell
 *     first when N_s allows (CoverEveryCell), exact in total;
 *  4. sampling: per cell, the most prominent key points up to N_c (N_c - 1
 *     in a cell of two or more samples with ReserveFreeSample), then the
 *     free samples by farthest-point seeding and LloydIterations Lloyd
 *     iterations inside the cell with the key samples fixed (Lloyd.h);
 *  5. cross-cell refinement (FeatureRefine.h): CrossCellIterations Lloyd
 *     iterations across cell borders; optionally (FillHoles) a bounded
 *     hole-filling pass; with
 *     input-point samples, CoveringRounds rounds of covering refinement
 *     (Covering.h); FinalLloydIterations Lloyd iterations across cell
 *     borders; then every point joins its nearest sample (the sample's
 *     cluster);
 *  6. output: each free sample is the input point nearest its position
 *     (InputPointSamples) or its cluster's centroid; with BoundSnappedHoles,
 *     the input-point samples whose cluster reaches past the largest hole
 *     that (approximate) minimax centres would leave move towards that
 *     centre, just far enough.
 *
 * Locality, for distributed runs: every step after the budget reads one ring
 * of cells, so a cell's samples depend only on the points within
 * InfluenceRingsOf(parameters) <= InfluenceRings rings of cells around it,
 * given the global grid (origin, cell size) and its budget. The budget share
 * of a cell is computed from its own points (and the global mean surface
 * variation with the adaptive weight); the apportionment (with the coverage
 * rule) is global: a distributed driver computes it over all cells and
 * passes every cell's budget, halo cells included, through
 * SimplifyParameters::CellBudget, with OutputCell selecting the cells whose
 * samples are output (vtkASMDistributed.h). The final Lloyd iterations
 * are local too (2 rings each; 4 when weighted, 2 for the first one after a
 * cross-cell step or a hole-filling round: InfluenceRingsOf), except the
 * mean variation of their weights, which a distributed driver sums over all
 * processes (SumOverProcesses). The hole filling's moves are global: each
 * process ranks its output cells' samples and points and the rankings and
 * removal costs are gathered (GatherOverProcesses, HoleFilling.h), so that
 * every process makes the same moves; its Lloyd step is local (2 rings per
 * round), and so is a covering round (2 rings). With ShareSamples, the
 * samples of cells owned elsewhere are exchanged after every step, and a
 * driver's halo needs only InfluenceRingsPerStep rings. The snapped-hole
 * bound is global, and a distributed driver takes it after this function,
 * over all processes (SnappedHoles.h: BoundSnappedHoles off here).
 */
#ifndef asm_core_FeatureSimplify_h
#define asm_core_FeatureSimplify_h

#include "Simplify.h"

namespace asmcore
{
/// Largest number of Lloyd iterations across cell borders.
constexpr int MaxCrossCellIterations = 4;
/// Largest number of final Lloyd iterations (vtkASMSimplify's clamp).
constexpr int MaxFinalLloydIterations = 8;
/// Hole-filling rounds of vtkASMSimplify (SimplifyParameters::HoleFillRounds).
constexpr int DefaultHoleFillRounds = 4;
/// Rings of cells a cell's result may depend on with vtkASMSimplify's
/// ranges (a bound): one for Lemma 2, two per cross-cell iteration, two per
/// hole-filling round, four per (weighted) final iteration, two for the
/// final assignment.
constexpr int InfluenceRings =
  1 + 2 * MaxCrossCellIterations + 2 * DefaultHoleFillRounds + 4 * MaxFinalLloydIterations + 2;

/// The rings a cell's result depends on with these parameters, given the
/// global grid, budgets and hole-filling moves.
VTKASMFILTERS_EXPORT int InfluenceRingsOf(const SimplifyParameters& parameters);

/// The rings of cells one step reads (given the global grid, budgets and
/// hole-filling moves), when the samples of every cell are exchanged with
/// its owner's after each step (SimplifyParameters::ShareSamples): 4 with
/// weighted final Lloyd iterations, 2 otherwise (a Lloyd step, a
/// hole-filling round, the final clusters; the key point validation reads
/// 1).
VTKASMFILTERS_EXPORT int InfluenceRingsPerStep(const SimplifyParameters& parameters);

/// How many times a run with these parameters calls SumOverProcesses (one
/// not cut short by an abort, an empty input or a limit): once per final
/// Lloyd iteration when they are weighted. (GatherOverProcesses is called
/// as many times as the hole filling's data asks: a distributed driver lets
/// a process whose run ended early take part in the others' collectives
/// until all are done, vtkASMDistributed.h.)
VTKASMFILTERS_EXPORT int CollectiveSumsOf(const SimplifyParameters& parameters);

/// Simplify in the feature-preserving mode (see above); same contract as
/// Simplify(): exactly min(N_s, ids.size()) samples, deterministic whatever
/// the thread count, Members partitioning the input points among the samples.
/// At most 2^31 - 1 samples (SampleId); more give an empty, Aborted result.
VTKASMFILTERS_EXPORT SimplifyResult SimplifyFeaturePreserving(Coordinates xyz, IdView ids,
  NormalField normals, const SimplifyParameters& parameters, const Execution& execution = {});
} // namespace asmcore

#endif
