// SPDX-License-Identifier: BSD-3-Clause
#include "PaperSimplify.h"

#include "Budget.h"
#include "CanonicalOrder.h"
#include "CellFrame.h"
#include "KeyPoints.h"
#include "Unclaimed.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>

namespace asmcore
{
namespace
{
// The groups of a cell's points (local indices) that become its samples,
// and per group the extreme point a key group stands for (-1: none).
struct Groups
{
  Clusters Members;
  std::vector<Index> Extreme;
  void Clear()
  {
    this->Members.Clear();
    this->Extreme.clear();
  }
  Index Size() const { return this->Members.Size(); }
};

// Step 6 of the pipeline (§3.3): from the key clusters and the cell's budget,
// the groups of points that become the cell's samples (appended to `groups`,
// cleared first). `xyz` (the cell's points, in the order of q) orders the
// key clusters for the random choice.
void CombineWithSampling(const LocalPoints& q, KeyClusters& kc, Index budget, std::uint64_t seed,
  const double* xyz, Groups& groups)
{
  groups.Clear();
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
      groups.Members.Add(&i, &i + 1);
      groups.Extreme.push_back(extreme[i] ? i : -1);
    }
    return;
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
      const double* pa = xyz + 3 * kc.Extreme[a];
      const double* pb = xyz + 3 * kc.Extreme[b];
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
      groups.Members.Add(kc.Key.Begin(k), kc.Key.End(k));
      groups.Extreme.push_back(kc.Extreme[k]);
    }
    return;
  }
  // §3.3 (iii): all key points, and N_c - C_n samples from the middle band.
  // When the bands hold most of the cell, the points farthest from each key
  // cluster's extreme are peeled off as single samples (its key point only
  // moves towards the extreme), until the budget can be met.
  Index wanted = budget - keyCount;
  Index shortfall = wanted - static_cast<Index>(kc.Middle.size());
  if (shortfall > 0)
  {
    wanted = static_cast<Index>(kc.Middle.size()); // the rest are peeled points
  }
  std::vector<Index> peeled;
  std::vector<Index>& members = groups.Members.Members;
  for (Index k = 0; k < keyCount; ++k)
  {
    const auto first = static_cast<std::ptrdiff_t>(members.size());
    members.insert(members.end(), kc.Key.Begin(k), kc.Key.End(k));
    if (shortfall > 0)
    {
      const Eigen::Vector3d e = q[kc.Extreme[k]];
      std::sort(members.begin() + first, members.end(), [&](Index a, Index b) {
        const double da = (q[a] - e).squaredNorm(), db = (q[b] - e).squaredNorm();
        return da < db || (da == db && a < b);
      });
      const Index peel = std::min<Index>(shortfall, static_cast<Index>(members.size() - first) - 1);
      for (Index p = 0; p < peel; ++p)
      {
        peeled.push_back(members.back());
        members.pop_back();
      }
      shortfall -= peel;
    }
    groups.Members.Offsets.push_back(static_cast<Index>(members.size()));
    groups.Extreme.push_back(kc.Extreme[k]);
  }
  for (Index p : peeled)
  {
    groups.Members.Add(&p, &p + 1);
    groups.Extreme.push_back(-1);
  }
  if (wanted > 0)
  {
    SplitInPlane(q, kc.Middle.data(), kc.Middle.data() + kc.Middle.size(), wanted, groups.Members);
    groups.Extreme.resize(static_cast<std::size_t>(groups.Size()), -1);
  }
}

std::uint64_t CellSeed(std::uint64_t seed, std::uint64_t cellKey)
{
  SplitMix64 mix(seed ^ (cellKey * 0xD1B54A32D192ED03ULL));
  return mix.Next();
}
} // namespace

SimplifyResult SimplifyPaper(Coordinates xyz, IdView ids, NormalField normals,
  const SimplifyParameters& parameters, const Execution& execution)
{
  SimplifyResult result;
  const Index total = static_cast<Index>(ids.size());
  const Index target = SampleTarget(parameters, total);
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
      CanonicalCell local;
      for (Index c = b; c < e; ++c)
      {
        local.Gather(xyz, grid.CellPoints(c), grid.CellSizeOf(c));
        frames[c] = ComputeCellFrame(
          local.Xyz.data(), IdView::Identity(static_cast<std::size_t>(grid.CellSizeOf(c))));
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
        std::fill(
          haloSlot.begin() + grid.CellStart[c], haloSlot.begin() + grid.CellStart[c + 1], 1);
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
  ResizeInParallel(
    result.Samples, static_cast<std::size_t>(sampleStart[cells]), Sample{}, execution);
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
  std::mutex duplicatesMutex; // (the pieces' duplicates, sorted at the end)
  auto processCells = [&](Index b, Index e) {
    LocalPoints q;
    CanonicalCell local;
    Groups groups;
    std::vector<char> grouped;
    std::vector<std::pair<Index, Index>> duplicates;
    std::vector<char> listed; // the cell's points whose duplicates are listed
    Index listedCell = -1;    // (the cell `listed` is of)
    for (Index c = b; c < e; ++c)
    {
      if (budget[c] == 0)
      {
        continue; // no sample: the points stay unclaimed in their slots
      }
      const Index n = grid.CellSizeOf(c);
      // The geometry reads the cell's points from a local copy (doubles, in
      // the cell's canonical order): local slot i is point points[i].
      local.Gather(xyz, result.Members.data() + grid.CellStart[c], n);
      const Index* points = local.Ids.data(); // (input point ids)
      const double* cellXyz = local.Xyz.data();
      const IdView slots = IdView::Identity(static_cast<std::size_t>(n));
      const CellFrame frame = framesFirst ? frames[c] : ComputeCellFrame(cellXyz, slots);
      KeyClusters kc = FindCellKeyClusters(cellXyz, slots, frame, rule, q);
      CombineWithSampling(
        q, kc, budget[c], CellSeed(parameters.RandomSeed, grid.CellKey[c]), cellXyz, groups);

      Index memberCursor = grid.CellStart[c];
      Index sampleIndex = sampleStart[c];
      for (Index g = 0; g < groups.Size(); ++g)
      {
        Sample& s = result.Samples[sampleIndex++];
        const Index* first = groups.Members.Begin(g);
        const Index* last = groups.Members.End(g);
        const Index extreme = groups.Extreme[g];
        const Eigen::Vector3d local = Centroid(q, first, last);
        const Index nearest = NearestMember(q, first, last, local);
        // A single point, or a snapped sample, is an input point exactly.
        const Eigen::Vector3d world = (parameters.Snap || last - first == 1)
          ? Eigen::Vector3d(
              cellXyz[3 * nearest], cellXyz[3 * nearest + 1], cellXyz[3 * nearest + 2])
          : Eigen::Vector3d(frame.Centroid + frame.Axes * local);
        Eigen::Vector3d normal = frame.Normal();
        Eigen::Vector3d reference = frame.Centroid - cloudCentroid;
        if (normals)
        {
          Eigen::Vector3d sum = Eigen::Vector3d::Zero();
          for (const Index* m = first; m != last; ++m)
          {
            Eigen::Vector3d v;
            normals.Get(points[*m], v.data());
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
        const auto getLocal = [&](Index j, double* p) { CopyPoint(cellXyz + 3 * j, p); };
        if (HasDuplicate(nearest, 0, n, getLocal))
        {
          if (listedCell != c)
          {
            listed.assign(static_cast<std::size_t>(n), 0);
            listedCell = c;
          }
          ListDuplicatesOnce(nearest, 0, n, getLocal, listed,
            [&](Index r, Index j) { duplicates.emplace_back(points[r], points[j]); });
        }
        s.MemberBegin = memberCursor;
        s.ClusterSize = static_cast<Index>(last - first);
        s.CoreSize = s.ClusterSize;
        s.SurfaceVariation = frame.SurfaceVariation();
        s.Key = extreme >= 0;
        if (s.Key)
        {
          const Eigen::Vector3d rep = parameters.Snap ? q[nearest] : local;
          s.KeyError = (rep - q[extreme]).norm();
        }
        for (const Index* m = first; m != last; ++m)
        {
          result.Members[memberCursor++] = points[*m];
        }
      }
      if (memberCursor < grid.CellStart[c + 1])
      {
        // Points in no group (§3.3 iv): unclaimed, after the cell's samples.
        grouped.assign(static_cast<std::size_t>(n), 0);
        for (Index m : groups.Members.Members)
        {
          grouped[m] = 1;
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
    if (!duplicates.empty())
    {
      const std::lock_guard<std::mutex> lock(duplicatesMutex);
      result.RepresentativeDuplicates.insert(
        result.RepresentativeDuplicates.end(), duplicates.begin(), duplicates.end());
    }
  };
  // Batches between progress reports, cut by point count: 20 from 2 M
  // points, one per 100 000 below. Each batch is a parallel loop of its own,
  // and a backend that starts its threads in every loop (STDThread in VTK
  // 9.1-9.2) pays for each; a small cloud's run is over before more reports
  // would show.
  const int batches = static_cast<int>(std::min<Index>(20, std::max<Index>(1, total / 100000)));
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

  std::sort(result.RepresentativeDuplicates.begin(), result.RepresentativeDuplicates.end());
  AttachUnclaimedPoints(xyz, grid, sampleStart, result, haloSlot, execution);

  SummarizeKeyPoints(result);
  return result;
}
} // namespace asmcore
