// SPDX-License-Identifier: BSD-3-Clause
/**
 * A mean in fixed point, so that parts summed on several processes (or by
 * several threads, in any order) give the whole's mean exactly: used for the
 * mean cluster variation (Lloyd.h's VariationScales) and for the effective
 * occupied-cell count of the automatic cell size (CellSize.h), serial and
 * distributed alike.
 */
#ifndef asm_core_ExactMean_h
#define asm_core_ExactMean_h

#include "vtkASMFiltersModule.h"

#include <vector>

namespace asmcore
{
/// A mean that does not depend on the order of its terms nor on how they
/// are split: each term is rounded to a multiple of 2^-40 (clamped to
/// [0, 4096)) and summed as integers, so parts summed on several processes
/// (Sums added element by element) give the whole's mean exactly.
struct VTKASMFILTERS_EXPORT ExactMean
{
  /// The integer sums: high and low parts of the fixed-point total, count.
  std::vector<long long> Sums = std::vector<long long>(3, 0);

  void Add(double value);
  /// The sum of the terms added (as rounded), over all parts once Sums are
  /// totals.
  double Total() const;
  /// The mean of the terms added (over all parts, once Sums are totals); 0
  /// when there are none.
  double Value() const;
};

} // namespace asmcore

#endif
