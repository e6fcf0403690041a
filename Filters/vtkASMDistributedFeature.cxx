// SPDX-License-Identifier: BSD-3-Clause
// Distributed runs of the feature-preserving mode (vtkASMDistributed.h):
// the halo width, the mode's budget rule, and every cell's budget on every
// process (halo cells are simplified too, as context, with their true
// budgets; only the owned cells' samples are output).
#include "vtkASMDistributed.h"

#include "Core/Budget.h"
#include "Core/FeatureSimplify.h"

#include "vtkMultiProcessController.h"

#include <algorithm>
#include <numeric>

namespace asmvtk
{
int HaloRingsFor(const asmcore::SimplifyParameters& parameters)
{
  if (parameters.Mode == asmcore::SimplifyMode::Paper)
  {
    return HaloRings;
  }
  return std::max(HaloRings, asmcore::InfluenceRingsOf(parameters) + FeatureHaloMargin);
}

std::vector<Index> ApportionCells(const std::vector<Index>& capacity,
  const std::vector<double>& variation, const asmcore::SimplifyParameters& parameters,
  Index target)
{
  if (parameters.Mode == asmcore::SimplifyMode::Paper)
  {
    return asmcore::ApportionBudget(
      asmcore::CellShares(capacity, variation, parameters), capacity, target);
  }
  // As SimplifyFeaturePreserving's step 3.
  const std::vector<double> share = asmcore::CellShares(
    capacity, variation, parameters, std::max(0.0, parameters.BudgetExponent));
  return asmcore::ApportionWithCoverage(share, capacity, target, parameters.CoverEveryCell);
}

void ShareAllBudgets(const Communication& comm, SimplifyShare& share)
{
  // (key / 2^32, key % 2^32, budget) as doubles: each part is exact.
  std::vector<double> mine;
  mine.reserve(3 * share.OwnedKeys.size());
  for (std::size_t c = 0; c < share.OwnedKeys.size(); ++c)
  {
    mine.insert(mine.end(), { static_cast<double>(share.OwnedKeys[c] >> 32),
                              static_cast<double>(share.OwnedKeys[c] & 0xFFFFFFFFULL),
                              static_cast<double>(share.Budgets[c]) });
  }
  const std::vector<double> all = comm.AllGather(mine);
  const std::size_t cells = all.size() / 3;
  std::vector<std::pair<std::uint64_t, Index>> table(cells);
  for (std::size_t c = 0; c < cells; ++c)
  {
    table[c] = { (static_cast<std::uint64_t>(all[3 * c]) << 32) |
        static_cast<std::uint64_t>(all[3 * c + 1]),
      static_cast<Index>(all[3 * c + 2]) };
  }
  std::sort(table.begin(), table.end());
  share.AllKeys.resize(cells);
  share.AllBudgets.resize(cells);
  for (std::size_t c = 0; c < cells; ++c)
  {
    share.AllKeys[c] = table[c].first;
    share.AllBudgets[c] = table[c].second;
  }
}

Index SimplifyShare::TrueBudgetOf(std::uint64_t key) const
{
  const auto it = std::lower_bound(this->AllKeys.begin(), this->AllKeys.end(), key);
  return (it != this->AllKeys.end() && *it == key)
    ? this->AllBudgets[static_cast<std::size_t>(it - this->AllKeys.begin())]
    : 0;
}

bool SimplifyShare::Owns(std::uint64_t key) const
{
  return std::binary_search(this->OwnedKeys.begin(), this->OwnedKeys.end(), key);
}
} // namespace asmvtk
