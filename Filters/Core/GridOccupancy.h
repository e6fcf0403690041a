// SPDX-License-Identifier: BSD-3-Clause
/**
 * Internals of Grid.cxx and CellSize.cxx (not installed, not for other
 * files): the occupied cells of a grid as a lock-free bitmap or a hash
 * table, the division-free cell coordinates, fixed work blocks, and the
 * marks a grid is finished from. Results never depend on how the
 * loops are cut, so the grid is the same whatever the thread count.
 */
#ifndef asm_core_GridOccupancy_h
#define asm_core_GridOccupancy_h

#include "Grid.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace asmcore
{
namespace occupancy
{
// Portable and inline (without -mpopcnt, __builtin_popcountll is a call).
inline int PopCount(std::uint64_t x)
{
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

inline int TrailingZeros(std::uint64_t x) // x != 0
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
inline Index BlockBegin(Index n, Index blocks, Index b)
{
  return n / blocks * b + (n % blocks) * b / blocks;
}

// Fixed blocks for loops whose per-block results are combined afterwards.
inline Index BlockCount(Index n, Index maxBlocks, Index minBlockSize)
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
  // Per axis: clamping before the floor gives the same cell as after it;
  // then the truncation is the floor (no branchy std::floor), and
  // 0 <= r < 2^21, so the conversions are one instruction each.
  void operator()(const double p[3], std::uint64_t ijk[3]) const
  {
#if defined(__SSE2__)
    // (x, y) and (z, z) at once.
    const __m128d r01 =
      _mm_min_pd(_mm_max_pd(_mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(p), _mm_loadu_pd(this->Origin)),
                              _mm_set1_pd(this->Inverse)),
                   _mm_setzero_pd()),
        _mm_loadu_pd(this->Top));
    const __m128d r22 =
      _mm_min_pd(_mm_max_pd(_mm_mul_pd(_mm_sub_pd(_mm_set1_pd(p[2]), _mm_set1_pd(this->Origin[2])),
                              _mm_set1_pd(this->Inverse)),
                   _mm_setzero_pd()),
        _mm_set1_pd(this->Top[2]));
    const __m128i k01 = _mm_cvttpd_epi32(r01);
    const __m128i k22 = _mm_cvttpd_epi32(r22);
    const __m128d f01 = _mm_sub_pd(r01, _mm_cvtepi32_pd(k01));
    const __m128d f22 = _mm_sub_pd(r22, _mm_cvtepi32_pd(k22));
    const __m128d low = _mm_set1_pd(1e-8), high = _mm_set1_pd(1.0 - 1e-8);
    const int in01 = _mm_movemask_pd(_mm_and_pd(_mm_cmpgt_pd(f01, low), _mm_cmplt_pd(f01, high)));
    const int in22 = _mm_movemask_pd(_mm_and_pd(_mm_cmpgt_pd(f22, low), _mm_cmplt_pd(f22, high)));
    const bool inside = in01 == 3 && in22 == 3; // every axis away from a cell border
    ijk[0] = static_cast<std::uint32_t>(_mm_cvtsi128_si32(k01));
    ijk[1] = static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_shuffle_epi32(k01, 1)));
    ijk[2] = static_cast<std::uint32_t>(_mm_cvtsi128_si32(k22));
#else
    bool inside = true; // every axis away from a cell border
    for (int a = 0; a < 3; ++a)
    {
      const double r =
        std::min(std::max((p[a] - this->Origin[a]) * this->Inverse, 0.0), this->Top[a]);
      const auto k = static_cast<std::int64_t>(r);
      const double frac = r - static_cast<double>(k);
      inside &= (frac > 1e-8) & (frac < 1.0 - 1e-8);
      ijk[a] = static_cast<std::uint64_t>(k);
    }
#endif
    if (!inside)
    {
      // Near a cell border (or clamped): exactly as GridSpec::CellOf (the
      // same cells on the other axes).
      for (int a = 0; a < 3; ++a)
      {
        double t = std::floor((p[a] - this->Origin[a]) / this->Size);
        t = std::min(std::max(t, 0.0), this->Top[a]);
        ijk[a] = static_cast<std::uint64_t>(t);
      }
    }
  }
  // Kept in the object (not read through a reference) so that the compiler
  // can hold them in registers across the stores of the loop.
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
  bool Init(const GridSpec& spec, Index points, const Execution& execution)
  {
    const double cells = static_cast<double>(spec.Dims[0]) * static_cast<double>(spec.Dims[1]) *
      static_cast<double>(spec.Dims[2]);
    const double limit =
      std::max(double(std::uint64_t(1) << 26), 16.0 * static_cast<double>(points));
    if (!(cells <= limit))
    {
      return false;
    }
    this->D0 = static_cast<std::uint64_t>(spec.Dims[0]);
    this->D01 = this->D0 * static_cast<std::uint64_t>(spec.Dims[1]);
    const std::uint64_t total = this->D01 * static_cast<std::uint64_t>(spec.Dims[2]);
    this->Words = static_cast<Index>((total + 63) / 64);
    this->Bits.reset(new std::atomic<std::uint64_t>[static_cast<std::size_t>(this->Words)]);
    execution.Run(0, this->Words, [this](Index b, Index e) {
      for (Index w = b; w < e; ++w)
      {
        this->Bits[w].store(0, std::memory_order_relaxed);
      }
    });
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
  // The number of bits set (sums of fixed blocks: any cut gives it).
  Index Count(const Execution& execution) const
  {
    const Index blocks = BlockCount(this->Words, 64, 1 << 14);
    std::vector<Index> sum(static_cast<std::size_t>(blocks), 0);
    execution.Run(0, blocks, [&](Index first, Index last) {
      for (Index k = first; k < last; ++k)
      {
        Index count = 0;
        const Index end = BlockBegin(this->Words, blocks, k + 1);
        for (Index w = BlockBegin(this->Words, blocks, k); w < end; ++w)
        {
          count += PopCount(this->Word(w));
        }
        sum[k] = count;
      }
    });
    Index total = 0;
    for (Index count : sum)
    {
      total += count;
    }
    return total;
  }
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
    std::vector<Index> oldValues;
    old.swap(this->Keys);
    oldValues.swap(this->Values);
    this->Resize(this->Bits + 1);
    for (std::size_t i = 0; i < old.size(); ++i)
    {
      if (old[i] != Empty)
      {
        this->Insert(old[i]);
        this->ValueOf(old[i]) = oldValues[i]; // values survive growth
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
inline void InsertKeys(Coordinates xyz, IdView ids, const GridSpec& spec, KeyTable& table)
{
  const FastCellOf cellOf(spec);
  std::uint64_t last = KeyTable::Empty;
  for (Index id : ids)
  {
    std::uint64_t ijk[3];
    double p[3];
    xyz.Get(id, p);
    cellOf(p, ijk);
    const std::uint64_t key = GridSpec::PackKey(ijk);
    if (key != last)
    {
      table.Insert(key);
      last = key;
    }
  }
}

// Marks the cells of the points in the bitmap; also stores each point's
// linear cell number in `linear` when not null (the bitmap then has fewer
// than 2^32 bits).
inline void MarkCells(Coordinates xyz, IdView ids, const GridSpec& spec, OccupancyBitmap& bitmap,
  std::uint32_t* linear, const Execution& execution)
{
  execution.Run(0, static_cast<Index>(ids.size()), [&](Index b, Index e) {
    const FastCellOf cellOf(spec); // a local copy: registers, no aliasing with the stores
    const OccupancyBitmap::Numbering numbering = bitmap.GetNumbering();
    std::uint64_t last = ~std::uint64_t(0);
    ForEachPoint(xyz, ids, b, e, [&](Index i, const double p[3]) {
      std::uint64_t ijk[3];
      cellOf(p, ijk);
      const std::uint64_t lin = ijk[0] + numbering.D0 * ijk[1] + numbering.D01 * ijk[2];
      if (linear)
      {
        linear[i] = static_cast<std::uint32_t>(lin);
      }
      if (lin != last)
      {
        bitmap.Set(lin);
        last = lin;
      }
    });
  });
}

// The first half of BuildCellGrid on a bitmap: the occupied cells and each
// point's linear cell number. A search for the cell size keeps the marks of
// its last count, and the grid is finished from them when that count is the
// answer.
struct CellMarks
{
  GridSpec Spec;
  OccupancyBitmap Bitmap;
  // Per point: linear cell number (half the memory of 64 bits), left
  // uninitialised until MarkCells writes it (no serial zero fill).
  std::unique_ptr<std::uint32_t[]> Cell;
  bool Valid = false;

  // False (and nothing marked) when the grid is too large for a bitmap.
  bool Mark(Coordinates xyz, IdView ids, const GridSpec& spec, const Execution& execution)
  {
    this->Valid = false;
    const Index n = static_cast<Index>(ids.size());
    const double cells = static_cast<double>(spec.Dims[0]) * static_cast<double>(spec.Dims[1]) *
      static_cast<double>(spec.Dims[2]);
    if (n == 0 || !(cells <= 4294967296.0) || !this->Bitmap.Init(spec, n, execution))
    {
      return false; // (32-bit linear cell numbers)
    }
    this->Spec = spec;
    this->Cell.reset(new std::uint32_t[static_cast<std::size_t>(n)]);
    MarkCells(xyz, ids, spec, this->Bitmap, this->Cell.get(), execution);
    this->Valid = true;
    return true;
  }
  Index Occupied(const Execution& execution) const { return this->Bitmap.Count(execution); }
};

// The grid from valid marks (which it consumes): the second half of
// BuildCellGrid (Grid.cxx).
CellGrid FinishCellGrid(IdView ids, CellMarks& marks, const Execution& execution);
} // namespace occupancy
} // namespace asmcore

#endif
