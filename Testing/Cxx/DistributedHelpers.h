// SPDX-License-Identifier: BSD-3-Clause
// Test helper for the distributed hooks: what the processes of a distributed
// run agree on before simplifying, computed here from the whole cloud.
#ifndef asm_test_DistributedHelpers_h
#define asm_test_DistributedHelpers_h

#include "Core/CanonicalOrder.h"
#include "Core/CellFrame.h"
#include "Core/Grid.h"
#include "Core/Simplify.h"
#include "TestHelpers.h"

#include <algorithm>
#include <array>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
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
    asmcore::CanonicalCell local; // (the core's order within a cell)
    for (asmcore::Index c = 0; c < this->Grid.NumberOfCells(); ++c)
    {
      this->Capacity.push_back(this->Grid.CellSizeOf(c));
      local.Gather(cloud.data(), this->Grid.CellIds(c));
      this->Variation.push_back(
        asmcore::ComputeCellFrame(local.Xyz.data(), asmcore::IdView::Identity(local.Ids.size()))
          .SurfaceVariation());
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
// A collective among `parties` threads (MPI's, for slabs run at once): each
// party's values wait for the others', and every party gets `combine` of
// all of them (in party order).
template <typename T>
class ThreadCollective
{
public:
  using Combine = std::function<std::vector<T>(const std::vector<std::vector<T>>&)>;
  ThreadCollective(int parties, Combine combine)
    : Parties(parties)
    , Parts(static_cast<std::size_t>(parties))
    , Join(std::move(combine))
  {
  }
  void Meet(int party, std::vector<T>& values)
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    const long long generation = this->Generation;
    this->Parts[party] = values;
    if (++this->Arrived == this->Parties)
    {
      this->Result = this->Join(this->Parts);
      this->Arrived = 0;
      ++this->Generation;
      this->Done.notify_all();
    }
    else
    {
      this->Done.wait(lock, [&] { return this->Generation != generation; });
    }
    values = this->Result;
    ++this->Calls;
  }
  int Calls = 0;

private:
  std::mutex Mutex;
  std::condition_variable Done;
  int Parties;
  int Arrived = 0;
  long long Generation = 0;
  std::vector<std::vector<T>> Parts;
  std::vector<T> Result;
  Combine Join;
};

// The sums' all-reduce, the hole filling's all-gather.
inline std::vector<long long> SumOf(const std::vector<std::vector<long long>>& parts)
{
  std::vector<long long> total(parts[0].size(), 0);
  for (const auto& part : parts)
  {
    for (std::size_t k = 0; k < total.size(); ++k)
    {
      total[k] += part[k];
    }
  }
  return total;
}

inline std::vector<double> Concatenated(const std::vector<std::vector<double>>& parts)
{
  std::vector<double> all;
  for (const auto& part : parts)
  {
    all.insert(all.end(), part.begin(), part.end());
  }
  return all;
}
} // namespace asmtest

#endif
