// SPDX-License-Identifier: BSD-3-Clause
/**
 * asm_profile: a small timing harness for optimising vtkASMSimplify (not the
 * official benchmark, see Benchmarks/). Generates a seeded synthetic cloud
 * (a sphere with bumps, points uniform by area, float coordinates) in memory,
 * or reads a PLY, and times vtkASMSimplify::Update() end to end.
 *
 *   asm_profile [--points N[,N...]] [--threads T[,T...]] [--runs R]
 *               [--fraction F] [--curvature] [--ply file] [--stages] [--floor]
 *               [--dump file] [--coherent] [--mode paper|feature] [--arrays]
 *               [--set Name=value,...] [--error] [--loops]
 *
 * --set sets more properties of vtkASMSimplify by name, as the benchmarks'
 * --asm does (asmbench::ApplyAsmSettings; e.g. --set FillHoles=0); it needs
 * the benchmarks' support library (built unless the benchmarks are off).
 * --mode picks vtkASMSimplify's Mode (default: the filter's default,
 * FEATURE_PRESERVING).
 * --arrays attaches a scan's usual point data to the input (RGB colour as
 * unsigned chars, a float intensity, float normals) so that the time of
 * their aggregation shows (it is the difference to a run without).
 * --coherent sorts the synthetic points along a Morton curve (scan-like
 * memory order; default: random order, the worst case for gathers).
 * --floor times the floor of any grid simplifier with a target count on
 * the input: bounds, one occupancy count, the grid and one pass over the
 * cells (floats in place, one thread).
 * --error also times vtkKeyPointError on the input and the last run's
 * output (with curvature when --curvature is given), as many runs, and
 * prints its median wall time and figures (to check that a change to the
 * measures leaves them unchanged).
 * --loops times asmcore::Simplify's parallel loops one by one, by call site
 * (the loop body's type), with each of --threads (default 1,2), and the time
 * outside them: what limits the speed-up from a second thread (medians of
 * --runs, wall ms; the filter's own parameters, --set included).
 * --stages also times the core's stages one by one (same calls as
 * asmcore::Simplify makes), one thread. --dump writes the output points,
 * original ids and key flags of the last run as text (for before/after
 * comparisons; with each point's ClusterSize). Times: medians of wall and of process CPU time (the
 * latter is robust to a loaded machine). Peak memory: VmHWM after resetting it (clear_refs 5) once
 * the input exists, minus the resident size then, per input point.
 */
#include "Core/Budget.h"
#include "Core/CellFrame.h"
#include "Core/CellSize.h"
#include "Core/Curvature.h"
#include "Core/Grid.h"
#include "Core/KeyPoints.h"
#include "Core/Neighbors.h"
#include "Core/Simplify.h"
#include "vtkASMFilterUtilities.h"
#include "vtkASMSimplifySteps.h"
#ifdef ASM_PROFILE_SETTINGS
#include "BenchmarkMethods.h"
#endif
#include "vtkASMSimplify.h"
#include "vtkKeyPointError.h"

#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <cxxabi.h>
#include <malloc.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU time of the whole process (all threads): robust to a loaded machine.
double Cpu()
{
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

long StatusKB(const char* field)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
  {
    if (line.rfind(field, 0) == 0)
    {
      return std::atol(line.c_str() + std::strlen(field));
    }
  }
  return -1;
}

void ResetPeak()
{
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
}

// Sphere of radius 1 with bumps r = 1 + 0.08 sin(5 theta) cos(4 phi) + 0.03 sin(17 ...),
// uniform by area (rejection on the area element), seeded.
vtkSmartPointer<vtkPolyData> Synthetic(vtkIdType n, unsigned seed, bool coherent)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  auto radius = [](double t, double p) {
    return 1.0 + 0.08 * std::sin(5 * t) * std::cos(4 * p) + 0.03 * std::sin(17 * t + 3 * p);
  };
  vtkNew<vtkFloatArray> data;
  data->SetNumberOfComponents(3);
  data->SetNumberOfTuples(n);
  float* out = data->GetPointer(0);
  vtkIdType made = 0;
  while (made < n)
  {
    const double z = 2.0 * uni(rng) - 1.0;
    const double p = 2.0 * M_PI * uni(rng);
    const double t = std::acos(z);
    const double r = radius(t, p);
    // Area element of r(t, p) relative to the unit sphere, roughly bounded by 1.6.
    const double h = 1e-5;
    const double rt = (radius(t + h, p) - radius(t - h, p)) / (2 * h);
    const double rp = (radius(t, p + h) - radius(t, p - h)) / (2 * h);
    const double s = std::max(std::sin(t), 1e-12);
    const double w = r * std::sqrt(r * r + rt * rt + rp * rp / (s * s)) / 1.6;
    if (uni(rng) > w)
    {
      continue;
    }
    const double st = std::sqrt(std::max(0.0, 1.0 - z * z));
    out[3 * made] = static_cast<float>(r * st * std::cos(p));
    out[3 * made + 1] = static_cast<float>(r * st * std::sin(p));
    out[3 * made + 2] = static_cast<float>(r * z);
    ++made;
  }
  if (coherent)
  {
    // Scan-like order: points sorted along a Morton curve of a 1024^3 grid.
    std::vector<std::pair<std::uint64_t, vtkIdType>> order(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      std::uint64_t code = 0;
      for (int a = 0; a < 3; ++a)
      {
        const auto q = static_cast<std::uint64_t>((out[3 * i + a] + 1.2) / 2.4 * 1023.0);
        for (int b = 0; b < 10; ++b)
          code |= ((q >> b) & 1) << (3 * b + a);
      }
      order[i] = { code, i };
    }
    std::sort(order.begin(), order.end());
    std::vector<float> sorted(3 * n);
    for (vtkIdType i = 0; i < n; ++i)
      std::copy(out + 3 * order[i].second, out + 3 * order[i].second + 3, &sorted[3 * i]);
    std::copy(sorted.begin(), sorted.end(), out);
  }
  vtkNew<vtkPoints> points;
  points->SetData(data);
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  return poly;
}

std::vector<long> ParseList(const char* s)
{
  std::vector<long> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
  {
    double x = std::atof(item.c_str());
    if (!item.empty() && (item.back() == 'k' || item.back() == 'K'))
      x *= 1e3;
    if (!item.empty() && (item.back() == 'M' || item.back() == 'm'))
      x *= 1e6;
    v.push_back(static_cast<long>(x));
  }
  return v;
}

// The curvature's parts at the given positions, as vtkASMSimplify computes
// it (the input's floats in place), one thread, best of 3: the tree over the
// input, the k nearest alone, and the whole estimate.
void TimeCurvature(
  vtkPolyData* input, const std::vector<double>& positions, const std::vector<double>& normals)
{
  using namespace asmcore;
  std::unique_ptr<double[]> copy;
  asmcore::PointIds idList;
  asmcore::IdView ids;
  const Coordinates xyz =
    asmvtk::PrepareCoordinates(input->GetPoints(), copy, idList, ids, false, true);
  const Index nq = static_cast<Index>(positions.size() / 3);
  double build = 1e9, knn = 1e9, all = 1e9;
  Neighbors tree;
  for (int r = 0; r < 3; ++r)
  {
    const double t0 = Cpu();
    tree.Build(xyz, ids);
    build = std::min(build, Cpu() - t0);
  }
  std::vector<Index> found;
  std::vector<double> d2;
  double check = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    const double t0 = Cpu();
    for (Index q = 0; q < nq; ++q)
    {
      tree.KNearest(positions.data() + 3 * q, DefaultCurvatureNeighbors, found, d2);
      check += d2.back();
    }
    knn = std::min(knn, Cpu() - t0);
  }
  // The neighbours' coordinates: from the tree's copies (what the curvature
  // reads since round 23), or gathered from the cloud (before).
  std::vector<double> local;
  double fromTree = 1e9, fromCloud = 1e9;
  for (int r = 0; r < 3; ++r)
  {
    double t0 = Cpu();
    for (Index q = 0; q < nq; ++q)
    {
      tree.KNearest(positions.data() + 3 * q, DefaultCurvatureNeighbors, found, d2, local);
      check += local[5];
    }
    fromTree = std::min(fromTree, Cpu() - t0);
    t0 = Cpu();
    for (Index q = 0; q < nq; ++q)
    {
      tree.KNearest(positions.data() + 3 * q, DefaultCurvatureNeighbors, found, d2);
      local.resize(3 * found.size());
      for (std::size_t j = 0; j < found.size(); ++j)
      {
        xyz.Get(found[j], local.data() + 3 * j);
      }
      check += local[5];
    }
    fromCloud = std::min(fromCloud, Cpu() - t0);
  }
  std::printf("    %d nearest with their coordinates, best of 3: from the tree %.1f ms, "
              "gathered from the cloud %.1f ms\n",
    DefaultCurvatureNeighbors, 1e3 * fromTree, 1e3 * fromCloud);
  for (int r = 0; r < 3; ++r)
  {
    const double t0 = Cpu();
    const auto estimates = EstimateCurvature(
      xyz, ids, tree, positions.data(), nq, normals.data(), DefaultCurvatureNeighbors, {});
    all = std::min(all, Cpu() - t0);
    check += estimates.empty() ? 0.0 : estimates[0].SurfaceVariation;
  }
  std::printf("    curvature at %lld positions, best of 3: tree %.1f ms, %d nearest %.1f ms "
              "(%.2f us each), estimates with their queries %.1f ms (check %g)\n",
    (long long)nq, 1e3 * build, DefaultCurvatureNeighbors, 1e3 * knn,
    1e6 * knn / std::max<Index>(nq, 1), 1e3 * all, check);
}

// The core's stages one by one, one thread (mirrors asmcore::Simplify).
void TimeStages(vtkPolyData* input, double fraction, int mode)
{
  using namespace asmcore;
  double t0 = Cpu();
  std::unique_ptr<double[]> copy;
  asmcore::PointIds idList;
  asmcore::IdView ids;
  const double* xyz = asmvtk::PrepareCoordinates(input->GetPoints(), copy, idList, ids).Doubles;
  double t1 = Cpu();
  double t2 = Cpu();
  const Index target = static_cast<Index>(std::llround(fraction * ids.size()));
  const Bounds bounds = ComputeBounds(xyz, ids);
  double t3 = Cpu();
  const double cellSize = AutomaticCellSize(xyz, ids, bounds, target / 8.0);
  double t4 = Cpu();
  const double search = t4 - t3; // before the extra counts below
  double best = 1e9;
  for (int r = 0; r < 7; ++r)
  {
    const double c0 = Cpu();
    CountOccupiedCells(xyz, ids, GridSpec::Make(bounds, cellSize));
    best = std::min(best, Cpu() - c0);
  }
  std::printf("    (one occupancy count, best of 7: %.1f ms)\n", 1e3 * best);
  t4 = Cpu();
  const CellGrid grid = BuildCellGrid(xyz, ids, GridSpec::Make(bounds, cellSize));
  double t5 = Cpu();
  const Index cells = grid.NumberOfCells();
  std::vector<CellFrame> frames(cells);
  for (Index c = 0; c < cells; ++c)
    frames[c] = ComputeCellFrame(xyz, grid.CellIds(c));
  double t6 = Cpu();
  std::vector<double> share(cells);
  std::vector<Index> capacity(cells);
  for (Index c = 0; c < cells; ++c)
  {
    capacity[c] = grid.CellSizeOf(c);
    share[c] = double(capacity[c]);
  }
  const std::vector<Index> budget = ApportionBudget(share, capacity, target);
  double t7 = Cpu();
  KeyPointRule rule;
  rule.CoordinateEpsilon = 1.2e-7;
  LocalPoints q;
  Index keys = 0;
  for (Index c = 0; c < cells; ++c)
  {
    KeyClusters kc = FindCellKeyClusters(xyz, grid.CellIds(c), frames[c], rule, q);
    keys += kc.Key.Size();
  }
  double t8 = Cpu();
  std::printf("  stages (1 thread, %lld points, %lld cells, %lld key clusters):\n",
    (long long)ids.size(), (long long)cells, (long long)keys);
  std::printf("    coordinates + finite ids %6.1f ms\n", 1e3 * (t1 - t0));
  std::printf("    finite ids             %8.1f ms\n", 1e3 * (t2 - t1));
  std::printf("    bounds                 %8.1f ms\n", 1e3 * (t3 - t2));
  std::printf("    automatic cell size    %8.1f ms\n", 1e3 * search);
  std::printf("    grid (hash + sort)     %8.1f ms\n", 1e3 * (t5 - t4));
  std::printf("    PCA per cell           %8.1f ms\n", 1e3 * (t6 - t5));
  std::printf("    budgets                %8.1f ms\n", 1e3 * (t7 - t6));
  std::printf("    key clusters (local frame, partition, link) %8.1f ms\n", 1e3 * (t8 - t7));
  std::printf("    (sampling, assembly, output arrays: the rest of the end-to-end time)\n");
  // Share of asmcore::Simplify's CPU time spent inside Execution loops (what
  // a second thread can share): an Amdahl bound robust to a loaded machine.
  std::vector<double> positions, normals;
  {
    double inside = 0.0;
    asmcore::Execution counting;
    counting.For = [&inside](Index b, Index e, const std::function<void(Index, Index)>& body) {
      const double c0 = Cpu();
      body(b, e);
      inside += Cpu() - c0;
    };
    SimplifyParameters parameters;
    parameters.NumberOfSamples = target;
    parameters.CoordinateEpsilon = 1.2e-7;
    if (mode == vtkASMSimplify::PAPER)
    {
      parameters.Mode = asmcore::SimplifyMode::Paper;
    }
    const double c0 = Cpu();
    const SimplifyResult result = Simplify(xyz, ids, nullptr, parameters, counting);
    const double total = Cpu() - c0;
    std::printf(
      "    asmcore::Simplify %.1f ms, %.1f %% of it in parallel loops: 2-thread bound %.2fx\n",
      1e3 * total, 100.0 * inside / total, 1.0 / ((total - inside) / total + 0.5 * inside / total));
    for (const Sample& s : result.Samples)
    {
      positions.insert(positions.end(), s.Position, s.Position + 3);
      normals.insert(normals.end(), s.Normal, s.Normal + 3);
    }
  }
  TimeCurvature(input, positions, normals);
}

// A loop body's call site, readable: its demangled type without argument
// lists and template arguments ("AssignPasses::{lambda#1}").
std::string CallSite(const std::type_info& type)
{
  int status = 0;
  char* raw = abi::__cxa_demangle(type.name(), nullptr, nullptr, &status);
  const std::string full = status == 0 && raw ? raw : type.name();
  std::free(raw);
  std::string out;
  int parens = 0, angles = 0;
  for (char ch : full)
  {
    if (ch == '(' && angles == 0)
      ++parens;
    else if (ch == ')' && angles == 0 && parens > 0)
      --parens;
    else if (ch == '<' && parens == 0)
      ++angles;
    else if (ch == '>' && parens == 0 && angles > 0)
      --angles;
    else if (parens == 0 && angles == 0)
      out += ch;
  }
  for (const std::string drop : { "asmcore::", "(anonymous namespace)::", "std::function" })
  {
    for (std::size_t at; (at = out.find(drop)) != std::string::npos;)
      out.erase(at, drop.size());
  }
  return out;
}

// asmcore::Simplify's parallel loops by call site, with each thread count:
// the median over runs of each site's summed wall time, and of the time
// outside the loops (what a second thread cannot share).
void TimeLoops(vtkPolyData* input, double fraction, int mode, int runs,
  const std::vector<long>& threadCounts, const std::function<bool(vtkASMSimplify*)>& settings)
{
  using namespace asmcore;
  std::unique_ptr<double[]> copy;
  PointIds idList;
  IdView ids;
  const Coordinates xyz = asmvtk::PrepareCoordinates(input->GetPoints(), copy, idList, ids);
  vtkNew<vtkASMSimplify> filter;
  if (mode >= 0)
    filter->SetMode(mode);
  settings(filter);
  const auto target = static_cast<vtkIdType>(std::llround(fraction * ids.size()));
  SimplifyParameters parameters = asmvtk::CoreParameters(filter, target);
  if (filter->GetRelativeErrorTolerance() && filter->GetErrorTolerance() > 0.0)
    parameters.ErrorTolerance *= ComputeBounds(xyz, ids).Diagonal();
  parameters.CoordinateEpsilon = xyz.Floats ? 1.1920928955078125e-07 : 2.220446049250313e-16;

  struct Site
  {
    std::string Name;
    long Calls = 0;
    std::map<long, std::vector<double>> Ms; // per thread count, per run
  };
  std::map<std::string, Site> sites; // by the body's mangled type name
  std::map<long, std::vector<double>> totalMs, outsideMs;
  for (int r = 0; r < runs; ++r)
  {
    for (long t : threadCounts)
    {
      vtkSMPTools::Initialize(static_cast<int>(t));
      std::map<std::string, double> run; // this run's ms per site
      int depth = 0;
      Execution execution;
      execution.For = [&](Index b, Index e, const std::function<void(Index, Index)>& body) {
        const double start = Now();
        ++depth;
        if (t > 1)
          vtkSMPTools::For(b, e, [&body](vtkIdType first, vtkIdType last) { body(first, last); });
        else
          Execution().Run(b, e, body); // (the filter's 1-thread way: the calling thread)
        --depth;
        if (depth == 0)
        {
          Site& site = sites[body.target_type().name()];
          if (site.Name.empty())
            site.Name = CallSite(body.target_type());
          site.Calls += (r == 0 && t == threadCounts.front()) ? 1 : 0;
          run[body.target_type().name()] += 1e3 * (Now() - start);
        }
      };
      malloc_trim(0);
      const double start = Now();
      const SimplifyResult result = Simplify(xyz, ids, nullptr, parameters, execution);
      const double total = 1e3 * (Now() - start);
      double inside = 0.0;
      for (auto& entry : sites)
      {
        const double ms = run.count(entry.first) ? run[entry.first] : 0.0;
        entry.second.Ms[t].push_back(ms);
        inside += ms;
      }
      totalMs[t].push_back(total);
      outsideMs[t].push_back(total - inside);
      if (result.Samples.size() != static_cast<std::size_t>(target))
        std::printf("    (%zu samples, not %lld)\n", result.Samples.size(), (long long)target);
    }
  }
  std::vector<const Site*> order;
  for (const auto& entry : sites)
    order.push_back(&entry.second);
  const long one = threadCounts.front();
  auto median = [](const std::map<long, std::vector<double>>& ms, long t) {
    const auto it = ms.find(t);
    return it == ms.end() || it->second.empty() ? 0.0 : Median(it->second);
  };
  std::sort(order.begin(), order.end(),
    [&](const Site* a, const Site* b) { return median(a->Ms, one) > median(b->Ms, one); });
  std::printf("  asmcore::Simplify's loops (%lld points, N_s %lld, wall ms, medians of %d runs):\n",
    (long long)ids.size(), (long long)target, runs);
  std::printf("    %6s", "calls");
  for (long t : threadCounts)
    std::printf(" %8ld thr", t);
  std::printf("  %6s  call site\n", "x");
  auto row = [&](const char* name, long calls, const std::map<long, std::vector<double>>& ms) {
    std::printf("    %6ld", calls);
    for (long t : threadCounts)
      std::printf(" %12.1f", median(ms, t));
    const double last = median(ms, threadCounts.back());
    std::printf("  %6.2f  %s\n", last > 0.0 ? median(ms, one) / last : 0.0, name);
  };
  row("asmcore::Simplify, in all", 1, totalMs);
  row("outside the loops", 0, outsideMs);
  for (const Site* site : order)
  {
    if (median(site->Ms, one) >= 0.05)
      row(site->Name.c_str(), site->Calls, site->Ms);
  }
}

// The floor of a grid simplifier with a target count, on this input (its
// own coordinates, floats in place, one thread, best of 3): the bounds, one
// occupancy count (the least a search for the cell size can do), the grid
// (hash + counting sort) and one pass over every cell's points (a centroid
// per cell) -- what the grouping alone costs, before any of ASM's per-cell
// steps.
void TimeFloor(vtkPolyData* input, double fraction)
{
  using namespace asmcore;
  std::unique_ptr<double[]> copy;
  asmcore::PointIds idList;
  asmcore::IdView ids;
  const Coordinates xyz =
    asmvtk::PrepareCoordinates(input->GetPoints(), copy, idList, ids, true, true);
  const auto n = static_cast<double>(ids.size());
  const double cellSize = AutomaticCellSize(xyz, ids, ComputeBounds(xyz, ids), fraction * n / 8.0);
  double best[5] = { 1e9, 1e9, 1e9, 1e9, 1e9 };
  double sum = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    const double t0 = Cpu();
    const Bounds bounds = ComputeBounds(xyz, ids);
    const double t1 = Cpu();
    const GridSpec spec = GridSpec::Make(bounds, cellSize);
    sum += static_cast<double>(CountOccupiedCells(xyz, ids, spec));
    const double t2 = Cpu();
    const CellGrid grid = BuildCellGrid(xyz, ids, spec);
    const double t3 = Cpu();
    for (Index c = 0; c < grid.NumberOfCells(); ++c)
    {
      double centroid[3] = { 0, 0, 0 };
      for (Index id : grid.CellIds(c))
      {
        double p[3];
        xyz.Get(id, p);
        for (int a = 0; a < 3; ++a)
          centroid[a] += p[a];
      }
      sum += centroid[0] + centroid[1] + centroid[2];
    }
    const double t4 = Cpu();
    const double part[5] = { t1 - t0, t2 - t1, t3 - t2, t4 - t3, t4 - t0 };
    for (int k = 0; k < 5; ++k)
      best[k] = std::min(best[k], part[k]);
  }
  const double ns = 1e9 / n;
  volatile double sink = sum; // (the centroids are computed, not optimised away)
  (void)sink;
  std::printf("  floor (1 thread, best of 3, ns per point): bounds %.1f, one occupancy count %.1f, "
              "grid %.1f, a pass over the cells %.1f; in all %.1f ns = %.1f M pt/s\n",
    ns * best[0], ns * best[1], ns * best[2], ns * best[3], ns * best[4], n / best[4] / 1e6);
}
} // namespace

// RGB colour, intensity and normals, as a scanner writes them (values from
// the coordinates: deterministic).
void AddScanArrays(vtkPolyData* input)
{
  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> intensity;
  intensity->SetName("Intensity");
  intensity->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int a = 0; a < 3; ++a)
    {
      rgb->SetTypedComponent(
        i, a, static_cast<unsigned char>(127.5 * (1.0 + p[a] / (r > 0 ? r : 1))));
      normals->SetTypedComponent(i, a, static_cast<float>(r > 0 ? p[a] / r : 0.0));
    }
    intensity->SetValue(i, static_cast<float>(r));
  }
  input->GetPointData()->AddArray(rgb);
  input->GetPointData()->AddArray(intensity);
  input->GetPointData()->SetNormals(normals);
}

// vtkKeyPointError on (original, simplified), `runs` times at the current
// thread count: median wall time and the figures of the last run.
void TimeKeyPointError(vtkPolyData* original, vtkPolyData* simplified, int runs, bool curvature)
{
  std::vector<double> times;
  vtkSmartPointer<vtkTable> figures;
  for (int r = 0; r < runs; ++r)
  {
    vtkNew<vtkKeyPointError> kpe;
    kpe->SetInputData(0, original);
    kpe->SetInputData(1, simplified);
    kpe->SetGenerateCurvature(curvature);
    const double start = Now();
    kpe->Update();
    times.push_back(Now() - start);
    figures = vtkTable::SafeDownCast(kpe->GetOutputDataObject(1));
  }
  auto figure = [&](const char* name) {
    vtkAbstractArray* column = figures ? figures->GetColumnByName(name) : nullptr;
    return column ? column->GetVariantValue(0).ToDouble() : std::nan("");
  };
  std::printf("    vtkKeyPointError %.4f s (median of %d): AKPE %.17g MKPE %.17g "
              "point-to-plane mean %.17g max %.17g Hausdorff %.17g\n",
    Median(times), runs, figure("AKPE"), figure("MKPE"), figure("PointToPlaneMean"),
    figure("PointToPlaneMax"), figure("HausdorffDistance"));
}

int main(int argc, char* argv[])
{
  std::vector<long> sizes = { 1000000 };
  std::vector<long> threads = { 1 };
  bool threadsGiven = false;
  int runs = 3;
  double fraction = 0.05;
  bool curvature = false, stages = false, coherent = false, arrays = false, floor = false;
  bool error = false, loops = false;
  const char* ply = nullptr;
  const char* dump = nullptr;
  int mode = -1;
  std::string settings;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const char* next = i + 1 < argc ? argv[i + 1] : "";
    if (a == "--points")
      sizes = ParseList(next), ++i;
    else if (a == "--threads")
      threads = ParseList(next), threadsGiven = true, ++i;
    else if (a == "--runs")
      runs = std::atoi(next), ++i;
    else if (a == "--fraction")
      fraction = std::atof(next), ++i;
    else if (a == "--ply")
      ply = next, ++i;
    else if (a == "--dump")
      dump = next, ++i;
    else if (a == "--mode")
      mode =
        std::string(next) == "paper" ? vtkASMSimplify::PAPER : vtkASMSimplify::FEATURE_PRESERVING,
      ++i;
    else if (a == "--set")
      settings = next, ++i;
    else if (a == "--curvature")
      curvature = true;
    else if (a == "--coherent")
      coherent = true;
    else if (a == "--arrays")
      arrays = true;
    else if (a == "--stages")
      stages = true;
    else if (a == "--floor")
      floor = true;
    else if (a == "--error")
      error = true;
    else if (a == "--loops")
      loops = true;
    else
    {
      std::fprintf(stderr, "unknown argument %s (see the header of asm_profile.cxx)\n", a.c_str());
      return 2;
    }
  }
  // The settings are applied to every run's filter; checked here once.
  auto applySettings = [&settings](vtkASMSimplify* filter) {
    if (settings.empty())
      return true;
#ifdef ASM_PROFILE_SETTINGS
    std::string error;
    if (asmbench::ApplyAsmSettings(filter, settings, error))
      return true;
    std::fprintf(stderr, "--set: %s\n", error.c_str());
#else
    (void)filter;
    std::fprintf(stderr, "--set needs the benchmarks (ASM_BUILD_BENCHMARKS)\n");
#endif
    return false;
  };
  {
    vtkNew<vtkASMSimplify> probe;
    if (!applySettings(probe))
      return 2;
  }
  if (ply)
    sizes = { 0 };
  vtkSMPTools::SetBackend("STDThread");
  std::printf("%10s %7s %9s %10s %9s %10s %9s %12s %10s\n", "points", "threads", "curvature",
    "wall s", "Mpts/s", "cpu s", "Mpts/cpu", "peak B/pt", "output");
  for (long n : sizes)
  {
    vtkSmartPointer<vtkPolyData> input;
    if (ply)
    {
      vtkNew<vtkPLYReader> reader;
      reader->SetFileName(ply);
      reader->Update();
      input = reader->GetOutput();
    }
    else
    {
      input = Synthetic(n, 42, coherent);
    }
    const vtkIdType np = input->GetNumberOfPoints();
    if (arrays)
      AddScanArrays(input);
    if (stages)
      TimeStages(input, fraction, mode);
    if (floor)
      TimeFloor(input, fraction);
    if (loops)
    {
      TimeLoops(input, fraction, mode, runs, threadsGiven ? threads : std::vector<long>{ 1, 2 },
        applySettings);
      continue;
    }
    for (long t : threads)
    {
      vtkSMPTools::Initialize(static_cast<int>(t));
      std::vector<double> times, cpu;
      double peak = 0.0;
      vtkIdType outCount = 0;
      vtkSmartPointer<vtkPolyData> last;
      for (int r = 0; r < runs; ++r)
      {
        vtkNew<vtkASMSimplify> filter;
        filter->SetInputData(input);
        filter->SetOutputFraction(fraction);
        filter->SetGenerateCurvature(curvature);
        if (mode >= 0)
          filter->SetMode(mode);
        applySettings(filter);
        malloc_trim(0);
        ResetPeak();
        const long base = StatusKB("VmRSS:");
        const double start = Now(), cpuStart = Cpu();
        filter->Update();
        times.push_back(Now() - start);
        cpu.push_back(Cpu() - cpuStart);
        const long hwm = StatusKB("VmHWM:");
        peak = std::max(peak, 1024.0 * double(hwm - base) / double(np));
        vtkPolyData* out = filter->GetOutput();
        outCount = out->GetNumberOfPoints();
        last = out;
        if (dump && r == runs - 1)
        {
          std::FILE* f = std::fopen(dump, "w");
          vtkDataArray* oid = out->GetPointData()->GetArray("vtkOriginalPointIds");
          vtkDataArray* key = out->GetPointData()->GetArray("KeyPoint");
          vtkDataArray* mc = out->GetPointData()->GetArray("MeanCurvature");
          vtkDataArray* size = out->GetPointData()->GetArray("ClusterSize");
          for (vtkIdType i = 0; i < outCount; ++i)
          {
            double p[3];
            out->GetPoint(i, p);
            std::fprintf(f, "%.17g %.17g %.17g %lld %d %lld", p[0], p[1], p[2],
              (long long)oid->GetTuple1(i), int(key->GetTuple1(i)), (long long)size->GetTuple1(i));
            if (mc)
              std::fprintf(f, " %.12g", mc->GetTuple1(i));
            std::fprintf(f, "\n");
          }
          std::fclose(f);
        }
      }
      const double med = Median(times);
      const double medCpu = Median(cpu);
      std::printf("%10lld %7ld %9s %10.4f %9.2f %10.4f %9.2f %12.1f %10lld\n", (long long)np, t,
        curvature ? "on" : "off", med, np / med / 1e6, medCpu, np / medCpu / 1e6, peak,
        (long long)outCount);
      std::fflush(stdout);
      if (error && last)
      {
        TimeKeyPointError(input, last, runs, curvature);
      }
    }
  }
  return 0;
}
