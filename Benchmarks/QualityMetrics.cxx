// SPDX-License-Identifier: BSD-3-Clause
#include "QualityMetrics.h"

#include "BenchmarkData.h"
#include "BenchmarkReport.h"

#include "Core/Metrics.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace asmbench
{
namespace
{
asmcore::Execution Parallel()
{
  asmcore::Execution e;
  e.For = [](asmcore::Index b, asmcore::Index end,
            const std::function<void(asmcore::Index, asmcore::Index)>& body) {
    vtkSMPTools::For(b, end, [&body](vtkIdType s, vtkIdType t) { body(s, t); });
  };
  return e;
}

std::vector<asmcore::Index> AllIds(std::size_t n)
{
  std::vector<asmcore::Index> ids(n);
  std::iota(ids.begin(), ids.end(), asmcore::Index(0));
  return ids;
}

double MeanSquare(const std::vector<double>& d)
{
  double s = 0.0;
  for (double v : d)
  {
    s += v * v;
  }
  return d.empty() ? 0.0 : s / static_cast<double>(d.size());
}
} // namespace

Reference::Reference(std::vector<double> xyz, std::vector<double> features)
  : Xyz(std::move(xyz))
  , Ids(AllIds(this->Xyz.size() / 3))
  , Features(std::move(features))
{
  this->Tree.Build(this->Xyz.data(), this->Ids);
  this->Diag = BoundingBoxDiagonal(this->Xyz);
}

Quality Reference::Measure(const std::vector<double>& simplified, int planeNeighbors) const
{
  Quality q;
  if (simplified.empty() || this->Ids.empty())
  {
    return q;
  }
  const asmcore::Execution execution = Parallel();
  const std::vector<asmcore::Index> sids = AllIds(simplified.size() / 3);
  const asmcore::Neighbors sampleTree(simplified.data(), sids);
  const double scale = this->Diag > 0.0 ? 1.0 / this->Diag : 1.0;

  std::vector<double> toSamples, toPlane;
  asmcore::SurfaceDistances(
    this->Xyz.data(), this->Ids, sampleTree, planeNeighbors, &toPlane, &toSamples, execution);
  const std::vector<double> toOriginal =
    asmcore::NearestDistances(simplified.data(), sids, this->Tree, execution);
  q.NNRms = scale * std::sqrt(0.5 * (MeanSquare(toSamples) + MeanSquare(toOriginal)));
  q.Hole = scale * *std::max_element(toSamples.begin(), toSamples.end());

  const asmcore::DistanceSummary plane = asmcore::Summarize(toPlane);
  q.PlaneMean = scale * plane.Mean;
  q.PlaneMax = scale * plane.Max;

  if (!this->Features.empty())
  {
    const asmcore::DistanceSummary tips = asmcore::Summarize(asmcore::NearestDistances(
      this->Features.data(), AllIds(this->Features.size() / 3), sampleTree, execution));
    q.HasTips = true;
    q.TipMean = scale * tips.Mean;
    q.TipMax = scale * tips.Max;
  }
  return q;
}

Quality MedianQuality(const std::vector<Quality>& draws)
{
  Quality median = draws.front();
  for (double Quality::*field : { &Quality::PlaneMean, &Quality::PlaneMax, &Quality::NNRms,
         &Quality::Hole, &Quality::TipMean, &Quality::TipMax })
  {
    std::vector<double> values;
    for (const Quality& q : draws)
    {
      values.push_back(q.*field);
    }
    median.*field = Median(values);
  }
  return median;
}
} // namespace asmbench
