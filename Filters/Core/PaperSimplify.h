// SPDX-License-Identifier: BSD-3-Clause
/**
 * The paper's pipeline read literally (ASM-spec.md, "Pipeline"), the Paper
 * mode of the ASM driver:
 *
 *  1. grid hashing (§3.5 step 1: automatic or given cell size);
 *  2. PCA of every cell (§3.2 i-iv);
 *  3. budgets N_c of Eq. 4, exact in total (Budget.h);
 *  4. key points: the clusters of the top and bottom bands along v2, their
 *     extremes, with the error bound of Eq. 5 (KeyPoints.h);
 *  5. the combination with sampling (§3.3 i-iv): all key points and median
 *     splits of the middle band, or N_c key clusters drawn at random, or
 *     every point when N_c >= n_c;
 *  6. the points left in no group join their nearest sample (Unclaimed.h),
 *     so that the samples' members partition the input points.
 *
 * Each cell writes its own samples: the result does not depend on the
 * thread count.
 */
#ifndef asm_core_PaperSimplify_h
#define asm_core_PaperSimplify_h

#include "Simplify.h"

namespace asmcore
{
/// Simplify in the Paper mode; same contract as Simplify().
VTKASMFILTERS_EXPORT SimplifyResult SimplifyPaper(Coordinates xyz, IdView ids, NormalField normals,
  const SimplifyParameters& parameters, const Execution& execution = {});
} // namespace asmcore

#endif
