// SPDX-License-Identifier: BSD-3-Clause
#include "Simplify.h"

#include "Budget.h"
#include "CellFrame.h"
#include "FeatureSimplify.h"
#include "CellSize.h"
#include "Grid.h"
#include "KeyPoints.h"
#include "Neighbors.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace asmcore
{
namespace
{
// A group of a cell's points (local indices) that becomes one sample.
struct Group
{
  std::vector<Index> Members;
  Index Extreme = -1; // key groups: the extreme point it stands for
};

// Step 6 of the pipeline (§3.3): from the key clusters and the cell's budget,
// the groups of points that become the cell's samples. `xyz` and `points`
// (the cell's input points) order the key clusters for the random choice.
std::vector<Group> CombineWithSampling(const LocalPoints& q, KeyClusters& kc, Index budget,
  std::uint64_t seed, const double* xyz, const Index* points)
{
  std::vector<Group> groups;
  const Index n = static_cast<Index>(q.size());
  const Index keyCount = kc.Key.Size();
  if (budget >= n)
  {
    // Every point is a sample; the extremes of the key clusters are key points.
    std::vector<char> extreme(static_cast<std::size_t>(n), 0);
    for (Index e : kc.Extreme)
    {
      extreme[e] = 1;
    }
    for (Index i = 0; i < n; ++i)
    {
      groups.push_back({ { i }, extreme[i] ? i : -1 });
    }
    return groups;
  }
  if (budget <= keyCount)
  {
    // §3.3 (iv): N_c of the C_n key points, chosen at random. The clusters
    // are drawn from in the order of their extreme points' coordinates, not
    // of their positions in the cell: the choice does not depend on the
    // order of the input points (nor on how a distributed run split them).
    std::vector<Index> pick(static_cast<std::size_t>(keyCount));
    std::iota(pick.begin(), pick.end(), Index(0));
    std::sort(pick.begin(), pick.end(), [&](Index a, Index b) {
      const double* pa = xyz + 3 * points[kc.Extreme[a]];
      const double* pb = xyz + 3 * points[kc.Extreme[b]];
      return std::lexicographical_compare(pa, pa + 3, pb, pb + 3) ||
        (std::equal(pa, pa + 3, pb) && a < b);
    });
    SplitMix64 rng(seed);
    for (Index i = 0; i < budget; ++i)
    {
      const Index j = i + static_cast<Index>(rng.Below(static_cast<std::uint64_t>(keyCount - i)));
      std::swap(pick[i], pick[j]);
    }
    pick.resize(static_cast<std::size_t>(budget));
    std::sort(pick.begin(), pick.end());
    for (Index k : pick)
    {
      groups.push_back({ { kc.Key.Begin(k), kc.Key.End(k) }, kc.Extreme[k] });
    }
    return groups;
  }
  // §3.3 (iii): all key points, and N_c - C_n samples from the middle band.
  Index wanted = budget - keyCount;
  for (Index k = 0; k < keyCount; ++k)
  {
    groups.push_back({ { kc.Key.Begin(k), kc.Key.End(k) }, kc.Extreme[k] });
  }
  Index shortfall = wanted - static_cast<Index>(kc.Middle.size());
  if (shortfall > 0)
  {
    // The bands hold most of the cell: peel the points farthest from each
    // key cluster's extreme off as single samples (its key point only moves
    // towards the extreme), until the budget can be met.
    std::vector<Group> peeled;
    for (Index k = 0; k < keyCount && shortfall > 0; ++k)
    {
      std::vector<Index>& members = groups[k].Members;
      const Eigen::Vector3d e = q[groups[k].Extreme];
      std::sort(members.begin(), members.end(), [&](Index a, Index b) {
        const double da = (q[a] - e).squaredNorm(), db = (q[b] - e).squaredNorm();
        return da < db || (da == db && a < b);
      });
      const Index peel = std::min<Index>(shortfall, static_cast<Index>(members.size()) - 1);
      for (Index p = 0; p < peel; ++p)
      {
        peeled.push_back({ { members.back() }, -1 });
        members.pop_back();
      }
      shortfall -= peel;
    }
    groups.insert(groups.end(), peeled.begin(), peeled.end());
    wanted = static_cast<Index>(kc.Middle.size());
  }
  if (wanted > 0)
  {
    Clusters middle;
    SplitInPlane(q, kc.Middle.data(), kc.Middle.data() + kc.Middle.size(), wanted, middle);
    for (Index k = 0; k < middle.Size(); ++k)
    {
      groups.push_back({ { middle.Begin(k), middle.End(k) }, -1 });
    }
  }
  return groups;
}

// Every point that no sample took (cells with a budget of 0, key clusters
// left out by §3.3 (iv)) joins the sample nearest to it, after that sample's
// own members: the member lists become a partition of the points, and the
// samples do not move. Points in slots marked in `haloSlot` (halo cells of
// a distributed run, owned by another process) are dropped instead.
void AttachUnclaimedPoints(const double* xyz, const std::vector<Index>& ids, SimplifyResult& result,
  const std::vector<char>& haloSlot, const Execution& execution)
{
  const Index total = static_cast<Index>(ids.size());
  const Index samples = static_cast<Index>(result.Samples.size());
  if (samples == 0)
  {
    return;
  }
  // Samples come in slot order, so the slots no sample covers are the gaps
  // between their member ranges: they hold the unclaimed points.
  std::vector<Index> unclaimed;
  auto collect = [&](Index begin, Index end) {
    for (Index slot = begin; slot < end; ++slot)
    {
      if (haloSlot.empty() || !haloSlot[slot])
      {
        unclaimed.push_back(result.Members[slot]);
      }
    }
  };
  Index cursor = 0;
  for (const Sample& s : result.Samples)
  {
    collect(cursor, s.MemberBegin);
    cursor = s.MemberBegin + s.ClusterSize;
  }
  collect(cursor, total);
  if (unclaimed.empty())
  {
    if (cursor != total || result.Samples[0].MemberBegin != 0)
    {
      // Only halo points were left out: close the gaps.
      std::vector<Index> members;
      members.reserve(static_cast<std::size_t>(total));
      for (Sample& s : result.Samples)
      {
        const Index begin = static_cast<Index>(members.size());
        members.insert(members.end(), result.Members.begin() + s.MemberBegin,
          result.Members.begin() + s.MemberBegin + s.ClusterSize);
        s.MemberBegin = begin;
      }
      result.Members.swap(members);
    }
    return;
  }
  std::vector<double> positions(static_cast<std::size_t>(3 * samples));
  std::vector<Index> sampleIds(static_cast<std::size_t>(samples));
  for (Index s = 0; s < samples; ++s)
  {
    std::copy(result.Samples[s].Position, result.Samples[s].Position + 3, &positions[3 * s]);
    sampleIds[s] = s;
  }
  const Neighbors tree(positions.data(), sampleIds, execution);
  std::vector<Index> owner(unclaimed.size());
  execution.Run(0, static_cast<Index>(unclaimed.size()), [&](Index b, Index e) {
    for (Index i = b; i < e; ++i)
    {
      const NearestPoint nearest = tree.Nearest(xyz + 3 * unclaimed[i]);
      owner[i] = nearest.Id >= 0 ? nearest.Id : 0;
    }
  });
  // Lay the members out again: each sample's own, then those that joined it.
  std::vector<Index> extra(static_cast<std::size_t>(samples) + 1, 0);
  for (Index o : owner)
  {
    ++extra[o + 1];
  }
  for (Index s = 0; s < samples; ++s)
  {
    extra[s + 1] += extra[s]; // offsets into the joined points, by sample
  }
  std::vector<Index> joined(unclaimed.size());
  {
    std::vector<Index> fill(extra.begin(), extra.end() - 1);
    for (std::size_t i = 0; i < unclaimed.size(); ++i)
    {
      joined[fill[owner[i]]++] = unclaimed[i];
    }
  }
  std::vector<Index> begin(static_cast<std::size_t>(samples) + 1, 0);
  for (Index s = 0; s < samples; ++s)
  {
    begin[s + 1] = begin[s] + result.Samples[s].ClusterSize + (extra[s + 1] - extra[s]);
  }
  std::vector<Index> members(static_cast<std::size_t>(begin[samples]));
  execution.Run(0, samples, [&](Index b, Index e) {
    for (Index s = b; s < e; ++s)
    {
      Sample& sample = result.Samples[s];
      const auto own = result.Members.begin() + sample.MemberBegin;
      const auto out = std::copy(own, own + sample.ClusterSize, members.begin() + begin[s]);
      std::copy(joined.begin() + extra[s], joined.begin() + extra[s + 1], out);
      sample.MemberBegin = begin[s];
      sample.ClusterSize = begin[s + 1] - begin[s];
    }
  });
  result.Members.swap(members);
}

std::uint64_t CellSeed(std::uint64_t seed, std::uint64_t cellKey)
{
  SplitMix64 mix(seed ^ (cellKey * 0xD1B54A32D192ED03ULL));
  return mix.Next();
}
} // namespace

double SamplesPerCellOf(const SimplifyParameters& parameters)
{
  const bool feature = parameters.Mode == SimplifyMode::FeaturePreserving;
  return std::max(1.0,
    feature && parameters.FeatureSamplesPerCell > 0.0 ? parameters.FeatureSamplesPerCell : parameters.SamplesPerCell);
}

double VariationWeightOf(const SimplifyParameters& parameters)
{
  if (parameters.Weight == WeightMode::SurfaceVariation)
  {
    return parameters.CurvatureWeight;
  }
  return parameters.Mode == SimplifyMode::FeaturePreserving ? std::max(0.0, parameters.VariationBudget) : 0.0;
}

std::vector<double> CellShares(const std::vector<Index>& capacity,
  const std::vector<double>& variation, const SimplifyParameters& parameters, double exponent)
{
  const std::size_t cells = capacity.size();
  double meanVariation = 0.0;
  Index total = 0;
  for (std::size_t c = 0; c < cells; ++c)
  {
    meanVariation += variation[c] * static_cast<double>(capacity[c]);
    total += capacity[c];
  }
  meanVariation /= static_cast<double>(std::max<Index>(1, total));
  std::vector<double> share(cells);
  const double k = VariationWeightOf(parameters);
  for (std::size_t c = 0; c < cells; ++c)
  {
    double weight = 1.0;
    if (k != 0.0 && meanVariation > 0.0)
    {
      weight += k * variation[c] / meanVariation;
    }
    const auto n = static_cast<double>(capacity[c]);
    share[c] = weight * (exponent == 1.0 ? n : std::pow(n, exponent));
  }
  return share;
}

std::vector<double> CellShares(const std::vector<CellFrame>& frames, const CellGrid& grid,
  const SimplifyParameters& parameters, double exponent, std::vector<Index>& capacity)
{
  const Index cells = grid.NumberOfCells();
  capacity.resize(static_cast<std::size_t>(cells));
  std::vector<double> variation(static_cast<std::size_t>(cells));
  for (Index c = 0; c < cells; ++c)
  {
    capacity[c] = grid.CellSizeOf(c);
    variation[c] = frames.empty() ? 0.0 : frames[c].SurfaceVariation();
  }
  return CellShares(capacity, variation, parameters, exponent);
}

CellGrid BuildRunGrid(const double* xyz, const std::vector<Index>& ids,
  const SimplifyParameters& parameters, Index target, const Execution& execution)
{
  if (parameters.Grid)
  {
    return BuildCellGrid(xyz, ids, *parameters.Grid, execution);
  }
  const Bounds bounds = ComputeBounds(xyz, ids, execution);
  const double cellSize = parameters.CellSize;
  if (cellSize > 0.0 && std::isfinite(cellSize))
  {
    return BuildCellGrid(xyz, ids, GridSpec::Make(bounds, cellSize), execution);
  }
  const double targetCells = static_cast<double>(target) / SamplesPerCellOf(parameters);
  return BuildAutomaticCellGrid(xyz, ids, bounds, targetCells, execution);
}

void SummarizeKeyPoints(SimplifyResult& result)
{
  // Summed in sample order: deterministic.
  result.NumberOfKeyPoints = 0;
  result.MKPE = 0.0;
  double sum = 0.0;
  for (const Sample& s : result.Samples)
  {
    if (s.Key)
    {
      ++result.NumberOfKeyPoints;
      sum += s.KeyError;
      result.MKPE = std::max(result.MKPE, s.KeyError);
    }
  }
  result.AKPE = result.NumberOfKeyPoints > 0 ? sum / static_cast<double>(result.NumberOfKeyPoints) : 0.0;
}

SimplifyResult Simplify(const double* xyz, const std::vector<Index>& ids, const double* normals,
  const SimplifyParameters& parameters, const Execution& execution)
{
  if (parameters.Mode == SimplifyMode::FeaturePreserving)
  {
    return SimplifyFeaturePreserving(xyz, ids, normals, parameters, execution);
  }
  SimplifyResult result;
  const Index total = static_cast<Index>(ids.size());
  const Index target = parameters.CellBudget
    ? total
    : std::max<Index>(0, std::min(parameters.NumberOfSamples, total));
  if (total == 0 || target == 0)
  {
    return result;
  }

  // 1. Hash the points into the grid.
  CellGrid grid = BuildRunGrid(xyz, ids, parameters, target, execution);
  if (execution.Report(0.1))
  {
    result.Aborted = true;
    return result;
  }
  const Index cells = grid.NumberOfCells();
  result.CellSize = grid.Spec.CellSize;
  result.NumberOfCells = cells;
  if (execution.Report(0.2))
  {
    result.Aborted = true;
    return result;
  }

  // 2. PCA of every cell (steps i-iv). Only the surface-variation weight
  // needs every cell's frame before the budgets; otherwise a cell's frame is
  // computed with its key points below, while its points are in cache.
  const bool framesFirst =
    !parameters.CellBudget && parameters.Weight == WeightMode::SurfaceVariation;
  std::vector<CellFrame> frames;
  if (framesFirst)
  {
    frames.resize(static_cast<std::size_t>(cells));
    execution.Run(0, cells, [&](Index b, Index e) {
      for (Index c = b; c < e; ++c)
      {
        frames[c] = ComputeCellFrame(xyz, grid.CellPoints(c), grid.CellSizeOf(c));
      }
    });
  }
  if (execution.Report(0.3))
  {
    result.Aborted = true;
    return result;
  }

  // 3. Budgets (Eq. 4), exact in total.
  std::vector<Index> budget;
  std::vector<char> haloSlot; // member slots of halo cells (distributed runs)
  if (parameters.CellBudget)
  {
    budget.resize(static_cast<std::size_t>(cells));
    for (Index c = 0; c < cells; ++c)
    {
      const Index b = parameters.CellBudget(grid.CellKey[c]);
      budget[c] = std::min(grid.CellSizeOf(c), std::max<Index>(0, b));
      if (b < 0)
      {
        haloSlot.resize(static_cast<std::size_t>(total), 0);
        std::fill(haloSlot.begin() + grid.CellStart[c], haloSlot.begin() + grid.CellStart[c + 1], 1);
      }
    }
  }
  else
  {
    std::vector<Index> capacity;
    const std::vector<double> share = CellShares(frames, grid, parameters, 1.0, capacity);
    budget = ApportionBudget(share, capacity, target);
  }
  std::vector<Index> sampleStart(static_cast<std::size_t>(cells) + 1, 0);
  for (Index c = 0; c < cells; ++c)
  {
    sampleStart[c + 1] = sampleStart[c] + budget[c];
  }
  result.Samples.resize(static_cast<std::size_t>(sampleStart[cells]));
  // The members start as the grid's order (the points cell by cell): each
  // cell rewrites its own range, from a copy of it, grouped by sample.
  result.Members = std::move(grid.Order);

  Eigen::Vector3d cloudCentroid = Eigen::Vector3d::Zero();
  if (parameters.CloudCentroid)
  {
    cloudCentroid = Eigen::Vector3d(parameters.CloudCentroid);
  }
  else
  {
    ComputeCentroid(xyz, ids, cloudCentroid.data(), execution);
  }

  KeyPointRule rule;
  rule.Alpha = parameters.Alpha;
  rule.ErrorTolerance = parameters.ErrorTolerance;
  rule.LinkFactor = parameters.LinkFactor;
  rule.CoordinateEpsilon = parameters.CoordinateEpsilon;
  rule.Snap = parameters.Snap;

  // 4-6. Key points, error bound and sampling, cell by cell. Each cell writes
  // its own slots, so the result does not depend on the thread count.
  auto processCells = [&](Index b, Index e) {
    LocalPoints q;
    std::vector<Index> cellPoints;
    for (Index c = b; c < e; ++c)
    {
      if (budget[c] == 0)
      {
        continue; // no sample: the points stay unclaimed in their slots
      }
      const Index n = grid.CellSizeOf(c);
      cellPoints.assign(result.Members.begin() + grid.CellStart[c],
        result.Members.begin() + grid.CellStart[c + 1]);
      const Index* points = cellPoints.data();
      const CellFrame frame = framesFirst ? frames[c] : ComputeCellFrame(xyz, points, n);
      KeyClusters kc = FindCellKeyClusters(xyz, points, n, frame, rule, q);
      const std::vector<Group> groups =
        CombineWithSampling(q, kc, budget[c], CellSeed(parameters.RandomSeed, grid.CellKey[c]), xyz, points);

      Index memberCursor = grid.CellStart[c];
      Index sampleIndex = sampleStart[c];
      for (const Group& group : groups)
      {
        Sample& s = result.Samples[sampleIndex++];
        const Index* first = group.Members.data();
        const Index* last = first + group.Members.size();
        const Eigen::Vector3d local = Centroid(q, first, last);
        const Index nearest = NearestMember(q, first, last, local);
        // A single point, or a snapped sample, is an input point exactly.
        const Eigen::Vector3d world = (parameters.Snap || group.Members.size() == 1)
          ? Eigen::Vector3d(xyz[3 * points[nearest]], xyz[3 * points[nearest] + 1],
              xyz[3 * points[nearest] + 2])
          : Eigen::Vector3d(frame.Centroid + frame.Axes * local);
        Eigen::Vector3d normal = frame.Normal();
        Eigen::Vector3d reference = frame.Centroid - cloudCentroid;
        if (normals)
        {
          Eigen::Vector3d sum = Eigen::Vector3d::Zero();
          for (Index m : group.Members)
          {
            const double* nm = normals + 3 * points[m];
            const Eigen::Vector3d v(nm[0], nm[1], nm[2]);
            if (v.allFinite())
            {
              sum += v;
            }
          }
          if (sum.squaredNorm() > 0.0)
          {
            reference = sum;
          }
        }
        if (normal.dot(reference) < 0.0)
        {
          normal = -normal;
        }
        for (int a = 0; a < 3; ++a)
        {
          s.Position[a] = world[a];
          s.Normal[a] = normal[a];
        }
        s.Representative = points[nearest];
        s.MemberBegin = memberCursor;
        s.ClusterSize = static_cast<Index>(group.Members.size());
        s.CoreSize = s.ClusterSize;
        s.SurfaceVariation = frame.SurfaceVariation();
        s.Key = group.Extreme >= 0;
        if (s.Key)
        {
          const Eigen::Vector3d rep = parameters.Snap ? q[nearest] : local;
          s.KeyError = (rep - q[group.Extreme]).norm();
        }
        for (Index m : group.Members)
        {
          result.Members[memberCursor++] = points[m];
        }
      }
      if (memberCursor < grid.CellStart[c + 1])
      {
        // Points in no group (§3.3 iv): unclaimed, after the cell's samples.
        std::vector<char> grouped(static_cast<std::size_t>(n), 0);
        for (const Group& group : groups)
        {
          for (Index m : group.Members)
          {
            grouped[m] = 1;
          }
        }
        for (Index i = 0; i < n; ++i)
        {
          if (!grouped[i])
          {
            result.Members[memberCursor++] = points[i];
          }
        }
      }
    }
  };
  // Batches between progress reports, cut by point count.
  const int batches = 20;
  Index cellBegin = 0;
  for (int batch = 1; batch <= batches && cellBegin < cells; ++batch)
  {
    const Index pointEnd = total * batch / batches;
    Index cellEnd = static_cast<Index>(
      std::upper_bound(grid.CellStart.begin(), grid.CellStart.end() - 1, pointEnd) -
      grid.CellStart.begin());
    cellEnd = std::max(cellBegin + 1, std::min(cells, cellEnd));
    if (batch == batches)
    {
      cellEnd = cells;
    }
    execution.Run(cellBegin, cellEnd, processCells);
    cellBegin = cellEnd;
    if (execution.Report(0.3 + 0.7 * batch / batches))
    {
      result.Samples.clear();
      result.Members.clear();
      result.Aborted = true;
      return result;
    }
  }

  AttachUnclaimedPoints(xyz, ids, result, haloSlot, execution);

  SummarizeKeyPoints(result);
  return result;
}
} // namespace asmcore
