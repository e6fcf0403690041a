// SPDX-License-Identifier: BSD-3-Clause
/**
 * Grid hashing (paper §3.5 step 1): a uniform grid of cubic cells and the
 * points sorted by cell (the automatic choice of the cell size: CellSize.h).
 *
 * Speed: no comparison sort. Occupied cells are marked in a bitmap over the
 * grid (parallel, lock-free) when the grid is small enough (at most
 * max(2^26, 16 N) cells), else in a hash set; points are then placed by a
 * counting sort (parallel blocks). The results are unique (cells ascending by
 * key, points by id within a cell), so they do not depend on the thread
 * count or on how the loops are cut.
 */
#ifndef asm_core_Grid_h
#define asm_core_Grid_h

#include "Common.h"

#include <algorithm>
#include <cmath>

namespace asmcore
{
/// Axis-aligned bounds of a set of points.
struct VTKASMFILTERS_EXPORT Bounds
{
  double Min[3] = { 0, 0, 0 };
  double Max[3] = { 0, 0, 0 };
  bool Valid = false; ///< false for an empty set

  double Extent(int axis) const { return this->Max[axis] - this->Min[axis]; }
  double Diagonal() const;
  double MaxExtent() const;
  /// The largest |coordinate| (0 for an empty set).
  double LargestMagnitude() const;
};

/// The coordinates the computations hold for. Squared distances and
/// covariances square the cloud's extent, and their sums add up to a point
/// count of them: with every |coordinate| at most MaxMagnitude (1e100) they
/// stay below 1e212 for 1e12 points. Squared point spacings must not
/// underflow: with the largest |coordinate| at least MinMagnitude (1e-100),
/// they stay far above the smallest double (2.2e-308). A sphere of radius
/// 2^k gives the same output, scaled by 2^k, for |k| <= 500 (1e150), and
/// a wrong one (fewer or no key points, NaN or zero curvatures) from
/// |k| = 520 on. Clouds whose points all lie at the origin are in range.
struct VTKASMFILTERS_EXPORT CoordinateRange
{
  static constexpr double MinMagnitude = 1e-100;
  static constexpr double MaxMagnitude = 1e100;
  /// Whether a cloud whose largest |coordinate| is `largest` is in range.
  static bool Holds(double largest)
  {
    return largest == 0.0 || (largest >= MinMagnitude && largest <= MaxMagnitude);
  }
};

/// Bounds of the points xyz[3*id] for id in ids.
VTKASMFILTERS_EXPORT Bounds ComputeBounds(
  Coordinates xyz, IdView ids, const Execution& execution = {});

/// Centroid of the points xyz[3*id] for id in ids (0 for none), summed in
/// fixed blocks: the same value whatever the thread count.
VTKASMFILTERS_EXPORT void ComputeCentroid(
  Coordinates xyz, IdView ids, double centroid[3], const Execution& execution = {});

/// A uniform grid: origin, cubic cell edge, and the number of cells per axis.
struct VTKASMFILTERS_EXPORT GridSpec
{
  double Origin[3] = { 0, 0, 0 };
  double CellSize = 1.0;
  std::int64_t Dims[3] = { 1, 1, 1 };

  /// Largest number of cells per axis: keys pack three 21-bit indices.
  static constexpr std::int64_t MaxDim = std::int64_t(1) << 21;

  /// A grid covering `bounds` with cells of edge `cellSize`. A cell size too
  /// small for MaxDim cells per axis (or not positive) is enlarged.
  static GridSpec Make(const Bounds& bounds, double cellSize);

  /// Packed key (z << 42 | y << 21 | x) of the cell holding p; points
  /// outside the grid are clamped to its border cells.
  std::uint64_t KeyOf(const double p[3]) const
  {
    std::uint64_t ijk[3];
    this->CellOf(p, ijk);
    return PackKey(ijk);
  }
  /// The packed key of integer cell coordinates (each below MaxDim).
  static std::uint64_t PackKey(const std::uint64_t ijk[3])
  {
    return (ijk[2] << 42) | (ijk[1] << 21) | ijk[0];
  }
  /// Integer cell coordinates of the cell holding p (clamped to the grid).
  void CellOf(const double p[3], std::uint64_t ijk[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      double t = std::floor((p[a] - this->Origin[a]) / this->CellSize);
      t = std::min(std::max(t, 0.0), static_cast<double>(this->Dims[a] - 1));
      ijk[a] = static_cast<std::uint64_t>(t);
    }
  }
  /// The integer cell coordinates of a key.
  void Unpack(std::uint64_t key, std::int64_t ijk[3]) const;
};

/// A 64-bit value (a cell key: up to 2^63) as two doubles, its exact 32-bit
/// halves, for collectives that move doubles (distributed runs).
template <typename DoubleVector>
inline void AppendAsDoubles(DoubleVector& out, std::uint64_t value)
{
  out.push_back(static_cast<double>(value >> 32));
  out.push_back(static_cast<double>(value & 0xFFFFFFFFULL));
}
/// The value AppendAsDoubles wrote at `in`.
inline std::uint64_t FromDoubles(const double* in)
{
  return (static_cast<std::uint64_t>(in[0]) << 32) | static_cast<std::uint64_t>(in[1]);
}

/// The points of a cloud grouped by grid cell.
struct VTKASMFILTERS_EXPORT CellGrid
{
  GridSpec Spec;
  PointArray<Index> Order;            ///< point ids sorted by (cell key, id)
  std::vector<Index> CellStart;       ///< cell c holds Order[CellStart[c], CellStart[c+1])
  std::vector<std::uint64_t> CellKey; ///< key of each non-empty cell, ascending
  /// True when the points were copied in cell order (the default mode): slot
  /// i holds point i, and Order is empty (8 bytes per point less).
  bool SlotOrder = false;

  Index NumberOfCells() const { return static_cast<Index>(this->CellKey.size()); }
  Index NumberOfPoints() const { return this->CellStart.empty() ? 0 : this->CellStart.back(); }
  Index CellSizeOf(Index c) const { return this->CellStart[c + 1] - this->CellStart[c]; }
  /// The point in slot i (Order[i], or i in slot order).
  Index PointAt(Index i) const { return this->SlotOrder ? i : this->Order[i]; }
  /// The points of cell c (not in slot order: see CellIds).
  const Index* CellPoints(Index c) const { return this->Order.data() + this->CellStart[c]; }
  /// The points of cell c in either order (in slot order, its slots).
  IdView CellIds(Index c) const
  {
    const auto n = static_cast<std::size_t>(this->CellSizeOf(c));
    return this->SlotOrder ? IdView::Range(this->CellStart[c], n) : IdView(this->CellPoints(c), n);
  }
};

/// The point id of each slot of a grid's order, taken over from that order
/// (which is released), in 32 bits when every id fits: for a copy of the
/// points in cell order (slot i holds point ids[i]), 4 bytes per point
/// instead of 8.
class VTKASMFILTERS_EXPORT SlotIds
{
public:
  SlotIds(PointArray<Index>& order, const Execution& execution = {});
  Index operator[](Index slot) const
  {
    return this->Wide.empty() ? static_cast<Index>(this->Narrow[slot]) : this->Wide[slot];
  }

private:
  PointArray<std::uint32_t> Narrow;
  PointArray<Index> Wide; ///< (when some id does not fit in 32 bits)
};

/// Hash the points into the grid `spec` (deterministic: ties by point id).
VTKASMFILTERS_EXPORT CellGrid BuildCellGrid(
  Coordinates xyz, IdView ids, const GridSpec& spec, const Execution& execution = {});

/// Number of non-empty cells of `spec`.
VTKASMFILTERS_EXPORT Index CountOccupiedCells(
  Coordinates xyz, IdView ids, const GridSpec& spec, const Execution& execution = {});

/// The keys of the non-empty cells of `spec`, ascending, each once.
VTKASMFILTERS_EXPORT std::vector<std::uint64_t> OccupiedCellKeys(
  Coordinates xyz, IdView ids, const GridSpec& spec, const Execution& execution = {});

} // namespace asmcore

#endif
