// SPDX-License-Identifier: BSD-3-Clause
#include "Unclaimed.h"

#include "CellNeighbors.h"
#include "Neighbors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
namespace
{
// A 3 x 3 x 3 block of cells holding more than this many samples leaves the
// nearest-sample search of its unclaimed points to a k-d tree (bounded work).
constexpr Index LargeRingSamples = 512;

// The sample nearest to each of the points xyz[3 * points[i]] (ties: the
// lower sample index), searched in the 3 x 3 x 3 block of cells around the
// point's cell: runs[r] = (c, i) says that the points from i to the next
// run's lie in cell c (the last run ends at points.size()). Cell c owns
// samples [sampleStart[c], sampleStart[c + 1]), which lie in its box. A
// neighbouring cell whose box is farther than the best sample so far is
// skipped, and a sample found within a cell's edge of its point is the
// nearest of all (any cell outside the block is farther); the other points,
// and those of a block holding very many samples, are left at -1 in `owner`
// for a global search. (On a noisy scan in the paper mode most points are
// unclaimed: 8 of 10 M on mpi_scaling.py's sphere at 1 %, where this search
// was half of the run; hence the gather of a run's points before the
// search, the compact sample positions and the nearer boxes first.)
void NearestSamplesInRing(Coordinates xyz, const CellGrid& grid,
  const std::vector<Index>& sampleStart, const SimplifyResult& result,
  const std::vector<Index>& points, const std::vector<std::pair<Index, Index>>& runs,
  std::vector<Index>& owner, const Execution& execution)
{
  const Index n = static_cast<Index>(points.size());
  const double h = grid.Spec.CellSize;
  // A margin far above the rounding of the positions (relative to their
  // magnitude: georeferenced clouds) and of the cell boxes.
  const double accept = h * h * (1.0 - 1e-6);
  // The samples' positions side by side (a Sample holds 104 bytes).
  const auto samples = static_cast<Index>(result.Samples.size());
  std::vector<double> positions(static_cast<std::size_t>(3 * samples));
  execution.Run(0, samples, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      std::copy(result.Samples[s].Position, result.Samples[s].Position + 3, &positions[3 * s]);
    }
  });
  // A neighbouring cell with samples: its samples and its offset along each
  // axis (0: below, 1: level, 2: above).
  struct Neighbour
  {
    Index First, Last;
    int Offset[3];
  };
  execution.Run(0, static_cast<Index>(runs.size()), [&](Index b, Index e) {
    Index ring[27];
    Neighbour around[26];
    std::vector<double> local;
    for (Index r = b; r < e; ++r)
    {
      const Index c = runs[r].first;
      const Index first = runs[r].second;
      const Index last = r + 1 < static_cast<Index>(runs.size()) ? runs[r + 1].second : n;
      CellNeighborsOf(grid, c, ring);
      Index ringSamples = 0;
      for (Index nb : ring)
      {
        ringSamples += nb < 0 ? 0 : sampleStart[nb + 1] - sampleStart[nb];
      }
      if (ringSamples > LargeRingSamples)
      {
        std::fill(owner.begin() + first, owner.begin() + last, Index(-1));
        continue;
      }
      // The neighbours that hold samples, those sharing a face first, then
      // an edge, then a corner: the nearer boxes lower the bound sooner.
      // (The answer does not depend on the order: a box is skipped only
      // when it lies farther than a sample found already.)
      int count = 0;
      for (int shared = 2; shared >= 0; --shared)
      {
        for (int k = 0; k < 27; ++k)
        {
          const int o[3] = { k % 3, (k / 3) % 3, k / 9 };
          const int level = (o[0] == 1) + (o[1] == 1) + (o[2] == 1);
          if (k != 13 && level == shared && ring[k] >= 0 &&
            sampleStart[ring[k] + 1] > sampleStart[ring[k]])
          {
            around[count++] = { sampleStart[ring[k]], sampleStart[ring[k] + 1],
              { o[0], o[1], o[2] } };
          }
        }
      }
      std::int64_t ijk[3];
      grid.Spec.Unpack(grid.CellKey[c], ijk);
      double lo[3], shrink[3];
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = grid.Spec.Origin[a] + h * static_cast<double>(ijk[a]);
        shrink[a] = 1e-9 * h + 1e-12 * std::abs(lo[a]);
      }
      // The run's points, gathered first (they are scattered in memory: a
      // tight loop keeps more of their loads in flight).
      local.resize(static_cast<std::size_t>(3 * (last - first)));
      for (Index i = first; i < last; ++i)
      {
        if (i + 16 < last)
        {
          Prefetch(xyz.Address(points[i + 16]));
        }
        xyz.Get(points[i], local.data() + 3 * (i - first));
      }
      for (Index i = first; i < last; ++i)
      {
        const double* p = local.data() + 3 * (i - first);
        // Squared gaps to the neighbouring boxes along each axis: below
        // (offset 0), none (1), above (2).
        double gap[3][3];
        for (int a = 0; a < 3; ++a)
        {
          const double below = std::max(0.0, p[a] - lo[a] - shrink[a]);
          const double above = std::max(0.0, lo[a] + h - p[a] - shrink[a]);
          gap[a][0] = below * below;
          gap[a][1] = 0.0;
          gap[a][2] = above * above;
        }
        Index best = -1;
        double bestD = std::numeric_limits<double>::infinity();
        auto scan = [&](Index from, Index to) {
          for (Index s = from; s < to; ++s)
          {
            const double* t = positions.data() + 3 * s;
            // As the k-d tree computes it (Neighbors.cxx): the same ties.
            const double dx = t[0] - p[0], dy = t[1] - p[1], dz = t[2] - p[2];
            const double d = dx * dx + dy * dy + dz * dz;
            const bool better = (d < bestD) | ((d == bestD) & (s < best));
            bestD = better ? d : bestD;
            best = better ? s : best;
          }
        };
        scan(
          sampleStart[c], sampleStart[c + 1]); // the own cell first: the best bound for the others
        for (int k = 0; k < count; ++k)
        {
          const Neighbour& nb = around[k];
          if (!(gap[0][nb.Offset[0]] + gap[1][nb.Offset[1]] + gap[2][nb.Offset[2]] > bestD))
          {
            scan(nb.First, nb.Last);
          }
        }
        owner[i] = bestD <= accept ? best : -1;
      }
    }
  });
}
} // namespace

void AttachUnclaimedPoints(Coordinates xyz, const CellGrid& grid,
  const std::vector<Index>& sampleStart, SimplifyResult& result, const std::vector<char>& haloSlot,
  const Execution& execution)
{
  const Index total = static_cast<Index>(result.Members.size());
  const Index samples = static_cast<Index>(result.Samples.size());
  const Index cells = grid.NumberOfCells();
  if (samples == 0)
  {
    return;
  }
  // The unclaimed slots of each cell follow its samples' members.
  auto claimedEnd = [&](Index c) {
    const Index last = sampleStart[c + 1] - 1;
    return last >= sampleStart[c]
      ? result.Samples[last].MemberBegin + result.Samples[last].ClusterSize
      : grid.CellStart[c];
  };
  std::vector<Index> unclaimed;
  std::vector<std::pair<Index, Index>> runs; // (cell, first position in unclaimed)
  bool haloDropped = false;
  for (Index c = 0; c < cells; ++c)
  {
    for (Index slot = claimedEnd(c); slot < grid.CellStart[c + 1]; ++slot)
    {
      if (haloSlot.empty() || !haloSlot[slot])
      {
        if (runs.empty() || runs.back().first != c)
        {
          runs.emplace_back(c, static_cast<Index>(unclaimed.size()));
        }
        unclaimed.push_back(result.Members[slot]);
      }
      else
      {
        haloDropped = true;
      }
    }
  }
  if (unclaimed.empty())
  {
    if (haloDropped)
    {
      // Only halo points were left out: close the gaps.
      PointArray<Index> members;
      members.reserve(static_cast<std::size_t>(total));
      for (Sample& s : result.Samples)
      {
        const Index begin = static_cast<Index>(members.size());
        members.insert(members.end(), result.Members.begin() + s.MemberBegin,
          result.Members.begin() + s.MemberBegin + s.ClusterSize);
        s.MemberBegin = begin;
      }
      result.Members.swap(members);
    }
    return;
  }
  std::vector<Index> owner(unclaimed.size());
  NearestSamplesInRing(xyz, grid, sampleStart, result, unclaimed, runs, owner, execution);
  std::vector<Index> far; // positions in `unclaimed` left to the global search
  for (std::size_t i = 0; i < owner.size(); ++i)
  {
    if (owner[i] < 0)
    {
      far.push_back(static_cast<Index>(i));
    }
  }
  if (!far.empty() && static_cast<double>(far.size()) * static_cast<double>(samples) <= 1e8)
  {
    // A few points (far outliers): every sample (ties: the lower index).
    execution.Run(0, static_cast<Index>(far.size()), [&](Index b, Index e) {
      for (Index i = b; i < e; ++i)
      {
        double p[3];
        xyz.Get(unclaimed[far[i]], p);
        Index best = 0;
        double bestD = std::numeric_limits<double>::infinity();
        for (Index s = 0; s < samples; ++s)
        {
          const double* t = result.Samples[s].Position;
          const double dx = t[0] - p[0], dy = t[1] - p[1], dz = t[2] - p[2];
          const double d = dx * dx + dy * dy + dz * dz;
          if (d < bestD)
          {
            bestD = d;
            best = s;
          }
        }
        owner[far[i]] = best;
      }
    });
  }
  else if (!far.empty())
  {
    std::vector<double> positions(static_cast<std::size_t>(3 * samples));
    std::vector<Index> sampleIds(static_cast<std::size_t>(samples));
    for (Index s = 0; s < samples; ++s)
    {
      std::copy(result.Samples[s].Position, result.Samples[s].Position + 3, &positions[3 * s]);
      sampleIds[s] = s;
    }
    const Neighbors tree(positions.data(), sampleIds, execution);
    execution.Run(0, static_cast<Index>(far.size()), [&](Index b, Index e) {
      for (Index i = b; i < e; ++i)
      {
        double p[3];
        xyz.Get(unclaimed[far[i]], p);
        const NearestPoint nearest = tree.Nearest(p);
        owner[far[i]] = nearest.Id >= 0 ? nearest.Id : 0;
      }
    });
  }
  // Lay the members out again, in place: each sample's own, then those that
  // joined it (in slot order). The own blocks keep their order, so those
  // moving towards the front move in increasing order and the others in
  // decreasing order, each into room already vacated (the unclaimed ids are
  // copied out); then the joined points fill the room left after each block.
  std::vector<Index> begin(static_cast<std::size_t>(samples) + 1, 0);
  for (Index o : owner)
  {
    ++begin[o + 1]; // joined points per sample
  }
  for (Index s = 0; s < samples; ++s)
  {
    begin[s + 1] += begin[s] + result.Samples[s].ClusterSize;
  }
  PointArray<Index>& members = result.Members;
  for (Index s = 0; s < samples; ++s)
  {
    const Sample& sample = result.Samples[s];
    if (begin[s] < sample.MemberBegin)
    {
      std::copy(members.begin() + sample.MemberBegin,
        members.begin() + sample.MemberBegin + sample.ClusterSize, members.begin() + begin[s]);
    }
  }
  const Index end = begin[samples];
  for (Index s = samples - 1, next = end; s >= 0; --s)
  {
    Sample& sample = result.Samples[s];
    if (begin[s] > sample.MemberBegin)
    {
      std::copy_backward(members.begin() + sample.MemberBegin,
        members.begin() + sample.MemberBegin + sample.ClusterSize,
        members.begin() + begin[s] + sample.ClusterSize);
    }
    sample.MemberBegin = begin[s];
    begin[s] += sample.ClusterSize; // where its joined points go
    sample.ClusterSize = next - sample.MemberBegin;
    next = sample.MemberBegin;
  }
  for (std::size_t i = 0; i < unclaimed.size(); ++i)
  {
    members[begin[owner[i]]++] = unclaimed[i];
  }
  members.resize(static_cast<std::size_t>(end)); // halo points dropped
}
} // namespace asmcore
