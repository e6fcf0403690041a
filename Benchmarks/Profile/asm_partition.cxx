// SPDX-License-Identifier: BSD-3-Clause
/**
 * asm_partition: what a distributed run's halo costs with K processes, for
 * the cell owners of vtkASMSimplify (boxes from a recursive bisection,
 * asmcore::CellPartition) and, for comparison, slabs along the grid's
 * longest axis balanced by point counts (the partition before 2026-11-25).
 * No MPI: the partition is computed here for K virtual processes, on the
 * grid the default mode would use (automatic cell size for N_s = fraction
 * x N and 4 samples per cell).
 *
 *   asm_partition [--input bumps:2M | file.ply] [--fraction 0.01]
 *                 [--processes 2,4,8,16,32,64] [--halo 2,6]
 *
 * A bad option exits with status 2 before any work, an input without any
 * finite point with status 1 (non-finite points are left out, as ASM does).
 *
 * Prints, per K and halo width (cell rings; 2: Paper mode, 6: the default
 * mode): the points held over all processes (owned + halo) per input point,
 * and the largest process's held points per N / K (its work and memory
 * relative to an even share without halo); then the time the boxes took to
 * build (one thread; a distributed run builds them over N / K points per
 * process).
 */
#include "BenchmarkArgs.h"
#include "BenchmarkData.h"
#include "Core/CellPartition.h"
#include "Core/CellSize.h"
#include "Core/Grid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace
{
// Slabs of the longest axis: each axis index goes to the slab holding the
// middle of its points (contiguous slabs of about N / K points).
std::vector<int> SlabOfIndex(
  const asmcore::GridSpec& grid, int axis, const std::vector<double>& xyz, int k)
{
  std::vector<long long> count(static_cast<std::size_t>(grid.Dims[axis]), 0);
  const std::size_t n = xyz.size() / 3;
  for (std::size_t i = 0; i < n; ++i)
  {
    std::uint64_t u[3];
    grid.CellOf(xyz.data() + 3 * i, u);
    ++count[u[axis]];
  }
  std::vector<int> slab(count.size(), 0);
  long long before = 0;
  for (std::size_t b = 0; b < count.size(); ++b)
  {
    const double middle = static_cast<double>(before) + 0.5 * static_cast<double>(count[b]);
    slab[b] = std::min(k - 1, static_cast<int>(middle * k / static_cast<double>(n)));
    before += count[b];
  }
  return slab;
}
} // namespace

int main(int argc, char* argv[])
{
  std::string input = "bumps:2M";
  double fraction = 0.01;
  std::vector<int> processes = { 2, 4, 8, 16, 32, 64 };
  std::vector<int> halos = { 2, 6 };
  const char* usage = "usage: asm_partition [--input bumps:2M | file.ply] [--fraction 0.01]\n"
                      "                     [--processes 2,4,8,16,32,64] [--halo 2,6]\n";
  try
  {
    for (int a = 1; a < argc; ++a)
    {
      const std::string flag = argv[a];
      if (flag == "--help" || flag == "-h")
      {
        std::printf("%s", usage);
        return 0;
      }
      else if (flag == "--input")
      {
        input = asmbench::OptionValue(argc, argv, a);
        std::string error;
        if (!asmbench::CheckInputSpec(input, error))
        {
          throw asmbench::UsageError("--input: " + error);
        }
      }
      else if (flag == "--fraction")
      {
        fraction = asmbench::ParseFraction(flag, asmbench::OptionValue(argc, argv, a));
      }
      else if (flag == "--processes")
      {
        processes.clear();
        for (long k :
          asmbench::ParseIntegerList(flag, asmbench::OptionValue(argc, argv, a), 1, 4096))
        {
          processes.push_back(static_cast<int>(k));
        }
      }
      else if (flag == "--halo")
      {
        halos.clear();
        for (long h :
          asmbench::ParseIntegerList(flag, asmbench::OptionValue(argc, argv, a), 0, 1000))
        {
          halos.push_back(static_cast<int>(h));
        }
      }
      else
      {
        throw asmbench::UsageError("unknown option " + asmbench::Quoted(flag));
      }
    }
  }
  catch (const asmbench::UsageError& e)
  {
    std::fprintf(stderr, "asm_partition: %s\n", e.what());
    return 2;
  }
  const asmbench::Input in = asmbench::MakeInput(input);
  if (in.NumberOfPoints() == 0)
  {
    std::fprintf(stderr, "asm_partition: no points in %s\n", input.c_str());
    return 1;
  }
  // The finite points only (the core's cell size and grid need finite bounds).
  std::vector<double> xyz = asmbench::Coordinates(in.Data);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < xyz.size(); i += 3)
  {
    if (std::isfinite(xyz[i]) && std::isfinite(xyz[i + 1]) && std::isfinite(xyz[i + 2]))
    {
      std::copy(xyz.begin() + i, xyz.begin() + i + 3, xyz.begin() + kept);
      kept += 3;
    }
  }
  if (kept < xyz.size())
  {
    std::fprintf(stderr, "asm_partition: %zu non-finite point(s) of %s left out\n",
      (xyz.size() - kept) / 3, input.c_str());
    xyz.resize(kept);
  }
  if (xyz.empty())
  {
    std::fprintf(stderr, "asm_partition: no finite points in %s\n", input.c_str());
    return 1;
  }
  const auto n = static_cast<asmcore::Index>(xyz.size() / 3);
  const asmcore::IdView ids = asmcore::IdView::Identity(static_cast<std::size_t>(n));
  const asmcore::Bounds bounds = asmcore::ComputeBounds(xyz.data(), ids);
  const double targetCells = fraction * static_cast<double>(n) / 4.0;
  const asmcore::GridSpec grid = asmcore::GridSpec::Make(
    bounds, asmcore::AutomaticCellSize(xyz.data(), ids, bounds, targetCells));
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    axis = grid.Dims[a] > grid.Dims[axis] ? a : axis;
  }
  std::printf(
    "%s: %lld points, grid %lld x %lld x %lld cells (N_s = %.3g x N, 4 samples per cell)\n\n",
    in.Name.c_str(), static_cast<long long>(n), static_cast<long long>(grid.Dims[0]),
    static_cast<long long>(grid.Dims[1]), static_cast<long long>(grid.Dims[2]), fraction);
  std::printf("| K | halo rings | held / N, boxes | held / N, slabs | busiest x N/K, boxes | "
              "busiest x N/K, slabs |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|\n");
  std::vector<double> buildSeconds; // (the boxes' build, one thread, all N points on one process)
  for (int k : processes)
  {
    const auto start = std::chrono::steady_clock::now();
    const asmcore::CellPartition boxes = asmcore::MakeCellPartition(grid, k, xyz.data(), ids);
    buildSeconds.push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    const std::vector<int> slabOf = SlabOfIndex(grid, axis, xyz, k);
    for (int h : halos)
    {
      std::vector<long long> inBox(static_cast<std::size_t>(k), 0);
      std::vector<long long> inSlab(static_cast<std::size_t>(k), 0);
      for (asmcore::Index i = 0; i < n; ++i)
      {
        std::int64_t ijk[3];
        boxes.CellOfPoint(xyz.data() + 3 * i, ijk);
        boxes.ForEachOwnerNear(ijk, h, [&](int q) { ++inBox[static_cast<std::size_t>(q)]; });
        const int first =
          slabOf[static_cast<std::size_t>(std::max<std::int64_t>(0, ijk[axis] - h))];
        const int last =
          slabOf[static_cast<std::size_t>(std::min(grid.Dims[axis] - 1, ijk[axis] + h))];
        for (int q = first; q <= last; ++q)
        {
          ++inSlab[static_cast<std::size_t>(q)];
        }
      }
      auto total = [&](const std::vector<long long>& v) {
        long long s = 0;
        for (long long x : v)
        {
          s += x;
        }
        return static_cast<double>(s) / static_cast<double>(n);
      };
      auto busiest = [&](const std::vector<long long>& v) {
        return static_cast<double>(*std::max_element(v.begin(), v.end())) * k /
          static_cast<double>(n);
      };
      std::printf("| %d | %d | %.3f | %.3f | %.3f | %.3f |\n", k, h, total(inBox), total(inSlab),
        busiest(inBox), busiest(inSlab));
    }
  }
  std::printf("\nBuilding the boxes (one thread, all %lld points):", static_cast<long long>(n));
  for (std::size_t j = 0; j < processes.size(); ++j)
  {
    std::printf(
      " K = %d %.3f s%s", processes[j], buildSeconds[j], j + 1 < processes.size() ? "," : "\n");
  }
  return 0;
}
