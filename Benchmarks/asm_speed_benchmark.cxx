// SPDX-License-Identifier: BSD-3-Clause
/**
 * asm_speed_benchmark: times vtkASMSimplify's configurations (both modes,
 * curvature off and on) against vtkVoxelGrid (leaf size searched, not timed,
 * so that its count is within 1 % of N_s) and vtkMaskPoints (random, exact
 * count) on the same inputs, at each output fraction and thread count
 * (vtkSMPTools' STDThread backend, or --backend), in one run (issue 8).
 *
 *   asm_speed_benchmark [--quick | --readme] [--runs 5] [--threads 1,2]
 *                       [--fractions 0.05,0.01,0.2] [--inputs spec,...]
 *                       [--no-memory] [--markdown] [--asm NAME:SETTINGS ...]
 *                       [--cgal] [--backend STDThread] [more inputs ...]
 *
 * --backend picks vtkSMPTools' backend (default STDThread; TBB or OpenMP when
 * this VTK has them, e.g. Debian's VTK 9.1: scripts/fetch-vtk91.sh).
 *
 * --asm adds a row for vtkASMSimplify with more properties set (the default
 * mode unless Mode=paper; ApplyAsmSettings), e.g. --asm "ASM fast:FillHoles=0";
 * the targets block checks "ASM default" and "ASM paper" only.
 *
 * --cgal also times CGAL's grid_simplify_point_set and
 * hierarchy_simplify_point_set (when built with Debian's libcgal-dev; each
 * driven within 1 % of N_s, the search not timed), the simplifiers issue 8
 * names as the usual choices, with the ratio of each ASM row to them. They
 * run on one thread and simplify in place: each run works on a copy of the
 * points made before its clock starts, and their memory counts that copy.
 *
 * --readme: the README's run, ~7 minutes on 2 idle cores: bunny,
 * bunny-scans (../shared/data), bumps at 100k, 1M, 4M, 14M; N_s = 5 % (and 1 %,
 * 20 % on bumps-1M); curvature off (also on at bumps-4M); runs 5; threads 1
 * and 2. It sets the inputs, fractions, runs and threads itself: --inputs,
 * --fractions, --runs, --threads or --quick with it are an error. --quick
 * sets the inputs, fractions and runs: --inputs, --fractions or --runs with
 * it are an error (more inputs after the options are added in both cases).
 *
 * A bad option exits with status 2 before any work. An input that cannot be
 * read (a missing, empty or non-PLY file) is reported and skipped, the other
 * inputs run, and the program exits with status 1. Two inputs of the same
 * name (kitten.ply and sub/kitten.ply) are told apart by a suffix ("kitten#2").
 *
 * Inputs: .ply paths, or synthetic "bumps:100k" ... "bumps:14M" (a bumpy
 * sphere sampled uniformly by area). Default: the bundled scans and bumps
 * at 100k, 1M, 4M, 14M; inputs named on the command line are added.
 *
 * Per row: median wall time of --runs runs of the filter's Update() alone
 * (interleaved over the methods and thread counts: TimeInterleaved),
 * M input points per second, for ASM rows the speed ratio to each peer
 * (peer time / ASM time: > 1 means ASM is faster), and the peak memory
 * beyond the input and the output, in bytes per input point (measured once,
 * with the first thread count, in a forked child: see PeakExtraBytes).
 */
#include "BenchmarkArgs.h"
#include "BenchmarkData.h"
#include "BenchmarkMethods.h"
#include "BenchmarkReport.h"
#include "SpeedTargets.h"

#include "vtkSMPTools.h"
#include "vtkVersion.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

using namespace asmbench;

namespace
{
void Usage()
{
  std::cout
    << "usage: asm_speed_benchmark [--quick | --readme] [--runs 5] [--threads 1,2]\n"
       "                           [--fractions 0.05,0.01,0.2] [--inputs spec,...]\n"
       "                           [--no-memory] [--markdown] [--asm NAME:SETTINGS ...] [input "
       "...]\n"
       "input: a .ply path, or bumps:100k, bumps:1M, bumps:4M, bumps:14M\n"
       "--readme: the README's run (~7 min on 2 idle cores): bunny, bunny-scans, bumps "
       "100k..14M,\n"
       "          N_s 5 % (1 %, 20 % on bumps-1M), curvature off (on too at 4M), 1 and 2 threads\n"
       "          (not with --quick, --inputs, --fractions, --runs or --threads)\n"
       "--quick: kitten and bumps:20k at 5 %, 1 run (not with --inputs, --fractions or --runs)\n"
       "--fractions: each in (0, 1], distinct; --threads, --runs: integers >= 1\n"
       "--asm: one more ASM row, e.g. --asm \"ASM fast:FillHoles=0,FinalLloydIterations=0\"\n"
       "       (the default mode with those properties; Mode=paper for the paper mode)\n"
       "--cgal: also CGAL's grid and hierarchy simplification (built with libcgal-dev)\n"
       "--backend: vtkSMPTools' backend (default STDThread; TBB, OpenMP where built)\n";
}

/// The first figure of /proc/loadavg ("?" elsewhere): timings on a busy machine are slower.
std::string LoadAverage()
{
  std::ifstream in("/proc/loadavg");
  std::string first;
  return in >> first ? first : std::string("?");
}

/// vtkSMPTools' backend of every timed run (--backend).
std::string Backend = "STDThread";

void SetThreads(int threads)
{
  vtkSMPTools::SetBackend(Backend.c_str());
  vtkSMPTools::Initialize(threads);
}

/// Timing of one method at one thread count.
struct Timing
{
  double Median = NAN;
  vtkIdType Count = 0;
};

/// Times every method at every thread count, `runs` times each, after one
/// untimed warm-up of each. The runs are interleaved (run 1 of every method
/// at every thread count, then run 2, ...), so that a drift of the machine's
/// speed during the run (other load, clocks) weighs on every thread count
/// alike instead of biasing the speed-ups. A method that throws is left out.
std::map<int, std::map<std::string, Timing>> TimeInterleaved(const std::vector<Method>& methods,
  const std::vector<int>& threads, int runs, const std::string& inputName)
{
  std::map<std::string, bool> failed;
  std::map<int, std::map<std::string, std::vector<double>>> seconds;
  std::map<int, std::map<std::string, Timing>> timings;
  auto run = [&](const Method& m, int t, bool timed) {
    if (failed[m.Name])
    {
      return;
    }
    try
    {
      const RunResult result = m.Run(false);
      if (timed)
      {
        seconds[t][m.Name].push_back(result.Seconds);
        timings[t][m.Name].Count = result.Count;
      }
    }
    catch (const std::exception& e)
    {
      std::cerr << m.Name << " failed on " << inputName << " (" << e.what() << "); row skipped\n";
      failed[m.Name] = true;
    }
  };
  for (int r = -1; r < runs; ++r) // r = -1: the warm-ups
  {
    for (int t : threads)
    {
      SetThreads(t);
      for (const Method& m : methods)
      {
        run(m, t, r >= 0);
      }
    }
  }
  for (int t : threads)
  {
    for (const Method& m : methods)
    {
      if (failed[m.Name])
      {
        timings[t].erase(m.Name);
      }
      else if (seconds[t].count(m.Name))
      {
        timings[t][m.Name].Median = Median(seconds[t][m.Name]);
      }
    }
  }
  return timings;
}

/// One input of the run with its own fractions, configurations and runs.
struct Job
{
  std::string Spec;
  std::vector<double> Fractions;
  bool Curvature = true; ///< also the ASM configurations with curvature on
  int Runs = 5;
};

} // namespace

int main(int argc, char* argv[])
{
  const std::string data = ASM_BENCHMARK_DATA_DIR;
  std::vector<std::string> inputs;
  for (const char* scan : { "bunny", "fandisk", "kitten", "laurana" })
  {
    inputs.push_back(data + "/" + scan + ".ply");
  }
  for (const char* size : { "bumps:100k", "bumps:1M", "bumps:4M", "bumps:14M" })
  {
    inputs.push_back(size);
  }
  std::vector<double> fractions = { 0.05, 0.01, 0.2 };
  std::vector<int> threads = { 1, 2 };
  int runs = 5;
  bool markdown = false, memory = true, readme = false, cgal = false;
  std::vector<std::string> extra;
  std::vector<AsmConfig> configs = AsmConfigurations(); // and the variants (--asm)
  std::set<std::string> given; // the options given (checked against --quick, --readme)
  try
  {
    for (int i = 1; i < argc; ++i)
    {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h")
      {
        Usage();
        return 0;
      }
      else if (arg == "--quick")
      {
        inputs = { data + "/kitten.ply", "bumps:20k" };
        fractions = { 0.05 };
        runs = 1;
      }
      else if (arg == "--readme")
      {
        readme = true;
      }
      else if (arg == "--markdown")
      {
        markdown = true;
      }
      else if (arg == "--cgal")
      {
        cgal = true;
        if (!HaveCGAL())
        {
          throw UsageError("--cgal: this build has no CGAL (install libcgal-dev and reconfigure)");
        }
      }
      else if (arg == "--no-memory")
      {
        memory = false;
      }
      else if (arg == "--runs")
      {
        runs = static_cast<int>(ParseInteger(arg, OptionValue(argc, argv, i), 1, 1000000));
      }
      else if (arg == "--inputs")
      {
        inputs = ParseList(arg, OptionValue(argc, argv, i),
          [](const std::string&, const std::string& spec) { return spec; });
      }
      else if (arg == "--fractions")
      {
        fractions = ParseFractionList(arg, OptionValue(argc, argv, i));
      }
      else if (arg == "--threads")
      {
        threads.clear();
        for (long t : ParseIntegerList(arg, OptionValue(argc, argv, i), 1, 4096))
        {
          threads.push_back(static_cast<int>(t));
        }
      }
      else if (arg == "--backend")
      {
        Backend = OptionValue(argc, argv, i);
        if (!vtkSMPTools::SetBackend(Backend.c_str()))
        {
          throw UsageError("--backend: this VTK has no vtkSMPTools backend " + Quoted(Backend));
        }
      }
      else if (arg == "--asm")
      {
        if (!AddAsmVariant(OptionValue(argc, argv, i), configs))
        {
          return 2;
        }
      }
      else if (arg.compare(0, 2, "--") == 0)
      {
        throw UsageError("unknown option " + Quoted(arg));
      }
      else
      {
        extra.push_back(arg);
      }
      given.insert(arg);
    }
    for (const char* mode : { "--readme", "--quick" })
    {
      if (!given.count(mode))
      {
        continue;
      }
      for (const char* option : { "--inputs", "--fractions", "--runs", "--threads", "--quick" })
      {
        const bool allowed = std::string(option) == mode ||
          (std::string(mode) == "--quick" && std::string(option) == "--threads");
        if (given.count(option) && !allowed)
        {
          throw UsageError(
            std::string(option) + " cannot be given with " + mode + " (" + mode + " sets it)");
        }
      }
    }
    const std::string badInput = CheckInputSpecs(inputs, extra);
    if (!badInput.empty())
    {
      throw UsageError("input: " + badInput);
    }
  }
  catch (const UsageError& e)
  {
    std::cerr << "asm_speed_benchmark: " << e.what() << "\n";
    return 2;
  }
  std::vector<Job> jobs;
  if (readme)
  {
    // The README's run (issue 8's inputs, trimmed to ~7 minutes on 2 cores).
    jobs.push_back({ data + "/bunny.ply", { 0.05 }, false, 5 });
    const std::string scans = ASM_BENCHMARK_SHARED_DATA_DIR "/bunny-scans.ply";
    if (std::ifstream(scans).good())
    {
      jobs.push_back({ scans, { 0.05 }, false, 5 });
    }
    jobs.push_back({ "bumps:100k", { 0.05 }, false, 5 });
    jobs.push_back({ "bumps:1M", { 0.05, 0.01, 0.2 }, false, 5 });
    jobs.push_back({ "bumps:4M", { 0.05 }, true, 5 });
    jobs.push_back({ "bumps:14M", { 0.05 }, false, 5 });
    threads = { 1, 2 };
    for (const std::string& spec : extra)
    {
      jobs.push_back({ spec, { 0.05 }, false, 5 });
    }
  }
  else
  {
    inputs.insert(inputs.end(), extra.begin(), extra.end());
    for (const std::string& spec : inputs)
    {
      jobs.push_back({ spec, fractions, true, runs });
    }
  }

  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
  const double started = Now();
  std::cout << "# asm_speed_benchmark" << (readme ? " --readme" : "") << ", " << date
            << ", median of "
            << (readme ? std::string("5 run(s)") : std::to_string(runs) + " run(s)") << ", VTK "
            << vtkVersion::GetVTKVersion() << ", vtkSMPTools " << Backend
            << " backend, load average " << LoadAverage() << "\n"
            << "# Mpt/s: million input points per second; x peer: peer time / ASM time (> 1: ASM"
               " faster); x thr: time with the first thread count / this row's; mem: peak memory"
               " beyond input and output, bytes per input point; *: count not within 1 % of N_s\n";

  // The peers each ASM row is compared with: (method name, column).
  std::vector<std::pair<std::string, std::string>> peers = { { "vtkVoxelGrid", "x vtkVoxelGrid" },
    { "vtkMaskPoints random", "x vtkMaskPoints" } };
  if (cgal)
  {
    peers.insert(
      peers.end(), { { "CGAL grid", "x CGAL grid" }, { "CGAL hierarchy", "x CGAL hierarchy" } });
  }
  std::vector<std::string> columns = { "input", "N", "N_s", "method", "threads", "median s",
    "Mpt/s" };
  for (const auto& peer : peers)
  {
    columns.push_back(peer.second);
  }
  columns.insert(columns.end(), { "x thr", "mem B/pt" });
  // Summary data: seconds per input point, by ASM configuration, fraction, input, threads.
  std::map<std::string, std::map<std::string, std::map<int, double>>>
    perPoint; // key: config@fraction
  std::vector<std::string> order;
  std::vector<Record> records;
  std::vector<std::string> unreadable;
  for (const Job& job : jobs)
  {
    SetThreads(threads.back());
    Input input = MakeInput(job.Spec);
    if (!input.Data)
    {
      std::cerr << "asm_speed_benchmark: input " << job.Spec << " skipped (not readable)\n";
      unreadable.push_back(job.Spec);
      continue;
    }
    // Two inputs of one name (kitten.ply, sub/kitten.ply): "kitten#2" for the second.
    const std::string name = input.Name;
    for (int copy = 2; std::find(order.begin(), order.end(), input.Name) != order.end(); ++copy)
    {
      input.Name = name + "#" + std::to_string(copy);
    }
    if (input.Name != name)
    {
      std::cerr << "asm_speed_benchmark: a second input named " << name << " (" << job.Spec
                << ") is reported as " << input.Name << "\n";
    }
    order.push_back(input.Name);
    const vtkIdType n = input.NumberOfPoints();
    for (double fraction : job.Fractions)
    {
      const vtkIdType target =
        std::max<vtkIdType>(1, std::llround(fraction * static_cast<double>(n)));
      SetThreads(threads.back());
      std::vector<Method> methods;
      for (const AsmConfig& c : configs)
      {
        if (c.Curvature && !job.Curvature)
        {
          continue;
        }
        Method m = MakeAsm(input.Data, target, c);
        if (m.Run)
        {
          methods.push_back(m);
        }
      }
      std::vector<Method> peerMethods = { MakeVoxelGrid(input.Data, target),
        MakeMaskPoints(input.Data, target, 1) };
      if (cgal)
      {
        peerMethods.push_back(MakeCgalGrid(input.Data, target));
        peerMethods.push_back(MakeCgalHierarchy(input.Data, target));
      }
      for (const Method& m : peerMethods)
      {
        if (m.Run) // the search is not timed; an empty Run: the peer cannot run this configuration
        {
          methods.push_back(m);
        }
      }

      Table table(columns);
      std::map<std::string, double> memoryPerPoint, firstMedian;
      const std::map<int, std::map<std::string, Timing>> timingsByThreads =
        TimeInterleaved(methods, threads, job.Runs, input.Name);
      for (int t : threads)
      {
        const auto measured = timingsByThreads.find(t);
        std::map<std::string, Timing> timings =
          measured == timingsByThreads.end() ? std::map<std::string, Timing>() : measured->second;
        if (memory && t == threads.front())
        {
          SetThreads(t);
          for (const Method& m : methods)
          {
            if (timings.count(m.Name))
            {
              const double bytes = PeakExtraBytes([&m]() { return m.Run(false).OutputBytes; });
              memoryPerPoint[m.Name] =
                bytes >= 0.0 ? std::max(0.0, bytes) / static_cast<double>(n) : NAN;
            }
          }
        }
        for (const Method& m : methods)
        {
          if (!timings.count(m.Name))
          {
            continue;
          }
          const Timing& timing = timings[m.Name];
          auto ratio = [&](const std::string& peer) {
            const auto it = timings.find(peer);
            return !m.IsASM         ? std::string()
              : it == timings.end() ? "-"
                                    : "x" + Format(it->second.Median / timing.Median, 3);
          };
          if (t == threads.front())
          {
            firstMedian[m.Name] = timing.Median;
          }
          const auto mem = memoryPerPoint.find(m.Name);
          const bool hasMemory = t == threads.front() && mem != memoryPerPoint.end();
          // "*": the method could not be driven within 1 % of N_s.
          const bool off = std::abs(static_cast<double>(timing.Count - target)) >
            std::max(0.5, 0.01 * static_cast<double>(target));
          std::vector<std::string> row = { input.Name, std::to_string(n),
            std::to_string(timing.Count) + (off ? "*" : ""), m.Name, std::to_string(t),
            Format(timing.Median, 3), Fixed(static_cast<double>(n) / timing.Median / 1e6, 1) };
          for (const auto& peer : peers)
          {
            row.push_back(ratio(peer.first));
          }
          row.push_back(t != threads.front() && firstMedian.count(m.Name)
              ? "x" + Fixed(firstMedian[m.Name] / timing.Median, 2)
              : "");
          row.push_back(hasMemory ? Fixed(mem->second, 1) : "");
          table.Add(row);
          records.push_back({ input.Name, n, fraction, m.Name, m.IsASM, t, timing.Median,
            hasMemory ? mem->second : NAN });
          if (m.IsASM)
          {
            perPoint[m.Name + " @ " + Format(100.0 * fraction, 3) + " %"][input.Name][t] =
              timing.Median / static_cast<double>(n);
          }
        }
      }
      // Print as we go: the full run takes a while.
      table.Print(std::cout, markdown);
      std::cout << "\n" << std::flush;
    }
  }

  // Summary: nanoseconds per input point on each input (first thread count),
  // speed-up from the first to the last thread count, and the spread of the
  // time per point over the inputs.
  std::cout << "## Summary: ns per input point with " << threads.front()
            << " thread(s) (speed-up with " << threads.back()
            << "); spread = max/min - 1 of ns per point over the synthetic bumps-* inputs\n\n";
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
  PrintTargets(records, threads);
  std::cout << "\n# load average at the end: " << LoadAverage() << "; wall time "
            << Fixed(Now() - started, 0) << " s\n";
  if (!unreadable.empty())
  {
    std::cerr << "asm_speed_benchmark: " << unreadable.size() << " input(s) not read:";
    for (const std::string& spec : unreadable)
    {
      std::cerr << " " << spec;
    }
    std::cerr << "\n";
    return 1;
  }
  return 0;
}
