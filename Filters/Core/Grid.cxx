// SPDX-License-Identifier: BSD-3-Clause
#include "Grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace asmcore
{
std::vector<Index> FinitePointIds(const double* xyz, Index n)
{
  std::vector<Index> ids;
  ids.reserve(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i)
  {
    const double* p = xyz + 3 * i;
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      ids.push_back(i);
    }
  }
  return ids;
}

double Bounds::Diagonal() const
{
  if (!this->Valid)
  {
    return 0.0;
  }
  return std::sqrt(this->Extent(0) * this->Extent(0) + this->Extent(1) * this->Extent(1) +
    this->Extent(2) * this->Extent(2));
}

double Bounds::MaxExtent() const
{
  return this->Valid ? std::max({ this->Extent(0), this->Extent(1), this->Extent(2) }) : 0.0;
}

Bounds ComputeBounds(const double* xyz, const std::vector<Index>& ids)
{
  Bounds b;
  if (ids.empty())
  {
    return b;
  }
  for (int a = 0; a < 3; ++a)
  {
    b.Min[a] = std::numeric_limits<double>::infinity();
    b.Max[a] = -std::numeric_limits<double>::infinity();
  }
  for (Index id : ids)
  {
    const double* p = xyz + 3 * id;
    for (int a = 0; a < 3; ++a)
    {
      b.Min[a] = std::min(b.Min[a], p[a]);
      b.Max[a] = std::max(b.Max[a], p[a]);
    }
  }
  b.Valid = true;
  return b;
}

GridSpec GridSpec::Make(const Bounds& bounds, double cellSize)
{
  GridSpec g;
  const double maxExtent = bounds.MaxExtent();
  // Smallest edge that keeps every axis within MaxDim cells (with a margin for
  // rounding), and a positive edge for a cloud of coincident points.
  double minSize = maxExtent / static_cast<double>(MaxDim - 2);
  if (!(minSize > 0.0))
  {
    minSize = std::max(std::abs(bounds.Min[0]), 1.0) * 1e-12;
  }
  g.CellSize = (std::isfinite(cellSize) && cellSize > minSize) ? cellSize : minSize;
  for (int a = 0; a < 3; ++a)
  {
    g.Origin[a] = bounds.Valid ? bounds.Min[a] : 0.0;
    const double extent = bounds.Valid ? bounds.Extent(a) : 0.0;
    g.Dims[a] = std::min<std::int64_t>(MaxDim,
      std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(extent / g.CellSize)) + 1));
  }
  return g;
}

std::uint64_t GridSpec::KeyOf(const double p[3]) const
{
  std::uint64_t key = 0;
  for (int a = 2; a >= 0; --a)
  {
    double t = std::floor((p[a] - this->Origin[a]) / this->CellSize);
    t = std::min(std::max(t, 0.0), static_cast<double>(this->Dims[a] - 1));
    key = (key << 21) | static_cast<std::uint64_t>(t);
  }
  return key;
}

void GridSpec::Unpack(std::uint64_t key, std::int64_t ijk[3]) const
{
  const std::uint64_t mask = (std::uint64_t(1) << 21) - 1;
  ijk[0] = static_cast<std::int64_t>(key & mask);
  ijk[1] = static_cast<std::int64_t>((key >> 21) & mask);
  ijk[2] = static_cast<std::int64_t>((key >> 42) & mask);
}

CellGrid BuildCellGrid(const double* xyz, const std::vector<Index>& ids, const GridSpec& spec)
{
  CellGrid grid;
  grid.Spec = spec;
  std::vector<std::pair<std::uint64_t, Index>> keyed(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    keyed[i] = { spec.KeyOf(xyz + 3 * ids[i]), ids[i] };
  }
  std::sort(keyed.begin(), keyed.end());
  grid.Order.resize(ids.size());
  for (std::size_t i = 0; i < keyed.size(); ++i)
  {
    grid.Order[i] = keyed[i].second;
    if (i == 0 || keyed[i].first != keyed[i - 1].first)
    {
      grid.CellKey.push_back(keyed[i].first);
      grid.CellStart.push_back(static_cast<Index>(i));
    }
  }
  grid.CellStart.push_back(static_cast<Index>(ids.size()));
  return grid;
}

Index CountOccupiedCells(const double* xyz, const std::vector<Index>& ids, const GridSpec& spec)
{
  std::vector<std::uint64_t> keys(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    keys[i] = spec.KeyOf(xyz + 3 * ids[i]);
  }
  std::sort(keys.begin(), keys.end());
  return static_cast<Index>(std::unique(keys.begin(), keys.end()) - keys.begin());
}

double AutomaticCellSize(
  const double* xyz, const std::vector<Index>& ids, const Bounds& bounds, double targetCells)
{
  return AutomaticCellSize(bounds, targetCells, ids.empty(), [&](const GridSpec& spec) {
    return static_cast<double>(CountOccupiedCells(xyz, ids, spec));
  });
}

double AutomaticCellSize(const Bounds& bounds, double targetCells, bool empty,
  const std::function<double(const GridSpec&)>& countOccupied)
{
  const double maxExtent = bounds.MaxExtent();
  if (empty || !(maxExtent > 0.0))
  {
    return GridSpec::Make(bounds, 0.0).CellSize; // one cell holds everything
  }
  // One cell for the whole cloud: slightly larger than the largest extent.
  const double oneCell = maxExtent * (1.0 + 1e-9);
  if (targetCells <= 1.0)
  {
    return oneCell;
  }
  // Start from the guess that the points sample a surface (count ~ h^-2),
  // then correct with the measured count and the measured local exponent.
  double h = maxExtent / std::sqrt(targetCells);
  double bestH = oneCell;
  double bestErr = std::abs(std::log(1.0 / targetCells));
  double prevH = 0.0, prevCount = 0.0;
  double dimension = 2.0;
  for (int iteration = 0; iteration < 12; ++iteration)
  {
    h = GridSpec::Make(bounds, h).CellSize;
    const double count = countOccupied(GridSpec::Make(bounds, h));
    const double err = std::abs(std::log(count / targetCells));
    if (err < bestErr)
    {
      bestErr = err;
      bestH = h;
    }
    if (err < 0.05) // within 5 %
    {
      break;
    }
    if (prevCount > 0.0 && count != prevCount && h != prevH)
    {
      const double measured = -std::log(count / prevCount) / std::log(h / prevH);
      dimension = std::min(3.0, std::max(0.5, measured));
    }
    prevH = h;
    prevCount = count;
    h *= std::pow(count / targetCells, 1.0 / dimension);
    h = std::min(h, oneCell);
  }
  return bestH;
}
} // namespace asmcore
