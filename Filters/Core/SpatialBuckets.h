// SPDX-License-Identifier: BSD-3-Clause
/**
 * The spatial splits of the k-d tree build (NeighborsBuild.cxx): a box cut
 * into 2^k buckets that nest as binary midpoint splits of its longest side
 * (SplitPlan), and the ranges, bounds and smallest ids of the points that
 * fall into each bucket (BucketSet). Private to the build.
 */
#ifndef asm_core_SpatialBuckets_h
#define asm_core_SpatialBuckets_h

#include "Common.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace asmcore
{
namespace buckets
{
// A spatial split of a box into 2^Used buckets: a grid whose cells are
// what halving the longest side Used times gives, so that the buckets nest
// as binary midpoint splits and listing the cells by their interleaved
// (Morton) index lists every split's halves as contiguous ranges. Bit t of
// a bucket index (t = 0 the most significant) splits along Sequence[t].
struct SplitPlan
{
  static constexpr int MostBits = 12;
  int Used = 0;
  int Bits[3] = { 0, 0, 0 };
  int Sequence[MostBits] = {};
  double Lo[3] = { 0, 0, 0 };
  double Scale[3] = { 0, 0, 0 };
  double Top[3] = { 0, 0, 0 };
  std::vector<int> Spread[3]; // cell index along an axis -> its bits of the bucket index

  /// A plan of about `n / LeafSize` (at most 2^maxBits) buckets over the
  /// box [lo, hi] (not a point); false if the box is too thin to divide.
  bool Make(const double lo[3], const double hi[3], Index n, Index leafSize, int maxBits)
  {
    double side[3];
    for (int a = 0; a < 3; ++a)
    {
      side[a] = hi[a] - lo[a];
      this->Lo[a] = lo[a];
      this->Bits[a] = 0;
    }
    int want = 1;
    while (want < maxBits && (leafSize << (want + 1)) <= n)
    {
      ++want;
    }
    for (this->Used = 0; this->Used < want; ++this->Used)
    {
      int longest = 0;
      for (int a = 1; a < 3; ++a)
      {
        longest = side[a] > side[longest] ? a : longest;
      }
      this->Sequence[this->Used] = longest;
      ++this->Bits[longest];
      side[longest] *= 0.5;
    }
    for (int a = 0; a < 3; ++a)
    {
      const int cells = 1 << this->Bits[a];
      this->Top[a] = static_cast<double>(cells - 1);
      this->Scale[a] = this->Bits[a] > 0 ? static_cast<double>(cells) / (hi[a] - lo[a]) : 0.0;
      if (!std::isfinite(this->Scale[a]))
      {
        return false;
      }
      this->Spread[a].assign(static_cast<std::size_t>(cells), 0);
      for (int t = 0, k = 0; t < this->Used; ++t)
      {
        if (this->Sequence[t] == a)
        {
          for (int c = 0; c < cells; ++c)
          {
            this->Spread[a][c] |= ((c >> (this->Bits[a] - 1 - k)) & 1) << (this->Used - 1 - t);
          }
          ++k;
        }
      }
    }
    return true;
  }
  int Buckets() const { return 1 << this->Used; }
  /// The bucket of p (inside the box): the cell index grows with each
  /// coordinate, so a split's low half lies strictly below its high half.
  template <typename Real>
  int BucketOf(const Real p[3]) const
  {
    int b = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double cell =
        std::min(this->Top[a], (static_cast<double>(p[a]) - this->Lo[a]) * this->Scale[a]);
      b |= this->Spread[a][static_cast<std::size_t>(cell)];
    }
    return b;
  }
};

// The ranges, bounds and smallest ids of the buckets of a split.
struct BucketSet
{
  std::vector<Index> Start;   // bucket b: entries [Start[b], Start[b + 1])
  std::vector<double> Lo, Hi; // 3 per bucket; meaningful for non-empty buckets
  std::vector<Index> MinId;
  void Reset(int buckets)
  {
    const auto n = static_cast<std::size_t>(buckets);
    this->Start.assign(n + 1, 0);
    this->Lo.assign(3 * n, std::numeric_limits<double>::infinity());
    this->Hi.assign(3 * n, -std::numeric_limits<double>::infinity());
    this->MinId.assign(n, std::numeric_limits<Index>::max());
  }
  Index Count(int b) const { return this->Start[b + 1] - this->Start[b]; }
};

inline Index LargestBucket(const BucketSet& buckets)
{
  Index largest = 0;
  for (std::size_t b = 0; b + 1 < buckets.Start.size(); ++b)
  {
    largest = std::max(largest, buckets.Start[b + 1] - buckets.Start[b]);
  }
  return largest;
}
} // namespace buckets
} // namespace asmcore

#endif
