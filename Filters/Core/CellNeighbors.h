// SPDX-License-Identifier: BSD-3-Clause
/**
 * Neighbouring grid cells: for every non-empty cell, the indices of the
 * non-empty cells of its 3 x 3 x 3 block (itself included), found by binary
 * search in the sorted cell keys. Used by every cross-cell step of the
 * feature-preserving mode (Lemma 2 across cell borders, Lloyd iterations
 * across cell borders), none of which looks farther than one ring of cells
 * per step (see InfluenceRings in FeatureSimplify.h).
 */
#ifndef asm_core_CellNeighbors_h
#define asm_core_CellNeighbors_h

#include "Grid.h"

#include <cstdint>
#include <limits>

namespace asmcore
{
/// A cell of the table: 32 bits (108 bytes per cell instead of 216), so a
/// table holds at most MaxTableCells cells (BuildCellNeighbors).
using CellRef = std::int32_t;

/// The 27 cells around each non-empty cell: entry 27 * c + k, k = (dz + 1) * 9
/// + (dy + 1) * 3 + (dx + 1), is the index of the non-empty cell at offset
/// (dx, dy, dz) from c, or -1 (empty or outside the grid). Entry 13 is c.
struct VTKASMFILTERS_EXPORT CellNeighborTable
{
  static constexpr Index MaxTableCells = std::numeric_limits<CellRef>::max();
  std::vector<CellRef> Cells;
  const CellRef* Of(Index c) const { return this->Cells.data() + 27 * c; }
  /// The 27 entries of cell c as a range (`for (Index nb : table.RingOf(c))`).
  struct Ring
  {
    const CellRef* First;
    const CellRef* begin() const { return this->First; }
    const CellRef* end() const { return this->First + 27; }
  };
  Ring RingOf(Index c) const { return { this->Of(c) }; }
};

/// The 27 entries of the table for cell c alone (as BuildCellNeighbors).
VTKASMFILTERS_EXPORT void CellNeighborsOf(const CellGrid& grid, Index c, Index out[27]);

/// Build the table for `grid` (runs over cells through `execution`); empty
/// when the grid has more than MaxTableCells non-empty cells.
VTKASMFILTERS_EXPORT CellNeighborTable BuildCellNeighbors(
  const CellGrid& grid, const Execution& execution = {});

/// Squared distance from p to the box of the cell with key `key` (0 inside).
VTKASMFILTERS_EXPORT double SquaredDistanceToCell(
  const GridSpec& spec, std::uint64_t key, const double p[3]);
} // namespace asmcore

#endif
