// SPDX-License-Identifier: BSD-3-Clause
/**
 * asm_profile: a small timing harness for optimising vtkASMSimplify (not the
 * official benchmark, see Benchmarks/). Generates a seeded synthetic cloud
 * (a sphere with bumps, points uniform by area, float coordinates) in memory,
 * or reads a PLY, and times vtkASMSimplify::Update() end to end.
 *
 * `asm_profile --help` prints the synopsis (in main, below); the options:
 *
 * --backend picks vtkSMPTools' backend (default STDThread; TBB or OpenMP
 * when this VTK has them, e.g. Debian's VTK 9.1: scripts/fetch-vtk91.sh).
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
 *
 * A bad option (or a --dump path that cannot be written) exits with status 2
 * before any work; a --ply without points, with status 1.
 */
#include "Profile.h"

#include "BenchmarkArgs.h"

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

#include <malloc.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using asmprofile::Cpu;
using asmprofile::Median;
using asmprofile::Now;

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
  std::string backend = "STDThread";
  const char* usage =
    "usage: asm_profile [--points N[,N...]] [--threads T[,T...]] [--runs R]\n"
    "                   [--fraction F] [--curvature] [--ply file] [--stages] [--floor]\n"
    "                   [--dump file] [--coherent] [--mode paper|feature] [--arrays]\n"
    "                   [--set Name=value,...] [--error] [--loops] [--backend B]\n"
    "(each option is described in the header of Benchmarks/Profile/asm_profile.cxx)\n";
  std::string plyPath, dumpPath;
  try
  {
    for (int i = 1; i < argc; ++i)
    {
      const std::string a = argv[i];
      if (a == "--points")
      {
        sizes.clear();
        for (std::int64_t n : asmbench::ParseCountList(a, asmbench::OptionValue(argc, argv, i)))
          sizes.push_back(static_cast<long>(n));
      }
      else if (a == "--threads")
        threads = asmbench::ParseIntegerList(a, asmbench::OptionValue(argc, argv, i), 1, 4096),
        threadsGiven = true;
      else if (a == "--runs")
        runs = static_cast<int>(
          asmbench::ParseInteger(a, asmbench::OptionValue(argc, argv, i), 1, 1000000));
      else if (a == "--fraction")
        fraction = asmbench::ParseFraction(a, asmbench::OptionValue(argc, argv, i));
      else if (a == "--ply")
      {
        plyPath = asmbench::OptionValue(argc, argv, i);
        if (plyPath.empty())
          throw asmbench::UsageError("--ply: an empty path");
        ply = plyPath.c_str();
      }
      else if (a == "--dump")
      {
        dumpPath = asmbench::OptionValue(argc, argv, i);
        std::FILE* f = dumpPath.empty() ? nullptr : std::fopen(dumpPath.c_str(), "w");
        if (!f)
          throw asmbench::UsageError("--dump: cannot write " + asmbench::Quoted(dumpPath));
        std::fclose(f);
        dump = dumpPath.c_str();
      }
      else if (a == "--mode")
      {
        const std::string value = asmbench::OptionValue(argc, argv, i);
        if (value != "paper" && value != "feature")
          throw asmbench::UsageError(
            "--mode: " + asmbench::Quoted(value) + " is not paper or feature");
        mode = value == "paper" ? vtkASMSimplify::PAPER : vtkASMSimplify::FEATURE_PRESERVING;
      }
      else if (a == "--set")
        settings = asmbench::OptionValue(argc, argv, i);
      else if (a == "--backend")
        backend = asmbench::OptionValue(argc, argv, i);
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
      else if (a == "--help" || a == "-h")
      {
        std::printf("%s", usage);
        return 0;
      }
      else
        throw asmbench::UsageError("unknown argument " + asmbench::Quoted(a));
    }
  }
  catch (const asmbench::UsageError& e)
  {
    std::fprintf(stderr, "asm_profile: %s\n", e.what());
    return 2;
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
  if (!vtkSMPTools::SetBackend(backend.c_str()))
  {
    std::fprintf(stderr, "this VTK has no vtkSMPTools backend %s\n", backend.c_str());
    return 2;
  }
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
      if (input->GetNumberOfPoints() == 0)
      {
        std::fprintf(
          stderr, "asm_profile: no points read from %s (not a PLY file, or empty)\n", ply);
        return 1;
      }
    }
    else
    {
      input = Synthetic(n, 42, coherent);
    }
    const vtkIdType np = input->GetNumberOfPoints();
    if (arrays)
      AddScanArrays(input);
    if (stages)
      asmprofile::TimeStages(input, fraction, mode);
    if (floor)
      asmprofile::TimeFloor(input, fraction);
    if (loops)
    {
      asmprofile::TimeLoops(input, fraction, mode, runs,
        threadsGiven ? threads : std::vector<long>{ 1, 2 }, applySettings);
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
          if (!f)
          {
            std::fprintf(stderr, "asm_profile: cannot write %s\n", dump);
            return 1;
          }
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
