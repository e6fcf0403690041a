// SPDX-License-Identifier: BSD-3-Clause
// Distributed runs of the feature-preserving mode (vtkASMDistributed.h):
// the halo width, the mode's budget rule, and every cell's budget on every
// process (halo cells are simplified too, as context, with their true
// budgets; only the owned cells' samples are output).
#include "vtkASMDistributed.h"

#include "Core/Budget.h"
#include "Core/FeatureSimplify.h"
#include "Core/Lloyd.h"
#include "Core/SnappedHoles.h"

#include "vtkMultiProcessController.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace asmvtk
{
int HaloRingsFor(const asmcore::SimplifyParameters& parameters)
{
  if (parameters.Mode == asmcore::SimplifyMode::Paper)
  {
    return HaloRings;
  }
  return std::max(HaloRings, asmcore::InfluenceRingsPerStep(parameters) + FeatureHaloMargin);
}

CollectiveChannel::CollectiveChannel(const Communication& comm)
  : Comm(comm)
{
}

std::vector<std::vector<double>> CollectiveChannel::Round(
  Kind kind, const std::vector<double>& payload, bool* exchange)
{
  // Each process sends (kind, length, payload); the gathered values are
  // walked in process order.
  std::vector<double> mine{ static_cast<double>(kind), static_cast<double>(payload.size()) };
  mine.insert(mine.end(), payload.begin(), payload.end());
  const std::vector<double> all = this->Comm.AllGather(mine);
  std::vector<std::vector<double>> payloads;
  if (exchange)
  {
    *exchange = false;
  }
  for (std::size_t at = 0; at + 1 < all.size();)
  {
    const auto length = static_cast<std::size_t>(all[at + 1]);
    if (all[at] != static_cast<double>(Done))
    {
      payloads.emplace_back(all.begin() + static_cast<std::ptrdiff_t>(at + 2),
        all.begin() + static_cast<std::ptrdiff_t>(at + 2 + length));
      if (exchange && all[at] == static_cast<double>(Exchange))
      {
        *exchange = true;
      }
    }
    at += 2 + length;
  }
  return payloads;
}

std::function<void(std::vector<long long>&)> CollectiveChannel::SumHook()
{
  return [this](std::vector<long long>& values) {
    // Each value as two exact 32-bit halves (sums of fixed-point terms pass
    // 2^53).
    std::vector<double> halves;
    for (long long v : values)
    {
      asmcore::AppendAsDoubles(halves, static_cast<std::uint64_t>(v));
    }
    std::vector<unsigned long long> sum(values.size(), 0);
    for (const std::vector<double>& other : this->Round(Data, halves))
    {
      for (std::size_t k = 0; k < values.size() && 2 * k + 1 < other.size(); ++k)
      {
        sum[k] += asmcore::FromDoubles(other.data() + 2 * k);
      }
    }
    for (std::size_t k = 0; k < values.size(); ++k)
    {
      values[k] = static_cast<long long>(sum[k]); // (two's complement: exact)
    }
  };
}

std::function<void(std::vector<double>&)> CollectiveChannel::GatherHook()
{
  return [this](std::vector<double>& values) {
    std::vector<double> all;
    for (const std::vector<double>& other : this->Round(Data, values))
    {
      all.insert(all.end(), other.begin(), other.end());
    }
    values.swap(all);
  };
}

std::function<void(
  const std::vector<std::uint64_t>&, const std::vector<Index>&, std::vector<double>&)>
CollectiveChannel::ShareHook(const SimplifyShare& share, int rings)
{
  return [this, &share, rings](const std::vector<std::uint64_t>& keys,
           const std::vector<Index>& start, std::vector<double>& positions) {
    // Owned cells to the processes whose halo holds them: the owners of
    // the cells within `rings` (cell key halves, sample count, positions).
    const asmcore::CellPartition& partition = share.Partition;
    std::vector<asmcore::PointArray<double>> send(static_cast<std::size_t>(this->Comm.Size()));
    for (std::size_t c = 0; c < keys.size(); ++c)
    {
      if (!share.Owns(keys[c]))
      {
        continue;
      }
      std::int64_t ijk[3];
      share.Grid.Unpack(keys[c], ijk);
      const Index n = start[c + 1] - start[c];
      partition.ForEachOwnerNear(ijk, rings, [&](int q) {
        if (q == this->Comm.Rank())
        {
          return;
        }
        asmcore::PointArray<double>& out = send[static_cast<std::size_t>(q)];
        asmcore::AppendAsDoubles(out, keys[c]);
        out.push_back(static_cast<double>(n));
        out.insert(
          out.end(), positions.begin() + 3 * start[c], positions.begin() + 3 * start[c + 1]);
      });
    }
    this->Round(Exchange, {}); // (finished processes take part in the exchange too)
    const asmcore::PointArray<double> received = this->Comm.Exchange(send);
    for (std::size_t at = 0; at + 2 < received.size();)
    {
      const std::uint64_t key = asmcore::FromDoubles(received.data() + at);
      const auto n = static_cast<Index>(received[at + 2]);
      at += 3;
      const auto it = std::lower_bound(keys.begin(), keys.end(), key);
      if (it != keys.end() && *it == key)
      {
        const auto c = static_cast<std::size_t>(it - keys.begin());
        if (start[c + 1] - start[c] == n) // (always: the same budgets and moves)
        {
          std::copy_n(received.begin() + static_cast<std::ptrdiff_t>(at), 3 * n,
            positions.begin() + 3 * start[c]);
        }
      }
      at += static_cast<std::size_t>(3 * n);
    }
  };
}

void CollectiveChannel::Finish()
{
  for (;;)
  {
    bool exchange = false;
    if (this->Round(Done, {}, &exchange).empty())
    {
      break;
    }
    if (exchange)
    {
      std::vector<asmcore::PointArray<double>> nothing(static_cast<std::size_t>(this->Comm.Size()));
      this->Comm.Exchange(nothing);
    }
  }
}

std::vector<Index> ApportionCells(const std::vector<Index>& capacity,
  const std::vector<double>& variation, const asmcore::SimplifyParameters& parameters, Index target)
{
  if (parameters.Mode == asmcore::SimplifyMode::Paper)
  {
    return asmcore::ApportionBudget(
      asmcore::CellShares(capacity, variation, parameters), capacity, target);
  }
  // As SimplifyFeaturePreserving's step 3.
  const std::vector<double> share =
    asmcore::CellShares(capacity, variation, parameters, std::max(0.0, parameters.BudgetExponent));
  return asmcore::ApportionWithCoverage(share, capacity, target, parameters.CoverEveryCell);
}

void ShareAllBudgets(const Communication& comm, SimplifyShare& share)
{
  // (key / 2^32, key % 2^32, budget) as doubles: each part is exact.
  std::vector<double> mine;
  mine.reserve(3 * share.OwnedKeys.size());
  for (std::size_t c = 0; c < share.OwnedKeys.size(); ++c)
  {
    asmcore::AppendAsDoubles(mine, share.OwnedKeys[c]);
    mine.push_back(static_cast<double>(share.Budgets[c]));
  }
  const std::vector<double> all = comm.AllGather(mine);
  const std::size_t cells = all.size() / 3;
  std::vector<std::pair<std::uint64_t, Index>> table(cells);
  for (std::size_t c = 0; c < cells; ++c)
  {
    table[c] = { asmcore::FromDoubles(all.data() + 3 * c), static_cast<Index>(all[3 * c + 2]) };
  }
  std::sort(table.begin(), table.end());
  share.AllKeys.resize(cells);
  share.AllBudgets.resize(cells);
  for (std::size_t c = 0; c < cells; ++c)
  {
    share.AllKeys[c] = table[c].first;
    share.AllBudgets[c] = table[c].second;
  }
}

Index SimplifyShare::TrueBudgetOf(std::uint64_t key) const
{
  const auto it = std::lower_bound(this->AllKeys.begin(), this->AllKeys.end(), key);
  return (it != this->AllKeys.end() && *it == key)
    ? this->AllBudgets[static_cast<std::size_t>(it - this->AllKeys.begin())]
    : 0;
}

bool SimplifyShare::Owns(std::uint64_t key) const
{
  return std::binary_search(this->OwnedKeys.begin(), this->OwnedKeys.end(), key);
}

void BoundSnappedHolesAcross(const Communication& comm, asmcore::Coordinates xyz,
  asmcore::SimplifyResult& result, const asmcore::Execution& execution)
{
  // This process's samples as BoundSnappedHoles takes them (the core laid
  // out each sample's members after the previous one's).
  const auto count = static_cast<Index>(result.Samples.size());
  std::vector<Index> memberStart(static_cast<std::size_t>(count) + 1, 0);
  std::vector<char> snapped(static_cast<std::size_t>(count), 0);
  std::vector<double> positions(static_cast<std::size_t>(3 * count));
  for (Index s = 0; s < count; ++s)
  {
    const asmcore::Sample& sample = result.Samples[s];
    memberStart[s] = sample.MemberBegin;
    memberStart[s + 1] = sample.MemberBegin + sample.ClusterSize;
    // (Key samples stay on their extreme point; a one-point cluster is its point.)
    snapped[s] = !sample.Key && sample.ClusterSize > 1;
    std::copy_n(sample.Position, 3, positions.data() + 3 * s);
  }
  const Index* members = result.Members.data();
  const std::vector<double> reach =
    asmcore::SnappedReaches(xyz, memberStart, members, positions.data(), execution);
  const double start = comm.Max(asmcore::FixedReach(reach, snapped));
  const std::vector<asmcore::SnapCandidate> mine = asmcore::SnapCandidates(
    xyz, memberStart, members, snapped, reach, start, positions.data(), execution);
  // Every process's candidates: (reach, radius, position).
  std::vector<double> values;
  values.reserve(5 * mine.size());
  for (const asmcore::SnapCandidate& c : mine)
  {
    const double* p = positions.data() + 3 * c.Sample;
    values.insert(values.end(), { c.Reach, c.Radius, p[0], p[1], p[2] });
  }
  const std::vector<double> all = comm.AllGather(values);
  std::vector<std::array<double, 5>> sorted(all.size() / 5);
  for (std::size_t k = 0; k < sorted.size(); ++k)
  {
    std::copy_n(all.data() + 5 * k, 5, sorted[k].data());
  }
  // Widest first; ties by position (the same order on every process).
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return a[0] > b[0] ||
      (a[0] == b[0] &&
        std::lexicographical_compare(a.begin() + 2, a.end(), b.begin() + 2, b.end()));
  });
  std::vector<std::pair<double, double>> reachAndRadius(sorted.size());
  for (std::size_t k = 0; k < sorted.size(); ++k)
  {
    reachAndRadius[k] = { sorted[k][0], sorted[k][1] };
  }
  const double limit = asmcore::SnapBound(start, reachAndRadius);
  asmcore::MoveSnappedSamples(xyz, memberStart, members, mine, limit, positions.data(), execution);
  for (const asmcore::SnapCandidate& c : mine)
  {
    std::copy_n(positions.data() + 3 * c.Sample, 3, result.Samples[c.Sample].Position);
  }
}
} // namespace asmvtk
