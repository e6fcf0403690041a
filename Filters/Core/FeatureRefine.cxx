// SPDX-License-Identifier: BSD-3-Clause
#include "FeatureRefine.h"

#include "Assignment.h"
#include "Covering.h"
#include "HoleFilling.h"

#include <cmath>
#include <limits>
#include <numeric>

namespace asmcore
{
using feature::OutputCells;
using feature::SampleInfo;

bool RefineAcrossCells(Coordinates P, const CellGrid& grid, const CellNeighborTable& neighbors,
  const SimplifyParameters& parameters, const Execution& execution, SampleSet& samples,
  std::vector<SampleInfo>& info, PointArray<SampleId>& assign)
{
  const Index cells = grid.NumberOfCells();
  Index count = samples.Size();
  // (Distributed runs: the halo cells' samples from their owners, after
  // every step that moves samples.)
  auto shareSamples = [&]() {
    if (parameters.ShareSamples)
    {
      parameters.ShareSamples(grid.CellKey, samples.Start, samples.Position);
    }
  };
  shareSamples();

  // Lloyd steps across cell borders: every point to its nearest sample,
  // every sample to its cluster's centroid.
  auto lloydStep = [&]() {
    AssignToSamples(P, grid, neighbors, samples, assign, execution);
    MoveToCentroids(P, grid, neighbors, assign, samples, execution);
  };
  for (int it = 0; it < CrossIterations(parameters); ++it)
  {
    lloydStep();
    shareSamples();
    if (execution.Report(0.6 + 0.2 * (it + 1) / CrossIterations(parameters)))
    {
      return false;
    }
  }
  // The cells whose samples are output (empty: all): the hole filling ranks
  // those, and the final Lloyd iterations' mean is over them.
  const std::vector<char> output = OutputCells(grid, parameters);
  // Hole filling; a distributed run ranks its output cells and gathers
  // (HoleFilling.h): the moves of a one-process run.
  HoleFillScope scope;
  if (parameters.FillHoles && parameters.HoleFillRounds > 0 && parameters.GatherOverProcesses)
  {
    std::vector<double> owned(1, 0.0);
    for (Index c = 0; c < cells; ++c)
    {
      const Index n = samples.Start[c + 1] - samples.Start[c];
      owned[0] += output.empty() || output[c] ? static_cast<double>(n) : 0.0;
    }
    parameters.GatherOverProcesses(owned);
    scope.TotalSamples = static_cast<Index>(std::accumulate(owned.begin(), owned.end(), 0.0));
    scope.Owned = output;
    scope.Gather = parameters.GatherOverProcesses;
  }
  const Index totalSamples = scope.TotalSamples >= 0 ? scope.TotalSamples : count;
  for (int round = 0; parameters.FillHoles && round < parameters.HoleFillRounds; ++round)
  {
    AssignToSamples(P, grid, neighbors, samples, assign, execution);
    std::vector<Index> order;
    const auto maxMoves =
      static_cast<Index>(std::llround(std::max(0.0, std::min(1.0, parameters.HoleFillFraction)) *
        static_cast<double>(totalSamples)));
    std::vector<char> moved;
    const Index before = count;
    if (FillHoles(
          P, grid, neighbors, assign, maxMoves, samples, order, moved, execution, 32, scope) == 0)
    {
      break;
    }
    count = samples.Size();
    std::vector<SampleInfo> regrouped(static_cast<std::size_t>(count));
    execution.Run(0, cells, [&](Index b, Index e) {
      for (Index c = b; c < e; ++c)
      {
        for (Index s = samples.Start[c]; s < samples.Start[c + 1]; ++s)
        {
          // (A sample from a cell not held here is a free one.)
          regrouped[s] = order[s] >= 0 ? info[order[s]] : SampleInfo();
          regrouped[s].Owner = c;
        }
      }
    });
    info.swap(regrouped);
    // One Lloyd step re-centres the moved samples and their neighbours.
    UpdateAssignment(P, grid, neighbors, samples, order, moved, assign, execution, before);
    MoveToCentroids(P, grid, neighbors, assign, samples, execution);
    shareSamples();
  }

  // Covering refinement of the input-point samples (Covering.h).
  const bool inputPoints = parameters.InputPointSamples || parameters.Snap;
  for (int round = 0; inputPoints && round < parameters.CoveringRounds; ++round)
  {
    RefineCovering(P, grid, neighbors, samples, assign, execution);
    shareSamples();
  }

  // Final Lloyd iterations across cell borders. With LloydVariationWeight
  // each point joins the sample of least m_s |p - s|^2, m_s from the
  // variation of s's plain cluster: the first iteration measures it on the
  // assignment the steps above left (a sample moved since by one Lloyd step
  // at most), the next ones assign again first (weights measured on the
  // weighted clusters would keep shrinking the same samples).
  for (int it = 0; it < parameters.FinalLloydIterations; ++it)
  {
    std::vector<double> scale;
    if (parameters.LloydVariationWeight > 0.0)
    {
      if (it > 0 || assign.size() != static_cast<std::size_t>(grid.NumberOfPoints()))
      {
        AssignToSamples(P, grid, neighbors, samples, assign, execution);
      }
      const std::vector<double> variation =
        ClusterVariations(P, grid, neighbors, assign, samples, execution);
      // The mean over the whole cloud: this run's output cells' samples, and
      // in a distributed run every other process's (an exact sum, so that
      // it does not depend on how the cloud is split).
      ExactMean mean;
      for (Index s = 0; s < count; ++s)
      {
        if (output.empty() || output[info[s].Owner])
        {
          mean.Add(variation[s]);
        }
      }
      if (parameters.SumOverProcesses)
      {
        parameters.SumOverProcesses(mean.Sums);
      }
      scale = VariationScales(variation, parameters.LloydVariationWeight,
        parameters.VariationCap > 0.0 ? parameters.VariationCap
                                      : std::numeric_limits<double>::infinity(),
        mean.Value());
    }
    AssignToSamples(
      P, grid, neighbors, samples, assign, execution, scale.empty() ? nullptr : scale.data());
    MoveToCentroids(P, grid, neighbors, assign, samples, execution);
    shareSamples();
  }
  return true;
}
} // namespace asmcore
