// SPDX-License-Identifier: BSD-3-Clause
#include "CanonicalOrder.h"

#include <algorithm>
#include <cstring>

namespace asmcore
{
namespace
{
// The hash of a position that orders a cell's points: each coordinate's
// bits (-0 as +0) times an odd constant, so that every bit reaches the
// leading bits, which pick the bucket.
inline std::uint64_t OrderHash(const double* p)
{
  std::uint64_t bits[3];
  const double q[3] = { p[0] + 0.0, p[1] + 0.0, p[2] + 0.0 };
  std::memcpy(bits, q, sizeof(bits));
  const std::uint64_t h = bits[0] * 0x9E3779B97F4A7C15ULL ^ bits[1] * 0xC2B2AE3D27D4EB4FULL ^
    bits[2] * 0x165667B19E3779F9ULL;
  return h ^ (h >> 31);
}
} // namespace

void CanonicalOrder(const double* xyz, const Index* ids, Index n, std::vector<Index>& order,
  CanonicalOrderScratch& scratch)
{
  order.resize(static_cast<std::size_t>(n));
  if (n < 2)
  {
    std::fill(order.begin(), order.end(), Index(0));
    return;
  }
  std::vector<std::uint64_t>& hash = scratch.Hash;
  std::vector<std::uint64_t>& sorted = scratch.Sorted;
  hash.resize(static_cast<std::size_t>(n));
  sorted.resize(static_cast<std::size_t>(n));
  // Buckets: the hash's leading `bits` bits, about one point per bucket.
  int bits = 1;
  while ((Index(1) << bits) < n && bits < 24)
  {
    ++bits;
  }
  const int shift = 64 - bits;
  std::vector<std::uint32_t>& count = scratch.Count;
  count.assign((std::size_t(1) << bits) + 1, 0);
  for (Index i = 0; i < n; ++i)
  {
    hash[i] = OrderHash(xyz + 3 * i);
    ++count[(hash[i] >> shift) + 1];
  }
  for (std::size_t b = 1; b < count.size(); ++b)
  {
    count[b] += count[b - 1];
  }
  for (Index i = 0; i < n; ++i)
  {
    const std::uint32_t at = count[hash[i] >> shift]++;
    order[at] = i;
    sorted[at] = hash[i];
  }
  // Within a bucket (a point or two), by the whole key (hash, x, y, z, id):
  // an insertion sort that stops at the bucket's start.
  auto before = [&](Index a, Index b) {
    if (hash[a] != hash[b])
    {
      return hash[a] < hash[b];
    }
    return PositionThenIdBefore(xyz + 3 * a, ids[a], xyz + 3 * b, ids[b]);
  };
  for (Index i = 1; i < n; ++i)
  {
    if ((sorted[i - 1] >> shift) != (sorted[i] >> shift) || sorted[i - 1] < sorted[i])
    {
      continue; // another bucket, or already after its predecessor
    }
    const Index moving = order[i];
    const std::uint64_t key = sorted[i];
    Index j = i;
    for (; j > 0 && (sorted[j - 1] >> shift) == (key >> shift) && before(moving, order[j - 1]); --j)
    {
      order[j] = order[j - 1];
      sorted[j] = sorted[j - 1];
    }
    order[j] = moving;
    sorted[j] = key;
  }
}

void CanonicalCell::Gather(Coordinates xyz, IdView points)
{
  const auto n = static_cast<Index>(points.size());
  this->Gathered.resize(static_cast<std::size_t>(3 * n));
  this->GatheredIds.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i)
  {
    if (i + 8 < n)
    {
      Prefetch(xyz.Address(points[i + 8])); // the points are scattered in memory
    }
    this->GatheredIds[i] = points[i];
    xyz.Get(this->GatheredIds[i], this->Gathered.data() + 3 * i);
  }
  CanonicalOrder(this->Gathered.data(), this->GatheredIds.data(), n, this->Order, this->Scratch);
  this->Xyz.resize(static_cast<std::size_t>(3 * n));
  this->Ids.resize(static_cast<std::size_t>(n));
  for (Index k = 0; k < n; ++k)
  {
    const Index i = this->Order[k];
    CopyPoint(this->Gathered.data() + 3 * i, this->Xyz.data() + 3 * k);
    this->Ids[k] = this->GatheredIds[i];
  }
}
} // namespace asmcore
