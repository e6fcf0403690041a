// SPDX-License-Identifier: BSD-3-Clause
#include "CellNeighbors.h"

#include <algorithm>

namespace asmcore
{
CellNeighborTable BuildCellNeighbors(const CellGrid& grid, const Execution& execution)
{
  CellNeighborTable table;
  const Index cells = grid.NumberOfCells();
  table.Cells.assign(static_cast<std::size_t>(27 * cells), -1);
  execution.Run(0, cells, [&](Index b, Index e) {
    for (Index c = b; c < e; ++c)
    {
      std::int64_t ijk[3];
      grid.Spec.Unpack(grid.CellKey[c], ijk);
      Index* out = table.Cells.data() + 27 * c;
      int k = 0;
      for (int dz = -1; dz <= 1; ++dz)
      {
        for (int dy = -1; dy <= 1; ++dy)
        {
          for (int dx = -1; dx <= 1; ++dx, ++k)
          {
            const std::int64_t n[3] = { ijk[0] + dx, ijk[1] + dy, ijk[2] + dz };
            bool inside = true;
            for (int a = 0; a < 3; ++a)
            {
              inside = inside && n[a] >= 0 && n[a] < grid.Spec.Dims[a];
            }
            if (!inside)
            {
              continue;
            }
            const std::uint64_t key = (static_cast<std::uint64_t>(n[2]) << 42) |
              (static_cast<std::uint64_t>(n[1]) << 21) | static_cast<std::uint64_t>(n[0]);
            const auto it = std::lower_bound(grid.CellKey.begin(), grid.CellKey.end(), key);
            if (it != grid.CellKey.end() && *it == key)
            {
              out[k] = static_cast<Index>(it - grid.CellKey.begin());
            }
          }
        }
      }
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
