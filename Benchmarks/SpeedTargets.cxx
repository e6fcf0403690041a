// SPDX-License-Identifier: BSD-3-Clause
#include "SpeedTargets.h"

#include "BenchmarkReport.h"

#include <algorithm>
#include <iostream>

namespace asmbench
{
namespace
{
double Mpts(const Record* r)
{
  return r ? static_cast<double>(r->N) / r->Median / 1e6 : NAN;
}

std::string Verdict(bool known, bool pass)
{
  return known ? (pass ? "PASS" : "FAIL") : "n/a ";
}
} // namespace

const Record* Find(const std::vector<Record>& records, const std::string& input, double fraction,
  const std::string& method, int threads)
{
  for (const Record& r : records)
  {
    if (r.Input == input && std::abs(r.Fraction - fraction) < 1e-9 && r.Method == method &&
      r.Threads == threads)
    {
      return &r;
    }
  }
  return nullptr;
}

void PrintTargets(const std::vector<Record>& records, const std::vector<int>& threads)
{
  const int one = 1, two = 2;
  const double five = 0.05;
  std::cout << "\n## Targets (issue 8), N_s = 5 %, curvature off\n\n";
  const char* modes[] = { "ASM paper", "ASM default" };
  const double goals[] = { 20.0, 10.0 };
  for (int i = 0; i < 2; ++i)
  {
    std::string detail;
    bool known = false, pass = true;
    for (const char* input : { "bumps-4M", "bumps-14M" })
    {
      const double rate = Mpts(Find(records, input, five, modes[i], one));
      if (std::isfinite(rate))
      {
        known = true;
        pass = pass && rate >= goals[i];
      }
      detail += std::string(" ") + input + " " + Fixed(rate, 1);
    }
    std::cout << Verdict(known, pass) << "  " << modes[i] << " >= " << goals[i]
              << " M input pt/s, 1 thread, 4M and 14M:" << detail << "\n";
  }
  {
    std::string detail;
    bool known = false, pass = true;
    for (const char* mode : modes)
    {
      for (const char* input : { "bumps-4M", "bumps-14M" })
      {
        const Record* a = Find(records, input, five, mode, one);
        const Record* b = Find(records, input, five, mode, two);
        const double speedup = a && b ? a->Median / b->Median : NAN;
        if (std::isfinite(speedup))
        {
          known = true;
          pass = pass && speedup >= 1.7;
        }
        detail += std::string(" ") + mode + " " + input + " " +
          (std::isfinite(speedup) ? "x" + Fixed(speedup, 2) : "-") + ";";
      }
    }
    std::cout << Verdict(known, pass)
              << "  >= 1.7x from 1 to 2 threads, both modes, 4M and 14M:" << detail << "\n";
  }
  {
    // Both modes faster than vtkVoxelGrid on every input, fraction and thread count.
    int cases = 0, wins = 0;
    double worst = INFINITY;
    std::string where;
    for (const Record& r : records)
    {
      if (r.Method != modes[0] && r.Method != modes[1])
      {
        continue;
      }
      const Record* voxel = Find(records, r.Input, r.Fraction, "vtkVoxelGrid", r.Threads);
      if (!voxel)
      {
        continue;
      }
      const double ratio = voxel->Median / r.Median;
      ++cases;
      wins += ratio > 1.0 ? 1 : 0;
      if (ratio < worst)
      {
        worst = ratio;
        where = r.Method + " on " + r.Input + " at " + Format(100.0 * r.Fraction, 3) + " %, " +
          std::to_string(r.Threads) + " thread(s)";
      }
    }
    std::cout << Verdict(cases > 0, wins == cases)
              << "  both modes faster than vtkVoxelGrid on every input: " << wins << "/" << cases
              << " cases, slowest x" << Fixed(worst, 2) << " (" << where << ")\n";
  }
  for (const char* mode : modes)
  {
    // Time per point over the synthetic sizes, 1 thread.
    double lo = INFINITY, hi = 0.0;
    std::string detail;
    int sizes = 0;
    for (const Record& r : records)
    {
      if (r.Method == mode && r.Threads == one && std::abs(r.Fraction - five) < 1e-9 &&
        r.Input.compare(0, 6, "bumps-") == 0)
      {
        const double ns = 1e9 * r.Median / static_cast<double>(r.N);
        lo = std::min(lo, ns);
        hi = std::max(hi, ns);
        ++sizes;
        detail += " " + r.Input + " " + Fixed(ns, 0) + " ns";
      }
    }
    const double spread = sizes > 1 ? 100.0 * (hi / lo - 1.0) : NAN;
    std::cout << Verdict(sizes > 1, spread < 25.0) << "  " << mode
              << ": time per point within 25 % from 100k to 14M, 1 thread: spread "
              << Fixed(spread, 0) << " %;" << detail << "\n";
  }
  {
    double worst = 0.0;
    std::string where;
    bool known = false;
    for (const Record& r : records)
    {
      if ((r.Method == modes[0] || r.Method == modes[1]) && std::isfinite(r.Memory))
      {
        known = true;
        if (r.Memory >= worst)
        {
          worst = r.Memory;
          where = r.Method + " on " + r.Input + " at " + Format(100.0 * r.Fraction, 3) + " %";
        }
      }
    }
    std::cout << Verdict(known, worst <= 48.0)
              << "  peak memory beyond input and output <= 48 B/pt, both modes:"
              << " largest " << Fixed(worst, 1) << " B/pt (" << where << ")\n";
  }
  if (std::find(threads.begin(), threads.end(), 1) == threads.end() ||
    std::find(threads.begin(), threads.end(), 2) == threads.end())
  {
    std::cout << "(threads 1 and 2 are both needed for every target)\n";
  }
}
} // namespace asmbench
