// SPDX-License-Identifier: BSD-3-Clause
#include "Assignment.h"

#include "Neighbors.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();

/// AssignToSamples for the points of a cell that owns many samples: a k-d
/// tree of the ring's samples (ties: lower index, as the brute-force search).
void AssignLargeCell(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, Index c, PointArray<SampleId>& assign, std::vector<Index>& ringSamples,
  const double* scale = nullptr)
{
  ringSamples.clear();
  for (int k = 0; k < 27; ++k)
  {
    const Index nb = neighbors.Of(c)[k];
    for (Index s = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && s < samples.Start[nb + 1]; ++s)
    {
      ringSamples.push_back(s);
    }
  }
  const double* pos = samples.Position.data();
  const Neighbors tree(pos, ringSamples);
  if (scale)
  {
    // Weighted (factors >= 1): the plain nearest sample s0 at d0 bounds the
    // answer's weighted distance by scale[s0] d0^2, so the answer lies within
    // d0 sqrt(scale[s0]) (widened against rounding); the least weighted
    // distance among those, ties: the lower index.
    std::vector<Index> near;
    for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
    {
      double p[3];
      xyz.Get(grid.PointAt(i), p);
      const NearestPoint nearest = tree.Nearest(p);
      Index best = -1;
      double bestD = Infinity;
      if (nearest.Id >= 0 && nearest.Distance == 0.0)
      {
        // Every sample at p's position is at weighted distance 0, and the
        // lowest index of those is the nearest's (its ties: the smaller id):
        // no ball to search (with coincident samples, a ball of all of them
        // for every point).
        best = nearest.Id;
      }
      else if (nearest.Id >= 0)
      {
        tree.Radius(p, nearest.Distance * std::sqrt(scale[nearest.Id]) * (1.0 + 1e-9), near);
        for (Index s : near)
        {
          const double d = scale[s] * SquaredDistance(p, pos + 3 * s);
          if (d < bestD || (d == bestD && s < best))
          {
            bestD = d;
            best = s;
          }
        }
      }
      assign[i] = static_cast<SampleId>(best);
    }
    return;
  }
  for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
  {
    const NearestPoint nearest = tree.Nearest(xyz.At(grid.PointAt(i)).data());
    assign[i] = static_cast<SampleId>(nearest.Id);
  }
}

/// d[l] = |p - (x[l], y[l], z[l])|^2 for l < 4, rounded as SquaredDistance
/// rounds ((dx^2 + dy^2) + dz^2): the same values, two at a time.
inline void FourSquaredDistances(
  const double p[3], const double* x, const double* y, const double* z, double d[4])
{
#if defined(__SSE2__)
  const __m128d px = _mm_set1_pd(p[0]), py = _mm_set1_pd(p[1]), pz = _mm_set1_pd(p[2]);
  for (int h = 0; h < 4; h += 2)
  {
    const __m128d dx = _mm_sub_pd(px, _mm_loadu_pd(x + h));
    const __m128d dy = _mm_sub_pd(py, _mm_loadu_pd(y + h));
    const __m128d dz = _mm_sub_pd(pz, _mm_loadu_pd(z + h));
    _mm_storeu_pd(
      d + h, _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)), _mm_mul_pd(dz, dz)));
  }
#else
  for (int l = 0; l < 4; ++l)
  {
    const double dx = p[0] - x[l], dy = p[1] - y[l], dz = p[2] - z[l];
    d[l] = dx * dx + dy * dy + dz * dz;
  }
#endif
}

// Samples in blocks of Lanes, coordinates apart (one array per axis, so
// that the distances of a block are computed together), in the order of
// the list they are filled from; the last block is padded with entries that
// never win (infinite gap and distance, index Unused).
struct SampleBlocks
{
  static constexpr int Lanes = 4; // (FourSquaredDistances)
  static constexpr Index Unused = std::numeric_limits<Index>::max();
  std::vector<double> X, Y, Z, Gap, Scale;
  std::vector<Index> Sample;

  /// From (squared gap, sample) pairs.
  void Fill(
    const std::vector<std::pair<double, Index>>& list, const double* pos, const double* scale)
  {
    const std::size_t n = list.size();
    const std::size_t padded = (n + Lanes - 1) / Lanes * Lanes;
    for (auto* v : { &this->X, &this->Y, &this->Z, &this->Gap, &this->Scale })
    {
      v->assign(padded, Infinity);
    }
    this->Sample.assign(padded, Unused);
    for (std::size_t j = 0; j < n; ++j)
    {
      const Index s = list[j].second;
      this->X[j] = pos[3 * s];
      this->Y[j] = pos[3 * s + 1];
      this->Z[j] = pos[3 * s + 2];
      this->Gap[j] = list[j].first;
      this->Scale[j] = scale ? scale[s] : 1.0;
      this->Sample[j] = s;
    }
  }
  std::size_t Blocks() const { return this->Sample.size() / Lanes; }
  /// The (weighted) squared distances from p to the samples of block k.
  template <bool Weighted>
  void Distances(const double p[3], std::size_t k, double d[Lanes]) const
  {
    const std::size_t j0 = k * Lanes;
    FourSquaredDistances(p, &this->X[j0], &this->Y[j0], &this->Z[j0], d);
    for (int l = 0; Weighted && l < Lanes; ++l)
    {
      d[l] *= this->Scale[j0 + l];
    }
  }
};

/// The box of each cell's samples (6 per cell: low x, y, z, high x, y, z;
/// empty boxes for cells without samples).
std::vector<double> SampleBoxes(const SampleSet& samples, Index cells, const Execution& execution)
{
  std::vector<double> boxes(static_cast<std::size_t>(6 * cells));
  const double* pos = samples.Position.data();
  execution.Run(0, cells, [&](Index b, Index e) {
    for (Index c = b; c < e; ++c)
    {
      double* box = &boxes[static_cast<std::size_t>(6 * c)];
      std::fill(box, box + 3, Infinity);
      std::fill(box + 3, box + 6, -Infinity);
      for (Index s = samples.Start[c]; s < samples.Start[c + 1]; ++s)
      {
        for (int a = 0; a < 3; ++a)
        {
          box[a] = std::min(box[a], pos[3 * s + a]);
          box[3 + a] = std::max(box[3 + a], pos[3 * s + a]);
        }
      }
    }
  });
  return boxes;
}

/// The squared gap between two boxes (low x, y, z, high x, y, z), rounded
/// as the gaps from the points of one to the other are (no more than them).
inline double BoxGap2(const double* a, const double* b)
{
  double g2 = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double g = std::max(0.0, std::max(a[k] - b[3 + k], b[k] - a[3 + k]));
    g2 += g * g;
  }
  return g2;
}

// The two passes of AssignToSamples, comparing scale[s] * d^2 when Weighted
// (a template parameter, so that the plain passes carry no multiply). With
// scale >= 1, scale * d^2 >= d^2 >= the squared box gap: the pruning of
// pass 2 holds as it is. Both passes give, over the samples they look at,
// the least (distance, index) pair: the same answer in any order.
template <bool Weighted>
void AssignPasses(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, PointArray<SampleId>& assign, const Execution& execution,
  const double* scale)
{
  assign.resize(static_cast<std::size_t>(grid.NumberOfPoints()));
  const double* pos = samples.Position.data();
  constexpr int Lanes = SampleBlocks::Lanes;
  const std::vector<double> sampleBoxes = SampleBoxes(samples, grid.NumberOfCells(), execution);
  execution.Run(0, grid.NumberOfCells(), [&](Index b, Index e) {
    std::vector<std::pair<double, Index>> list; // (squared gap to the box, sample)
    SampleBlocks candidates;
    std::vector<Index> ringSamples;
    std::vector<double> cellD2; // pass 1's squared distances of the cell's points
    for (Index c = b; c < e; ++c)
    {
      const Index first = samples.Start[c], last = samples.Start[c + 1];
      if (last - first > LargeCellBudget)
      {
        AssignLargeCell(xyz, grid, neighbors, samples, c, assign, ringSamples, scale);
        continue;
      }
      // Pass 1: the nearest of the cell's own samples, and the farthest any
      // point of the cell is from it (the search radius for the others).
      double reach = 0.0;
      double box[6] = { Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity };
      cellD2.resize(static_cast<std::size_t>(grid.CellSizeOf(c)));
      for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
      {
        double p[3];
        xyz.Get(grid.PointAt(i), p);
        Index best = -1;
        double bestD = Infinity;
        for (Index s = first; s < last; ++s)
        {
          double d = SquaredDistance(p, pos + 3 * s);
          if (Weighted)
          {
            d *= scale[s];
          }
          if (d < bestD)
          {
            bestD = d;
            best = s;
          }
        }
        assign[i] = static_cast<SampleId>(best);
        cellD2[static_cast<std::size_t>(i - grid.CellStart[c])] = bestD;
        reach = std::max(reach, bestD);
        for (int a = 0; a < 3; ++a)
        {
          box[a] = std::min(box[a], p[a]);
          box[3 + a] = std::max(box[3 + a], p[a]);
        }
      }
      // The neighbours' samples that can be nearer for some point of c:
      // within `reach` of the box of c's points.
      list.clear();
      const CellRef* ring = neighbors.Of(c);
      const double r = std::sqrt(reach);
      for (int k = 0; k < 27; ++k)
      {
        const Index nb = ring[k];
        if (k == 13 || nb < 0 || (BoxGap2(box, &sampleBoxes[6 * nb]) > reach && std::isfinite(r)))
        {
          continue; // (no sample of nb can be within reach: a whole cell at once)
        }
        for (Index s = samples.Start[nb]; s < samples.Start[nb + 1]; ++s)
        {
          const double* t = pos + 3 * s;
          double g2 = 0.0;
          for (int a = 0; a < 3; ++a)
          {
            // (Branch-free: at most one of the two differences is positive.)
            const double g = std::max(0.0, std::max(box[a] - t[a], t[a] - box[3 + a]));
            g2 += g * g;
          }
          if (!(g2 > reach) || !std::isfinite(r))
          {
            list.emplace_back(g2, s);
          }
        }
      }
      if (list.empty())
      {
        continue;
      }
      // Pass 2: those candidates, a block at a time, nearest the box first;
      // a point lies in the box, so it is at least the box gap away from a
      // candidate, and no block after one whose first gap exceeds the best
      // distance so far can hold a nearer one (ties: the lower index).
      std::sort(list.begin(), list.end());
      candidates.Fill(list, pos, scale);
      const std::size_t blocks = candidates.Blocks();
      for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
      {
        double p[3];
        xyz.Get(grid.PointAt(i), p);
        Index best = assign[i];
        double bestD = cellD2[static_cast<std::size_t>(i - grid.CellStart[c])];
        for (std::size_t k = 0; k < blocks && !(candidates.Gap[k * Lanes] > bestD); ++k)
        {
          const std::size_t j0 = k * Lanes;
          double d[Lanes];
          candidates.Distances<Weighted>(p, k, d);
          if (std::min(std::min(d[0], d[1]), std::min(d[2], d[3])) > bestD)
          {
            continue; // (the usual case: the cell's own sample stays nearest)
          }
          for (int l = 0; l < Lanes; ++l)
          {
            const Index s = candidates.Sample[j0 + l];
            if (d[l] < bestD || (d[l] == bestD && s < best))
            {
              bestD = d[l];
              best = s;
            }
          }
        }
        assign[i] = static_cast<SampleId>(best);
      }
    }
  });
}

} // namespace

void AssignToSamples(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, PointArray<SampleId>& assign, const Execution& execution,
  const double* scale)
{
  if (scale)
  {
    AssignPasses<true>(xyz, grid, neighbors, samples, assign, execution, scale);
  }
  else
  {
    AssignPasses<false>(xyz, grid, neighbors, samples, assign, execution, scale);
  }
}

void UpdateAssignment(Coordinates xyz, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SampleSet& samples, const std::vector<Index>& previous, const std::vector<char>& moved,
  PointArray<SampleId>& assign, const Execution& execution, Index previousCount)
{
  const Index count = samples.Size();
  const Index cells = grid.NumberOfCells();
  // Old slot -> new slot (-1: the sample left the set).
  std::vector<Index> renumber(
    static_cast<std::size_t>(previousCount < 0 ? count : previousCount), -1);
  for (Index s = 0; s < count; ++s)
  {
    if (previous[s] >= 0)
    {
      renumber[previous[s]] = s;
    }
  }
  const double* pos = samples.Position.data();
  execution.Run(0, cells, [&](Index b, Index e) {
    std::vector<Index> near; // the moved samples of the ring
    std::vector<Index> ringSamples;
    for (Index c = b; c < e; ++c)
    {
      if (samples.Start[c + 1] - samples.Start[c] > LargeCellBudget)
      {
        // A cell owning many samples searches them with a k-d tree, as
        // AssignToSamples does (the same answers, in O(log) per point).
        AssignLargeCell(xyz, grid, neighbors, samples, c, assign, ringSamples);
        continue;
      }
      const CellRef* ring = neighbors.Of(c);
      near.clear();
      for (int k = 0; k < 27; ++k)
      {
        const Index nb = ring[k];
        for (Index s = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && s < samples.Start[nb + 1]; ++s)
        {
          if (moved[s])
          {
            near.push_back(s);
          }
        }
      }
      for (Index i = grid.CellStart[c]; i < grid.CellStart[c + 1]; ++i)
      {
        double p[3];
        xyz.Get(grid.PointAt(i), p);
        const Index before = assign[i] >= 0 ? renumber[assign[i]] : -1;
        Index best = before;
        // (Its sample, if it stayed, is where it was: the same distance.)
        double bestD = before < 0 ? Infinity : SquaredDistance(p, pos + 3 * before);
        auto consider = [&](Index s) {
          const double d = SquaredDistance(p, pos + 3 * s);
          if (d < bestD || (d == bestD && s < best))
          {
            bestD = d;
            best = s;
          }
        };
        if (before < 0 || moved[before])
        {
          // Its sample left (or it had none): the whole ring again.
          best = -1;
          bestD = Infinity;
          for (int k = 0; k < 27; ++k)
          {
            const Index nb = ring[k];
            for (Index s = nb < 0 ? 0 : samples.Start[nb]; nb >= 0 && s < samples.Start[nb + 1];
                 ++s)
            {
              consider(s);
            }
          }
        }
        else
        {
          // Its sample stayed: only a moved sample can now be nearer.
          for (Index s : near)
          {
            consider(s);
          }
        }
        assign[i] = static_cast<SampleId>(best);
      }
    }
  });
}
} // namespace asmcore
