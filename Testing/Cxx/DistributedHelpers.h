// SPDX-License-Identifier: BSD-3-Clause
// Test helper for the distributed hooks: what the processes of a distributed
// run agree on before simplifying, computed here from the whole cloud.
#ifndef asm_test_DistributedHelpers_h
#define asm_test_DistributedHelpers_h

#include "Core/CellFrame.h"
#include "Core/Grid.h"
#include "Core/Simplify.h"
#include "TestHelpers.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace asmtest
{
/// The global grid (cells of edge `cellSize` over the cloud's bounds), each
/// cell's point count and surface variation in key order, and the cloud's
/// centroid.
struct GlobalCells
{
  asmcore::GridSpec Spec;
  asmcore::CellGrid Grid;
  std::vector<asmcore::Index> Capacity;
  std::vector<double> Variation;
  double Centroid[3] = { 0, 0, 0 };

  GlobalCells(const Cloud& cloud, asmcore::IdView ids, double cellSize)
  {
    const asmcore::Bounds bounds = asmcore::ComputeBounds(cloud.data(), ids);
    this->Spec = asmcore::GridSpec::Make(bounds, cellSize);
    this->Grid = asmcore::BuildCellGrid(cloud.data(), ids, this->Spec);
    for (asmcore::Index c = 0; c < this->Grid.NumberOfCells(); ++c)
    {
      this->Capacity.push_back(this->Grid.CellSizeOf(c));
      this->Variation.push_back(
        asmcore::ComputeCellFrame(cloud.data(), this->Grid.CellIds(c)).SurfaceVariation());
    }
    for (asmcore::Index id : ids)
    {
      for (int a = 0; a < 3; ++a)
      {
        this->Centroid[a] += cloud[3 * id + a] / static_cast<double>(ids.size());
      }
    }
  }

  /// budget[c] (cells in key order) by cell key.
  std::map<std::uint64_t, asmcore::Index> ByKey(const std::vector<asmcore::Index>& budget) const
  {
    std::map<std::uint64_t, asmcore::Index> byKey;
    for (asmcore::Index c = 0; c < this->Grid.NumberOfCells(); ++c)
    {
      byKey[this->Grid.CellKey[c]] = budget[c];
    }
    return byKey;
  }
};
/// (x, y, z, then what `fields` gives) of every sample of `r`, sorted: a
/// result compared whatever the order its samples come in.
template <std::size_t N, typename Fields>
std::vector<std::array<double, N>> SortedSamples(const asmcore::SimplifyResult& r, Fields fields)
{
  std::vector<std::array<double, N>> s;
  for (const asmcore::Sample& sample : r.Samples)
  {
    std::array<double, N> row{ sample.Position[0], sample.Position[1], sample.Position[2] };
    fields(sample, row.data() + 3);
    s.push_back(row);
  }
  std::sort(s.begin(), s.end());
  return s;
}
} // namespace asmtest

#endif
