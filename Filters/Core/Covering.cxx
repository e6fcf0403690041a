// SPDX-License-Identifier: BSD-3-Clause
#include "Covering.h"

#include "GroupBy.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

namespace asmcore
{
void RefineCovering(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  SampleSet& samples, PointArray<SampleId>& assign, const Execution& execution)
{
  AssignToSamples(xyz, grid, neighbors, samples, assign, execution);
  const Index count = samples.Size();
  const Index points = static_cast<Index>(assign.size());
  // The members (point slots) of every sample, in slot order.
  std::vector<Index> start;
  std::vector<Index> members;
  GroupBy(
    points, count, [&](Index i) { return assign[i]; }, [](Index i) { return i; }, start, members,
    execution);
  // A slot's point, as three doubles (a value).
  auto at = [xyz, &grid](Index slot) { return xyz.At(grid.PointAt(slot)); };
  execution.Run(0, count, [&](Index b, Index e) {
    std::vector<std::pair<double, Index>> candidates; // (squared distance to the centroid, slot)
    for (Index s = b; s < e; ++s)
    {
      const Index first = start[s], last = start[s + 1];
      if (samples.Fixed[s] || last == first)
      {
        continue;
      }
      double* position = samples.Position.data() + 3 * s;
      double centroid[3] = { 0.0, 0.0, 0.0 };
      for (Index m = first; m < last; ++m)
      {
        for (int a = 0; a < 3; ++a)
        {
          centroid[a] += at(members[m])[a];
        }
      }
      for (int a = 0; a < 3; ++a)
      {
        centroid[a] /= static_cast<double>(last - first);
      }
      candidates.clear();
      Index current = -1; // the member the sample sits on, if any
      for (Index m = first; m < last; ++m)
      {
        candidates.emplace_back(SquaredDistance(at(members[m]).data(), centroid), members[m]);
        if (current < 0 && SquaredDistance(at(members[m]).data(), position) == 0.0)
        {
          current = members[m];
        }
      }
      // The CoveringCandidates smallest (distance, slot) pairs, ascending
      // (the pairs are distinct: one selection, one order).
      const auto keep = std::min<std::size_t>(candidates.size(), CoveringCandidates);
      if (keep < candidates.size())
      {
        std::nth_element(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(keep),
          candidates.end());
        candidates.resize(keep);
      }
      std::sort(candidates.begin(), candidates.end());
      if (current >= 0)
      {
        candidates.emplace_back(0.0, current);
      }
      // The candidate whose farthest member is nearest (ties, rounding
      // included: the first position, whatever the order of the points).
      double bestRadius = std::numeric_limits<double>::infinity();
      Index best = -1;
      for (const auto& candidate : candidates)
      {
        const std::array<double, 3> c = at(candidate.second);
        double radius = 0.0;
        const double stop = bestRadius * (1.0 + 1e-12);
        for (Index m = first; m < last && radius <= stop; ++m)
        {
          radius = std::max(radius, SquaredDistance(at(members[m]).data(), c.data()));
        }
        if (best < 0 ||
          (NearlyEqual(radius, bestRadius) ? PositionBefore(c.data(), at(best).data())
                                           : radius < bestRadius))
        {
          bestRadius = radius;
          best = candidate.second;
        }
      }
      xyz.Get(grid.PointAt(best), position);
    }
  });
}
} // namespace asmcore
