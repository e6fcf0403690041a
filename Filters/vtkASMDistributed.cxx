// SPDX-License-Identifier: BSD-3-Clause
// MPI runs: the grid partition into boxes of cells, the global budgets and the
// preparation of a process's share (vtkASMDistributed.h); the communication
// is in vtkASMDistributedCommunication.cxx, the redistribution of the points
// in vtkASMDistributedRedistribute.cxx.
#include "vtkASMDistributed.h"

#include "vtkASMFilterUtilities.h"

#include "Core/Budget.h"
#include "Core/CanonicalOrder.h"
#include "Core/CellFrame.h"
#include "Core/CellSize.h"
#include "Core/ExactMean.h"
#include "Core/Grid.h"

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkMultiProcessController.h"
#include "vtkMultiProcessStream.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>

namespace asmvtk
{
namespace
{
std::uint64_t Mix(std::uint64_t key)
{
  asmcore::SplitMix64 mix(key);
  return mix.Next();
}
} // namespace

//------------------------------------------------------------------------------
Index CountOccupiedCells(const Communication& comm, const double* xyz, asmcore::IdView ids,
  const asmcore::GridSpec& spec, const asmcore::Execution& execution)
{
  if (comm.Size() == 1)
  {
    return asmcore::CountOccupiedCells(xyz, ids, spec, execution);
  }
  const std::vector<std::uint64_t> keys = asmcore::OccupiedCellKeys(xyz, ids, spec, execution);
  // Each key is counted by one process, chosen by a hash of the key.
  std::vector<asmcore::PointArray<long long>> send(static_cast<std::size_t>(comm.Size()));
  for (std::uint64_t key : keys)
  {
    send[Mix(key) % static_cast<std::uint64_t>(comm.Size())].push_back(static_cast<long long>(key));
  }
  asmcore::PointArray<long long> mine = comm.Exchange(send);
  std::sort(mine.begin(), mine.end());
  const Index distinct = static_cast<Index>(std::unique(mine.begin(), mine.end()) - mine.begin());
  return comm.Sum(distinct);
}

//------------------------------------------------------------------------------
double EffectiveOccupiedCells(const Communication& comm, const double* xyz, asmcore::IdView ids,
  const asmcore::GridSpec& spec, double minPoints, const asmcore::Execution& execution)
{
  if (comm.Size() == 1)
  {
    return asmcore::EffectiveOccupiedCells(xyz, ids, spec, minPoints);
  }
  // This process's (key, points) per cell, to the process counting the key
  // (chosen by a hash of the key), which adds up the cell's points over the
  // processes and takes its share; the shares summed in fixed point.
  std::vector<std::uint64_t> keys(ids.size());
  execution.Run(0, static_cast<Index>(ids.size()), [&](Index b, Index e) {
    for (Index i = b; i < e; ++i)
    {
      keys[i] = spec.KeyOf(xyz + 3 * ids[i]);
    }
  });
  std::sort(keys.begin(), keys.end());
  std::vector<asmcore::PointArray<long long>> send(static_cast<std::size_t>(comm.Size()));
  for (std::size_t i = 0; i < keys.size();)
  {
    std::size_t j = i;
    while (j < keys.size() && keys[j] == keys[i])
    {
      ++j;
    }
    auto& to = send[Mix(keys[i]) % static_cast<std::uint64_t>(comm.Size())];
    to.push_back(static_cast<long long>(keys[i]));
    to.push_back(static_cast<long long>(j - i));
    i = j;
  }
  std::vector<std::uint64_t>().swap(keys);
  const asmcore::PointArray<long long> mine = comm.Exchange(send);
  std::vector<std::pair<long long, long long>> cells(mine.size() / 2);
  for (std::size_t c = 0; c < cells.size(); ++c)
  {
    cells[c] = { mine[2 * c], mine[2 * c + 1] };
  }
  std::sort(cells.begin(), cells.end());
  asmcore::ExactMean effective;
  for (std::size_t i = 0; i < cells.size();)
  {
    long long points = 0;
    std::size_t j = i;
    for (; j < cells.size() && cells[j].first == cells[i].first; ++j)
    {
      points += cells[j].second;
    }
    effective.Add(asmcore::SparseCellShare(static_cast<Index>(points), minPoints));
    i = j;
  }
  comm.Sum(effective.Sums);
  return effective.Total();
}

//------------------------------------------------------------------------------
double AutomaticCellSize(const Communication& comm, const double* xyz, asmcore::IdView ids,
  const asmcore::Bounds& bounds, Index total, double targetCells,
  const asmcore::Execution& execution)
{
  // As the serial search (asmcore::AutomaticCellSize): first on the
  // subsample picked by coordinates (the same points however the cloud is
  // split), then on all points, the distinct cells counted over the
  // processes.
  const asmcore::PointArray<double> subset =
    asmcore::CellSizeSubsample(xyz, ids, static_cast<double>(total), targetCells, execution);
  double start = 0.0;
  if (comm.Sum(static_cast<Index>(subset.size())) > 0)
  {
    std::vector<Index> subsetIds(subset.size() / 3);
    std::iota(subsetIds.begin(), subsetIds.end(), Index(0));
    start = asmcore::AutomaticCellSize(
      bounds, targetCells, total == 0, [&](const asmcore::GridSpec& spec) {
        return static_cast<double>(
          CountOccupiedCells(comm, subset.data(), subsetIds, spec, execution));
      });
  }
  double cellSize = asmcore::AutomaticCellSize(
    bounds, targetCells, total == 0,
    [&](const asmcore::GridSpec& spec) {
      return static_cast<double>(CountOccupiedCells(comm, xyz, ids, spec, execution));
    },
    start);
  // Then, when sparse cells (far outliers, stray points) make up a fifth of
  // the count, again with each cell counted by its share
  // (asmcore::SparseCellsDominate).
  if (total > 0 && targetCells > 1.0 && bounds.MaxExtent() > 0.0)
  {
    const double minPoints = asmcore::SparseCellPoints(total, targetCells);
    auto effective = [&](const asmcore::GridSpec& spec) {
      return EffectiveOccupiedCells(comm, xyz, ids, spec, minPoints, execution);
    };
    const asmcore::GridSpec found = asmcore::GridSpec::Make(bounds, cellSize);
    if (asmcore::SparseCellsDominate(effective(found),
          static_cast<double>(CountOccupiedCells(comm, xyz, ids, found, execution))))
    {
      cellSize = asmcore::AutomaticCellSize(bounds, targetCells, false, effective);
    }
  }
  return cellSize;
}

//------------------------------------------------------------------------------
asmcore::CellPartition MakeCellPartition(const Communication& comm, const asmcore::GridSpec& grid,
  const double* xyz, asmcore::IdView ids, const asmcore::Execution& execution)
{
  return asmcore::MakeCellPartition(
    grid, comm.Size(), xyz, ids, [&comm](std::vector<long long>& counts) { comm.Sum(counts); },
    execution);
}

//------------------------------------------------------------------------------
void GlobalCentroid(const Communication& comm, const double* xyz, asmcore::IdView ids, Index total,
  double centroid[3])
{
  std::vector<double> sum(3, 0.0);
  for (Index id : ids)
  {
    for (int a = 0; a < 3; ++a)
    {
      sum[a] += xyz[3 * id + a];
    }
  }
  comm.Sum(sum);
  for (int a = 0; a < 3; ++a)
  {
    centroid[a] = total > 0 ? sum[a] / static_cast<double>(total) : 0.0;
  }
}

//------------------------------------------------------------------------------
void DropGhostPoints(vtkPointSet* input, asmcore::IdView& ids, asmcore::PointIds& list)
{
  vtkUnsignedCharArray* ghosts = GhostFlags(input);
  if (!ghosts)
  {
    return; // (a short ghost array is not read: it is dropped from the output)
  }
  asmcore::PointIds kept;
  kept.reserve(ids.size());
  for (Index id : ids)
  {
    if (!(ghosts->GetValue(id) &
          (vtkDataSetAttributes::DUPLICATEPOINT | vtkDataSetAttributes::HIDDENPOINT)))
    {
      kept.push_back(id);
    }
  }
  list.swap(kept);
  ids = list;
}

//------------------------------------------------------------------------------
std::vector<Index> GlobalBudgets(const Communication& comm, const std::vector<std::uint64_t>& keys,
  const std::vector<Index>& capacity, const std::vector<double>& variation,
  const asmcore::SimplifyParameters& parameters, Index target)
{
  if (comm.Size() == 1)
  {
    return ApportionCells(capacity, variation, parameters, target);
  }
  // Cells travel as (key / 2^32, key % 2^32, count, variation) as doubles:
  // each part is exact (keys reach 2^63, beyond a double's 2^53).
  constexpr int W = 4;
  std::vector<double> mine;
  mine.reserve(W * keys.size());
  for (std::size_t c = 0; c < keys.size(); ++c)
  {
    asmcore::AppendAsDoubles(mine, keys[c]);
    mine.insert(mine.end(), { static_cast<double>(capacity[c]), variation[c] });
  }
  long long n = static_cast<long long>(mine.size());
  std::vector<long long> counts(static_cast<std::size_t>(comm.Size()));
  comm.Controller()->AllGather(&n, counts.data(), 1);
  std::vector<vtkIdType> lengths(counts.begin(), counts.end());
  std::vector<vtkIdType> offsets(lengths.size(), 0);
  for (std::size_t r = 1; r < lengths.size(); ++r)
  {
    offsets[r] = offsets[r - 1] + lengths[r - 1];
  }
  const vtkIdType total = offsets.back() + lengths.back();
  std::vector<double> all(
    static_cast<std::size_t>(comm.Rank() == 0 ? std::max<vtkIdType>(total, 1) : 1));
  double dummy = 0.0;
  comm.Controller()->GatherV(mine.empty() ? &dummy : mine.data(), all.data(),
    static_cast<vtkIdType>(mine.size()), lengths.data(), offsets.data(), 0);

  // Process 0: every cell, in key order, as the serial code sees them.
  std::vector<double> budgets(
    static_cast<std::size_t>(comm.Rank() == 0 ? std::max<vtkIdType>(total / W, 1) : 1));
  if (comm.Rank() == 0)
  {
    const std::size_t cells = static_cast<std::size_t>(total / W);
    std::vector<std::size_t> order(cells);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return all[W * a] < all[W * b] ||
        (all[W * a] == all[W * b] && all[W * a + 1] < all[W * b + 1]);
    });
    std::vector<Index> cap(cells);
    std::vector<double> var(cells);
    for (std::size_t i = 0; i < cells; ++i)
    {
      cap[i] = static_cast<Index>(all[W * order[i] + 2]);
      var[i] = all[W * order[i] + 3];
    }
    const std::vector<Index> sorted = ApportionCells(cap, var, parameters, target);
    for (std::size_t i = 0; i < cells; ++i)
    {
      budgets[order[i]] = static_cast<double>(sorted[i]); // back in gathered order
    }
  }
  std::vector<vtkIdType> cellLengths(lengths.size()), cellOffsets(lengths.size());
  for (std::size_t r = 0; r < lengths.size(); ++r)
  {
    cellLengths[r] = lengths[r] / W;
    cellOffsets[r] = offsets[r] / W;
  }
  std::vector<double> back(std::max<std::size_t>(keys.size(), 1));
  comm.Controller()->ScatterV(budgets.data(), back.data(), cellLengths.data(), cellOffsets.data(),
    static_cast<vtkIdType>(keys.size()), 0);
  std::vector<Index> result(keys.size());
  for (std::size_t c = 0; c < keys.size(); ++c)
  {
    result[c] = static_cast<Index>(back[c]);
  }
  return result;
}

//------------------------------------------------------------------------------
Index SimplifyShare::BudgetOf(std::uint64_t key) const
{
  const auto it = std::lower_bound(this->OwnedKeys.begin(), this->OwnedKeys.end(), key);
  return (it != this->OwnedKeys.end() && *it == key)
    ? this->Budgets[static_cast<std::size_t>(it - this->OwnedKeys.begin())]
    : -1; // a halo cell
}

SimplifyShare PrepareSimplify(const Communication& comm, vtkPointSet* input, const double* xyz,
  asmcore::IdView ids, const asmcore::SimplifyParameters& parameters,
  const asmcore::Execution& execution)
{
  SimplifyShare share;
  const Index total = comm.Sum(static_cast<Index>(ids.size()));
  const asmcore::Bounds bounds = comm.Union(asmcore::ComputeBounds(xyz, ids, execution));
  share.Diagonal = bounds.Diagonal();
  GlobalCentroid(comm, xyz, ids, total, share.Centroid);

  // 1. One global grid; the automatic size counts distinct cells globally.
  double cellSize = parameters.CellSize;
  if (!(cellSize > 0.0) || !std::isfinite(cellSize))
  {
    const double targetCells = static_cast<double>(std::min(parameters.NumberOfSamples, total)) /
      asmcore::SamplesPerCellOf(parameters);
    cellSize = AutomaticCellSize(comm, xyz, ids, bounds, total, targetCells, execution);
  }
  share.Grid = asmcore::GridSpec::Make(bounds, cellSize);

  // 2. Owners, redistribution with the halo, canonical order.
  share.Partition = MakeCellPartition(comm, share.Grid, xyz, ids, execution);
  share.Cloud =
    Redistribute(comm, input, xyz, ids, share.Partition, HaloRingsFor(parameters), execution);

  // 3. The owned cells (consecutive runs of a key), and one global budget.
  const LocalCloud& cloud = share.Cloud;
  std::vector<Index> capacity;
  std::vector<double> variation;
  asmcore::CanonicalCell local;
  for (Index c = 0; c < cloud.Cells.NumberOfCells(); ++c)
  {
    const Index i = cloud.Cells.CellStart[c];
    const Index j = cloud.Cells.CellStart[c + 1];
    if (cloud.Owned[i])
    {
      share.OwnedKeys.push_back(cloud.Cells.CellKey[c]);
      capacity.push_back(j - i);
      // The same frame the core computes (same points, in the same,
      // canonical, order).
      double v = 0.0;
      if (asmcore::VariationWeightOf(parameters) != 0.0)
      {
        local.Gather(cloud.Xyz.data(), asmcore::IdView::Range(i, static_cast<std::size_t>(j - i)));
        v = asmcore::ComputeCellFrame(local.Xyz.data(), asmcore::IdView::Identity(local.Ids.size()))
              .SurfaceVariation();
      }
      variation.push_back(v);
    }
  }
  share.Budgets = GlobalBudgets(comm, share.OwnedKeys, capacity, variation, parameters,
    std::min(parameters.NumberOfSamples, total));
  if (parameters.Mode == asmcore::SimplifyMode::FeaturePreserving)
  {
    ShareAllBudgets(comm, share); // halo cells need their true budgets
  }
  return share;
}

void RunOnShare(const SimplifyShare& share, asmcore::SimplifyParameters& parameters)
{
  parameters.Grid = &share.Grid;
  parameters.Cells = &share.Cloud.Cells;
  if (parameters.Mode == asmcore::SimplifyMode::Paper)
  {
    parameters.CellBudget = [&share](std::uint64_t key) { return share.BudgetOf(key); };
  }
  else
  {
    // Halo cells are simplified too, with their true budgets, as context
    // for the cross-cell steps; only the owned cells' samples are output.
    parameters.CellBudget = [&share](std::uint64_t key) { return share.TrueBudgetOf(key); };
    parameters.OutputCell = [&share](std::uint64_t key) { return share.Owns(key); };
  }
  parameters.CloudCentroid = share.Centroid;
}

void CombineFigures(
  const Communication& comm, const SimplifyShare& share, asmcore::SimplifyResult& result)
{
  const Index keys = comm.Sum(result.NumberOfKeyPoints);
  const double sum = comm.Sum(result.AKPE * static_cast<double>(result.NumberOfKeyPoints));
  result.MKPE = comm.Max(result.MKPE);
  result.AKPE = keys > 0 ? sum / static_cast<double>(keys) : 0.0;
  result.NumberOfKeyPoints = keys;
  result.CellSize = share.Grid.CellSize;
  result.Aborted = comm.Max(result.Aborted ? 1.0 : 0.0) > 0.0;
}
} // namespace asmvtk
