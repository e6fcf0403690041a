// SPDX-License-Identifier: BSD-3-Clause
#include "Grid.h"

#include "GridOccupancy.h"
#include "GroupBy.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>

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

double Bounds::LargestMagnitude() const
{
  double largest = 0.0;
  for (int a = 0; this->Valid && a < 3; ++a)
  {
    largest = std::max({ largest, std::abs(this->Min[a]), std::abs(this->Max[a]) });
  }
  return largest;
}

using namespace occupancy;

Bounds ComputeBounds(Coordinates xyz, IdView ids, const Execution& execution)
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
      ForEachPoint(xyz, ids, BlockBegin(n, blocks, k), BlockBegin(n, blocks, k + 1),
        [&pb](Index, const double p[3]) {
          for (int a = 0; a < 3; ++a)
          {
            pb.Min[a] = std::min(pb.Min[a], p[a]);
            pb.Max[a] = std::max(pb.Max[a], p[a]);
          }
        });
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

void ComputeCentroid(Coordinates xyz, IdView ids, double centroid[3], const Execution& execution)
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
      ForEachPoint(xyz, ids, BlockBegin(n, blocks, k), BlockBegin(n, blocks, k + 1),
        [&sum](Index, const double p[3]) {
          sum[0] += p[0];
          sum[1] += p[1];
          sum[2] += p[2];
        });
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
  // rounding), and a positive edge for a cloud of coincident points; never
  // below the smallest normal double, whose inverse is finite (an extent of
  // 1e-303 would give a subnormal edge, and 0 * (1 / edge) a NaN cell).
  double minSize = maxExtent / static_cast<double>(MaxDim - 2);
  if (!(minSize > 0.0))
  {
    minSize = std::max(std::abs(bounds.Min[0]), 1.0) * 1e-12;
  }
  minSize = std::max(minSize, std::numeric_limits<double>::min());
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

namespace occupancy
{
// Counting sort of the points by dense cell number `cell[i]` (of ids[i]),
// stable: in each cell, points keep the order of `ids`, then ties by id.
// Fills grid.CellStart and grid.Order; grid.CellKey is set.
template <typename CellNumber>
void SortIntoCells(IdView ids, const CellNumber* cell, CellGrid& grid, const Execution& execution)
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
        std::sort(
          grid.Order.begin() + grid.CellStart[c], grid.Order.begin() + grid.CellStart[c + 1]);
      }
    });
  }
}

// The grid from valid marks (which it consumes).
CellGrid FinishCellGrid(IdView ids, CellMarks& marks, const Execution& execution)
{
  CellGrid grid;
  grid.Spec = marks.Spec;
  const OccupancyBitmap& bitmap = marks.Bitmap;
  std::uint32_t* cell = marks.Cell.get();
  const Index n = static_cast<Index>(ids.size());
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
        grid.CellKey[c++] =
          bitmap.KeyOfLinear(64 * static_cast<std::uint64_t>(w) + TrailingZeros(bits));
      }
    }
  });
  execution.Run(0, n, [&](Index b, Index e) {
    for (Index i = b; i < e; ++i)
    {
      const std::uint64_t lin = cell[i];
      const std::uint64_t below = (std::uint64_t(1) << (lin & 63)) - 1;
      cell[i] = static_cast<std::uint32_t>(
        rank[lin >> 6] + PopCount(bitmap.Word(static_cast<Index>(lin >> 6)) & below));
    }
  });
  SortIntoCells(ids, cell, grid, execution);
  marks.Cell.reset();
  marks.Valid = false;
  return grid;
}
} // namespace occupancy

CellGrid BuildCellGrid(
  Coordinates xyz, IdView ids, const GridSpec& spec, const Execution& execution)
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
  KeyTable table;
  InsertKeys(xyz, ids, spec, table);
  grid.CellKey = table.SortedKeys();
  for (std::size_t c = 0; c < grid.CellKey.size(); ++c)
  {
    table.ValueOf(grid.CellKey[c]) = static_cast<Index>(c);
  }
  // Dense cell numbers: 32 bits unless there are 2^32 cells or more.
  auto sort = [&](auto number) {
    using CellNumber = decltype(number);
    std::vector<CellNumber> cell(static_cast<std::size_t>(n));
    execution.Run(0, n, [&](Index b, Index e) {
      const FastCellOf cellOf(spec);
      ForEachPoint(xyz, ids, b, e, [&](Index i, const double p[3]) {
        std::uint64_t ijk[3];
        cellOf(p, ijk);
        cell[i] = static_cast<CellNumber>(table.Find(GridSpec::PackKey(ijk)));
      });
    });
    SortIntoCells(ids, cell.data(), grid, execution);
  };
  if (grid.CellKey.size() <= std::numeric_limits<std::uint32_t>::max())
  {
    sort(std::uint32_t(0));
  }
  else
  {
    sort(std::uint64_t(0));
  }
  return grid;
}

SlotIds::SlotIds(PointArray<Index>& order, const Execution& execution)
{
  const auto n = static_cast<Index>(order.size());
  this->Narrow.resize(order.size());
  std::atomic<bool> fits{ true };
  execution.Run(0, n, [&](Index b, Index e) {
    for (Index i = b; i < e; ++i)
    {
      const Index id = order[i];
      if (id < 0 || id > static_cast<Index>(std::numeric_limits<std::uint32_t>::max()))
      {
        fits.store(false, std::memory_order_relaxed);
        return;
      }
      this->Narrow[i] = static_cast<std::uint32_t>(id);
    }
  });
  if (fits.load())
  {
    PointArray<Index>().swap(order);
  }
  else
  {
    PointArray<std::uint32_t>().swap(this->Narrow);
    this->Wide.swap(order);
  }
}

namespace
{
// The number of distinct cells of the points, for grids too large for a
// bitmap: the points' keys are computed in parallel, then each of a fixed
// number of partitions (by a hash of the key, not the table's) counts its
// keys in a table of its own, a sixteenth of the size.
Index CountDistinctCells(
  Coordinates xyz, IdView ids, const GridSpec& spec, const Execution& execution)
{
  const Index n = static_cast<Index>(ids.size());
  std::unique_ptr<std::uint64_t[]> key(new std::uint64_t[static_cast<std::size_t>(n)]);
  execution.Run(0, n, [&](Index b, Index e) {
    const FastCellOf cellOf(spec);
    ForEachPoint(xyz, ids, b, e, [&](Index i, const double p[3]) {
      std::uint64_t ijk[3];
      cellOf(p, ijk);
      key[i] = GridSpec::PackKey(ijk);
    });
  });
  constexpr Index Partitions = 16;
  auto partitionOf = [](std::uint64_t k) {
    k ^= k >> 33;
    k *= 0xFF51AFD7ED558CCDULL;
    k ^= k >> 33;
    return static_cast<Index>(k & (Partitions - 1));
  };
  std::vector<Index> count(static_cast<std::size_t>(Partitions), 0);
  execution.Run(0, Partitions, [&](Index first, Index last) {
    for (Index part = first; part < last; ++part)
    {
      KeyTable table;
      std::uint64_t previous = KeyTable::Empty;
      for (Index i = 0; i < n; ++i)
      {
        const std::uint64_t k = key[i];
        if (k != previous && partitionOf(k) == part)
        {
          table.Insert(k);
        }
        previous = k;
      }
      count[part] = table.Size();
    }
  });
  Index total = 0;
  for (Index c : count)
  {
    total += c;
  }
  return total;
}
} // namespace

Index CountOccupiedCells(
  Coordinates xyz, IdView ids, const GridSpec& spec, const Execution& execution)
{
  if (ids.empty())
  {
    return 0;
  }
  OccupancyBitmap bitmap;
  if (bitmap.Init(spec, static_cast<Index>(ids.size()), execution))
  {
    MarkCells(xyz, ids, spec, bitmap, nullptr, execution);
    return bitmap.Count(execution);
  }
  return CountDistinctCells(xyz, ids, spec, execution);
}

std::vector<std::uint64_t> OccupiedCellKeys(
  Coordinates xyz, IdView ids, const GridSpec& spec, const Execution& execution)
{
  if (ids.empty())
  {
    return {};
  }
  OccupancyBitmap bitmap;
  if (!bitmap.Init(spec, static_cast<Index>(ids.size()), execution))
  {
    KeyTable table;
    InsertKeys(xyz, ids, spec, table);
    return table.SortedKeys();
  }
  MarkCells(xyz, ids, spec, bitmap, nullptr, execution);
  // (The bits are numbered in key order.)
  std::vector<std::uint64_t> keys;
  keys.reserve(static_cast<std::size_t>(bitmap.Count(execution)));
  for (Index w = 0; w < bitmap.Words; ++w)
  {
    for (std::uint64_t bits = bitmap.Word(w); bits != 0; bits &= bits - 1)
    {
      keys.push_back(bitmap.KeyOfLinear(64 * static_cast<std::uint64_t>(w) + TrailingZeros(bits)));
    }
  }
  return keys;
}
} // namespace asmcore
