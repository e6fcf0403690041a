// SPDX-License-Identifier: BSD-3-Clause
#include "BlockNeighbors.h"

#include "Grid.h"
#include "Neighbors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
namespace
{
// Fewer queries than this per block on average: one search per query.
constexpr double MinQueriesPerBlock = 3.0;
// The block edge in typical k-th neighbour distances. Measured on 4 M
// points against their ASM simplification (vtkKeyPointError, k = 8): of
// 0.5, 1, 1.5 and 2, 1 was fastest at 1 % and 5 %; at 20 % (about 13
// queries a block) 2 was 6 % faster, hence the widening below.
constexpr double BlockEdge = 1.0;
// Blocks with fewer queries than this on average are made wider (by at
// most MaxWidening), on a surface as many more queries as the square.
constexpr double FullBlock = 32.0;
constexpr double MaxWidening = 2.0;
// Queries whose k-th neighbour distance sets the block edge (the median).
constexpr Index Probes = 255;
// Widening of the radii against rounding (distances are accurate to a few
// units in the last place, relative to themselves).
constexpr double Slack = 1e-9;

// The squared distance as the tree evaluates it (Neighbors.cxx: point minus
// query, per axis, summed in this order): the same numbers, the same ranks.
inline double TreeSquaredDistance(const double* x, const double* q)
{
  const double dx = x[0] - q[0];
  const double dy = x[1] - q[1];
  const double dz = x[2] - q[2];
  return dx * dx + dy * dy + dz * dz;
}

inline bool Finite(const double* p)
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// The k least candidates by (squared distance, position, id), sorted, as
// Neighbors::KNearestByPosition ranks them; `Xyz` holds the candidates'
// points side by side, and Slots where each kept one is among them.
class KBest
{
public:
  void Reset(int k, const double* xyz)
  {
    this->K = k;
    this->Count = 0;
    this->Xyz = xyz;
    this->Ids.resize(static_cast<std::size_t>(k));
    this->D.resize(static_cast<std::size_t>(k));
    this->Slots.resize(static_cast<std::size_t>(k));
  }
  bool Full() const { return this->Count == this->K; }
  double Worst() const { return this->D[static_cast<std::size_t>(this->K - 1)]; }
  bool Accepts(double d, Index id, std::size_t slot) const
  {
    return this->Count < this->K ||
      this->Precedes(d, id, slot, static_cast<std::size_t>(this->K - 1));
  }
  void Add(double d, Index id, std::size_t slot)
  {
    std::size_t i = static_cast<std::size_t>(this->Count < this->K ? this->Count++ : this->K - 1);
    while (i > 0 && this->Precedes(d, id, slot, i - 1))
    {
      this->D[i] = this->D[i - 1];
      this->Ids[i] = this->Ids[i - 1];
      this->Slots[i] = this->Slots[i - 1];
      --i;
    }
    this->D[i] = d;
    this->Ids[i] = id;
    this->Slots[i] = slot;
  }
  std::vector<Index> Ids;
  std::vector<double> D;
  std::vector<std::size_t> Slots; // where each is among the candidates

private:
  // Whether candidate (d, id, slot) ranks before the kept one at i.
  bool Precedes(double d, Index id, std::size_t slot, std::size_t i) const
  {
    if (d != this->D[i])
    {
      return d < this->D[i];
    }
    const double* a = this->Xyz + 3 * slot;
    const double* b = this->Xyz + 3 * this->Slots[i];
    return PositionThenIdBefore(a, id, b, this->Ids[i]);
  }
  int K = 0;
  int Count = 0;
  const double* Xyz = nullptr;
};

// The median k-th neighbour distance of up to Probes queries spread evenly
// over the list (deterministic).
double TypicalKthDistance(const double* q, IdView positions, const Neighbors& surface, int k)
{
  const Index n = static_cast<Index>(positions.size());
  const Index probes = std::min(n, Probes);
  std::vector<double> r;
  std::vector<Index> near;
  std::vector<double> sq;
  for (Index j = 0; j < probes; ++j)
  {
    surface.KNearest(q + 3 * positions[static_cast<std::size_t>(j * n / probes)], k, near, sq);
    if (!sq.empty())
    {
      r.push_back(std::sqrt(sq.back()));
    }
  }
  if (r.empty())
  {
    return 0.0;
  }
  std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
  return r[r.size() / 2];
}

// Buffers of one thread.
struct BlockScratch
{
  std::vector<double> Queries; // the block's points
  std::vector<Index> Near;
  std::vector<double> NearSq;
  std::vector<Index> Candidates;
  std::vector<double> CandidateSq;
  std::vector<double> CandidateXyz;   // side by side
  std::vector<double> CandidateReach; // distance to the block's centroid
  KBest Best;
  std::vector<Index> Ids;
  std::vector<double> Sq;
  std::vector<double> NearXyz; // the answer's points, side by side
};

// The direct search of one query, and its visit.
void SearchOne(Index query, const double* p, const Neighbors& surface, int k,
  const KNearestVisit& visit, BlockScratch& s)
{
  surface.KNearestByPosition(p, k, s.Ids, s.Sq, s.NearXyz);
  visit(KNearestAnswer{ query, p, s.Ids, s.Sq, s.NearXyz.data() });
}

// The queries `slots` of one block: one k-nearest and one radius search
// around their centroid, then each query among the candidates.
void SearchBlock(const double* q, const Index* slots, Index m, const Neighbors& surface, int k,
  const KNearestVisit& visit, BlockScratch& s)
{
  s.Queries.resize(static_cast<std::size_t>(3 * m));
  double c[3] = { 0.0, 0.0, 0.0 };
  for (Index j = 0; j < m; ++j)
  {
    CopyPoint(q + 3 * slots[j], s.Queries.data() + 3 * j);
    for (int a = 0; a < 3; ++a)
    {
      c[a] += s.Queries[static_cast<std::size_t>(3 * j + a)];
    }
  }
  for (double& v : c)
  {
    v /= static_cast<double>(m);
  }
  double spread2 = 0.0;
  for (Index j = 0; j < m; ++j)
  {
    spread2 = std::max(spread2, TreeSquaredDistance(s.Queries.data() + 3 * j, c));
  }
  surface.KNearest(c, k, s.Near, s.NearSq);
  const double reach = s.NearSq.empty()
    ? std::numeric_limits<double>::quiet_NaN()
    : (std::sqrt(s.NearSq.back()) + 2.0 * std::sqrt(spread2)) * (1.0 + Slack);
  if (!std::isfinite(reach))
  {
    // Coordinates near the overflow (a centroid or a distance beyond the
    // largest double): each query on its own.
    for (Index j = 0; j < m; ++j)
    {
      SearchOne(slots[j], s.Queries.data() + 3 * j, surface, k, visit, s);
    }
    return;
  }
  // (Of a point repeated many times, k copies: a query never takes more.)
  surface.RadiusForKNearest(c, reach, k, s.Candidates, s.CandidateSq, s.CandidateXyz);
  const std::size_t count = s.Candidates.size();
  s.CandidateReach.resize(count);
  for (std::size_t j = 0; j < count; ++j)
  {
    s.CandidateReach[j] = std::sqrt(s.CandidateSq[j]);
  }
  for (Index j = 0; j < m; ++j)
  {
    const double* p = s.Queries.data() + 3 * j;
    // A candidate x with |x - c| - |p - c| beyond p's k-th distance is not
    // among p's k nearest; the candidates come sorted by |x - c|.
    const double offset = std::sqrt(TreeSquaredDistance(p, c)) * (1.0 + Slack);
    double cutoff = std::numeric_limits<double>::infinity();
    s.Best.Reset(k, s.CandidateXyz.data());
    for (std::size_t x = 0; x < count && s.CandidateReach[x] - offset <= cutoff; ++x)
    {
      const double d = TreeSquaredDistance(s.CandidateXyz.data() + 3 * x, p);
      const Index id = s.Candidates[x];
      if (s.Best.Accepts(d, id, x))
      {
        s.Best.Add(d, id, x);
        if (s.Best.Full())
        {
          cutoff = std::sqrt(s.Best.Worst()) * (1.0 + Slack);
        }
      }
    }
    if (!s.Best.Full())
    {
      // (Cannot happen: c's own k nearest are candidates. Kept exact anyway.)
      SearchOne(slots[j], p, surface, k, visit, s);
      continue;
    }
    s.NearXyz.resize(static_cast<std::size_t>(3 * k));
    for (std::size_t i = 0; i < static_cast<std::size_t>(k); ++i)
    {
      CopyPoint(s.CandidateXyz.data() + 3 * s.Best.Slots[i], s.NearXyz.data() + 3 * i);
    }
    visit(KNearestAnswer{ slots[j], p, s.Best.Ids, s.Best.D, s.NearXyz.data() });
  }
}
} // namespace

void ForEachKNearest(const double* xyz, IdView ids, const Neighbors& surface, int k,
  const KNearestVisit& visit, const Execution& execution)
{
  ForEachKNearest(
    xyz, ids, surface, k, [&visit]() { return visit; }, execution);
}

void ForEachKNearest(const double* xyz, IdView ids, const Neighbors& surface, int k,
  const KNearestVisitMaker& makeVisit, const Execution& execution)
{
  const Index n = static_cast<Index>(ids.size());
  if (n == 0 || k <= 0 || surface.Empty())
  {
    return;
  }
  // The queries by position (in place when the ids are a range) and the
  // positions of the finite ones.
  bool range = true;
  for (Index i = 1; i < n && range; ++i)
  {
    range = ids[i] == ids[0] + i;
  }
  std::vector<double> copy;
  if (!range)
  {
    copy.resize(static_cast<std::size_t>(3 * n));
    execution.Run(0, n, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i)
      {
        CopyPoint(xyz + 3 * ids[i], copy.data() + 3 * i);
      }
    });
  }
  const double* q = range ? xyz + 3 * ids[0] : copy.data();
  Index finite = 0;
  for (Index i = 0; i < n; ++i)
  {
    finite += Finite(q + 3 * i) ? 1 : 0;
  }
  if (finite == 0)
  {
    return;
  }
  std::vector<Index> listed; // (only when some are not finite)
  if (finite < n)
  {
    listed.reserve(static_cast<std::size_t>(finite));
    for (Index i = 0; i < n; ++i)
    {
      if (Finite(q + 3 * i))
      {
        listed.push_back(i);
      }
    }
  }
  const IdView positions =
    finite < n ? IdView(listed) : IdView::Identity(static_cast<std::size_t>(n));

  // Blocks: the cells of a grid about one k-th neighbour distance wide.
  const double edge = BlockEdge * TypicalKthDistance(q, positions, surface, k);
  const Vec3Field queries(q);
  const Bounds bounds = ComputeBounds(queries, positions, execution);
  if (!std::isfinite(bounds.MaxExtent()))
  {
    // An extent beyond the largest double has no grid: each query on its
    // own, in the order of the list.
    execution.Run(0, finite, [&](Index b, Index e) {
      const KNearestVisit visit = makeVisit();
      BlockScratch s;
      for (Index j = b; j < e; ++j)
      {
        const Index i = positions[static_cast<std::size_t>(j)];
        SearchOne(i, q + 3 * i, surface, k, visit, s);
      }
    });
    return;
  }
  CellGrid grid = BuildCellGrid(queries, positions, GridSpec::Make(bounds, edge), execution);
  const double perBlock = static_cast<double>(finite) / static_cast<double>(grid.NumberOfCells());
  if (perBlock >= MinQueriesPerBlock && perBlock < FullBlock)
  {
    // Few queries per block (a simplification keeping a large share): wider
    // blocks, each with more queries on about the same candidates' share.
    const double wider = std::min(MaxWidening, std::sqrt(FullBlock / perBlock));
    grid = BuildCellGrid(queries, positions, GridSpec::Make(bounds, edge * wider), execution);
  }
  const Index cells = grid.NumberOfCells();
  const bool blocks = surface.Size() > k &&
    static_cast<double>(finite) >= MinQueriesPerBlock * static_cast<double>(cells);
  execution.Run(0, cells, [&](Index b, Index e) {
    const KNearestVisit visit = makeVisit();
    BlockScratch s;
    for (Index c = b; c < e; ++c)
    {
      const Index* slots = grid.CellPoints(c);
      const Index m = grid.CellSizeOf(c);
      if (blocks)
      {
        SearchBlock(q, slots, m, surface, k, visit, s);
        continue;
      }
      for (Index j = 0; j < m; ++j)
      {
        SearchOne(slots[j], q + 3 * slots[j], surface, k, visit, s);
      }
    }
  });
}
} // namespace asmcore
