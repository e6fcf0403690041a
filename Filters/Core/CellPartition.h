// SPDX-License-Identifier: BSD-3-Clause
/**
 * Which process owns each grid cell in a distributed run: a recursive
 * bisection of the grid into boxes of cells. Each box of k processes is cut
 * across its longest side (in cells) where the points on the low side make
 * the share of floor(k / 2) of them, until every process has its box. Boxes
 * keep the halo (the cells within a few rings of a box that a process also
 * holds) small: with slabs along one axis, a slab of S cell layers carries
 * 2h halo layers, which dominates once S nears h (many processes); a box's
 * halo grows with its surface instead.
 */
#ifndef asm_core_CellPartition_h
#define asm_core_CellPartition_h

#include "Grid.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace asmcore
{
/// The boxes of cells, as a tree: node 0 is the root; a leaf is a box and its
/// owner. A process owns at most one box; one may own none (when there are
/// more processes than cells to cut between them).
struct VTKASMFILTERS_EXPORT CellPartition
{
  struct Node
  {
    int Axis = -1;          ///< the cut's axis; -1: a leaf
    std::int64_t Split = 0; ///< cells below Split along Axis are in Low, the others in High
    int Low = -1;
    int High = -1;
    int Rank = 0; ///< a leaf's owner
  };
  GridSpec Grid;
  std::vector<Node> Nodes;

  /// The leaf (node index) holding cell ijk (inside the grid).
  int LeafOf(const std::int64_t ijk[3]) const
  {
    int node = 0;
    while (this->Nodes[node].Axis >= 0)
    {
      const Node& n = this->Nodes[node];
      node = ijk[n.Axis] < n.Split ? n.Low : n.High;
    }
    return node;
  }
  /// The owner of cell ijk (inside the grid).
  int OwnerOf(const std::int64_t ijk[3]) const { return this->Nodes[this->LeafOf(ijk)].Rank; }
  /// The cell holding p (GridSpec::CellOf, as signed indices).
  void CellOfPoint(const double p[3], std::int64_t ijk[3]) const
  {
    std::uint64_t u[3];
    this->Grid.CellOf(p, u);
    for (int a = 0; a < 3; ++a)
    {
      ijk[a] = static_cast<std::int64_t>(u[a]);
    }
  }
  /// The owner of the cell holding p (clamped to the grid).
  int OwnerOfPoint(const double p[3]) const
  {
    std::int64_t ijk[3];
    this->CellOfPoint(p, ijk);
    return this->OwnerOf(ijk);
  }
  /// Calls visit(rank) once for each process whose box has a cell within
  /// `rings` cells of cell ijk along every axis (the 3 x 3 x 3 block for 1),
  /// in increasing rank order.
  template <typename Visit>
  void ForEachOwnerNear(const std::int64_t ijk[3], int rings, Visit&& visit) const
  {
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node& n = this->Nodes[stack[--top]];
      if (n.Axis < 0)
      {
        visit(n.Rank);
        continue;
      }
      // (High pushed first: Low, the lower ranks, is visited first.)
      if (ijk[n.Axis] + rings >= n.Split)
      {
        stack[top++] = n.High;
      }
      if (ijk[n.Axis] - rings < n.Split)
      {
        stack[top++] = n.Low;
      }
    }
  }
};

/// The partition of `grid` over `processes` processes, balanced by the
/// points xyz[3 * id], id in ids (this process's). `sum` adds a vector over
/// the processes (in place; empty: this process holds every point): one
/// collective per level of the tree, ceil(log2(processes)) in all. Every
/// process gets the same tree.
VTKASMFILTERS_EXPORT CellPartition MakeCellPartition(const GridSpec& grid, int processes,
  Coordinates xyz, IdView ids, const std::function<void(std::vector<long long>&)>& sum = {},
  const Execution& execution = {});
} // namespace asmcore

#endif
