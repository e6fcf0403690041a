// SPDX-License-Identifier: BSD-3-Clause
// Shapes and small utilities shared by the GoogleTest tests.
#ifndef asm_TestHelpers_h
#define asm_TestHelpers_h

#include "Core/CellNeighbors.h"
#include "Core/Common.h"
#include "Core/Grid.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace asmtest
{
/// Points as N x 3 doubles.
using Cloud = std::vector<double>;

inline void Add(Cloud& c, double x, double y, double z)
{
  c.push_back(x);
  c.push_back(y);
  c.push_back(z);
}

/// Points of a regular (n x n) grid over [-half, half]^2 with z = f(x, y).
template <typename F>
Cloud GridSurface(int n, double half, F f)
{
  Cloud c;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      const double x = -half + 2.0 * half * i / (n - 1);
      const double y = -half + 2.0 * half * j / (n - 1);
      Add(c, x, y, f(x, y));
    }
  }
  return c;
}

/// n random points on a sphere of the given radius and centre.
inline Cloud Sphere(
  std::size_t n, double radius, unsigned seed = 7, double cx = 0, double cy = 0, double cz = 0)
{
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i)
  {
    double v[3] = { g(rng), g(rng), g(rng) };
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    Add(c, cx + radius * v[0] / l, cy + radius * v[1] / l, cz + radius * v[2] / l);
  }
  return c;
}

/// The ids 0 .. N-1 of a cloud's points.
inline std::vector<std::int64_t> AllIds(const Cloud& c)
{
  std::vector<std::int64_t> ids(c.size() / 3);
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    ids[i] = static_cast<std::int64_t>(i);
  }
  return ids;
}

/// The grid of cells of edge h over all points of a cloud (from its
/// bounds), and the grid's table of neighbouring cells.
struct GriddedCloud
{
  asmcore::CellGrid Grid;
  asmcore::CellNeighborTable Neighbors;
};
inline GriddedCloud Gridded(const Cloud& c, double h)
{
  const auto ids = AllIds(c);
  GriddedCloud g;
  g.Grid = asmcore::BuildCellGrid(
    c.data(), ids, asmcore::GridSpec::Make(asmcore::ComputeBounds(c.data(), ids), h));
  g.Neighbors = asmcore::BuildCellNeighbors(g.Grid);
  return g;
}

/// Cuts ranges into uneven pieces and runs them on two threads: the results
/// must not depend on how the work is cut or scheduled.
inline asmcore::Execution UnevenTwoThreads()
{
  asmcore::Execution execution;
  execution.For = [](asmcore::Index begin, asmcore::Index end,
                    const std::function<void(asmcore::Index, asmcore::Index)>& body) {
    const asmcore::Index n = end - begin;
    const asmcore::Index cut1 = begin + n / 7, cut2 = begin + n / 7 + (n * 3) / 5;
    std::thread other([&] { body(cut1, cut2); });
    body(begin, cut1);
    body(cut2, end);
    other.join();
  };
  return execution;
}

inline std::string DataFile(const std::string& name)
{
  return std::string(ASM_TEST_DATA_DIR) + "/" + name;
}
} // namespace asmtest

#endif
