// SPDX-License-Identifier: BSD-3-Clause
#include "CellSize.h"

#include "ExactMean.h"
#include "GridOccupancy.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

namespace asmcore
{
using namespace occupancy;

double EffectiveOccupiedCells(Coordinates xyz, IdView ids, const GridSpec& spec, double minPoints)
{
  // Points per cell in a hash table, then the cells in increasing key order
  // (the order of the sum): no sort of one key per point.
  KeyTable table;
  std::uint64_t last = KeyTable::Empty;
  Index* run = nullptr;
  for (Index id : ids)
  {
    double p[3];
    xyz.Get(id, p);
    const std::uint64_t key = spec.KeyOf(p);
    if (key != last)
    {
      table.Insert(key);
      run = &table.ValueOf(key);
      last = key;
    }
    ++*run;
  }
  ExactMean count;
  for (std::uint64_t key : table.SortedKeys())
  {
    count.Add(SparseCellShare(table.Find(key), minPoints));
  }
  return count.Total();
}

double SparseCellShare(Index points, double minPoints)
{
  return std::min(1.0, static_cast<double>(points) / minPoints);
}

double SparseCellPoints(Index points, double targetCells)
{
  return std::max(1.0, static_cast<double>(points) / targetCells / 8.0);
}

bool SparseCellsDominate(double effective, double raw)
{
  return !(effective >= 0.8 * raw);
}

namespace
{

// The cell edge for which count(spec) is about targetCells (> 1), for a
// cloud of largest extent > 0.
template <typename Count>
double SearchCellSize(const Bounds& bounds, double targetCells, Count&& count, double start = 0.0)
{
  const double maxExtent = bounds.MaxExtent();
  const double oneCell = maxExtent * (1.0 + 1e-9);
  // Start from the guess that the points sample a surface (count ~ h^-2),
  // unless a start is given, then correct with the measured count and the
  // measured local exponent.
  double h = start > 0.0 ? std::min(start, oneCell) : maxExtent / std::sqrt(targetCells);
  double bestH = oneCell;
  double bestErr = std::abs(std::log(1.0 / targetCells));
  double prevH = 0.0, prevCount = 0.0;
  double dimension = 2.0;
  for (int iteration = 0; iteration < 12; ++iteration)
  {
    h = GridSpec::Make(bounds, h).CellSize;
    const double n = count(GridSpec::Make(bounds, h));
    const double err = std::abs(std::log(n / targetCells));
    if (err < bestErr)
    {
      bestErr = err;
      bestH = h;
    }
    if (err < 0.05) // within 5 %
    {
      break;
    }
    if (prevCount > 0.0 && n != prevCount && h != prevH)
    {
      const double measured = -std::log(n / prevCount) / std::log(h / prevH);
      dimension = std::min(3.0, std::max(0.5, measured));
    }
    prevH = h;
    prevCount = n;
    h *= std::pow(n / targetCells, 1.0 / dimension);
    h = std::min(h, oneCell);
  }
  return bestH;
}
} // namespace

double AutomaticCellSize(const Bounds& bounds, double targetCells, bool empty,
  const std::function<double(const GridSpec&)>& countOccupied, double start)
{
  const double maxExtent = bounds.MaxExtent();
  if (empty || !(maxExtent > 0.0))
  {
    return GridSpec::Make(bounds, 0.0).CellSize; // one cell holds everything
  }
  if (targetCells <= 1.0)
  {
    return maxExtent * (1.0 + 1e-9); // one cell for the whole cloud
  }
  return SearchCellSize(bounds, targetCells, countOccupied, start);
}

PointArray<double> CellSizeSubsample(
  Coordinates xyz, IdView ids, double totalPoints, double targetCells, const Execution& execution)
{
  PointArray<double> subset;
  if (totalPoints < 200000.0 || !(targetCells > 1.0))
  {
    return subset;
  }
  const double stride = std::max(4.0, std::floor(totalPoints / targetCells / 32.0));
  // Picked when the hash's high 32 bits fall below 2^32 / stride.
  const auto below = static_cast<std::uint64_t>(4294967296.0 / stride);
  // One pass over fixed blocks, each keeping its picked points (in the
  // order of `ids`), then the blocks' points concatenated.
  const Index n = static_cast<Index>(ids.size());
  const Index blocks = BlockCount(n, 64, 1 << 15);
  std::vector<std::vector<double>> picked(static_cast<std::size_t>(blocks));
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      std::vector<double>& mine = picked[k];
      const Index begin = BlockBegin(n, blocks, k), end = BlockBegin(n, blocks, k + 1);
      mine.reserve(
        static_cast<std::size_t>(3.0 * static_cast<double>(end - begin) / stride * 1.25) + 24);
      ForEachPoint(xyz, ids, begin, end, [&mine, below](Index, const double p[3]) {
        if ((CoordinateHash(p) >> 32) < below)
        {
          mine.push_back(p[0]); // (inline: a range insert is a call per point)
          mine.push_back(p[1]);
          mine.push_back(p[2]);
        }
      });
    }
  });
  std::vector<std::size_t> start(static_cast<std::size_t>(blocks) + 1, 0);
  for (Index k = 0; k < blocks; ++k)
  {
    start[k + 1] = start[k] + picked[k].size();
  }
  subset.resize(start[blocks]);
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      std::copy(
        picked[k].begin(), picked[k].end(), subset.begin() + static_cast<std::ptrdiff_t>(start[k]));
      std::vector<double>().swap(picked[k]);
    }
  });
  return subset;
}

namespace
{
// The search on the subsample, as a start for the full search (0: none).
double SubsampleStart(
  Coordinates xyz, IdView ids, const Bounds& bounds, double targetCells, const Execution& execution)
{
  const PointArray<double> subset =
    CellSizeSubsample(xyz, ids, static_cast<double>(ids.size()), targetCells, execution);
  if (subset.empty())
  {
    return 0.0;
  }
  PointIds subsetIds(subset.size() / 3);
  execution.Run(0, static_cast<Index>(subsetIds.size()),
    [&](Index b, Index e) { std::iota(subsetIds.begin() + b, subsetIds.begin() + e, b); });
  return SearchCellSize(bounds, targetCells, [&](const GridSpec& spec) {
    return static_cast<double>(CountOccupiedCells(subset.data(), subsetIds, spec, execution));
  });
}

// The outlier-robust search: each cell counted by min(1, points / minimum).
double SearchIgnoringSparseCells(
  Coordinates xyz, IdView ids, const Bounds& bounds, double targetCells)
{
  const double minPoints = SparseCellPoints(static_cast<Index>(ids.size()), targetCells);
  return SearchCellSize(bounds, targetCells,
    [&](const GridSpec& spec) { return EffectiveOccupiedCells(xyz, ids, spec, minPoints); });
}
} // namespace

double AutomaticCellSize(
  Coordinates xyz, IdView ids, const Bounds& bounds, double targetCells, const Execution& execution)
{
  return BuildAutomaticCellGrid(xyz, ids, bounds, targetCells, execution).Spec.CellSize;
}

CellGrid BuildAutomaticCellGrid(
  Coordinates xyz, IdView ids, const Bounds& bounds, double targetCells, const Execution& execution)
{
  const double maxExtent = bounds.MaxExtent();
  if (ids.empty() || !(maxExtent > 0.0))
  {
    return BuildCellGrid(
      xyz, ids, GridSpec::Make(bounds, 0.0), execution); // one cell holds everything
  }
  if (targetCells <= 1.0)
  {
    // One cell for the whole cloud: slightly larger than the largest extent.
    return BuildCellGrid(xyz, ids, GridSpec::Make(bounds, maxExtent * (1.0 + 1e-9)), execution);
  }
  // The full search's counts keep their marks: the last count is usually
  // the answer, and the grid is then finished from its marks.
  const double start = SubsampleStart(xyz, ids, bounds, targetCells, execution);
  CellMarks marks;
  const double h = SearchCellSize(
    bounds, targetCells,
    [&](const GridSpec& spec) {
      return static_cast<double>(marks.Mark(xyz, ids, spec, execution)
          ? marks.Occupied(execution)
          : CountOccupiedCells(xyz, ids, spec, execution));
    },
    start);
  const GridSpec found = GridSpec::Make(bounds, h);
  CellGrid grid = (marks.Valid && marks.Spec.CellSize == found.CellSize)
    ? FinishCellGrid(ids, marks, execution)
    : BuildCellGrid(xyz, ids, found, execution);
  // The outlier-robust count, from the grid's cells (the sum of
  // EffectiveOccupiedCells).
  const double minPoints = SparseCellPoints(static_cast<Index>(ids.size()), targetCells);
  ExactMean effective;
  for (Index c = 0; c < grid.NumberOfCells(); ++c)
  {
    effective.Add(SparseCellShare(grid.CellSizeOf(c), minPoints));
  }
  if (!SparseCellsDominate(effective.Total(), static_cast<double>(grid.NumberOfCells())))
  {
    return grid;
  }
  return BuildCellGrid(xyz, ids,
    GridSpec::Make(bounds, SearchIgnoringSparseCells(xyz, ids, bounds, targetCells)), execution);
}
} // namespace asmcore
