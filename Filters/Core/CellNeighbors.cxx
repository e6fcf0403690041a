// SPDX-License-Identifier: BSD-3-Clause
#include "CellNeighbors.h"

#include <algorithm>

namespace asmcore
{
void CellNeighborsOf(const CellGrid& grid, Index c, Index out[27])
{
  std::int64_t ijk[3];
  grid.Spec.Unpack(grid.CellKey[c], ijk);
  const auto keys = grid.CellKey.begin();
  const auto keysEnd = grid.CellKey.end();
  // The three cells dx = -1, 0, 1 of a row (dy, dz) have consecutive keys:
  // one search per row finds them all.
  const std::int64_t x0 = std::max<std::int64_t>(0, ijk[0] - 1);
  const std::int64_t x1 = std::min<std::int64_t>(grid.Spec.Dims[0] - 1, ijk[0] + 1);
  int k = 0;
  for (int dz = -1; dz <= 1; ++dz)
  {
    for (int dy = -1; dy <= 1; ++dy, k += 3)
    {
      std::fill_n(out + k, 3, Index(-1));
      const std::int64_t y = ijk[1] + dy, z = ijk[2] + dz;
      if (y < 0 || y >= grid.Spec.Dims[1] || z < 0 || z >= grid.Spec.Dims[2])
      {
        continue;
      }
      const std::uint64_t row =
        (static_cast<std::uint64_t>(z) << 42) | (static_cast<std::uint64_t>(y) << 21);
      auto it = std::lower_bound(keys, keysEnd, row | static_cast<std::uint64_t>(x0));
      for (; it != keysEnd && *it <= (row | static_cast<std::uint64_t>(x1)); ++it)
      {
        const auto x = static_cast<std::int64_t>(*it & ((std::uint64_t(1) << 21) - 1));
        out[k + static_cast<int>(x - ijk[0]) + 1] = static_cast<Index>(it - keys);
      }
    }
  }
}

CellNeighborTable BuildCellNeighbors(const CellGrid& grid, const Execution& execution)
{
  CellNeighborTable table;
  const Index cells = grid.NumberOfCells();
  if (cells > CellNeighborTable::MaxTableCells)
  {
    return table;
  }
  table.Cells.resize(static_cast<std::size_t>(27 * cells));
  execution.Run(0, cells, [&](Index b, Index e) {
    Index ring[27];
    for (Index c = b; c < e; ++c)
    {
      CellNeighborsOf(grid, c, ring);
      std::copy_n(ring, 27, table.Cells.data() + 27 * c); // (each < cells: fits)
    }
  });
  return table;
}

double SquaredDistanceToCell(const GridSpec& spec, std::uint64_t key, const double p[3])
{
  std::int64_t ijk[3];
  spec.Unpack(key, ijk);
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double lo = spec.Origin[a] + spec.CellSize * static_cast<double>(ijk[a]);
    const double hi = lo + spec.CellSize;
    const double g = p[a] < lo ? lo - p[a] : (p[a] > hi ? p[a] - hi : 0.0);
    d2 += g * g;
  }
  return d2;
}
} // namespace asmcore
