// SPDX-License-Identifier: BSD-3-Clause
// SelectFirst (the median splits' selection): the same first entries as a
// full sort, with and without its fallback, and a bounded amount of work on
// an input built to defeat its median-of-three pivot.
#include "Core/Quickselect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <random>
#include <string>
#include <vector>

using asmcore::Index;

namespace
{
struct Entry
{
  int Value;
  Index Id;
};

bool ByValueThenId(const Entry& x, const Entry& y)
{
  return x.Value < y.Value || (x.Value == y.Value && x.Id < y.Id);
}

// Whether e[0, nth) holds exactly the nth first entries of e by
// ByValueThenId (the entries being distinct by Id).
bool SelectsFirst(std::vector<Entry> e, const std::vector<Entry>& sortedAll, Index nth)
{
  std::sort(e.begin(), e.begin() + nth, ByValueThenId);
  for (Index i = 0; i < nth; ++i)
  {
    if (e[i].Id != sortedAll[i].Id)
    {
      return false;
    }
  }
  return true;
}

// McIlroy's adversary ("A Killer Adversary for Quicksort", 1999): values
// are decided while the algorithm compares. Every entry starts as "gas"
// (above every decided value); when two gas entries meet, the one last
// seen as a pivot candidate is frozen at the next lowest value, so the
// pivots end up among the smallest entries.
struct Adversary
{
  std::vector<int> Value;
  int Gas;
  int Solid = 0;
  Index Candidate = 0;
  long long Comparisons = 0;

  explicit Adversary(Index n)
    : Value(static_cast<std::size_t>(n), static_cast<int>(n))
    , Gas(static_cast<int>(n))
  {
  }

  bool Before(const Entry& x, const Entry& y)
  {
    ++this->Comparisons;
    if (this->Value[x.Id] == this->Gas && this->Value[y.Id] == this->Gas)
    {
      this->Value[x.Id == this->Candidate ? x.Id : y.Id] = this->Solid++;
    }
    if (this->Value[x.Id] == this->Gas)
    {
      this->Candidate = x.Id;
    }
    else if (this->Value[y.Id] == this->Gas)
    {
      this->Candidate = y.Id;
    }
    return this->Value[x.Id] < this->Value[y.Id];
  }
};

// The adversary's comparisons for SelectFirst(n / 2) of n entries, and the
// values it decided (the entries still gas keep the value n).
long long AdversaryRun(Index n, int maxRounds, bool& fellBack, std::vector<int>& values)
{
  std::vector<Entry> e(static_cast<std::size_t>(n)), tmp(e.size());
  for (Index i = 0; i < n; ++i)
  {
    e[i] = Entry{ 0, i };
  }
  Adversary adversary(n);
  fellBack = asmcore::SelectFirst(
    e.data(), n, n / 2,
    [&adversary](const Entry& x, const Entry& y) { return adversary.Before(x, y); }, tmp.data(),
    maxRounds);
  values = adversary.Value;
  return adversary.Comparisons;
}
} // namespace

TEST(Quickselect, SelectFirstMatchesFullSort)
{
  std::mt19937_64 random(11);
  for (const Index n : { 1, 2, 16, 17, 33, 100, 1000 })
  {
    for (const int range : { 3, 1 << 20 }) // many ties, then few
    {
      std::uniform_int_distribution<int> value(0, range);
      std::vector<Entry> input(static_cast<std::size_t>(n));
      for (Index i = 0; i < n; ++i)
      {
        input[i] = Entry{ value(random), i };
      }
      std::shuffle(input.begin(), input.end(), random);
      std::vector<Entry> sorted = input;
      std::sort(sorted.begin(), sorted.end(), ByValueThenId);
      for (const Index nth : { Index(0), Index(1), n / 3, n / 2, n - 1, n })
      {
        for (const int maxRounds : { 0, 1, 64 })
        {
          SCOPED_TRACE("n " + std::to_string(n) + " range " + std::to_string(range) + " nth " +
            std::to_string(nth) + " maxRounds " + std::to_string(maxRounds));
          std::vector<Entry> e = input, tmp(input.size());
          asmcore::SelectFirst(e.data(), n, nth, ByValueThenId, tmp.data(), maxRounds);
          EXPECT_TRUE(SelectsFirst(e, sorted, nth));
        }
      }
    }
  }
}

TEST(Quickselect, FallbackBoundsTheWorkOnAKillerInput)
{
  const Index n = 4000;
  bool fellBack = false;
  std::vector<int> values;
  // Without the fallback the adversary makes the selection quadratic: each
  // round removes a handful of entries.
  const long long unbounded = AdversaryRun(n, INT_MAX, fellBack, values);
  EXPECT_FALSE(fellBack);
  EXPECT_GT(unbounded, static_cast<long long>(n) * n / 16);
  // With it, at most 64 partitions of at most n entries, then introselect
  // (346 k comparisons here, against 6.0 M).
  const long long bounded = AdversaryRun(n, 64, fellBack, values);
  EXPECT_TRUE(fellBack);
  EXPECT_LT(bounded, 128LL * n);

  // The adversary's values as a fixed input: the selection takes the same
  // path (every answer it gave holds for them), falls back, and is right.
  std::vector<Entry> e(static_cast<std::size_t>(n)), tmp(e.size());
  for (Index i = 0; i < n; ++i)
  {
    e[i] = Entry{ values[i], i };
  }
  std::vector<Entry> sorted = e;
  std::sort(sorted.begin(), sorted.end(), ByValueThenId);
  EXPECT_TRUE(asmcore::SelectFirst(e.data(), n, n / 2, ByValueThenId, tmp.data()));
  EXPECT_TRUE(SelectsFirst(e, sorted, n / 2));
}
