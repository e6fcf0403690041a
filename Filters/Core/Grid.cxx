// SPDX-License-Identifier: BSD-3-Clause
#include "Grid.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <cmath>
#include <limits>
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

namespace
{
// Portable and inline (without -mpopcnt, __builtin_popcountll is a call).
int PopCount(std::uint64_t x)
{
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

int TrailingZeros(std::uint64_t x) // x != 0
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_ctzll(x);
#else
  int c = 0;
  for (; !(x & 1); x >>= 1)
  {
    ++c;
  }
  return c;
#endif
}

// [begin, end) of block b of `blocks` over n items.
Index BlockBegin(Index n, Index blocks, Index b)
{
  return n / blocks * b + (n % blocks) * b / blocks;
}

// Fixed blocks for loops whose per-block results are combined afterwards.
Index BlockCount(Index n, Index maxBlocks, Index minBlockSize)
{
  return std::max<Index>(1, std::min<Index>(maxBlocks, n / minBlockSize));
}

// GridSpec::CellOf without divisions, same result: x * (1 / h) is within a
// few ulps of x / h, so their floors agree unless x / h is within 1e-8 of an
// integer (the grid spans at most 2^21 cells: the error is below 1e-9); then
// the division decides.
struct FastCellOf
{
  explicit FastCellOf(const GridSpec& spec)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Origin[a] = spec.Origin[a];
      this->Top[a] = static_cast<double>(spec.Dims[a] - 1);
    }
    this->Size = spec.CellSize;
    this->Inverse = 1.0 / spec.CellSize;
  }
  // Kept in the object (not read through a reference) so that the compiler
  // can hold them in registers across the stores of the loop.
  void operator()(const double p[3], std::uint64_t ijk[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      const double x = p[a] - this->Origin[a];
      // Clamping before the floor gives the same cell as after it; then the
      // truncation is the floor (no branchy std::floor).
      const double r = std::min(std::max(x * this->Inverse, 0.0), this->Top[a]);
      std::uint64_t k = static_cast<std::uint64_t>(r);
      const double frac = r - static_cast<double>(k);
      if (!(frac > 1e-8 && frac < 1.0 - 1e-8))
      {
        // Near a cell border (or clamped): exactly as GridSpec::CellOf.
        double t = std::floor(x / this->Size);
        t = std::min(std::max(t, 0.0), this->Top[a]);
        k = static_cast<std::uint64_t>(t);
      }
      ijk[a] = k;
    }
  }
  double Origin[3];
  double Top[3];
  double Size;
  double Inverse;
};

// One bit per cell of the grid (cells numbered x + D0 (y + D1 z), which is
// the order of the packed keys), set concurrently without locks.
class OccupancyBitmap
{
public:
  // False when the grid has too many cells for a bitmap of reasonable size.
  bool Init(const GridSpec& spec, Index points)
  {
    const double cells = static_cast<double>(spec.Dims[0]) * static_cast<double>(spec.Dims[1]) *
      static_cast<double>(spec.Dims[2]);
    const double limit = std::max(double(std::uint64_t(1) << 26), 16.0 * static_cast<double>(points));
    if (!(cells <= limit))
    {
      return false;
    }
    this->D0 = static_cast<std::uint64_t>(spec.Dims[0]);
    this->D01 = this->D0 * static_cast<std::uint64_t>(spec.Dims[1]);
    const std::uint64_t total = this->D01 * static_cast<std::uint64_t>(spec.Dims[2]);
    this->Words = static_cast<Index>((total + 63) / 64);
    this->Bits.reset(new std::atomic<std::uint64_t>[static_cast<std::size_t>(this->Words)]);
    for (Index w = 0; w < this->Words; ++w)
    {
      this->Bits[w].store(0, std::memory_order_relaxed);
    }
    return true;
  }
  struct Numbering
  {
    std::uint64_t D0, D01;
  };
  Numbering GetNumbering() const { return { this->D0, this->D01 }; }
  std::uint64_t Linear(const std::uint64_t ijk[3]) const
  {
    return ijk[0] + this->D0 * ijk[1] + this->D01 * ijk[2];
  }
  void Set(std::uint64_t lin)
  {
    const std::uint64_t bit = std::uint64_t(1) << (lin & 63);
    std::atomic<std::uint64_t>& word = this->Bits[static_cast<std::size_t>(lin >> 6)];
    if (!(word.load(std::memory_order_relaxed) & bit))
    {
      word.fetch_or(bit, std::memory_order_relaxed);
    }
  }
  std::uint64_t Word(Index w) const { return this->Bits[w].load(std::memory_order_relaxed); }
  std::uint64_t KeyOfLinear(std::uint64_t lin) const
  {
    const std::uint64_t z = lin / this->D01;
    const std::uint64_t rest = lin - z * this->D01;
    const std::uint64_t y = rest / this->D0;
    return (z << 42) | (y << 21) | (rest - y * this->D0);
  }
  Index Words = 0;

private:
  std::uint64_t D0 = 1, D01 = 1;
  std::unique_ptr<std::atomic<std::uint64_t>[]> Bits;
};

// Open-addressing map from cell key to a value; keys < 2^63, so all ones
// marks an empty slot.
class KeyTable
{
public:
  static constexpr std::uint64_t Empty = ~std::uint64_t(0);
  KeyTable() { this->Resize(10); }
  // Inserts key (value 0); true if it was new.
  bool Insert(std::uint64_t key)
  {
    if (2 * (this->Count + 1) > static_cast<Index>(this->Keys.size()))
    {
      this->Grow();
    }
    std::size_t slot = this->Slot(key);
    while (this->Keys[slot] != Empty)
    {
      if (this->Keys[slot] == key)
      {
        return false;
      }
      slot = (slot + 1) & this->Mask;
    }
    this->Keys[slot] = key;
    ++this->Count;
    return true;
  }
  Index& ValueOf(std::uint64_t key) // key must be present
  {
    std::size_t slot = this->Slot(key);
    while (this->Keys[slot] != key)
    {
      slot = (slot + 1) & this->Mask;
    }
    return this->Values[slot];
  }
  Index Find(std::uint64_t key) const // key must be present
  {
    std::size_t slot = this->Slot(key);
    while (this->Keys[slot] != key)
    {
      slot = (slot + 1) & this->Mask;
    }
    return this->Values[slot];
  }
  Index Size() const { return this->Count; }
  std::vector<std::uint64_t> SortedKeys() const
  {
    std::vector<std::uint64_t> keys;
    keys.reserve(static_cast<std::size_t>(this->Count));
    for (std::uint64_t k : this->Keys)
    {
      if (k != Empty)
      {
        keys.push_back(k);
      }
    }
    std::sort(keys.begin(), keys.end());
    return keys;
  }

private:
  std::size_t Slot(std::uint64_t key) const
  {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> this->Shift);
  }
  void Resize(int bits)
  {
    this->Keys.assign(std::size_t(1) << bits, Empty);
    this->Values.assign(std::size_t(1) << bits, 0);
    this->Mask = (std::size_t(1) << bits) - 1;
    this->Shift = 64 - bits;
    this->Bits = bits;
    this->Count = 0;
  }
  void Grow()
  {
    std::vector<std::uint64_t> old;
    old.swap(this->Keys);
    this->Resize(this->Bits + 1);
    for (std::uint64_t k : old)
    {
      if (k != Empty)
      {
        this->Insert(k);
      }
    }
  }
  std::vector<std::uint64_t> Keys;
  std::vector<Index> Values;
  std::size_t Mask = 0;
  int Shift = 64;
  int Bits = 0;
  Index Count = 0;
};

// Distinct keys of the points, in a table (sequential: the fallback for
// grids too large for a bitmap).
void InsertKeys(const double* xyz, const std::vector<Index>& ids, const GridSpec& spec, KeyTable& table)
{
  const FastCellOf cellOf(spec);
  std::uint64_t last = KeyTable::Empty;
  for (Index id : ids)
  {
    std::uint64_t ijk[3];
    cellOf(xyz + 3 * id, ijk);
    const std::uint64_t key = (ijk[2] << 42) | (ijk[1] << 21) | ijk[0];
    if (key != last)
    {
      table.Insert(key);
      last = key;
    }
  }
}

// Marks the cells of the points in the bitmap; also stores each point's
// linear cell number in `linear` when not null.
void MarkCells(const double* xyz, const std::vector<Index>& ids, const GridSpec& spec,
  OccupancyBitmap& bitmap, std::uint64_t* linear, const Execution& execution)
{
  execution.Run(0, static_cast<Index>(ids.size()), [&](Index b, Index e) {
    const FastCellOf cellOf(spec); // a local copy: registers, no aliasing with the stores
    const OccupancyBitmap::Numbering numbering = bitmap.GetNumbering();
    const Index* id = ids.data();
    std::uint64_t last = ~std::uint64_t(0);
    for (Index i = b; i < e; ++i)
    {
      std::uint64_t ijk[3];
      cellOf(xyz + 3 * id[i], ijk);
      const std::uint64_t lin = ijk[0] + numbering.D0 * ijk[1] + numbering.D01 * ijk[2];
      if (linear)
      {
        linear[i] = lin;
      }
      if (lin != last)
      {
        bitmap.Set(lin);
        last = lin;
      }
    }
  });
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

CellGrid BuildCellGrid(
  const double* xyz, const std::vector<Index>& ids, const GridSpec& spec, const Execution& execution)
{
  CellGrid grid;
  grid.Spec = spec;
  const Index n = static_cast<Index>(ids.size());
  grid.CellStart.assign(1, 0);
  if (n == 0)
  {
    return grid;
  }
  // 1. The cell of every point, as a dense cell number in key order.
  std::vector<std::uint64_t> cell(static_cast<std::size_t>(n));
  OccupancyBitmap bitmap;
  if (bitmap.Init(spec, n))
  {
    MarkCells(xyz, ids, spec, bitmap, cell.data(), execution);
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
    execution.Run(0, n, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i)
      {
        const std::uint64_t lin = cell[i];
        const std::uint64_t below = (std::uint64_t(1) << (lin & 63)) - 1;
        cell[i] = static_cast<std::uint64_t>(rank[lin >> 6]) + PopCount(bitmap.Word(static_cast<Index>(lin >> 6)) & below);
      }
    });
  }
  else
  {
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
  }
  const Index cells = static_cast<Index>(grid.CellKey.size());

  // 2. Counting sort by cell, stable: in each cell, points keep the order of
  // `ids`. Blocks count their points per cell, then scatter them.
  Index blocks = BlockCount(n, 8, 1 << 16);
  while (blocks > 1 && blocks * cells > n / 2)
  {
    --blocks; // bounded scratch: the per-block counts stay below 4 bytes a point
  }
  std::vector<Index> offset(static_cast<std::size_t>(blocks * cells), 0);
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      Index* count = offset.data() + k * cells;
      const Index end = BlockBegin(n, blocks, k + 1);
      for (Index i = BlockBegin(n, blocks, k); i < end; ++i)
      {
        ++count[cell[i]];
      }
    }
  });
  grid.CellStart.resize(static_cast<std::size_t>(cells) + 1);
  Index running = 0;
  for (Index c = 0; c < cells; ++c)
  {
    grid.CellStart[c] = running;
    for (Index k = 0; k < blocks; ++k)
    {
      const Index count = offset[k * cells + c];
      offset[k * cells + c] = running;
      running += count;
    }
  }
  grid.CellStart[cells] = running;
  grid.Order.resize(static_cast<std::size_t>(n));
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index k = first; k < last; ++k)
    {
      Index* next = offset.data() + k * cells;
      const Index end = BlockBegin(n, blocks, k + 1);
      for (Index i = BlockBegin(n, blocks, k); i < end; ++i)
      {
        grid.Order[next[cell[i]]++] = ids[i];
      }
    }
  });

  // 3. Ties by id: already so when `ids` ascends (FinitePointIds), else sort
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

double AutomaticCellSize(const double* xyz, const std::vector<Index>& ids, const Bounds& bounds,
  double targetCells, const Execution& execution)
{
  return AutomaticCellSize(bounds, targetCells, ids.empty(), [&](const GridSpec& spec) {
    return static_cast<double>(CountOccupiedCells(xyz, ids, spec, execution));
  });
}

double AutomaticCellSize(const Bounds& bounds, double targetCells, bool empty,
  const std::function<double(const GridSpec&)>& countOccupied)
{
  const double maxExtent = bounds.MaxExtent();
  if (empty || !(maxExtent > 0.0))
  {
    return GridSpec::Make(bounds, 0.0).CellSize; // one cell holds everything
  }
  // One cell for the whole cloud: slightly larger than the largest extent.
  const double oneCell = maxExtent * (1.0 + 1e-9);
  if (targetCells <= 1.0)
  {
    return oneCell;
  }
  // Start from the guess that the points sample a surface (count ~ h^-2),
  // then correct with the measured count and the measured local exponent.
  double h = maxExtent / std::sqrt(targetCells);
  double bestH = oneCell;
  double bestErr = std::abs(std::log(1.0 / targetCells));
  double prevH = 0.0, prevCount = 0.0;
  double dimension = 2.0;
  for (int iteration = 0; iteration < 12; ++iteration)
  {
    h = GridSpec::Make(bounds, h).CellSize;
    const double count = countOccupied(GridSpec::Make(bounds, h));
    const double err = std::abs(std::log(count / targetCells));
    if (err < bestErr)
    {
      bestErr = err;
      bestH = h;
    }
    if (err < 0.05) // within 5 %
    {
      break;
    }
    if (prevCount > 0.0 && count != prevCount && h != prevH)
    {
      const double measured = -std::log(count / prevCount) / std::log(h / prevH);
      dimension = std::min(3.0, std::max(0.5, measured));
    }
    prevH = h;
    prevCount = count;
    h *= std::pow(count / targetCells, 1.0 / dimension);
    h = std::min(h, oneCell);
  }
  return bestH;
}
} // namespace asmcore
