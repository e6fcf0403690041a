// SPDX-License-Identifier: BSD-3-Clause
#include "FeatureOutput.h"

#include "CanonicalOrder.h"
#include "SnappedHoles.h"

#include <algorithm>
#include <array>
#include <limits>

namespace asmcore
{
namespace feature
{
std::vector<char> OutputCells(const CellGrid& grid, const SimplifyParameters& parameters)
{
  std::vector<char> output;
  if (parameters.OutputCell)
  {
    output.resize(static_cast<std::size_t>(grid.NumberOfCells()));
    for (Index c = 0; c < grid.NumberOfCells(); ++c)
    {
      output[c] = parameters.OutputCell(grid.CellKey[c]) ? 1 : 0;
    }
  }
  return output;
}

void FillEmptyClusters(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, const std::vector<SampleInfo>& info, PointArray<SampleId>& assign,
  std::vector<Index>& count, const std::vector<char>& output)
{
  // A point can be taken while it is unassigned or its cluster has two
  // members or more, unless it is the extreme point of the key sample it
  // belongs to (the key sample stands for that point, on it or not: taken,
  // it would be output twice, once snapped to by the sample that took it).
  // Counts only fall, or rise from 0 to 1, and a key sample's own point is
  // never taken: a point that cannot be taken never can again, so each
  // cell's scan starts after its leading points that cannot (cursor), and
  // every sample's scan ends at a point at its very position (nothing is
  // nearer; ties: the first). So many samples at one position (a cloud of
  // identical points) cost a scan of the cell in all, not one each.
  auto eligible = [&](Index i) {
    const SampleId s = assign[i];
    return s < 0 || (count[s] >= 2 && !(samples.Fixed[s] && info[s].Point == i));
  };
  std::vector<Index> cursor; // per cell (made at the first empty sample)
  auto take = [&](Index s, Index i) {
    if (assign[i] >= 0)
    {
      --count[assign[i]];
    }
    assign[i] = static_cast<SampleId>(s);
    ++count[s];
  };
  std::vector<Index> leftover; // samples whose ring has no point to give
  // Slot i as sample position p's nearest so far (strictly nearer: ties
  // keep the first).
  auto offer = [&](Index i, const double* p, Index& best, double& bestD) {
    if (!eligible(i))
    {
      return;
    }
    double x[3];
    xyz.Get(grid.PointAt(i), x);
    const double d = SquaredDistance(x, p);
    if (d < bestD)
    {
      bestD = d;
      best = i;
    }
  };
  for (Index s = 0; s < samples.Size(); ++s)
  {
    if (count[s] > 0)
    {
      continue;
    }
    if (cursor.empty())
    {
      cursor.assign(grid.CellStart.begin(), grid.CellStart.end() - 1);
    }
    const double* p = samples.Position.data() + 3 * s;
    const CellRef* ring = neighbors.Of(info[s].Owner);
    Index best = -1;
    double bestD = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 27 && bestD > 0.0; ++k)
    {
      const Index nb = ring[k];
      if (nb < 0)
      {
        continue;
      }
      const Index end = grid.CellStart[nb + 1];
      Index i = cursor[nb];
      while (i < end && !eligible(i))
      {
        ++i;
      }
      cursor[nb] = i;
      for (; i < end && bestD > 0.0; ++i)
      {
        offer(i, p, best, bestD);
      }
    }
    if (best >= 0)
    {
      take(s, best);
    }
    else
    {
      leftover.push_back(s);
    }
  }
  // Samples whose ring had no point to give (N_s close to N): the nearest
  // point that can be taken anywhere (ties: the first slot). One exists
  // while a sample is empty and there are at least as many points as
  // samples: N points in fewer than N_s clusters leave one with two members
  // or one point unassigned.
  // A distributed run looks at what it outputs only (see the header): the
  // halo's clusters are exact near its own cells only, and a halo cell's
  // sample may be empty here while its members lie beyond the halo.
  const auto outputs = [&](Index cell) { return output.empty() || output[cell]; };
  if (leftover.empty())
  {
    return;
  }
  std::vector<Index> candidates; // (slot order)
  for (Index c = 0; c < grid.NumberOfCells(); ++c)
  {
    for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
    {
      if (eligible(i) && outputs(assign[i] < 0 ? c : info[assign[i]].Owner))
      {
        candidates.push_back(i);
      }
    }
  }
  for (const Index s : leftover)
  {
    if (!outputs(info[s].Owner))
    {
      continue;
    }
    const double* p = samples.Position.data() + 3 * s;
    Index best = -1;
    double bestD = std::numeric_limits<double>::infinity();
    for (const Index i : candidates)
    {
      offer(i, p, best, bestD);
    }
    if (best >= 0)
    {
      take(s, best);
    }
  }
}

void PlaceOutputSamples(Coordinates P, const CellGrid& grid, const SlotIds& idOf,
  const std::vector<Index>& memberStart, const SimplifyParameters& parameters, SampleSet& samples,
  std::vector<SampleInfo>& info, PointArray<Index>& members,
  std::vector<std::pair<Index, Index>>& duplicates, const Execution& execution)
{
  const Index count = samples.Size();
  const bool inputPointSamples = parameters.Snap || parameters.InputPointSamples;
  const auto getP = [&P](Index j, double* x) { P.Get(j, x); };
  std::vector<char> twinned(static_cast<std::size_t>(count), 0); // (see the end)
  execution.Run(0, count, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      double* p = samples.Position.data() + 3 * s;
      const Index* first = members.data() + memberStart[s]; // slots
      const Index size = memberStart[s + 1] - memberStart[s];
      // The member nearest the sample, as a slot (ties: by position, then
      // by input point id).
      Index nearest = info[s].Point;
      double bestD = std::numeric_limits<double>::infinity();
      double mean[3] = { 0.0, 0.0, 0.0 };
      for (Index m = 0; m < size; ++m)
      {
        double x[3];
        P.Get(first[m], x);
        for (int a = 0; a < 3; ++a)
        {
          mean[a] += x[a];
        }
        const double d = SquaredDistance(x, p);
        // Ties, rounding included (a two-point cluster's centre is as near
        // to both): the first position, whatever the order of the points.
        // (Duplicates: the lower id.)
        const bool tie = NearlyEqual(d, bestD);
        if (tie && nearest >= 0)
        {
          const std::array<double, 3> y = P.At(nearest);
          if (PositionThenIdBefore(x, idOf[first[m]], y.data(), idOf[nearest]))
          {
            bestD = d;
            nearest = first[m];
          }
        }
        else if (tie || d < bestD)
        {
          bestD = d;
          nearest = first[m];
        }
      }
      if (nearest < 0)
      {
        nearest = grid.CellStart[info[s].Owner]; // no member could be found
      }
      const bool fixed = samples.Fixed[s] != 0;
      const bool snap = inputPointSamples && !(fixed && parameters.ExtremeKeyPoints);
      // A key sample placed on its extreme point stands for that point, even
      // when the point joined another sample's cluster (a tie with a sample
      // at the same position): its position is exactly that input point.
      if (!(fixed && parameters.ExtremeKeyPoints && info[s].Point >= 0))
      {
        info[s].Point = nearest;
      }
      twinned[static_cast<std::size_t>(s)] =
        HasDuplicate(info[s].Point, 0, grid.NumberOfPoints(), getP) ? 1 : 0;
      // A free sample that is not snapped is its final cluster's centroid.
      if (snap)
      {
        P.Get(nearest, p);
      }
      else if (!fixed && size > 0)
      {
        for (int a = 0; a < 3; ++a)
        {
          p[a] = mean[a] / static_cast<double>(size);
        }
      }
    }
  });
  if (parameters.BoundSnappedHoles)
  {
    std::vector<char> snapped(static_cast<std::size_t>(count), 0);
    for (Index s = 0; s < count; ++s)
    {
      // (Snap is the user's demand for input points: left alone.)
      snapped[s] = parameters.InputPointSamples && !parameters.Snap && !samples.Fixed[s] &&
        memberStart[s + 1] - memberStart[s] > 1;
    }
    BoundSnappedHoles(P, memberStart, members.data(), snapped, samples.Position.data(), execution);
  }
  execution.Run(0, static_cast<Index>(members.size()), [&](Index b, Index e) {
    for (Index j = b; j < e; ++j)
    {
      members[j] = idOf[members[j]];
    }
  });
  // The representatives' exact duplicates: their neighbours in slot order
  // (each cell's points are in canonical order), found above.
  duplicates.clear();
  std::vector<char> listed; // (allocated at the first representative with a duplicate)
  for (std::size_t s = 0; s < info.size(); ++s)
  {
    const Index point = info[s].Point;
    if (s < twinned.size() && twinned[s])
    {
      listed.resize(static_cast<std::size_t>(grid.NumberOfPoints()), 0);
      ListDuplicatesOnce(point, 0, grid.NumberOfPoints(), getP, listed,
        [&](Index r, Index j) { duplicates.emplace_back(idOf[r], idOf[j]); });
    }
    info[s].Point = idOf[point];
  }
  std::sort(duplicates.begin(), duplicates.end());
}

void LayOutSamples(Coordinates xyz, IdView ids, NormalField normals,
  const std::vector<CellSurface>& surfaces, const std::vector<SampleInfo>& info,
  const SampleSet& samples, const std::vector<Index>& memberStart,
  const SimplifyParameters& parameters, SimplifyResult& result, const Execution& execution)
{
  const Index count = samples.Size();
  Eigen::Vector3d cloudCentroid;
  if (parameters.CloudCentroid)
  {
    cloudCentroid = Eigen::Vector3d(parameters.CloudCentroid);
  }
  else
  {
    ComputeCentroid(xyz, ids, cloudCentroid.data(), execution);
  }
  ResizeInParallel(result.Samples, static_cast<std::size_t>(count), Sample{}, execution);
  execution.Run(0, count, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      Sample& out = result.Samples[s];
      const CellSurface& surface = surfaces[info[s].Owner];
      out.MemberBegin = memberStart[s];
      out.ClusterSize = memberStart[s + 1] - memberStart[s];
      out.Representative = info[s].Point;
      std::copy_n(samples.Position.data() + 3 * s, 3, out.Position);
      // The normal: the cell's, oriented along the members' input normals,
      // else away from the cloud's centroid.
      Eigen::Vector3d normalSum = Eigen::Vector3d::Zero();
      for (Index m = 0; normals && m < out.ClusterSize; ++m)
      {
        Eigen::Vector3d v;
        normals.Get(result.Members[out.MemberBegin + m], v.data());
        if (v.allFinite())
        {
          normalSum += v;
        }
      }
      Eigen::Vector3d normal = surface.Normal;
      const Eigen::Vector3d reference = normalSum.squaredNorm() > 0.0
        ? normalSum
        : Eigen::Vector3d(surface.Centroid - cloudCentroid);
      if (normal.dot(reference) < 0.0)
      {
        normal = -normal;
      }
      std::copy(normal.data(), normal.data() + 3, out.Normal);
      out.SurfaceVariation = surface.SurfaceVariation;
      out.Key = samples.Fixed[s] != 0;
      out.KeyError = info[s].KeyError;
    }
  });
}

// Distributed runs: only the samples of the cells this process outputs (its
// own), with their members; the others were computed as context.
void KeepOutputCells(
  SimplifyResult& result, const std::vector<SampleInfo>& info, const std::vector<char>& output)
{
  UnwrittenArray<Sample> samples;
  PointArray<Index> members;
  for (std::size_t s = 0; s < result.Samples.size(); ++s)
  {
    if (!output[info[s].Owner])
    {
      continue;
    }
    Sample sample = result.Samples[s];
    const auto begin = result.Members.begin() + sample.MemberBegin;
    sample.MemberBegin = static_cast<Index>(members.size());
    members.insert(members.end(), begin, begin + sample.ClusterSize);
    samples.push_back(sample);
  }
  result.Samples.swap(samples);
  result.Members.swap(members);
}
} // namespace feature
} // namespace asmcore
