// SPDX-License-Identifier: BSD-3-Clause
#include "Budget.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace asmcore
{
namespace
{
// Largest-remainder apportionment of `total` among `cells` by `share`, where
// no cell's quota reaches its capacity. Adds to `budget`.
void LargestRemainder(const std::vector<Index>& cells, const std::vector<double>& share,
  const std::vector<Index>& capacity, Index total, std::vector<Index>& budget)
{
  double sum = 0.0;
  for (Index c : cells)
  {
    sum += share[c];
  }
  std::vector<std::pair<double, Index>> remainders; // (-fraction, cell)
  remainders.reserve(cells.size());
  Index given = 0;
  for (Index c : cells)
  {
    const double quota = static_cast<double>(total) * share[c] / sum;
    Index whole = static_cast<Index>(std::floor(quota));
    whole = std::max<Index>(0, std::min(whole, capacity[c] - budget[c]));
    budget[c] += whole;
    given += whole;
    remainders.emplace_back(-(quota - std::floor(quota)), c);
  }
  std::sort(remainders.begin(), remainders.end());
  // Rounding may leave more (or, with floating-point error, fewer) units
  // than cells; cycle until the total is exact.
  Index left = total - given;
  while (left > 0)
  {
    bool progress = false;
    for (const auto& r : remainders)
    {
      if (left == 0)
      {
        break;
      }
      if (budget[r.second] < capacity[r.second])
      {
        ++budget[r.second];
        --left;
        progress = true;
      }
    }
    if (!progress)
    {
      break;
    }
  }
  for (auto it = remainders.rbegin(); left < 0 && it != remainders.rend(); ++it)
  {
    if (budget[it->second] > 0)
    {
      --budget[it->second];
      ++left;
    }
  }
}
} // namespace

std::vector<Index> ApportionBudget(
  const std::vector<double>& share, const std::vector<Index>& capacity, Index total)
{
  const std::size_t n = capacity.size();
  std::vector<Index> budget(n, 0);
  const Index room = std::accumulate(capacity.begin(), capacity.end(), Index(0));
  Index remaining = std::max<Index>(0, std::min(total, room));

  std::vector<Index> active;
  std::vector<Index> idle; // zero share: served last
  for (std::size_t c = 0; c < n; ++c)
  {
    if (capacity[c] <= 0)
    {
      continue;
    }
    (share[c] > 0.0 ? active : idle).push_back(static_cast<Index>(c));
  }
  // Fix the cells whose quota reaches their capacity, and share again.
  while (remaining > 0 && !active.empty())
  {
    double sum = 0.0;
    for (Index c : active)
    {
      sum += share[c];
    }
    std::vector<Index> next;
    next.reserve(active.size());
    Index fixed = 0;
    for (Index c : active)
    {
      if (static_cast<double>(remaining) * share[c] / sum >= static_cast<double>(capacity[c]))
      {
        budget[c] = capacity[c];
        fixed += capacity[c];
      }
      else
      {
        next.push_back(c);
      }
    }
    if (fixed == 0)
    {
      LargestRemainder(active, share, capacity, remaining, budget);
      remaining = 0;
      break;
    }
    remaining -= fixed;
    active.swap(next);
  }
  // Only when every cell with a share is full: the idle cells, in order.
  for (Index c : idle)
  {
    const Index take = std::min(remaining, capacity[c]);
    budget[c] += take;
    remaining -= take;
  }
  return budget;
}

std::vector<Index> ApportionWithCoverage(
  const std::vector<double>& share, const std::vector<Index>& capacity, Index total, bool cover)
{
  if (!cover)
  {
    return ApportionBudget(share, capacity, total);
  }
  const std::size_t n = capacity.size();
  std::vector<Index> occupied;
  for (std::size_t c = 0; c < n; ++c)
  {
    if (capacity[c] > 0)
    {
      occupied.push_back(static_cast<Index>(c));
    }
  }
  std::vector<Index> budget(n, 0);
  if (total < static_cast<Index>(occupied.size()))
  {
    // Not enough for every cell: the cells of largest share.
    std::stable_sort(
      occupied.begin(), occupied.end(), [&](Index a, Index b) { return share[a] > share[b]; });
    for (Index i = 0; i < std::max<Index>(0, total); ++i)
    {
      budget[occupied[i]] = 1;
    }
    return budget;
  }
  std::vector<Index> rest(capacity);
  for (Index c : occupied)
  {
    rest[c] -= 1;
  }
  budget = ApportionBudget(share, rest, total - static_cast<Index>(occupied.size()));
  for (Index c : occupied)
  {
    budget[c] += 1;
  }
  return budget;
}
} // namespace asmcore
