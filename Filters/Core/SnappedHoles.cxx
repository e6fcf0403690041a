// SPDX-License-Identifier: BSD-3-Clause
#include "SnappedHoles.h"

#include "Lloyd.h"
#include "Selection.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

namespace asmcore
{
namespace
{
// The squared distance from p to the farthest of the points xyz[first[m]].
double SquaredReach(Coordinates xyz, const Index* first, Index n, const double p[3])
{
  double r = 0.0;
  for (Index m = 0; m < n; ++m)
  {
    r = std::max(r, SquaredDistance(xyz.At(first[m]).data(), p));
  }
  return r;
}
} // namespace

double MinimaxCentre(
  Coordinates xyz, const Index* first, Index n, const double start[3], double centre[3])
{
  constexpr int Steps = 64;
  double c[3] = { start[0], start[1], start[2] };
  if (n <= 0)
  {
    std::copy_n(c, 3, centre);
    return 0.0;
  }
  double best = std::numeric_limits<double>::infinity();
  for (int step = 1; step <= Steps; ++step)
  {
    Index far = 0;
    double farD = -1.0;
    for (Index m = 0; m < n; ++m)
    {
      const double d = SquaredDistance(xyz.At(first[m]).data(), c);
      if (d > farD)
      {
        farD = d;
        far = m;
      }
    }
    if (farD < best)
    {
      best = farD;
      std::copy_n(c, 3, centre);
    }
    double f[3];
    xyz.Get(first[far], f);
    for (int a = 0; a < 3; ++a)
    {
      c[a] += (f[a] - c[a]) / static_cast<double>(step + 1);
    }
  }
  return best;
}

namespace
{
// Moves the sample at `position` from there towards `to` only as far as
// `limit` (a squared reach) needs: the reach along the segment is convex,
// so bisection.
void MoveWithinBound(
  Coordinates xyz, const Index* first, Index n, const double* to, double limit, double* position)
{
  const double from[3] = { position[0], position[1], position[2] };
  auto at = [&](double t, double p[3]) {
    for (int a = 0; a < 3; ++a)
    {
      p[a] = from[a] + t * (to[a] - from[a]);
    }
  };
  double lo = 0.0, hi = 1.0; // reach above the bound at lo, within it at hi
  for (int step = 0; step < 20; ++step)
  {
    const double mid = 0.5 * (lo + hi);
    double p[3];
    at(mid, p);
    (SquaredReach(xyz, first, n, p) > limit ? lo : hi) = mid;
  }
  at(hi, position);
}
} // namespace

std::vector<double> SnappedReaches(Coordinates xyz, const std::vector<Index>& memberStart,
  const Index* members, const double* positions, const Execution& execution)
{
  const Index count = static_cast<Index>(memberStart.size()) - 1;
  std::vector<double> reach(static_cast<std::size_t>(std::max<Index>(count, 0)), 0.0);
  execution.Run(0, count, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      reach[s] = SquaredReach(
        xyz, members + memberStart[s], memberStart[s + 1] - memberStart[s], positions + 3 * s);
    }
  });
  return reach;
}

double FixedReach(const std::vector<double>& reach, const std::vector<char>& snapped)
{
  double limit = 0.0;
  for (std::size_t s = 0; s < reach.size(); ++s)
  {
    if (!snapped[s])
    {
      limit = std::max(limit, reach[s]);
    }
  }
  return limit;
}

std::vector<SnapCandidate> SnapCandidates(Coordinates xyz, const std::vector<Index>& memberStart,
  const Index* members, const std::vector<char>& snapped, const std::vector<double>& reach,
  double start, const double* positions, const Execution& execution)
{
  std::vector<SnapCandidate> candidates;
  for (std::size_t s = 0; s < reach.size(); ++s)
  {
    if (snapped[s] && reach[s] > start)
    {
      SnapCandidate c;
      c.Sample = static_cast<Index>(s);
      c.Reach = reach[s];
      candidates.push_back(c);
    }
  }
  execution.Run(0, static_cast<Index>(candidates.size()), [&](Index b, Index e) {
    for (Index k = b; k < e; ++k)
    {
      SnapCandidate& c = candidates[k];
      const Index s = c.Sample;
      c.Radius = MinimaxCentre(xyz, members + memberStart[s], memberStart[s + 1] - memberStart[s],
        positions + 3 * s, c.Centre);
    }
  });
  return candidates;
}

double SnapBound(double start, const std::vector<std::pair<double, double>>& reachAndRadius)
{
  double limit = start;
  for (const auto& candidate : reachAndRadius)
  {
    if (!(candidate.first > limit))
    {
      break;
    }
    limit = std::max(limit, candidate.second);
  }
  return limit;
}

void MoveSnappedSamples(Coordinates xyz, const std::vector<Index>& memberStart,
  const Index* members, const std::vector<SnapCandidate>& candidates, double limit,
  double* positions, const Execution& execution)
{
  execution.Run(0, static_cast<Index>(candidates.size()), [&](Index b, Index e) {
    for (Index k = b; k < e; ++k)
    {
      const SnapCandidate& c = candidates[k];
      if (c.Reach > limit)
      {
        const Index s = c.Sample;
        MoveWithinBound(xyz, members + memberStart[s], memberStart[s + 1] - memberStart[s],
          c.Centre, limit, positions + 3 * s);
      }
    }
  });
}

void BoundSnappedHoles(Coordinates xyz, const std::vector<Index>& memberStart, const Index* members,
  const std::vector<char>& snapped, double* positions, const Execution& execution)
{
  const std::vector<double> reach = SnappedReaches(xyz, memberStart, members, positions, execution);
  double limit = FixedReach(reach, snapped); // squared largest hole so far
  // Only those that reach past the fixed samples can move or raise the bound:
  // widest first (ties: lower index), sorted in parallel.
  std::vector<RankedValue> ranked;
  for (std::size_t s = 0; s < reach.size(); ++s)
  {
    if (snapped[s] && reach[s] > limit)
    {
      ranked.emplace_back(reach[s], static_cast<Index>(s));
    }
  }
  SortRanked(ranked, execution);
  // Widest first, in batches whose centres are computed in parallel (the
  // bound takes them in order, up to the first cluster within it: the
  // others need no centre).
  const Index batch = 256;
  std::vector<SnapCandidate> moves;
  for (std::size_t begin = 0; begin < ranked.size(); begin += batch)
  {
    if (!(ranked[begin].first > limit))
    {
      break;
    }
    const std::size_t end = std::min(ranked.size(), begin + static_cast<std::size_t>(batch));
    std::vector<SnapCandidate> part(end - begin);
    execution.Run(0, static_cast<Index>(part.size()), [&](Index b, Index e) {
      for (Index k = b; k < e; ++k)
      {
        SnapCandidate& c = part[k];
        c.Sample = ranked[begin + static_cast<std::size_t>(k)].second;
        c.Reach = reach[c.Sample];
        c.Radius = MinimaxCentre(xyz, members + memberStart[c.Sample],
          memberStart[c.Sample + 1] - memberStart[c.Sample], positions + 3 * c.Sample, c.Centre);
      }
    });
    bool done = false;
    for (const SnapCandidate& c : part)
    {
      if (!(c.Reach > limit))
      {
        done = true;
        break;
      }
      limit = std::max(limit, c.Radius);
      moves.push_back(c);
    }
    if (done)
    {
      break;
    }
  }
  // Each of those moves from its input point towards its centre only as far
  // as the bound needs.
  MoveSnappedSamples(xyz, memberStart, members, moves, limit, positions, execution);
}
} // namespace asmcore
