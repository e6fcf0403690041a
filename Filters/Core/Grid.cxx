// SPDX-License-Identifier: BSD-3-Clause
#include "Grid.h"

#include "GridOccupancy.h"
#include "GroupBy.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <cmath>
#include <limits>
#include <cstring>
#include <numeric>
#include <utility>

namespace asmcore
{
std::vector<Index> FinitePointIds(const double* xyz, Index n)
{
  std::vector<Index> ids;
  ids.reserve(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i)
  {
    const double* p = xyz + 3 * i;
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      ids.push_back(i);
    }
  }
  return ids;
}

double Bounds::Diagonal() const
{
  if (!this->Valid)
  {
    return 0.0;
  }
  return std::sqrt(this->Extent(0) * this->Extent(0) + this->Extent(1) * this->Extent(1) +
    this->Extent(2) * this->Extent(2));
}

double Bounds::MaxExtent() const
{
  return this->Valid ? std::max({ this->Extent(0), this->Extent(1), this->Extent(2) }) : 0.0;
}

using namespace occupancy;

namespace
{
// A point's coordinates hashed (the bits of the three doubles, mixed).
inline std::uint64_t CoordinateHash(const double* p)
{
  std::uint64_t bits[3];
  std::memcpy(bits, p, sizeof(bits));
  SplitMix64 mix(bits[0] ^ ((bits[1] << 21) | (bits[1] >> 43)) ^ ((bits[2] << 42) | (bits[2] >> 22)));
  return mix.Next();
}

} // namespace

Bounds ComputeBounds(const double* xyz, const std::vector<Index>& ids, const Execution& execution)
{
  Bounds b;
  if (ids.empty())
  {
    return b;
  }
  // Min and max are exact: any split of the work gives the same bounds.
  const Index n = static_cast<Index>(ids.size());
  const Index blocks = BlockCount(n, 64, 1 << 15);
  std::vector<Bounds> partial(static_cast<std::size_t>(blocks));
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      Bounds& pb = partial[k];
      for (int a = 0; a < 3; ++a)
      {
        pb.Min[a] = std::numeric_limits<double>::infinity();
        pb.Max[a] = -std::numeric_limits<double>::infinity();
      }
      const Index end = BlockBegin(n, blocks, k + 1);
      for (Index i = BlockBegin(n, blocks, k); i < end; ++i)
      {
        const double* p = xyz + 3 * ids[i];
        for (int a = 0; a < 3; ++a)
        {
          pb.Min[a] = std::min(pb.Min[a], p[a]);
          pb.Max[a] = std::max(pb.Max[a], p[a]);
        }
      }
    }
  });
  b = partial[0];
  for (const Bounds& pb : partial)
  {
    for (int a = 0; a < 3; ++a)
    {
      b.Min[a] = std::min(b.Min[a], pb.Min[a]);
      b.Max[a] = std::max(b.Max[a], pb.Max[a]);
    }
  }
  b.Valid = true;
  return b;
}

void ComputeCentroid(
  const double* xyz, const std::vector<Index>& ids, double centroid[3], const Execution& execution)
{
  centroid[0] = centroid[1] = centroid[2] = 0.0;
  const Index n = static_cast<Index>(ids.size());
  if (n == 0)
  {
    return;
  }
  const Index blocks = BlockCount(n, 64, 1 << 15);
  std::vector<double> partial(static_cast<std::size_t>(3 * blocks), 0.0);
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      double sum[3] = { 0.0, 0.0, 0.0 };
      const Index end = BlockBegin(n, blocks, k + 1);
      for (Index i = BlockBegin(n, blocks, k); i < end; ++i)
      {
        const double* p = xyz + 3 * ids[i];
        sum[0] += p[0];
        sum[1] += p[1];
        sum[2] += p[2];
      }
      std::copy(sum, sum + 3, &partial[3 * k]);
    }
  });
  for (Index k = 0; k < blocks; ++k)
  {
    for (int a = 0; a < 3; ++a)
    {
      centroid[a] += partial[3 * k + a];
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    centroid[a] /= static_cast<double>(n);
  }
}

GridSpec GridSpec::Make(const Bounds& bounds, double cellSize)
{
  GridSpec g;
  const double maxExtent = bounds.MaxExtent();
  // Smallest edge that keeps every axis within MaxDim cells (with a margin for
  // rounding), and a positive edge for a cloud of coincident points.
  double minSize = maxExtent / static_cast<double>(MaxDim - 2);
  if (!(minSize > 0.0))
  {
    minSize = std::max(std::abs(bounds.Min[0]), 1.0) * 1e-12;
  }
  g.CellSize = (std::isfinite(cellSize) && cellSize > minSize) ? cellSize : minSize;
  for (int a = 0; a < 3; ++a)
  {
    g.Origin[a] = bounds.Valid ? bounds.Min[a] : 0.0;
    const double extent = bounds.Valid ? bounds.Extent(a) : 0.0;
    g.Dims[a] = std::min<std::int64_t>(MaxDim,
      std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(extent / g.CellSize)) + 1));
  }
  return g;
}

void GridSpec::Unpack(std::uint64_t key, std::int64_t ijk[3]) const
{
  const std::uint64_t mask = (std::uint64_t(1) << 21) - 1;
  ijk[0] = static_cast<std::int64_t>(key & mask);
  ijk[1] = static_cast<std::int64_t>((key >> 21) & mask);
  ijk[2] = static_cast<std::int64_t>((key >> 42) & mask);
}

namespace
{
// The first half of BuildCellGrid on a bitmap: the occupied cells and each
// point's linear cell number. A search for the cell size keeps the marks of
// its last count, and the grid is finished from them when that count is the
// answer.
struct CellMarks
{
  GridSpec Spec;
  OccupancyBitmap Bitmap;
  std::vector<std::uint64_t> Cell; // per point: linear cell number
  bool Valid = false;

  // False (and nothing marked) when the grid is too large for a bitmap.
  bool Mark(const double* xyz, const std::vector<Index>& ids, const GridSpec& spec,
    const Execution& execution)
  {
    this->Valid = false;
    const Index n = static_cast<Index>(ids.size());
    if (n == 0 || !this->Bitmap.Init(spec, n))
    {
      return false;
    }
    this->Spec = spec;
    this->Cell.resize(static_cast<std::size_t>(n));
    MarkCells(xyz, ids, spec, this->Bitmap, this->Cell.data(), execution);
    this->Valid = true;
    return true;
  }
  Index Occupied() const
  {
    Index count = 0;
    for (Index w = 0; w < this->Bitmap.Words; ++w)
    {
      count += PopCount(this->Bitmap.Word(w));
    }
    return count;
  }
};

// Counting sort of the points by dense cell number `cell[i]` (of ids[i]),
// stable: in each cell, points keep the order of `ids`, then ties by id.
// Fills grid.CellStart and grid.Order; grid.CellKey is set.
void SortIntoCells(const std::vector<Index>& ids, const std::vector<std::uint64_t>& cell,
  CellGrid& grid, const Execution& execution)
{
  const Index n = static_cast<Index>(ids.size());
  const Index cells = static_cast<Index>(grid.CellKey.size());
  GroupBy(
    n, cells, [&](Index i) { return static_cast<Index>(cell[i]); }, [&](Index i) { return ids[i]; },
    grid.CellStart, grid.Order, execution);

  // Ties by id: already so when `ids` ascends (FinitePointIds), else sort
  // each cell.
  std::atomic<bool> ascending{ true };
  execution.Run(1, n, [&](Index b, Index e) {
    for (Index i = b; i < e; ++i)
    {
      if (ids[i - 1] > ids[i])
      {
        ascending.store(false, std::memory_order_relaxed);
        return;
      }
    }
  });
  if (!ascending.load())
  {
    execution.Run(0, cells, [&](Index b, Index e) {
      for (Index c = b; c < e; ++c)
      {
        std::sort(grid.Order.begin() + grid.CellStart[c], grid.Order.begin() + grid.CellStart[c + 1]);
      }
    });
  }
}

// The grid from valid marks (which it consumes).
CellGrid FinishCellGrid(const std::vector<Index>& ids, CellMarks& marks, const Execution& execution)
{
  CellGrid grid;
  grid.Spec = marks.Spec;
  const OccupancyBitmap& bitmap = marks.Bitmap;
  std::vector<std::uint64_t>& cell = marks.Cell;
  // The cells in key order, and each point's dense cell number.
  std::vector<Index> rank(static_cast<std::size_t>(bitmap.Words) + 1, 0);
  for (Index w = 0; w < bitmap.Words; ++w)
  {
    rank[w + 1] = rank[w] + PopCount(bitmap.Word(w));
  }
  grid.CellKey.resize(static_cast<std::size_t>(rank[bitmap.Words]));
  execution.Run(0, bitmap.Words, [&](Index b, Index e) {
    for (Index w = b; w < e; ++w)
    {
      Index c = rank[w];
      for (std::uint64_t bits = bitmap.Word(w); bits; bits &= bits - 1)
      {
        grid.CellKey[c++] = bitmap.KeyOfLinear(64 * static_cast<std::uint64_t>(w) + TrailingZeros(bits));
      }
    }
  });
  execution.Run(0, static_cast<Index>(cell.size()), [&](Index b, Index e) {
    for (Index i = b; i < e; ++i)
    {
      const std::uint64_t lin = cell[i];
      const std::uint64_t below = (std::uint64_t(1) << (lin & 63)) - 1;
      cell[i] = static_cast<std::uint64_t>(rank[lin >> 6]) + PopCount(bitmap.Word(static_cast<Index>(lin >> 6)) & below);
    }
  });
  SortIntoCells(ids, cell, grid, execution);
  marks.Valid = false;
  return grid;
}
} // namespace

CellGrid BuildCellGrid(
  const double* xyz, const std::vector<Index>& ids, const GridSpec& spec, const Execution& execution)
{
  const Index n = static_cast<Index>(ids.size());
  if (n == 0)
  {
    CellGrid grid;
    grid.Spec = spec;
    grid.CellStart.assign(1, 0);
    return grid;
  }
  CellMarks marks;
  if (marks.Mark(xyz, ids, spec, execution))
  {
    return FinishCellGrid(ids, marks, execution);
  }
  // Grids too large for a bitmap: the occupied cells in a hash table.
  CellGrid grid;
  grid.Spec = spec;
  std::vector<std::uint64_t> cell(static_cast<std::size_t>(n));
  KeyTable table;
  InsertKeys(xyz, ids, spec, table);
  grid.CellKey = table.SortedKeys();
  for (std::size_t c = 0; c < grid.CellKey.size(); ++c)
  {
    table.ValueOf(grid.CellKey[c]) = static_cast<Index>(c);
  }
  execution.Run(0, n, [&](Index b, Index e) {
    const FastCellOf cellOf(spec);
    for (Index i = b; i < e; ++i)
    {
      std::uint64_t ijk[3];
      cellOf(xyz + 3 * ids[i], ijk);
      cell[i] = static_cast<std::uint64_t>(table.Find((ijk[2] << 42) | (ijk[1] << 21) | ijk[0]));
    }
  });
  SortIntoCells(ids, cell, grid, execution);
  return grid;
}

Index CountOccupiedCells(
  const double* xyz, const std::vector<Index>& ids, const GridSpec& spec, const Execution& execution)
{
  if (ids.empty())
  {
    return 0;
  }
  OccupancyBitmap bitmap;
  if (bitmap.Init(spec, static_cast<Index>(ids.size())))
  {
    MarkCells(xyz, ids, spec, bitmap, nullptr, execution);
    Index count = 0;
    for (Index w = 0; w < bitmap.Words; ++w)
    {
      count += PopCount(bitmap.Word(w));
    }
    return count;
  }
  KeyTable table;
  InsertKeys(xyz, ids, spec, table);
  return table.Size();
}

namespace
{
// Non-empty cells of `spec`, each counted by min(1, points / minPoints): a
// cell too sparse to get a sample of its own (a far outlier, a stray point)
// counts for its share only.
double EffectiveOccupiedCells(
  const double* xyz, const std::vector<Index>& ids, const GridSpec& spec, double minPoints)
{
  // Points per cell in a hash table, then the cells in increasing key order
  // (the order of the sum): no sort of one key per point.
  KeyTable table;
  std::uint64_t last = KeyTable::Empty;
  Index* run = nullptr;
  for (Index id : ids)
  {
    const std::uint64_t key = spec.KeyOf(xyz + 3 * id);
    if (key != last)
    {
      table.Insert(key);
      run = &table.ValueOf(key);
      last = key;
    }
    ++*run;
  }
  const std::vector<std::uint64_t> keys = table.SortedKeys();
  double count = 0.0;
  for (std::uint64_t key : keys)
  {
    count += std::min(1.0, static_cast<double>(table.Find(key)) / minPoints);
  }
  return count;
}

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

std::vector<double> CellSizeSubsample(const double* xyz, const std::vector<Index>& ids,
  double totalPoints, double targetCells, const Execution& execution)
{
  std::vector<double> subset;
  if (totalPoints < 200000.0 || !(targetCells > 1.0))
  {
    return subset;
  }
  const double stride = std::max(4.0, std::floor(totalPoints / targetCells / 32.0));
  // Picked when the hash's high 32 bits fall below 2^32 / stride.
  const auto below = static_cast<std::uint64_t>(4294967296.0 / stride);
  // Two passes over fixed blocks: flag and count, then copy (the order of
  // `ids`).
  const Index n = static_cast<Index>(ids.size());
  const Index blocks = BlockCount(n, 64, 1 << 15);
  std::vector<Index> start(static_cast<std::size_t>(blocks) + 1, 0);
  std::vector<unsigned char> picked(static_cast<std::size_t>(n));
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      Index count = 0;
      const Index end = BlockBegin(n, blocks, k + 1);
      for (Index i = BlockBegin(n, blocks, k); i < end; ++i)
      {
        const bool pick = (CoordinateHash(xyz + 3 * ids[i]) >> 32) < below;
        picked[i] = pick ? 1 : 0;
        count += pick ? 1 : 0;
      }
      start[k + 1] = count;
    }
  });
  for (Index k = 0; k < blocks; ++k)
  {
    start[k + 1] += start[k];
  }
  subset.resize(static_cast<std::size_t>(3 * start[blocks]));
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      double* out = subset.data() + 3 * start[k];
      const Index end = BlockBegin(n, blocks, k + 1);
      for (Index i = BlockBegin(n, blocks, k); i < end; ++i)
      {
        if (picked[i])
        {
          std::copy_n(xyz + 3 * ids[i], 3, out);
          out += 3;
        }
      }
    }
  });
  return subset;
}

namespace
{
// The search on the subsample, as a start for the full search (0: none).
double SubsampleStart(const double* xyz, const std::vector<Index>& ids, const Bounds& bounds,
  double targetCells, const Execution& execution)
{
  const std::vector<double> subset =
    CellSizeSubsample(xyz, ids, static_cast<double>(ids.size()), targetCells, execution);
  if (subset.empty())
  {
    return 0.0;
  }
  std::vector<Index> subsetIds(subset.size() / 3);
  std::iota(subsetIds.begin(), subsetIds.end(), Index(0));
  return SearchCellSize(bounds, targetCells, [&](const GridSpec& spec) {
    return static_cast<double>(CountOccupiedCells(subset.data(), subsetIds, spec, execution));
  });
}

// The points per cell below which a cell counts by its share in the
// outlier-robust occupancy: less than one sample's worth at 8 samples per
// target cell.
double SparseCellPoints(Index points, double targetCells)
{
  return std::max(1.0, static_cast<double>(points) / targetCells / 8.0);
}

// Far outliers and stray points each occupy a cell of their own: when such
// sparse cells make up a fifth of the count, they would drive the cell size
// of the whole cloud.
bool SparseCellsDominate(double effective, double raw)
{
  return !(effective >= 0.8 * raw);
}

// The outlier-robust search: each cell counted by min(1, points / minimum).
double SearchIgnoringSparseCells(const double* xyz, const std::vector<Index>& ids,
  const Bounds& bounds, double targetCells)
{
  const double minPoints = SparseCellPoints(static_cast<Index>(ids.size()), targetCells);
  return SearchCellSize(bounds, targetCells,
    [&](const GridSpec& spec) { return EffectiveOccupiedCells(xyz, ids, spec, minPoints); });
}
} // namespace

double AutomaticCellSize(const double* xyz, const std::vector<Index>& ids, const Bounds& bounds,
  double targetCells, const Execution& execution)
{
  const double maxExtent = bounds.MaxExtent();
  if (ids.empty() || !(maxExtent > 0.0))
  {
    return GridSpec::Make(bounds, 0.0).CellSize; // one cell holds everything
  }
  // One cell for the whole cloud: slightly larger than the largest extent.
  if (targetCells <= 1.0)
  {
    return maxExtent * (1.0 + 1e-9);
  }
  const double start = SubsampleStart(xyz, ids, bounds, targetCells, execution);
  double lastH = -1.0, lastCount = 0.0;
  const double h = SearchCellSize(bounds, targetCells, [&](const GridSpec& spec) {
    lastH = spec.CellSize;
    lastCount = static_cast<double>(CountOccupiedCells(xyz, ids, spec, execution));
    return lastCount;
  }, start);
  const GridSpec found = GridSpec::Make(bounds, h);
  const double raw = found.CellSize == lastH
    ? lastCount
    : static_cast<double>(CountOccupiedCells(xyz, ids, found, execution));
  const double minPoints = SparseCellPoints(static_cast<Index>(ids.size()), targetCells);
  if (!SparseCellsDominate(EffectiveOccupiedCells(xyz, ids, found, minPoints), raw))
  {
    return h;
  }
  return SearchIgnoringSparseCells(xyz, ids, bounds, targetCells);
}

CellGrid BuildAutomaticCellGrid(const double* xyz, const std::vector<Index>& ids,
  const Bounds& bounds, double targetCells, const Execution& execution)
{
  const double maxExtent = bounds.MaxExtent();
  if (ids.empty() || !(maxExtent > 0.0) || targetCells <= 1.0)
  {
    return BuildCellGrid(
      xyz, ids, GridSpec::Make(bounds, AutomaticCellSize(xyz, ids, bounds, targetCells)), execution);
  }
  // The full search's counts keep their marks: the last count is usually
  // the answer, and the grid is then finished from its marks.
  const double start = SubsampleStart(xyz, ids, bounds, targetCells, execution);
  CellMarks marks;
  const double h = SearchCellSize(bounds, targetCells, [&](const GridSpec& spec) {
    return static_cast<double>(marks.Mark(xyz, ids, spec, execution)
        ? marks.Occupied()
        : CountOccupiedCells(xyz, ids, spec, execution));
  }, start);
  const GridSpec found = GridSpec::Make(bounds, h);
  CellGrid grid = (marks.Valid && marks.Spec.CellSize == found.CellSize)
    ? FinishCellGrid(ids, marks, execution)
    : BuildCellGrid(xyz, ids, found, execution);
  // The outlier-robust count, from the grid's cells in key order (the sum
  // of EffectiveOccupiedCells, in the same order).
  const double minPoints = SparseCellPoints(static_cast<Index>(ids.size()), targetCells);
  double effective = 0.0;
  for (Index c = 0; c < grid.NumberOfCells(); ++c)
  {
    effective += std::min(1.0, static_cast<double>(grid.CellSizeOf(c)) / minPoints);
  }
  if (!SparseCellsDominate(effective, static_cast<double>(grid.NumberOfCells())))
  {
    return grid;
  }
  return BuildCellGrid(xyz, ids,
    GridSpec::Make(bounds, SearchIgnoringSparseCells(xyz, ids, bounds, targetCells)), execution);
}
} // namespace asmcore
