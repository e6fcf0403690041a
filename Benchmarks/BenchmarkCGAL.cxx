// SPDX-License-Identifier: BSD-3-Clause
// CGAL's point-set simplifiers as benchmark peers (built only when CGAL's
// headers are found: ASM_BENCHMARK_HAVE_CGAL).
#include "BenchmarkMethods.h"

#include "BenchmarkData.h"

#include <cmath>

#ifdef ASM_BENCHMARK_HAVE_CGAL
#include <CGAL/Simple_cartesian.h>
#include <CGAL/grid_simplify_point_set.h>
#include <CGAL/hierarchy_simplify_point_set.h>

#include <memory>
#endif

namespace asmbench
{
#ifdef ASM_BENCHMARK_HAVE_CGAL
namespace
{
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Points = std::vector<Point>;

// The finite points of `input` (CGAL's simplifiers crash on a NaN; ASM
// skips the non-finite points too).
std::shared_ptr<const Points> ToCgal(vtkPolyData* input)
{
  const std::vector<double> xyz = Coordinates(input);
  auto points = std::make_shared<Points>();
  points->reserve(xyz.size() / 3);
  for (std::size_t i = 0; i < xyz.size(); i += 3)
  {
    if (std::isfinite(xyz[i]) && std::isfinite(xyz[i + 1]) && std::isfinite(xyz[i + 2]))
    {
      points->emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
    }
  }
  return points;
}

/// Runs `simplify` (returns the end of the kept range) on a copy of the
/// points (the copy is not timed).
template <typename Simplify>
RunResult RunCgal(const Points& original, bool keep, const Simplify& simplify)
{
  Points points = original;
  const double start = Now();
  const auto end = simplify(points);
  RunResult r;
  r.Seconds = Now() - start;
  r.Count = static_cast<vtkIdType>(end - points.begin());
  r.OutputBytes = static_cast<double>(r.Count) * sizeof(Point);
  if (keep)
  {
    r.Xyz.reserve(static_cast<std::size_t>(3 * r.Count));
    for (auto it = points.begin(); it != end; ++it)
    {
      r.Xyz.insert(r.Xyz.end(), { it->x(), it->y(), it->z() });
    }
  }
  return r;
}
} // namespace

bool HaveCGAL()
{
  return true;
}

Method MakeCgalGrid(vtkPolyData* input, vtkIdType target)
{
  const auto points = ToCgal(input);
  auto run = [points](double epsilon, bool keep) {
    return RunCgal(
      *points, keep, [epsilon](Points& p) { return CGAL::grid_simplify_point_set(p, epsilon); });
  };
  const double diagonal = input->GetLength(); // bounding-box diagonal
  vtkIdType found = 0;
  const double epsilon = SearchScale([&run](double e) { return run(e, false).Count; }, target,
    diagonal / std::sqrt(static_cast<double>(target)), 2.0, 0.01, 40, found, 40);
  Method m;
  m.Name = "CGAL grid";
  m.Note = "epsilon " + std::to_string(epsilon);
  m.Run = [run, epsilon](bool keep) { return run(epsilon, keep); };
  return m;
}

Method MakeCgalHierarchy(vtkPolyData* input, vtkIdType target)
{
  const auto points = ToCgal(input);
  auto run = [points](unsigned int size, double variation, bool keep) {
    return RunCgal(*points, keep, [size, variation](Points& p) {
      return CGAL::hierarchy_simplify_point_set(
        p, CGAL::parameters::size(size).maximum_variation(variation));
    });
  };
  const double slack = std::max(0.5, 0.01 * static_cast<double>(target));
  // The count falls as the cluster size grows: the smallest size whose
  // count is <= target (bisection), then a smaller maximum variation (more
  // splits) to come up to target. The bisection starts from a bracket
  // around N / N_s, found by doubling or halving (a few runs on a large
  // cloud, where [1, N] would take log2 N).
  const unsigned int n = static_cast<unsigned int>(std::max<vtkIdType>(2, points->size()));
  unsigned int lo = 1, hi = n;
  vtkIdType hiCount = 0;
  const unsigned int guess = static_cast<unsigned int>(std::min<double>(n,
    std::max(2.0, static_cast<double>(n) / static_cast<double>(std::max<vtkIdType>(1, target)))));
  const vtkIdType guessCount = run(guess, 1.0 / 3.0, false).Count;
  if (guessCount > target)
  {
    lo = hi = guess; // count(lo) > target
    hiCount = guessCount;
    while (hiCount > target && hi < n)
    {
      lo = hi;
      hi = hi >= n / 2 ? n : 2 * hi;
      hiCount = run(hi, 1.0 / 3.0, false).Count;
    }
  }
  else
  {
    hi = guess;
    hiCount = guessCount;
    for (unsigned int s = guess / 2; s > 1; s /= 2)
    {
      const vtkIdType c = run(s, 1.0 / 3.0, false).Count;
      if (c > target)
      {
        lo = s;
        break;
      }
      hi = s;
      hiCount = c;
    }
  }
  while (hi - lo > 1)
  {
    const unsigned int mid = lo + (hi - lo) / 2;
    const vtkIdType c = run(mid, 1.0 / 3.0, false).Count;
    if (c > target)
    {
      lo = mid;
    }
    else
    {
      hi = mid;
      hiCount = c;
    }
  }
  double variation = 1.0 / 3.0;
  if (std::abs(static_cast<double>(hiCount - target)) > slack)
  {
    double vLo = 1e-6, vHi = 1.0 / 3.0; // count(vLo) > target >= count(vHi)
    double bestVariation = vHi;
    vtkIdType best = hiCount;
    for (int i = 0; i < 30; ++i)
    {
      const double v = std::sqrt(vLo * vHi);
      const vtkIdType c = run(hi, v, false).Count;
      if (std::abs(static_cast<double>(c - target)) < std::abs(static_cast<double>(best - target)))
      {
        best = c;
        bestVariation = v;
      }
      if (std::abs(static_cast<double>(c - target)) <= slack)
      {
        break;
      }
      (c > target ? vLo : vHi) = v;
    }
    variation = bestVariation;
  }
  Method m;
  m.Name = "CGAL hierarchy";
  m.Note = "size " + std::to_string(hi) + ", variation " + std::to_string(variation);
  const unsigned int size = hi;
  m.Run = [run, size, variation](bool keep) { return run(size, variation, keep); };
  return m;
}

#else

bool HaveCGAL()
{
  return false;
}
Method MakeCgalGrid(vtkPolyData*, vtkIdType)
{
  return Method{ "CGAL grid", false, "not built", {} };
}
Method MakeCgalHierarchy(vtkPolyData*, vtkIdType)
{
  return Method{ "CGAL hierarchy", false, "not built", {} };
}
#endif
} // namespace asmbench
