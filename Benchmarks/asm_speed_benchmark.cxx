// SPDX-License-Identifier: BSD-3-Clause
/**
 * asm_speed_benchmark: times vtkASMSimplify's configurations (both modes,
 * curvature off and on) against vtkVoxelGrid (leaf size searched, not timed,
 * so that its count is within 1 % of N_s) and vtkMaskPoints (random, exact
 * count) on the same inputs, at each output fraction and thread count
 * (vtkSMPTools' STDThread backend), in one run (issue 8).
 *
 *   asm_speed_benchmark [--quick] [--runs 5] [--threads 1,2]
 *                       [--fractions 0.05,0.01,0.2] [--inputs spec,...]
 *                       [--no-memory] [--markdown] [more inputs ...]
 *
 * Inputs: .ply paths, or synthetic "bumps:100k" ... "bumps:14M" (a bumpy
 * sphere sampled uniformly by area). Default: the bundled scans and bumps
 * at 100k, 1M, 4M, 14M; inputs named on the command line are added.
 *
 * Per row: median wall time of --runs runs of the filter's Update() alone,
 * M input points per second, for ASM rows the speed ratio to each peer
 * (peer time / ASM time: > 1 means ASM is faster), and the peak memory
 * beyond the input and the output, in bytes per input point (measured once,
 * with the first thread count, in a forked child: see PeakExtraBytes).
 */
#include "BenchmarkData.h"
#include "BenchmarkMethods.h"
#include "BenchmarkReport.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>

using namespace asmbench;

namespace
{
void Usage()
{
  std::cout << "usage: asm_speed_benchmark [--quick] [--runs 5] [--threads 1,2]\n"
               "                           [--fractions 0.05,0.01,0.2] [--inputs spec,...]\n"
               "                           [--no-memory] [--markdown] [input ...]\n"
               "input: a .ply path, or bumps:100k, bumps:1M, bumps:4M, bumps:14M\n";
}

/// The first figure of /proc/loadavg ("?" elsewhere): timings on a busy machine are slower.
std::string LoadAverage()
{
  std::ifstream in("/proc/loadavg");
  std::string first;
  return in >> first ? first : std::string("?");
}

void SetThreads(int threads)
{
  vtkSMPTools::SetBackend("STDThread");
  vtkSMPTools::Initialize(threads);
}

/// Timing of one method at one thread count.
struct Timing
{
  double Median = NAN;
  vtkIdType Count = 0;
};
} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> inputs;
  for (const char* scan : { "bunny", "fandisk", "kitten", "laurana" })
  {
    inputs.push_back(std::string(ASM_BENCHMARK_DATA_DIR) + "/" + scan + ".ply");
  }
  for (const char* size : { "bumps:100k", "bumps:1M", "bumps:4M", "bumps:14M" })
  {
    inputs.push_back(size);
  }
  std::vector<double> fractions = { 0.05, 0.01, 0.2 };
  std::vector<int> threads = { 1, 2 };
  int runs = 5;
  bool markdown = false, memory = true;
  std::vector<std::string> extra;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--help" || arg == "-h")
    {
      Usage();
      return 0;
    }
    else if (arg == "--quick")
    {
      inputs = { std::string(ASM_BENCHMARK_DATA_DIR) + "/kitten.ply", "bumps:20k" };
      fractions = { 0.05 };
      runs = 1;
    }
    else if (arg == "--markdown")
    {
      markdown = true;
    }
    else if (arg == "--no-memory")
    {
      memory = false;
    }
    else if (arg == "--runs" && hasValue)
    {
      runs = std::max(1, std::atoi(argv[++i]));
    }
    else if (arg == "--inputs" && hasValue)
    {
      inputs = SplitList(argv[++i]);
    }
    else if (arg == "--fractions" && hasValue)
    {
      fractions.clear();
      for (const auto& f : SplitList(argv[++i]))
      {
        fractions.push_back(std::atof(f.c_str()));
      }
    }
    else if (arg == "--threads" && hasValue)
    {
      threads.clear();
      for (const auto& t : SplitList(argv[++i]))
      {
        threads.push_back(std::max(1, std::atoi(t.c_str())));
      }
    }
    else if (arg.compare(0, 2, "--") == 0)
    {
      Usage();
      return 2;
    }
    else
    {
      extra.push_back(arg);
    }
  }
  inputs.insert(inputs.end(), extra.begin(), extra.end());

  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
  std::cout << "# asm_speed_benchmark, " << date << ", median of " << runs
            << " run(s), vtkSMPTools STDThread backend, load average " << LoadAverage() << "\n"
            << "# Mpt/s: million input points per second; x peer: peer time / ASM time (> 1: ASM"
               " faster); mem: peak memory beyond input and output, bytes per input point; *: count not within 1 % of N_s\n";

  Table table({ "input", "N", "N_s", "method", "threads", "median s", "Mpt/s", "x vtkVoxelGrid",
    "x vtkMaskPoints", "mem B/pt" });
  // Summary data: seconds per input point, by ASM configuration, fraction, input, threads.
  std::map<std::string, std::map<std::string, std::map<int, double>>> perPoint; // key: config@fraction
  std::vector<std::string> order;
  for (const std::string& spec : inputs)
  {
    SetThreads(threads.back());
    const Input input = MakeInput(spec);
    if (!input.Data)
    {
      continue;
    }
    order.push_back(input.Name);
    const vtkIdType n = input.NumberOfPoints();
    for (double fraction : fractions)
    {
      const vtkIdType target = std::max<vtkIdType>(1, std::llround(fraction * static_cast<double>(n)));
      SetThreads(threads.back());
      std::vector<Method> methods;
      for (const AsmConfig& c : AsmConfigurations())
      {
        Method m = MakeAsm(input.Data, target, c);
        if (m.Run)
        {
          methods.push_back(m);
        }
      }
      methods.push_back(MakeVoxelGrid(input.Data, target)); // the search is not timed
      methods.push_back(MakeMaskPoints(input.Data, target, 1));

      std::map<std::string, double> memoryPerPoint;
      for (int t : threads)
      {
        SetThreads(t);
        std::map<std::string, Timing> timings;
        for (const Method& m : methods)
        {
          std::vector<double> seconds;
          Timing timing;
          m.Run(false); // warm-up, not timed
          for (int r = 0; r < runs; ++r)
          {
            const RunResult result = m.Run(false);
            seconds.push_back(result.Seconds);
            timing.Count = result.Count;
          }
          timing.Median = Median(seconds);
          timings[m.Name] = timing;
          if (memory && t == threads.front())
          {
            const double bytes = PeakExtraBytes([&m]() { return m.Run(false).OutputBytes; });
            memoryPerPoint[m.Name] = bytes >= 0.0 ? std::max(0.0, bytes) / static_cast<double>(n) : NAN;
          }
        }
        for (const Method& m : methods)
        {
          const Timing& timing = timings[m.Name];
          auto ratio = [&](const char* peer) {
            return m.IsASM ? "x" + Format(timings[peer].Median / timing.Median, 3) : std::string();
          };
          const auto mem = memoryPerPoint.find(m.Name);
          // "*": the method could not be driven within 1 % of N_s.
          const bool off = std::abs(static_cast<double>(timing.Count - target)) >
            std::max(0.5, 0.01 * static_cast<double>(target));
          table.Add({ input.Name, std::to_string(n), std::to_string(timing.Count) + (off ? "*" : ""), m.Name,
            std::to_string(t), Format(timing.Median, 3),
            Fixed(static_cast<double>(n) / timing.Median / 1e6, 1), ratio("vtkVoxelGrid"),
            ratio("vtkMaskPoints random"),
            t == threads.front() && mem != memoryPerPoint.end() ? Fixed(mem->second, 1) : "" });
          if (m.IsASM)
          {
            perPoint[m.Name + " @ " + Format(100.0 * fraction, 3) + " %"][input.Name][t] =
              timing.Median / static_cast<double>(n);
          }
        }
      }
      // Print as we go: the full run takes a while.
      table.Print(std::cout, markdown);
      std::cout << "\n";
      table = Table({ "input", "N", "N_s", "method", "threads", "median s", "Mpt/s",
        "x vtkVoxelGrid", "x vtkMaskPoints", "mem B/pt" });
    }
  }

  // Summary: nanoseconds per input point on each input (first thread count),
  // speed-up from the first to the last thread count, and the spread of the
  // time per point over the inputs.
  std::cout << "## Summary: ns per input point with " << threads.front() << " thread(s) (speed-up with "
            << threads.back() << "); spread = max/min - 1 of ns per point over the synthetic bumps-* inputs\n\n";
  std::vector<std::string> header = { "ASM configuration" };
  header.insert(header.end(), order.begin(), order.end());
  header.push_back("spread");
  Table summary(header);
  for (const auto& entry : perPoint)
  {
    std::vector<std::string> cells = { entry.first };
    double lo = INFINITY, hi = 0.0;
    for (const std::string& name : order)
    {
      const auto it = entry.second.find(name);
      if (it == entry.second.end() || !it->second.count(threads.front()))
      {
        cells.push_back("-");
        continue;
      }
      const double first = it->second.at(threads.front());
      if (name.compare(0, 6, "bumps-") == 0) // spread over the synthetic sizes
      {
        lo = std::min(lo, first);
        hi = std::max(hi, first);
      }
      std::string cell = Fixed(1e9 * first, 0);
      if (threads.size() > 1 && it->second.count(threads.back()))
      {
        cell += " (x" + Fixed(first / it->second.at(threads.back()), 2) + ")";
      }
      cells.push_back(cell);
    }
    cells.push_back(hi > 0.0 ? Fixed(100.0 * (hi / lo - 1.0), 0) + " %" : "-");
    summary.Add(cells);
  }
  summary.Print(std::cout, markdown);
  std::cout << "\n# load average at the end: " << LoadAverage() << "\n";
  return 0;
}
