// SPDX-License-Identifier: BSD-3-Clause
// The hole filling's greedy matching (HoleFillingSteps.h: MatchToGaps).
#include "GroupBy.h"
#include "HoleFillingSteps.h"

#include <algorithm>
#include <limits>

namespace asmcore
{
namespace holes
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();

// The cheapest candidates into the largest gaps, while it pays.
//
// The removal costs are computed ahead, in parallel batches of the next
// candidates, with the limit of the gap at hand: gaps come largest first, so
// a cost that reaches it refuses every later gap too, and a cost below it is
// complete. A move changes one sample's position: a candidate with a member
// in the ring of that sample's cell (touched after its batch) has its cost
// computed again when its turn comes. The decisions are those of a serial
// scan. A distributed run computes its own candidates' costs and gathers
// every process's: every process makes the same decisions.
class GapMatching
{
public:
  GapMatching(const Context& context, const std::vector<Candidate>& candidates)
    : Ctx(context)
    , Candidates(candidates)
    , Count(static_cast<Index>(candidates.size()))
    , Cost(static_cast<std::size_t>(this->Count), Infinity)
    , RingBits(static_cast<std::size_t>(this->Count), 0)
    , HeirStart(static_cast<std::size_t>(this->Count), 0)
    , HeirCount(static_cast<std::size_t>(this->Count), 0)
    , BatchOf(static_cast<std::size_t>(this->Count), -1)
    , Blocked(static_cast<std::size_t>(this->Count), 0)
    , TouchedCell(
        context.Distributed() ? 0 : static_cast<std::size_t>(context.Grid.NumberOfCells()), -1)
  {
    this->GroupMembers();
  }

  std::vector<Move> Run(const std::vector<Gap>& gaps, Index firstBatch);

private:
  void GroupMembers();
  double RemovalCost(Index k, double limit, std::vector<Index>& heirs) const;
  std::uint32_t MemberCells(Index k) const;
  void ComputeCosts(const std::vector<Index>& which, double limit);
  void GatherCosts(const std::vector<Index>& which);
  // Candidate k's heirs (candidate numbers), in Heirs.
  const Index* HeirsBegin(Index k) const { return this->Heirs.data() + this->HeirStart[k]; }
  const Index* HeirsEnd(Index k) const { return this->HeirsBegin(k) + this->HeirCount[k]; }
  bool IsCurrent(Index k) const;
  void MarkTouched(Index k);

  const Context& Ctx;
  const std::vector<Candidate>& Candidates;
  const Index Count;
  std::vector<Index> CandidateOf; // per sample held here (-1: not a candidate)
  std::vector<Index> Start;       // this run's own candidates' members (point slots)
  std::vector<Index> Members;
  std::vector<double> Cost;
  std::vector<std::uint32_t> RingBits; // the cells of the members, as bits of the ring
  // (Heirs and blocks only matter for candidates: by candidate number.)
  // Every computation's heirs are appended to one array (a few per
  // candidate, no small allocation each), HeirStart / HeirCount the last.
  std::vector<Index> Heirs;
  std::vector<Index> HeirStart;
  std::vector<Index> HeirCount;
  std::vector<std::vector<Index>> Scratch; // heirs per entry of `which`, reused
  std::vector<Index> BatchOf;              // the moves made before its cost was computed
  std::vector<char> Blocked;
  // The last move out of each cell's ring: by cell here (serial), by cell
  // key for cells held anywhere (distributed).
  std::vector<Index> TouchedCell;
  KeyTable TouchedKey;
  Index Moves = 0;
};

// The candidate each sample held here is, and the members (point slots) of
// this run's own candidates, by counting sort.
void GapMatching::GroupMembers()
{
  this->CandidateOf.assign(static_cast<std::size_t>(this->Ctx.Samples.Size()), -1);
  for (Index k = 0; k < this->Count; ++k)
  {
    if (this->Candidates[k].Held >= 0)
    {
      this->CandidateOf[this->Candidates[k].Held] = k;
    }
  }
  const PointArray<SampleId>& assign = this->Ctx.Assign;
  GroupBy(
    static_cast<Index>(assign.size()), this->Count,
    [&](Index i) {
      const Index k = assign[i] >= 0 ? this->CandidateOf[assign[i]] : Index(-1);
      return k >= 0 && this->Candidates[k].Local >= 0 ? k : Index(-1);
    },
    [](Index i) { return i; }, this->Start, this->Members, this->Ctx.Exec);
}

// The cost of removing candidate k, and who takes over its members
// (`heirs`). Stops as soon as the cost reaches `limit` (the move is then
// refused whatever the rest would add; `heirs` is complete only below the
// limit). Reads the positions of the samples of its members' rings. Bounded
// work: a sample among more than 4 * LargeCellBudget ring samples is not a
// candidate (moving one of many changes little anyway).
double GapMatching::RemovalCost(Index k, double limit, std::vector<Index>& heirs) const
{
  const SampleSet& samples = this->Ctx.Samples;
  const CellNeighborTable& neighbors = this->Ctx.Neighbors;
  double cost = 0.0;
  heirs.clear();
  const Index s = this->Candidates[k].Local;
  Index ringSamples = 0;
  for (const Index nb : neighbors.RingOf(CellOfSample(samples, s)))
  {
    ringSamples += nb < 0 ? 0 : samples.Start[nb + 1] - samples.Start[nb];
  }
  if (ringSamples > 4 * LargeCellBudget)
  {
    return Infinity;
  }
  for (Index m = this->Start[k]; m < this->Start[k + 1]; ++m)
  {
    const Index slot = this->Members[m];
    double p[3];
    this->Ctx.Xyz.Get(this->Ctx.Grid.PointAt(slot), p);
    double best = Infinity;
    Index heir = -1;
    for (const Index nb : neighbors.RingOf(this->Ctx.CellOfSlot(slot)))
    {
      for (Index t = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && t < samples.Start[nb + 1]; ++t)
      {
        const double d = SquaredDistance(p, samples.Position.data() + 3 * t);
        if (t != s && d < best)
        {
          best = d;
          heir = t;
        }
      }
    }
    cost = std::max(cost, best);
    if (!(cost < limit))
    {
      return cost;
    }
    if (heir >= 0 && std::find(heirs.begin(), heirs.end(), heir) == heirs.end())
    {
      heirs.push_back(heir);
    }
  }
  return cost;
}

// The cells of candidate k's members, as bits of its cell's ring (a member
// joined a sample of its own ring): a move out of the ring of one of them
// changes the candidate's cost.
std::uint32_t GapMatching::MemberCells(Index k) const
{
  const CellGrid& grid = this->Ctx.Grid;
  const CellRef* ring =
    this->Ctx.Neighbors.Of(CellOfSample(this->Ctx.Samples, this->Candidates[k].Local));
  std::uint32_t bits = 0;
  Index cell = -1;
  for (Index m = this->Start[k]; m < this->Start[k + 1]; ++m)
  {
    const Index slot = this->Members[m];
    if (cell >= 0 && slot >= grid.CellStart[cell] && slot < grid.CellStart[cell + 1])
    {
      continue;
    }
    cell = this->Ctx.CellOfSlot(slot);
    int r = 0;
    while (r < 27 && ring[r] != cell)
    {
      ++r;
    }
    bits |= r < 27 ? std::uint32_t(1) << r : (std::uint32_t(1) << 27) - 1;
  }
  return bits;
}

// The costs (with member cells and heirs) of the candidates `which` that
// this run ranks; then, distributed, every process's.
void GapMatching::ComputeCosts(const std::vector<Index>& which, double limit)
{
  if (this->Scratch.size() < which.size())
  {
    this->Scratch.resize(which.size());
  }
  auto range = [&](Index b, Index e) {
    for (Index j = b; j < e; ++j)
    {
      const Index k = which[j];
      if (this->Candidates[k].Local < 0)
      {
        continue;
      }
      this->Cost[k] = this->RemovalCost(k, limit, this->Scratch[j]);
      this->RingBits[k] = this->MemberCells(k);
    }
  };
  // (A candidate at its turn alone: no parallel loop to start.)
  const auto n = static_cast<Index>(which.size());
  if (n < 4)
  {
    range(0, n);
  }
  else
  {
    this->Ctx.Exec.Run(0, n, range);
  }
  for (std::size_t j = 0; j < which.size(); ++j)
  {
    const Index k = which[j];
    this->BatchOf[k] = this->Moves;
    if (this->Candidates[k].Local < 0)
    {
      continue;
    }
    this->HeirStart[k] = static_cast<Index>(this->Heirs.size());
    for (Index t : this->Scratch[j])
    {
      if (this->CandidateOf[t] >= 0)
      {
        this->Heirs.push_back(this->CandidateOf[t]);
      }
    }
    this->HeirCount[k] = static_cast<Index>(this->Heirs.size()) - this->HeirStart[k];
  }
  if (this->Ctx.Distributed())
  {
    this->GatherCosts(which);
  }
}

// Every process's costs of `which`: records of (k, cost, member cells,
// heirs, each heir's candidate number).
void GapMatching::GatherCosts(const std::vector<Index>& which)
{
  std::vector<double> values;
  for (Index k : which)
  {
    if (this->Candidates[k].Local >= 0)
    {
      values.insert(values.end(),
        { static_cast<double>(k), this->Cost[k], static_cast<double>(this->RingBits[k]),
          static_cast<double>(this->HeirCount[k]) });
      for (const Index* h = this->HeirsBegin(k); h != this->HeirsEnd(k); ++h)
      {
        values.push_back(static_cast<double>(*h));
      }
    }
  }
  this->Ctx.Scope.Gather(values);
  for (std::size_t at = 0; at < values.size();)
  {
    const auto k = static_cast<Index>(values[at]);
    this->Cost[k] = values[at + 1];
    this->RingBits[k] = static_cast<std::uint32_t>(values[at + 2]);
    const auto heirs = static_cast<Index>(values[at + 3]);
    at += 4;
    this->HeirStart[k] = static_cast<Index>(this->Heirs.size());
    this->HeirCount[k] = heirs;
    for (Index h = 0; h < heirs; ++h, ++at)
    {
      this->Heirs.push_back(static_cast<Index>(values[at]));
    }
  }
}

// Whether candidate k's cost still holds: no move since its computation out
// of the ring of one of its members' cells.
bool GapMatching::IsCurrent(Index k) const
{
  if (!this->Ctx.Distributed())
  {
    const CellRef* ring =
      this->Ctx.Neighbors.Of(CellOfSample(this->Ctx.Samples, this->Candidates[k].Local));
    for (int r = 0; r < 27; ++r)
    {
      if ((this->RingBits[k] & (std::uint32_t(1) << r)) && ring[r] >= 0 &&
        this->TouchedCell[ring[r]] >= this->BatchOf[k])
      {
        return false;
      }
    }
    return true;
  }
  std::uint64_t ring[27];
  RingKeys(this->Ctx.Grid.Spec, this->Candidates[k].Key.Cell, ring);
  for (int r = 0; r < 27; ++r)
  {
    if (this->RingBits[k] & (std::uint32_t(1) << r))
    {
      const Index touched = ring[r] == NoCell ? -1 : this->TouchedKey.Find(ring[r]);
      if (touched >= 0 && touched >= this->BatchOf[k])
      {
        return false;
      }
    }
  }
  return true;
}

// Candidate k moves now: the ring of its cell is touched.
void GapMatching::MarkTouched(Index k)
{
  if (this->Ctx.Distributed())
  {
    std::uint64_t ring[27];
    RingKeys(this->Ctx.Grid.Spec, this->Candidates[k].Key.Cell, ring);
    for (std::uint64_t key : ring)
    {
      if (key != NoCell)
      {
        this->TouchedKey.Set(key, this->Moves);
      }
    }
    return;
  }
  for (const Index nb :
    this->Ctx.Neighbors.RingOf(CellOfSample(this->Ctx.Samples, this->Candidates[k].Held)))
  {
    if (nb >= 0)
    {
      this->TouchedCell[nb] = this->Moves;
    }
  }
}

// The most crowded candidates are tried in turn for each gap, from the
// largest; a candidate whose removal would leave a hole as large as this gap
// is passed over (it cannot pay for a smaller gap either), and a gap no
// candidate pays for is left for the next one (the smaller gaps still
// shorten the nearest-neighbour distances).
std::vector<Move> GapMatching::Run(const std::vector<Gap>& gaps, Index firstBatch)
{
  SampleSet& samples = this->Ctx.Samples;
  const bool distributed = this->Ctx.Distributed();
  auto isBlocked = [&](Index k) { return this->Blocked[k] != 0; };
  Index computed = 0;                           // candidates [0, computed) have a cost
  Index batch = std::max<Index>(1, firstBatch); // doubles up to 1024 (1: stays)
  Index next = 0;
  std::vector<Move> made;
  made.reserve(gaps.size());
  std::vector<Index> which;
  which.reserve(1024);
  for (std::size_t gap = 0; gap < gaps.size(); ++gap)
  {
    const double limit = gaps[gap].Distance2;
    for (int tries = 0; tries < 8; ++tries)
    {
      while (next < this->Count && isBlocked(next))
      {
        ++next;
      }
      if (next >= this->Count)
      {
        break;
      }
      const Index k = next++;
      if (k >= computed)
      {
        const Index end = std::min(this->Count, k + batch);
        which.clear();
        for (Index j = k; j < end; ++j)
        {
          if (!isBlocked(j))
          {
            which.push_back(j);
          }
        }
        this->ComputeCosts(which, limit);
        computed = end;
        batch = batch > 1 ? std::min<Index>(1024, 2 * batch) : 1;
      }
      if (!this->IsCurrent(k))
      {
        // (Distributed: with the next stale candidates of the batch, one
        // gather for up to 64.)
        which.assign(1, k);
        for (Index j = k + 1; distributed && j < computed && which.size() < 64; ++j)
        {
          if (!isBlocked(j) && !this->IsCurrent(j))
          {
            which.push_back(j);
          }
        }
        this->ComputeCosts(which, limit);
      }
      if (!(this->Cost[k] < limit))
      {
        continue;
      }
      this->Blocked[k] = 1;
      for (const Index* t = this->HeirsBegin(k); t != this->HeirsEnd(k); ++t)
      {
        this->Blocked[*t] = 1;
      }
      const Index s = this->Candidates[k].Held;
      if (s >= 0)
      {
        std::copy_n(gaps[gap].Position, 3, samples.Position.data() + 3 * s);
      }
      this->MarkTouched(k);
      // (A serial run names its moves here: its candidates carry no key.)
      made.emplace_back(
        distributed ? this->Candidates[k].Key : this->Ctx.KeyOf(s, CellOfSample(samples, s)),
        static_cast<Index>(gap));
      ++this->Moves;
      break;
    }
  }
  return made;
}
} // namespace

std::vector<Move> MatchToGaps(const Context& context, const std::vector<Candidate>& candidates,
  const std::vector<Gap>& gaps, Index firstBatch)
{
  if (gaps.empty() || candidates.empty())
  {
    return {};
  }
  GapMatching matching(context, candidates);
  return matching.Run(gaps, firstBatch);
}
} // namespace holes
} // namespace asmcore
