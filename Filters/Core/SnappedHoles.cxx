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

void BoundSnappedHoles(Coordinates xyz, const std::vector<Index>& memberStart, const Index* members,
  const std::vector<char>& snapped, double* positions, const Execution& execution)
{
  const Index count = static_cast<Index>(snapped.size());
  auto membersOf = [&](Index s) { return members + memberStart[s]; };
  auto sizeOf = [&](Index s) { return memberStart[s + 1] - memberStart[s]; };
  std::vector<double> reach(static_cast<std::size_t>(count), 0.0); // squared, from the sample
  execution.Run(0, count, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      reach[s] = SquaredReach(xyz, membersOf(s), sizeOf(s), positions + 3 * s);
    }
  });
  double limit = 0.0; // squared largest hole so far
  for (Index s = 0; s < count; ++s)
  {
    if (!snapped[s])
    {
      limit = std::max(limit, reach[s]);
    }
  }
  // Only those that reach past the fixed samples can move or raise the bound:
  // widest first (ties: lower index), sorted in parallel.
  std::vector<RankedValue> ranked;
  for (Index s = 0; s < count; ++s)
  {
    if (snapped[s] && reach[s] > limit)
    {
      ranked.emplace_back(reach[s], s);
    }
  }
  SortRanked(ranked, execution);
  std::vector<Index> order(ranked.size());
  for (std::size_t k = 0; k < ranked.size(); ++k)
  {
    order[k] = ranked[k].second;
  }
  // Widest first, in batches whose centres are computed in parallel; the
  // bound takes them in order, up to the first cluster within it.
  const Index batch = 256;
  std::vector<double> centre(static_cast<std::size_t>(3 * batch)), radius(static_cast<std::size_t>(batch));
  std::vector<std::pair<Index, std::array<double, 3>>> moves;
  bool done = false;
  for (Index begin = 0; begin < static_cast<Index>(order.size()) && !done; begin += batch)
  {
    const Index end = std::min<Index>(static_cast<Index>(order.size()), begin + batch);
    if (!(reach[order[begin]] > limit))
    {
      break;
    }
    execution.Run(begin, end, [&](Index b, Index e) {
      for (Index k = b; k < e; ++k)
      {
        const Index s = order[k];
        radius[k - begin] = MinimaxCentre(
          xyz, membersOf(s), sizeOf(s), positions + 3 * s, centre.data() + 3 * (k - begin));
      }
    });
    for (Index k = begin; k < end; ++k)
    {
      if (!(reach[order[k]] > limit))
      {
        done = true;
        break;
      }
      limit = std::max(limit, radius[k - begin]);
      const double* c = centre.data() + 3 * (k - begin);
      moves.push_back({ order[k], { c[0], c[1], c[2] } });
    }
  }
  // Each of those moves from its input point towards its centre only as far
  // as the bound needs (the reach along the segment is convex: bisection).
  execution.Run(0, static_cast<Index>(moves.size()), [&](Index b, Index e) {
    for (Index k = b; k < e; ++k)
    {
      const Index s = moves[k].first;
      if (!(reach[s] > limit))
      {
        continue;
      }
      double* position = positions + 3 * s;
      const double* from = position;
      const double* to = moves[k].second.data();
      auto at = [&](double t, double p[3]) {
        for (int a = 0; a < 3; ++a)
        {
          p[a] = from[a] + t * (to[a] - from[a]);
        }
      };
      auto reachAt = [&](double t) {
        double p[3];
        at(t, p);
        return SquaredReach(xyz, membersOf(s), sizeOf(s), p);
      };
      double lo = 0.0, hi = 1.0; // reach above the bound at lo, within it at hi
      for (int step = 0; step < 20; ++step)
      {
        const double mid = 0.5 * (lo + hi);
        (reachAt(mid) > limit ? lo : hi) = mid;
      }
      double p[3];
      at(hi, p);
      std::copy_n(p, 3, position);
    }
  });
}
} // namespace asmcore
