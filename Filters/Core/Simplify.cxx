// SPDX-License-Identifier: BSD-3-Clause
#include "Simplify.h"

#include "CellFrame.h"
#include "CellSize.h"
#include "FeatureSimplify.h"
#include "Grid.h"
#include "PaperSimplify.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asmcore
{
Index SampleTarget(const SimplifyParameters& parameters, Index total)
{
  return parameters.CellBudget ? total
                               : std::max<Index>(0, std::min(parameters.NumberOfSamples, total));
}

double SamplesPerCellOf(const SimplifyParameters& parameters)
{
  const bool feature = parameters.Mode == SimplifyMode::FeaturePreserving;
  return std::max(1.0,
    feature && parameters.FeatureSamplesPerCell > 0.0 ? parameters.FeatureSamplesPerCell
                                                      : parameters.SamplesPerCell);
}

double VariationWeightOf(const SimplifyParameters& parameters)
{
  if (parameters.Weight == WeightMode::SurfaceVariation)
  {
    return parameters.CurvatureWeight;
  }
  return parameters.Mode == SimplifyMode::FeaturePreserving
    ? std::max(0.0, parameters.VariationBudget)
    : 0.0;
}

double VariationCapOf(const SimplifyParameters& parameters)
{
  const bool feature = parameters.Mode == SimplifyMode::FeaturePreserving &&
    parameters.Weight != WeightMode::SurfaceVariation;
  return feature && parameters.VariationCap > 0.0 ? parameters.VariationCap
                                                  : std::numeric_limits<double>::infinity();
}

std::vector<double> CellShares(const std::vector<Index>& capacity,
  const std::vector<double>& variation, const SimplifyParameters& parameters, double exponent)
{
  const std::size_t cells = capacity.size();
  double meanVariation = 0.0;
  Index total = 0;
  for (std::size_t c = 0; c < cells; ++c)
  {
    meanVariation += variation[c] * static_cast<double>(capacity[c]);
    total += capacity[c];
  }
  meanVariation /= static_cast<double>(std::max<Index>(1, total));
  std::vector<double> share(cells);
  const double k = VariationWeightOf(parameters);
  const double cap = VariationCapOf(parameters);
  for (std::size_t c = 0; c < cells; ++c)
  {
    double weight = 1.0;
    if (k != 0.0 && meanVariation > 0.0)
    {
      // Past the cap the ratio r counts as sqrt(cap * r): still growing.
      const double r = variation[c] / meanVariation;
      weight += k * (r > cap ? std::sqrt(cap * r) : r);
    }
    const auto n = static_cast<double>(capacity[c]);
    share[c] = weight * (exponent == 1.0 ? n : std::pow(n, exponent));
  }
  return share;
}

std::vector<double> CellShares(const std::vector<CellFrame>& frames, const CellGrid& grid,
  const SimplifyParameters& parameters, double exponent, std::vector<Index>& capacity)
{
  const Index cells = grid.NumberOfCells();
  capacity.resize(static_cast<std::size_t>(cells));
  std::vector<double> variation(static_cast<std::size_t>(cells));
  for (Index c = 0; c < cells; ++c)
  {
    capacity[c] = grid.CellSizeOf(c);
    variation[c] = frames.empty() ? 0.0 : frames[c].SurfaceVariation();
  }
  return CellShares(capacity, variation, parameters, exponent);
}

CellGrid BuildRunGrid(Coordinates xyz, IdView ids, const SimplifyParameters& parameters,
  Index target, const Execution& execution)
{
  const auto n = static_cast<Index>(ids.size());
  if (parameters.Cells && parameters.Cells->NumberOfPoints() == n)
  {
    CellGrid grid;
    grid.Spec = parameters.Cells->Spec;
    grid.CellStart = parameters.Cells->CellStart;
    grid.CellKey = parameters.Cells->CellKey;
    grid.Order.resize(ids.size());
    execution.Run(0, n, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i)
      {
        grid.Order[i] = ids[i];
      }
    });
    return grid;
  }
  if (parameters.Grid)
  {
    return BuildCellGrid(xyz, ids, *parameters.Grid, execution);
  }
  const Bounds bounds = ComputeBounds(xyz, ids, execution);
  const double cellSize = parameters.CellSize;
  if (cellSize > 0.0 && std::isfinite(cellSize))
  {
    return BuildCellGrid(xyz, ids, GridSpec::Make(bounds, cellSize), execution);
  }
  const double targetCells = static_cast<double>(target) / SamplesPerCellOf(parameters);
  return BuildAutomaticCellGrid(xyz, ids, bounds, targetCells, execution);
}

void SummarizeKeyPoints(SimplifyResult& result)
{
  // Summed in sample order: deterministic.
  result.NumberOfKeyPoints = 0;
  result.MKPE = 0.0;
  double sum = 0.0;
  for (const Sample& s : result.Samples)
  {
    if (s.Key)
    {
      ++result.NumberOfKeyPoints;
      sum += s.KeyError;
      result.MKPE = std::max(result.MKPE, s.KeyError);
    }
  }
  result.AKPE =
    result.NumberOfKeyPoints > 0 ? sum / static_cast<double>(result.NumberOfKeyPoints) : 0.0;
}

SimplifyResult Simplify(Coordinates xyz, IdView ids, NormalField normals,
  const SimplifyParameters& parameters, const Execution& execution)
{
  if (parameters.Mode == SimplifyMode::FeaturePreserving)
  {
    return SimplifyFeaturePreserving(xyz, ids, normals, parameters, execution);
  }
  return SimplifyPaper(xyz, ids, normals, parameters, execution);
}
} // namespace asmcore
