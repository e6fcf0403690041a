// SPDX-License-Identifier: BSD-3-Clause
#include "FeatureSimplify.h"

#include "Assignment.h"
#include "Budget.h"
#include "CanonicalOrder.h"
#include "CellFrame.h"
#include "CellNeighbors.h"
#include "FeatureKeyPoints.h"
#include "FeatureOutput.h"
#include "FeatureRefine.h"
#include "Grid.h"
#include "GroupBy.h"
#include "Lloyd.h"
#include "Neighbors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <type_traits>

namespace asmcore
{
using feature::CellSurface;
using feature::FillEmptyClusters;
using feature::KeepOutputCells;
using feature::LayOutSamples;
using feature::OutputCells;
using feature::PlaceOutputSamples;
using feature::SampleInfo;

namespace
{
// Points that no sample within the searched cell rings took (sparse clouds
// with fewer samples than cells) join the nearest sample anywhere, so that
// the clusters stay a partition of the points.
void JoinUnassignedPoints(Coordinates P, const SampleSet& samples, Index count,
  PointArray<SampleId>& assign, const Execution& execution)
{
  if (count == 0 || std::find(assign.begin(), assign.end(), Index(-1)) == assign.end())
  {
    return;
  }
  std::vector<Index> sampleIds(static_cast<std::size_t>(count));
  std::iota(sampleIds.begin(), sampleIds.end(), Index(0));
  const Neighbors tree(samples.Position.data(), sampleIds);
  execution.Run(0, static_cast<Index>(assign.size()), [&](Index b, Index e) {
    for (Index i = b; i < e; ++i)
    {
      if (assign[i] < 0)
      {
        const NearestPoint nearest = tree.Nearest(P.At(i).data());
        assign[i] = nearest.Id >= 0 ? nearest.Id : 0;
      }
    }
  });
}
} // namespace

int InfluenceRingsOf(const SimplifyParameters& parameters)
{
  // A Lloyd step moves a sample to the centroid of points of its cell's
  // ring, each assigned among the samples of its own ring: 2 rings. A
  // hole-filling round is one such step after its moves, which every process
  // makes alike (HoleFilling.h), from spreads, gaps and removal costs that
  // read 2 rings around a process's own cells: 2 rings. A weighted step
  // also reads the variations of the clusters around those samples,
  // measured on an assignment of their own: 4; but the first one measures
  // them on the assignment of the step before it (computed on that step's
  // samples, whose influence is 2 rings narrower): 2 when there is such a
  // step. A covering round moves each sample within its own cluster: 2.
  const int holeRounds = parameters.FillHoles ? std::max(0, parameters.HoleFillRounds) : 0;
  const bool inputPoints = parameters.InputPointSamples || parameters.Snap;
  const int coveringRounds = inputPoints ? std::max(0, parameters.CoveringRounds) : 0;
  const int finalIterations = std::max(0, parameters.FinalLloydIterations);
  int finalRings = 2 * finalIterations;
  if (parameters.LloydVariationWeight > 0.0 && finalIterations > 0)
  {
    const bool stepBefore = CrossIterations(parameters) > 0 || holeRounds > 0 || coveringRounds > 0;
    finalRings = (stepBefore ? 2 : 4) + 4 * (finalIterations - 1);
  }
  return 1 + 2 * CrossIterations(parameters) + 2 * holeRounds + 2 * coveringRounds + finalRings + 2;
}

int InfluenceRingsPerStep(const SimplifyParameters& parameters)
{
  // A weighted step reads the variations of the clusters of the samples
  // around: their members' assignment, 4 rings (the first one reuses the
  // previous step's assignment, which is exact 1 ring less far: the same
  // 4). Any other step: 2.
  return parameters.LloydVariationWeight > 0.0 && parameters.FinalLloydIterations > 0 ? 4 : 2;
}

int CollectiveSumsOf(const SimplifyParameters& parameters)
{
  return parameters.Mode == SimplifyMode::Paper || parameters.LloydVariationWeight <= 0.0
    ? 0
    : std::max(0, parameters.FinalLloydIterations);
}

SimplifyResult SimplifyFeaturePreserving(Coordinates xyz, IdView ids, NormalField normals,
  const SimplifyParameters& parameters, const Execution& execution)
{
  SimplifyResult result;
  const Index total = static_cast<Index>(ids.size());
  // Distributed runs (Simplify.h): the budgets come from CellBudget.
  const Index target = SampleTarget(parameters, total);
  if (total == 0 || target == 0)
  {
    return result;
  }
  auto abort = [&](double fraction) {
    if (execution.Report(fraction))
    {
      result = SimplifyResult();
      result.Aborted = true;
      return true;
    }
    return false;
  };

  // 1. Grid (given in distributed runs).
  CellGrid original = BuildRunGrid(xyz, ids, parameters, target, execution);
  if (abort(0.1))
  {
    return result;
  }
  // Every later pass reads the points cell by cell: a copy in cell order
  // (slot i holds point original.Order[i]) keeps those reads sequential,
  // each cell's points in its canonical order (CanonicalCell: the result
  // does not depend on the input's order). Of the input's type: a
  // float cloud's copy is floats (12 bytes per point). (Left uninitialised:
  // the parallel copy takes the page faults.)
  std::unique_ptr<double[]> cellDoubles;
  std::unique_ptr<float[]> cellFloats;
  const auto copyInCellOrder = [&](auto* to) {
    using T = std::remove_pointer_t<decltype(to)>;
    execution.Run(0, original.NumberOfCells(), [&](Index b, Index e) {
      CanonicalCell local;
      for (Index c = b; c < e; ++c)
      {
        const Index first = original.CellStart[c], n = original.CellSizeOf(c);
        Index* cellIds = original.Order.data() + first;
        local.Gather(xyz, cellIds, n);
        for (Index k = 0; k < n; ++k)
        {
          for (int a = 0; a < 3; ++a)
          {
            to[3 * (first + k) + a] = static_cast<T>(local.Xyz[3 * k + a]);
          }
          cellIds[k] = local.Ids[k];
        }
      }
    });
  };
  if (xyz.Floats)
  {
    cellFloats.reset(new float[static_cast<std::size_t>(3 * total)]);
    copyInCellOrder(cellFloats.get());
  }
  else
  {
    cellDoubles.reset(new double[static_cast<std::size_t>(3 * total)]);
    copyInCellOrder(cellDoubles.get());
  }
  // (released before the output)
  Coordinates P = xyz.Floats ? Coordinates(cellFloats.get()) : Coordinates(cellDoubles.get());
  // The same cells over the copy, in slot order, and each slot's point id.
  CellGrid grid;
  grid.Spec = original.Spec;
  grid.CellStart.swap(original.CellStart);
  grid.CellKey.swap(original.CellKey);
  grid.SlotOrder = true; // (no identity list: 8 bytes per point less)
  auto slotIds = std::make_unique<const SlotIds>(original.Order, execution);
  const SlotIds& idOf = *slotIds;
  const Index cells = grid.NumberOfCells();
  const double h = grid.Spec.CellSize;
  result.CellSize = h;
  result.NumberOfCells = cells;
  CellNeighborTable neighbors = BuildCellNeighbors(grid, execution);
  if (cells > CellNeighborTable::MaxTableCells)
  {
    result.Aborted = true; // (more cells than the neighbour table can number)
    return result;
  }
  if (abort(0.2))
  {
    return result;
  }

  // 2. Per-cell analysis: PCA frame and key points.
  std::vector<CellFrame> frames(static_cast<std::size_t>(cells));
  execution.Run(0, cells, [&](Index b, Index e) {
    for (Index c = b; c < e; ++c)
    {
      frames[c] = ComputeCellFrame(P, grid.CellIds(c));
    }
  });
  FeatureKeyOptions keyOptions;
  keyOptions.Rule.Alpha = parameters.Alpha;
  keyOptions.Rule.ErrorTolerance = parameters.ErrorTolerance;
  keyOptions.Rule.LinkFactor = parameters.FeatureLinkFactor;
  keyOptions.Rule.CoordinateEpsilon = parameters.CoordinateEpsilon;
  keyOptions.Rule.Snap = parameters.Snap;
  keyOptions.Validate = parameters.ValidateKeyPoints;
  keyOptions.Radius = std::max(1e-6, std::min(1.0, parameters.KeyPointRadius)) * h;
  keyOptions.MinimumProminence = std::max(0.0, parameters.KeyPointProminence) * keyOptions.Radius;
  keyOptions.InPlaneExtremes = parameters.InPlaneKeyPoints;
  keyOptions.ExtremeRepresentative = parameters.ExtremeKeyPoints;
  keyOptions.SparseCells = parameters.SparseCellKeyPoints;
  std::vector<std::vector<FeatureKey>> keys(static_cast<std::size_t>(cells));
  execution.Run(0, cells, [&](Index b, Index e) {
    LocalPoints q;
    for (Index c = b; c < e; ++c)
    {
      keys[c] = FindFeatureKeys(P, grid, neighbors, frames[c], c, keyOptions, q);
    }
  });
  if (abort(0.4))
  {
    return result;
  }

  // 3. Budget: N_c ~ w_c * n_c^gamma, one per cell first when N_s allows.
  std::vector<Index> budget;
  if (parameters.CellBudget)
  {
    budget.resize(static_cast<std::size_t>(cells));
    for (Index c = 0; c < cells; ++c)
    {
      budget[c] =
        std::min(grid.CellSizeOf(c), std::max<Index>(0, parameters.CellBudget(grid.CellKey[c])));
    }
  }
  else
  {
    std::vector<Index> capacity;
    const std::vector<double> share =
      CellShares(frames, grid, parameters, std::max(0.0, parameters.BudgetExponent), capacity);
    budget = ApportionWithCoverage(share, capacity, target, parameters.CoverEveryCell);
  }

  // 4. Sampling inside each cell: key samples, then Lloyd with keys fixed.
  SampleSet samples;
  samples.Start.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (Index c = 0; c < cells; ++c)
  {
    samples.Start[c + 1] = samples.Start[c] + budget[c];
  }
  Index count = samples.Start[cells]; // (the hole filling may change this run's share)
  if (count > static_cast<Index>(std::numeric_limits<SampleId>::max()))
  {
    result.Aborted = true; // (SampleId: more samples than the assignments can number)
    return result;
  }
  samples.Position.assign(static_cast<std::size_t>(3 * count), 0.0);
  samples.Fixed.assign(static_cast<std::size_t>(count), 0);
  std::vector<SampleInfo> info(static_cast<std::size_t>(count));
  execution.Run(0, cells, [&](Index b, Index e) {
    CellScratch scratch;
    std::vector<Index> exclude;
    for (Index c = b; c < e; ++c)
    {
      const Index first = samples.Start[c];
      // (ReserveFreeSample: a cell of two or more samples keeps a free one.)
      const Index keyBudget =
        parameters.ReserveFreeSample && budget[c] > 1 ? budget[c] - 1 : budget[c];
      const Index keyCount = std::min<Index>(keyBudget, static_cast<Index>(keys[c].size()));
      exclude.clear();
      for (Index s = first; s < samples.Start[c + 1]; ++s)
      {
        info[s].Owner = c;
      }
      for (Index k = 0; k < keyCount; ++k)
      {
        const FeatureKey& key = keys[c][k];
        std::copy(key.Position, key.Position + 3, samples.Position.data() + 3 * (first + k));
        samples.Fixed[first + k] = 1;
        info[first + k].Point = key.Point;
        info[first + k].KeyError = key.Error;
        exclude.push_back(key.Point);
      }
      RelaxCell(P, grid.CellIds(c), frames[c], exclude, first, keyCount, budget[c],
        parameters.LloydIterations, samples, scratch);
    }
  });
  // The key points are placed: released (the budgets are in samples.Start),
  // and of the frames only what the output needs is kept.
  std::vector<std::vector<FeatureKey>>().swap(keys);
  std::vector<Index>().swap(budget);
  std::vector<CellSurface> surfaces(static_cast<std::size_t>(cells));
  for (Index c = 0; c < cells; ++c)
  {
    surfaces[c] = { frames[c].Normal(), frames[c].Centroid, frames[c].SurfaceVariation() };
  }
  std::vector<CellFrame>().swap(frames);
  if (abort(0.6))
  {
    return result;
  }
  // 5. Cross-cell refinement (FeatureRefine.h).
  PointArray<SampleId> assign; // (the distances are recomputed: AssignedDistance2)
  if (!RefineAcrossCells(P, grid, neighbors, parameters, execution, samples, info, assign))
  {
    result = SimplifyResult();
    result.Aborted = true;
    return result;
  }
  count = samples.Size();

  // Clusters: every point joins its nearest sample.
  AssignToSamples(P, grid, neighbors, samples, assign, execution);
  JoinUnassignedPoints(P, samples, count, assign, execution);
  std::vector<Index> clusterSize(static_cast<std::size_t>(count), 0);
  for (Index s : assign)
  {
    if (s >= 0)
    {
      ++clusterSize[s];
    }
  }
  const std::vector<char> output = OutputCells(grid, parameters); // (empty: all)
  FillEmptyClusters(P, grid, neighbors, samples, info, assign, clusterSize, output);
  // The last step that looks across cells: the table is released.
  std::vector<CellRef>().swap(neighbors.Cells);
  // The members of each sample as slots of the cell-ordered copy (in slot
  // order) for the output's first step, which reads their coordinates there
  // (a cluster's points are near each other in memory, not scattered over
  // the input).
  std::vector<Index> memberStart;
  // (Small per-block counts, an eighth of an Index per point: at most two
  // blocks at 5 %.)
  GroupBy(
    total, count, [&](Index i) { return assign[i]; }, [](Index i) { return i; }, memberStart,
    result.Members, execution, 8, 1 << 16, 0.125);
  PointArray<SampleId>().swap(assign);
  std::vector<Index>().swap(clusterSize); // (the groups' sizes, from memberStart)
  if (abort(0.9))
  {
    return result;
  }

  // Output, step 1, with the copy: the samples' final positions and
  // representatives; then the members and representatives become input
  // point ids, and the copy is released.
  PlaceOutputSamples(P, grid, idOf, memberStart, parameters, samples, info, result.Members,
    result.RepresentativeDuplicates, execution);
  cellFloats.reset();
  cellDoubles.reset();
  slotIds.reset();
  P = Coordinates();

  // Step 2: the samples.
  LayOutSamples(
    xyz, ids, normals, surfaces, info, samples, memberStart, parameters, result, execution);
  if (parameters.OutputCell)
  {
    KeepOutputCells(result, info, output);
  }
  SummarizeKeyPoints(result);
  execution.Report(1.0);
  return result;
}
} // namespace asmcore
