// SPDX-License-Identifier: BSD-3-Clause
/**
 * asm_quality_benchmark: scores vtkASMSimplify's modes against the usual
 * downsamplers at the same output count (issue 7). See QualityMetrics.h for
 * the measures (all in per mille of the input's bounding-box diagonal).
 *
 *   asm_quality_benchmark [--fractions 0.01,0.05,0.2] [--inputs spec,...]
 *                         [--quick] [--markdown] [--asm NAME:SETTINGS ...]
 *                         [more inputs ...]
 *
 * --asm adds a row for vtkASMSimplify with more properties set (the default
 * mode unless Mode=paper; ApplyAsmSettings), e.g. --asm "ASM fast:FillHoles=0":
 * its ratios, its summary line and its own targets block (against the peers
 * and the paper mode) are printed; the default mode's targets ignore it.
 *
 * An input is a .ply path or a synthetic shape "spikes:100k",
 * "bracket:100k", "terrain:100k" (with known feature points) or "bumps:1M".
 * Default inputs: the bundled scans (Testing/Data) and the three synthetic
 * shapes at 100 k points; inputs named on the command line are added (an
 * input whose name is already in the list is skipped, with a message).
 * --quick sets the inputs and fractions: --inputs or --fractions with it
 * are an error (inputs after the options are added).
 *
 * A bad option exits with status 2 before any work. An input that cannot be
 * read (a missing, empty or non-PLY file) is reported and skipped, the other
 * inputs run, and the program exits with status 1. Points with a NaN or
 * infinite coordinate are left out of an input (with a message).
 */
#include "BenchmarkArgs.h"
#include "BenchmarkData.h"
#include "BenchmarkMethods.h"
#include "BenchmarkReport.h"
#include "QualityMetrics.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <iostream>
#include <map>
#include <set>

using namespace asmbench;

namespace
{
/// The measures, in column order: name, accessor, whether only for shapes with features.
struct Measure
{
  const char* Name;
  double (*Get)(const Quality&);
  bool Tips;
};
const std::vector<Measure>& Measures()
{
  static const std::vector<Measure> m = {
    { "p2plane mean", [](const Quality& q) { return q.PlaneMean; }, false },
    { "p2plane max", [](const Quality& q) { return q.PlaneMax; }, false },
    { "NN RMS", [](const Quality& q) { return q.NNRms; }, false },
    { "hole", [](const Quality& q) { return q.Hole; }, false },
    { "tip mean", [](const Quality& q) { return q.TipMean; }, true },
    { "tip max", [](const Quality& q) { return q.TipMax; }, true },
  };
  return m;
}

struct Row
{
  std::string Method;
  bool IsASM = false;
  vtkIdType Count = 0;
  double Seconds = 0.0;
  Quality Q;
};

/// A random method is drawn this many times (seeds 1, 2, ...), and each of
/// its measures is the median over the draws: one lucky or unlucky draw does
/// not decide a comparison.
constexpr unsigned RandomDraws = 5;

/// The row of method m: one run, or the medians of RandomDraws draws (the
/// count of the first, which all random peers meet exactly).
Row Measured(const Method& m, const Reference& reference)
{
  const unsigned draws = m.Reseed ? RandomDraws : 1;
  std::vector<Quality> qualities;
  std::vector<double> seconds;
  vtkIdType count = 0;
  for (unsigned d = 1; d <= draws; ++d)
  {
    if (m.Reseed)
    {
      m.Reseed(d);
    }
    const RunResult r = m.Run(true);
    count = d == 1 ? r.Count : count;
    seconds.push_back(r.Seconds);
    qualities.push_back(reference.Measure(r.Xyz));
  }
  return { m.Name, m.IsASM, count, Median(seconds), MedianQuality(qualities) };
}

/// Per ASM configuration and measure: ratios to the best peer, and wins.
struct Tally
{
  std::map<std::string, std::vector<double>> Ratios; ///< measure -> ratios
  std::map<std::string, int> Wins;                   ///< measure -> cases where ratio <= 1
  std::map<std::string, int> Cases;
  int HoleNotWorseThanVoxel = 0;
  int HoleCases = 0;
};

/// The methods' rows of one input at one fraction, kept for the targets block.
struct Case
{
  double Fraction;
  std::string Input;
  bool Tips;
  std::vector<Row> Rows;
};

/// The targets of issue 7 for `mode`, per fraction: best of all methods (the
/// peers and the other ASM modes, except those in `ignore`) on p2plane mean
/// and on NN RMS on >= 80 % of the inputs; largest hole <= vtkVoxelGrid's on
/// >= 80 %; lowest tip error (mean) on every synthetic shape.
void PrintTargets(const std::vector<Case>& cases, const std::vector<double>& fractions,
  const std::string& mode, const std::set<std::string>& ignore)
{
  std::cout << "\n## Targets (issue 7) for " << mode
            << ", per fraction (best = <= every other method)\n\n";
  auto verdict = [](int wins, int total, double share) {
    return total == 0 ? "n/a " : (wins >= share * total - 1e-9 ? "PASS" : "FAIL");
  };
  for (double fraction : fractions)
  {
    int total = 0, planeWins = 0, nnWins = 0, holeCases = 0, holeWins = 0, tipCases = 0,
        tipWins = 0;
    std::string planeLost, nnLost, holeLost, tipLost;
    for (const Case& c : cases)
    {
      if (std::abs(c.Fraction - fraction) > 1e-12)
      {
        continue;
      }
      const Row* self = nullptr;
      const Row* voxel = nullptr;
      for (const Row& row : c.Rows)
      {
        self = row.Method == mode ? &row : self;
        voxel = row.Method == "vtkVoxelGrid" ? &row : voxel;
      }
      if (!self)
      {
        continue;
      }
      auto best = [&](double (*get)(const Quality&)) {
        for (const Row& row : c.Rows)
        {
          if (&row != self && !ignore.count(row.Method) && get(row.Q) < get(self->Q))
          {
            return false;
          }
        }
        return true;
      };
      ++total;
      const bool plane = best([](const Quality& q) { return q.PlaneMean; });
      const bool nn = best([](const Quality& q) { return q.NNRms; });
      planeWins += plane;
      nnWins += nn;
      planeLost += plane ? "" : " " + c.Input;
      nnLost += nn ? "" : " " + c.Input;
      if (voxel)
      {
        ++holeCases;
        const bool hole = self->Q.Hole <= voxel->Q.Hole;
        holeWins += hole;
        holeLost += hole ? "" : " " + c.Input;
      }
      if (c.Tips)
      {
        ++tipCases;
        const bool tip = best([](const Quality& q) { return q.TipMean; });
        tipWins += tip;
        tipLost += tip ? "" : " " + c.Input;
      }
    }
    const std::string at = "N_s = " + Format(100.0 * fraction, 3) + " %: ";
    auto line = [&](const char* what, int wins, int cases, double share, const std::string& lost) {
      std::cout << verdict(wins, cases, share) << "  " << at << what << " " << wins << "/" << cases
                << " inputs" << (lost.empty() ? std::string() : " (not on:" + lost + ")") << "\n";
    };
    line("best p2plane mean on >= 80 % of the inputs:", planeWins, total, 0.8, planeLost);
    line("best NN RMS on >= 80 % of the inputs:", nnWins, total, 0.8, nnLost);
    line("hole <= vtkVoxelGrid's on >= 80 % of the inputs:", holeWins, holeCases, 0.8, holeLost);
    line("lowest tip mean error on every synthetic shape:", tipWins, tipCases, 1.0, tipLost);
  }
}

void Usage()
{
  std::cout
    << "usage: asm_quality_benchmark [--fractions 0.01,0.05,0.2] [--inputs spec,...]\n"
       "                             [--quick] [--markdown] [--asm NAME:SETTINGS ...] [input ...]\n"
       "input: a .ply path, or spikes:100k, bracket:100k, terrain:100k, bumps:1M\n"
       "--fractions: each in (0, 1], distinct\n"
       "--quick: kitten and spikes:20k at 5 % (not with --inputs or --fractions)\n"
       "--asm: one more ASM row, e.g. --asm \"ASM fast:FillHoles=0,FinalLloydIterations=0\"\n"
       "       (the default mode with those properties; Mode=paper for the paper mode)\n";
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> inputs;
  for (const char* scan : { "bunny", "fandisk", "kitten", "laurana" })
  {
    inputs.push_back(std::string(ASM_BENCHMARK_DATA_DIR) + "/" + scan + ".ply");
  }
  for (const char* shape : { "spikes:100k", "bracket:100k", "terrain:100k" })
  {
    inputs.push_back(shape);
  }
  std::vector<double> fractions = { 0.01, 0.05, 0.2 };
  bool markdown = false;
  std::vector<std::string> extra;
  std::vector<AsmConfig> variants;
  try
  {
    bool quick = false, listed = false;
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
        quick = true;
        inputs = { std::string(ASM_BENCHMARK_DATA_DIR) + "/kitten.ply", "spikes:20k" };
        fractions = { 0.05 };
      }
      else if (arg == "--markdown")
      {
        markdown = true;
      }
      else if (arg == "--inputs")
      {
        listed = true;
        inputs = ParseList(arg, OptionValue(argc, argv, i),
          [](const std::string&, const std::string& spec) { return spec; });
      }
      else if (arg == "--fractions")
      {
        listed = true;
        fractions = ParseFractionList(arg, OptionValue(argc, argv, i));
      }
      else if (arg == "--asm")
      {
        if (!AddAsmVariant(OptionValue(argc, argv, i), variants))
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
    }
    if (quick && listed)
    {
      throw UsageError("--inputs and --fractions cannot be given with --quick (--quick sets them)");
    }
    const std::string badInput = CheckInputSpecs(inputs, extra);
    if (!badInput.empty())
    {
      throw UsageError("input: " + badInput);
    }
  }
  catch (const UsageError& e)
  {
    std::cerr << "asm_quality_benchmark: " << e.what() << "\n";
    return 2;
  }
  inputs.insert(inputs.end(), extra.begin(), extra.end());

  vtkSMPTools::SetBackend("STDThread");
  std::vector<AsmConfig> configs;
  for (const AsmConfig& c : AsmConfigurations())
  {
    if (!c.Curvature && AsmModeAvailable(c.Mode)) // curvature does not move points
    {
      configs.push_back(c);
    }
  }
  configs.insert(configs.end(), variants.begin(), variants.end());
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
  std::cout << "# asm_quality_benchmark, " << date << ", "
            << vtkSMPTools::GetEstimatedNumberOfThreads()
            << " thread(s); CGAL peers: " << (HaveCGAL() ? "yes" : "no (not built)")
            << "; ASM modes: " << configs.size() << "\n"
            << "# distances in per mille of the input's bounding-box diagonal; p2plane: original"
               " points to a plane fitted to their 8 nearest samples; NN RMS: sqrt of the mean of"
               " both directions' mean squares; hole: max distance original -> nearest sample;"
               " tip: known feature point -> nearest sample\n";

  std::map<std::string, Tally> tallies;
  // One line per ASM configuration, input and fraction: its ratios to the best peer.
  std::vector<std::string> ratioHeader = { "ASM mode", "input", "N_s" };
  for (const Measure& measure : Measures())
  {
    ratioHeader.push_back(measure.Name);
  }
  ratioHeader.push_back("hole / vtkVoxelGrid");
  Table ratios(ratioHeader);
  std::set<std::string> seen;
  std::vector<std::string> unreadable;
  std::vector<Case> cases;
  for (const std::string& spec : inputs)
  {
    Input input = MakeInput(spec);
    if (!input.Data)
    {
      std::cerr << "asm_quality_benchmark: input " << spec << " skipped (not readable)\n";
      unreadable.push_back(spec);
      continue;
    }
    if (seen.count(input.Name))
    {
      std::cerr << "asm_quality_benchmark: input " << spec << " skipped (an input named "
                << input.Name << " is in the list already)\n";
      continue;
    }
    seen.insert(input.Name);
    // The measures need finite points (ASM and CGAL's peers skip the others).
    if (const std::int64_t dropped = DropNonFinite(input))
    {
      std::cerr << "asm_quality_benchmark: " << dropped << " point(s) of " << spec
                << " with a NaN or infinite coordinate left out\n";
      if (input.NumberOfPoints() == 0)
      {
        unreadable.push_back(spec);
        continue;
      }
    }
    const vtkIdType n = input.NumberOfPoints();
    const Reference reference(Coordinates(input.Data), input.Features);
    for (double fraction : fractions)
    {
      const vtkIdType target =
        std::max<vtkIdType>(1, std::llround(fraction * static_cast<double>(n)));
      std::vector<Method> methods;
      for (const AsmConfig& c : configs)
      {
        methods.push_back(MakeAsm(input.Data, target, c));
      }
      methods.push_back(MakeVoxelGrid(input.Data, target));
      methods.push_back(MakeMaskPoints(input.Data, target, 1));
      methods.push_back(MakeMaskPoints(input.Data, target, 2));
      if (HaveCGAL())
      {
        methods.push_back(MakeCgalGrid(input.Data, target));
        methods.push_back(MakeCgalHierarchy(input.Data, target));
      }
      std::vector<Row> rows;
      for (const Method& m : methods)
      {
        if (!m.Run)
        {
          continue;
        }
        try
        {
          rows.push_back(Measured(m, reference));
        }
        catch (const std::exception& e)
        {
          std::cerr << m.Name << " failed on " << input.Name << " (" << e.what() << "); skipped\n";
        }
      }
      const bool tips = !input.Features.empty();
      cases.push_back({ fraction, input.Name, tips, rows });
      std::vector<std::string> header = { "method", "N_s", "time s" };
      for (const Measure& measure : Measures())
      {
        if (tips || !measure.Tips)
        {
          header.push_back(measure.Name);
        }
      }
      Table table(header);
      for (const Row& row : rows)
      {
        // "*": the method could not be driven within 1 % of N_s.
        const bool off =
          std::abs(static_cast<double>(row.Count - target)) > std::max(0.5, 0.01 * target);
        std::vector<std::string> cells = { row.Method, std::to_string(row.Count) + (off ? "*" : ""),
          Format(row.Seconds, 3) };
        for (const Measure& measure : Measures())
        {
          if (tips || !measure.Tips)
          {
            cells.push_back(Fixed(1000.0 * measure.Get(row.Q), 3));
          }
        }
        table.Add(cells);
      }
      // Ratio of each ASM configuration to the best peer, per measure.
      const Row* voxel = nullptr;
      for (const Row& row : rows)
      {
        voxel = row.Method == "vtkVoxelGrid" ? &row : voxel;
      }
      for (const Row& row : rows)
      {
        if (!row.IsASM)
        {
          continue;
        }
        Tally& tally = tallies[row.Method];
        std::vector<std::string> cells = { row.Method + " / best peer", "", "" };
        std::vector<std::string> compact = { row.Method, input.Name,
          Format(100.0 * fraction, 3) + " %" };
        for (const Measure& measure : Measures())
        {
          if (!tips && measure.Tips)
          {
            compact.push_back("");
            continue;
          }
          double best = INFINITY;
          for (const Row& peer : rows)
          {
            if (!peer.IsASM)
            {
              best = std::min(best, measure.Get(peer.Q));
            }
          }
          const double value = measure.Get(row.Q);
          const double ratio = best > 0.0 ? value / best : (value > 0.0 ? INFINITY : 1.0);
          cells.push_back(Fixed(ratio, 2));
          compact.push_back(Fixed(ratio, 2));
          tally.Ratios[measure.Name].push_back(ratio);
          tally.Wins[measure.Name] += ratio <= 1.0 ? 1 : 0;
          tally.Cases[measure.Name] += 1;
        }
        if (voxel)
        {
          tally.HoleNotWorseThanVoxel += row.Q.Hole <= voxel->Q.Hole ? 1 : 0;
          tally.HoleCases += 1;
        }
        compact.push_back(
          voxel && voxel->Q.Hole > 0.0 ? Fixed(row.Q.Hole / voxel->Q.Hole, 2) : "-");
        ratios.Add(compact);
        table.Add(cells);
      }
      std::cout << "\n## " << input.Name << ": N = " << n << ", N_s = " << target << " ("
                << Format(100.0 * fraction, 3) << " %)\n\n";
      table.Print(std::cout, markdown);
    }
  }

  std::cout << "\n## Ratios: ASM / best peer per input (< 1: ASM better than every peer)\n\n";
  ratios.Print(std::cout, markdown);

  // Summary: per ASM configuration and measure, the cases where it is not
  // worse than the best peer, and the median ratio.
  std::cout << "\n## Summary: ASM / best peer over all inputs and fractions (median ratio; cases"
               " where ASM <= best peer)\n\n";
  std::vector<std::string> header = { "ASM mode" };
  for (const Measure& measure : Measures())
  {
    header.push_back(measure.Name);
  }
  header.push_back("hole <= vtkVoxelGrid");
  Table summary(header);
  for (const AsmConfig& c : configs)
  {
    const Tally& tally = tallies[c.Name];
    std::vector<std::string> cells = { c.Name };
    for (const Measure& measure : Measures())
    {
      const auto ratios = tally.Ratios.find(measure.Name);
      if (ratios == tally.Ratios.end())
      {
        cells.push_back("-");
        continue;
      }
      cells.push_back("x" + Fixed(Median(ratios->second), 2) + " (" +
        std::to_string(tally.Wins.at(measure.Name)) + "/" +
        std::to_string(tally.Cases.at(measure.Name)) + ")");
    }
    cells.push_back(
      std::to_string(tally.HoleNotWorseThanVoxel) + "/" + std::to_string(tally.HoleCases));
    summary.Add(cells);
  }
  summary.Print(std::cout, markdown);
  bool hasDefault = false;
  for (const AsmConfig& c : configs)
  {
    hasDefault = hasDefault || c.Name == "ASM default";
  }
  // The variants (--asm) are settings of a mode: the default mode is not
  // compared with them, and each of them is compared with the peers and the
  // paper mode only.
  std::set<std::string> variantNames;
  for (const AsmConfig& c : configs)
  {
    if (c.Variant)
    {
      variantNames.insert(c.Name);
    }
  }
  if (hasDefault)
  {
    PrintTargets(cases, fractions, "ASM default", variantNames);
  }
  else
  {
    std::cout << "\n## Targets (issue 7): n/a (no feature-preserving mode in this build)\n";
  }
  for (const std::string& name : variantNames)
  {
    std::set<std::string> others = variantNames;
    others.insert("ASM default");
    PrintTargets(cases, fractions, name, others);
  }
  if (!unreadable.empty())
  {
    std::cerr << "asm_quality_benchmark: " << unreadable.size() << " input(s) not read:";
    for (const std::string& spec : unreadable)
    {
      std::cerr << " " << spec;
    }
    std::cerr << "\n";
    return 1;
  }
  return 0;
}
