// SPDX-License-Identifier: BSD-3-Clause
// asm_profile --loops: asmcore::Simplify's parallel loops by call site, with
// 1 and 2 threads, and the time outside them (see asm_profile.cxx).
#include "Profile.h"

#include "Core/Grid.h"
#include "Core/Simplify.h"
#include "vtkASMFilterUtilities.h"
#include "vtkASMSimplify.h"
#include "vtkASMSimplifySteps.h"

#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <cxxabi.h>
#include <malloc.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

namespace asmprofile
{
namespace
{
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

} // namespace

// asmcore::Simplify's parallel loops by call site, with each thread count:
// the median over runs of each site's summed wall time, and of the time
// outside the loops (what a second thread cannot share).
void TimeLoops(vtkPolyData* input, double fraction, int mode, int runs,
  const std::vector<long>& threadCounts, const std::function<bool(vtkASMSimplify*)>& settings)
{
  using namespace asmcore;
  const InputCoordinates cloud(input);
  const Coordinates xyz = cloud.Xyz;
  const IdView ids = cloud.Ids;
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
} // namespace asmprofile
