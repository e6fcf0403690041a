// SPDX-License-Identifier: BSD-3-Clause
#include "BenchmarkMethods.h"

#include "BenchmarkData.h"
#include "BenchmarkReport.h"

#include "vtkASMSimplify.h"
#include "vtkMaskPoints.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkVoxelGrid.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <limits>
#include <map>
#include <type_traits>
#include <utility>

namespace asmbench
{
bool DivisionsFit(const std::array<int, 3>& d)
{
  return d[0] >= 1 && d[1] >= 1 && d[2] >= 1 &&
    static_cast<double>(d[0]) * static_cast<double>(d[1]) * static_cast<double>(d[2]) <=
    MaxVoxelBins;
}

std::array<int, 3> VoxelDivisions(const double bounds[6], double s)
{
  double range[3], longest = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    range[k] = std::isfinite(bounds[2 * k + 1] - bounds[2 * k])
      ? std::max(0.0, bounds[2 * k + 1] - bounds[2 * k])
      : 0.0;
    longest = std::max(longest, range[k]);
  }
  if (!(s > 0.0) || !std::isfinite(s))
  {
    s = std::isinf(s) ? longest + 1.0
                      : longest / std::cbrt(MaxVoxelBins); // +inf: one cell; NaN, <= 0: fine
  }
  s = std::max(s, 1e-12 * std::max(longest, 1e-300));
  std::array<int, 3> d = { 1, 1, 1 };
  for (int pass = 0; pass < 200; ++pass)
  {
    double bins = 1.0;
    for (int k = 0; k < 3; ++k)
    {
      d[k] = static_cast<int>(std::max(1.0, std::min(1048576.0, std::round(range[k] / s))));
      bins *= d[k];
    }
    if (DivisionsFit(d))
    {
      return d;
    }
    // Too many bins: grow the cell (at least 1 %: rounding can leave the product just above).
    s *= std::max(1.01, std::cbrt(bins / MaxVoxelBins));
  }
  return { 1, 1, 1 };
}

namespace
{
// vtkASMSimplify gains a mode property in the quality work (issue 7). Until
// then the one pipeline is the paper's: detect the property at compile time
// so that this file builds before and after it lands.
template <typename T, typename = void>
struct HasModes : std::false_type
{
};
template <typename T>
struct HasModes<T,
  std::void_t<decltype(std::declval<T&>().SetModeToPaper()),
    decltype(std::declval<T&>().SetModeToFeaturePreserving())>> : std::true_type
{
};

template <typename T>
bool ApplyMode(T* filter, AsmMode mode)
{
  if constexpr (HasModes<T>::value)
  {
    if (mode == AsmMode::Paper)
    {
      filter->SetModeToPaper();
    }
    else
    {
      filter->SetModeToFeaturePreserving();
    }
    return true;
  }
  else
  {
    (void)filter;
    return mode == AsmMode::Paper;
  }
}

double MemoryBytes(vtkDataObject* data)
{
  return data ? 1024.0 * static_cast<double>(data->GetActualMemorySize()) : 0.0;
}

/// Runs a configured VTK filter once, timing Update() alone.
RunResult RunFilter(vtkAlgorithm* filter, bool keepPoints)
{
  filter->Modified();
  const double start = Now();
  filter->Update();
  RunResult r;
  r.Seconds = Now() - start;
  vtkPolyData* output = vtkPolyData::SafeDownCast(filter->GetOutputDataObject(0));
  r.Count = output ? output->GetNumberOfPoints() : 0;
  r.OutputBytes = MemoryBytes(output);
  if (keepPoints && output)
  {
    r.Xyz = Coordinates(output);
  }
  // Free the output now: the next run's memory should not include it.
  filter->GetOutputDataObject(0)->Initialize();
  return r;
}
} // namespace

const std::vector<AsmConfig>& AsmConfigurations()
{
  // clang-format off
  static const std::vector<AsmConfig> table = {
    // name                 mode                         curvature
    { "ASM default",        AsmMode::FeaturePreserving, false },
    { "ASM default +curv",  AsmMode::FeaturePreserving, true },
    { "ASM paper",          AsmMode::Paper,             false },
    { "ASM paper +curv",    AsmMode::Paper,             true },
  };
  // clang-format on
  return table;
}

namespace
{
using Setter = bool (*)(vtkASMSimplify* filter, double value, double& held);

// name -> sets the property to the value; if the property holds another
// value then (clamped, rounded), puts the previous one back and returns
// false, with the value it would hold in `held`.
// clang-format off
#define ASM_SETTING(name)                                                                          \
  {                                                                                                \
    #name, [](vtkASMSimplify* f, double v, double& held) {                                         \
      const auto previous = f->Get##name();                                                        \
      f->Set##name(static_cast<decltype(previous)>(v));                                            \
      held = static_cast<double>(f->Get##name());                                                  \
      if (held != v)                                                                               \
      {                                                                                            \
        f->Set##name(previous);                                                                    \
        return false;                                                                              \
      }                                                                                            \
      return true;                                                                                 \
    }                                                                                              \
  }
const std::map<std::string, Setter>& AsmSetters()
{
  static const std::map<std::string, Setter> setters = {
    ASM_SETTING(ValidateKeyPoints), ASM_SETTING(KeyPointRadius), ASM_SETTING(KeyPointProminence),
    ASM_SETTING(InPlaneKeyPoints), ASM_SETTING(ExtremeKeyPoints), ASM_SETTING(CoverEveryCell),
    ASM_SETTING(BudgetExponent), ASM_SETTING(LloydIterations), ASM_SETTING(CrossCellIterations),
    ASM_SETTING(InputPointSamples), ASM_SETTING(FillHoles), ASM_SETTING(HoleFillFraction),
    ASM_SETTING(FeatureSamplesPerCell), ASM_SETTING(VariationBudget), ASM_SETTING(VariationCap),
    ASM_SETTING(ReserveFreeSample), ASM_SETTING(FinalLloydIterations),
    ASM_SETTING(LloydVariationWeight), ASM_SETTING(CoveringRounds),
    ASM_SETTING(SparseCellKeyPoints), ASM_SETTING(BoundSnappedHoles), ASM_SETTING(CellSize),
    ASM_SETTING(SamplesPerCell), ASM_SETTING(Alpha), ASM_SETTING(ErrorTolerance),
    ASM_SETTING(RelativeErrorTolerance), ASM_SETTING(WeightMode), ASM_SETTING(CurvatureWeight),
    ASM_SETTING(RandomSeed), ASM_SETTING(SnapToInputPoints), ASM_SETTING(GenerateCurvature),
    ASM_SETTING(CurvatureNeighbors), ASM_SETTING(MinimumPointsForThreads),
  };
  // clang-format on
  return setters;
}
#undef ASM_SETTING
} // namespace

std::string AsmSettingNames()
{
  std::string names = "Mode";
  for (const auto& setter : AsmSetters())
  {
    names += ", " + setter.first;
  }
  return names;
}

bool ApplyAsmSettings(vtkASMSimplify* filter, const std::string& settings, std::string& error)
{
  for (const std::string& item : SplitList(settings))
  {
    const std::size_t eq = item.find('=');
    const std::string name = item.substr(0, eq);
    const std::string text = eq == std::string::npos ? std::string() : item.substr(eq + 1);
    if (eq == std::string::npos || name.empty() || text.empty())
    {
      error = "\"" + item + "\" is not Name=value";
      return false;
    }
    if (name == "Mode")
    {
      if (text != "paper" && text != "feature")
      {
        error = "Mode is paper or feature, not \"" + text + "\"";
        return false;
      }
      ApplyMode(filter, text == "paper" ? AsmMode::Paper : AsmMode::FeaturePreserving);
      continue;
    }
    const auto setter = AsmSetters().find(name);
    if (setter == AsmSetters().end())
    {
      error = "no property " + name + " (known: " + AsmSettingNames() + ")";
      return false;
    }
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !std::isfinite(value))
    {
      error = name + ": \"" + text + "\" is not a number";
      return false;
    }
    double held = 0.0;
    if (!setter->second(filter, value, held))
    {
      error = name + "=" + text + " is not accepted (the property holds " + Format(held, 6) + ")";
      return false;
    }
  }
  return true;
}

const std::vector<std::string>& PeerMethodNames()
{
  static const std::vector<std::string> names = { "vtkVoxelGrid", "vtkMaskPoints random",
    "vtkMaskPoints strat.", "CGAL grid", "CGAL hierarchy" };
  return names;
}

bool ParseAsmVariant(const std::string& spec, AsmConfig& config, std::string& error)
{
  const std::size_t colon = spec.find(':');
  if (colon == std::string::npos || colon == 0)
  {
    error = "\"" + spec + "\" is not NAME:SETTINGS";
    return false;
  }
  config = AsmConfig{ spec.substr(0, colon), AsmMode::FeaturePreserving, false,
    spec.substr(colon + 1), true };
  for (const AsmConfig& standard : AsmConfigurations())
  {
    if (standard.Name == config.Name)
    {
      error = "\"" + config.Name + "\" is the name of a standard configuration";
      return false;
    }
  }
  for (const std::string& peer : PeerMethodNames())
  {
    if (peer == config.Name)
    {
      error = "\"" + config.Name + "\" is the name of a peer method";
      return false;
    }
  }
  vtkNew<vtkASMSimplify> probe; // the settings are checked once here
  if (!ApplyAsmSettings(probe.Get(), config.Settings, error))
  {
    return false;
  }
  config.Mode =
    probe->GetMode() == vtkASMSimplify::PAPER ? AsmMode::Paper : AsmMode::FeaturePreserving;
  return true;
}

bool AddAsmVariant(const std::string& spec, std::vector<AsmConfig>& configs)
{
  AsmConfig variant;
  std::string error;
  if (!ParseAsmVariant(spec, variant, error))
  {
    std::cerr << "--asm: " << error << "\n";
    return false;
  }
  for (const AsmConfig& c : configs)
  {
    if (c.Name == variant.Name)
    {
      std::cerr << "--asm: a second configuration named \"" << variant.Name << "\"\n";
      return false;
    }
  }
  configs.push_back(variant);
  return true;
}

bool AsmModeAvailable(AsmMode mode)
{
  vtkNew<vtkASMSimplify> probe;
  return ApplyMode(probe.Get(), mode);
}

double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double SearchScale(const std::function<vtkIdType(double)>& count, vtkIdType target, double initial,
  double exponent, double tolerance, int maxEvaluations, vtkIdType& found, int probes)
{
  const double slack = std::max(0.5, tolerance * static_cast<double>(target));
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  double s = initial, best = initial;
  found = -1;
  for (int i = 0; i < maxEvaluations; ++i)
  {
    const vtkIdType c = count(s);
    if (found < 0 ||
      std::abs(static_cast<double>(c - target)) < std::abs(static_cast<double>(found - target)))
    {
      found = c;
      best = s;
    }
    if (std::abs(static_cast<double>(c - target)) <= slack)
    {
      break;
    }
    (c > target ? lo : hi) = s;
    double next = c > 0
      ? s * std::pow(static_cast<double>(c) / static_cast<double>(target), 1.0 / exponent)
      : s / 4.0;
    if (lo > 0.0 && std::isfinite(hi))
    {
      if (hi / lo < 1.0 + 1e-12)
      {
        break;
      }
      if (!(next > lo && next < hi))
      {
        next = std::sqrt(lo * hi);
      }
    }
    s = next;
  }
  // Counts of grids jump when cell borders cross dense features (axis-aligned
  // faces): when still outside the tolerance, probe around the best scale.
  const double base = best;
  for (int j = 1; j <= probes && std::abs(static_cast<double>(found - target)) > slack; ++j)
  {
    const double s2 = base * (1.0 + (j % 2 ? 1.0 : -1.0) * 0.0025 * ((j + 1) / 2));
    const vtkIdType c = count(s2);
    if (std::abs(static_cast<double>(c - target)) < std::abs(static_cast<double>(found - target)))
    {
      found = c;
      best = s2;
    }
  }
  return best;
}

Method MakeAsm(vtkPolyData* input, vtkIdType target, const AsmConfig& config)
{
  Method m;
  m.Name = config.Name;
  m.IsASM = true;
  vtkSmartPointer<vtkASMSimplify> asmFilter = vtkSmartPointer<vtkASMSimplify>::New();
  if (!ApplyMode(asmFilter.Get(), config.Mode))
  {
    return m; // this mode does not exist in this build: empty Run
  }
  asmFilter->SetInputData(input);
  asmFilter->SetTargetModeToNumberOfOutputPoints();
  asmFilter->SetNumberOfOutputPoints(target);
  asmFilter->SetGenerateCurvature(config.Curvature);
  std::string error;
  if (!ApplyAsmSettings(asmFilter.Get(), config.Settings, error))
  {
    std::cerr << config.Name << ": " << error << "\n";
    return m; // (ParseAsmVariant checked the settings already)
  }
  m.Run = [asmFilter](bool keep) { return RunFilter(asmFilter, keep); };
  return m;
}

Method MakeVoxelGrid(vtkPolyData* input, vtkIdType target)
{
  // vtkVoxelGrid's bins always span the bounds exactly, so its count depends
  // only on the integer divisions: search a cubic leaf size s (divisions
  // round(range / s)), then, when that cannot come within 1 %, move up
  // to two divisions per axis at a time (greedy, the 124 neighbouring triples).
  auto voxel = vtkSmartPointer<vtkVoxelGrid>::New();
  voxel->SetInputData(input);
  voxel->SetConfigurationStyleToManual();
  std::map<std::array<int, 3>, vtkIdType> counts;
  auto count = [&voxel, &counts](const std::array<int, 3>& d) {
    const auto known = counts.find(d);
    if (known != counts.end())
    {
      return known->second;
    }
    // Never hand vtkVoxelGrid more bins than MaxBins: its locator and bin map
    // allocate every bin (past 2^31 the sizes overflow: std::bad_array_new_length).
    if (!DivisionsFit(d))
    {
      return counts[d] = 0;
    }
    voxel->SetDivisions(d[0], d[1], d[2]);
    try
    {
      counts[d] = RunFilter(voxel, false).Count;
    }
    catch (const std::exception& e)
    {
      std::cerr << "vtkVoxelGrid " << d[0] << " x " << d[1] << " x " << d[2] << " failed ("
                << e.what() << "); configuration skipped\n";
      counts[d] = 0;
    }
    if (std::getenv("ASM_BENCHMARK_DEBUG"))
    {
      std::cerr << "vtkVoxelGrid " << d[0] << " x " << d[1] << " x " << d[2] << ": " << counts[d]
                << "\n";
    }
    return counts[d];
  };
  double bounds[6];
  input->GetBounds(bounds);
  auto divisions = [&bounds](double s) { return VoxelDivisions(bounds, s); };
  vtkIdType found = 0;
  const double leaf = SearchScale([&](double s) { return count(divisions(s)); }, target,
    input->GetLength() / std::sqrt(static_cast<double>(target)), 2.0, 0.01, 40, found);
  std::array<int, 3> best = divisions(leaf);
  const double slack = std::max(0.5, 0.01 * static_cast<double>(target));
  auto error = [target](vtkIdType c) { return std::abs(static_cast<double>(c - target)); };
  // (Only on inputs small enough for 124 more runs per step to be cheap.)
  const bool cheap = input->GetNumberOfPoints() <= 2000000;
  for (int step = 0; cheap && step < 30 && error(count(best)) > slack; ++step)
  {
    std::array<int, 3> next = best;
    for (int dx = -2; dx <= 2; ++dx)
    {
      for (int dy = -2; dy <= 2; ++dy)
      {
        for (int dz = -2; dz <= 2; ++dz)
        {
          const std::array<int, 3> d = { std::max(1, best[0] + dx), std::max(1, best[1] + dy),
            std::max(1, best[2] + dz) };
          if (DivisionsFit(d) && error(count(d)) < error(count(next)))
          {
            next = d;
          }
        }
      }
    }
    if (next == best)
    {
      break;
    }
    best = next;
  }
  voxel->SetDivisions(best[0], best[1], best[2]);
  Method m;
  m.Name = "vtkVoxelGrid";
  if (!DivisionsFit(best) || count(best) <= 0)
  {
    std::cerr << "vtkVoxelGrid: no configuration within " << MaxVoxelBins
              << " bins reaches N_s = " << target << "; skipped\n";
    return m; // empty Run: skipped
  }
  m.Note = "divisions " + std::to_string(best[0]) + " x " + std::to_string(best[1]) + " x " +
    std::to_string(best[2]);
  m.Run = [voxel](bool keep) { return RunFilter(voxel, keep); };
  return m;
}

Method MakeMaskPoints(vtkPolyData* input, vtkIdType target, int randomModeType)
{
  auto mask = vtkSmartPointer<vtkMaskPoints>::New();
  mask->SetInputData(input);
  mask->RandomModeOn();
  mask->SetRandomModeType(randomModeType);
  mask->SetMaximumNumberOfPoints(target);
  mask->SetOnRatio(1);
  mask->GenerateVerticesOn();
  mask->SingleVertexPerCellOn();
  mask->SetRandomSeed(1);
  Method m;
  m.Name = randomModeType == 2 ? "vtkMaskPoints strat." : "vtkMaskPoints random";
  m.Run = [mask](bool keep) { return RunFilter(mask, keep); };
  // VTK 9.2's vtkMaskPoints draws its random (1) and stratified (2) modes
  // from the C library's global generator, which its RandomSeed does not
  // reset (that seeds the spatial modes only).
  m.Reseed = [](unsigned seed) { std::srand(seed); };
  return m;
}
} // namespace asmbench
