// SPDX-License-Identifier: BSD-3-Clause
/**
 * The paper mode's last step (§3.3): the points that no sample took join the
 * sample nearest to them, so that the samples' member lists partition the
 * cloud (the attributes of every input point reach an output point).
 */
#ifndef asm_core_Unclaimed_h
#define asm_core_Unclaimed_h

#include "Simplify.h"

namespace asmcore
{
/// Every point that no sample took (cells with a budget of 0, key clusters
/// left out by §3.3 (iv)) joins the sample nearest to it, after that sample's
/// own members: the member lists become a partition of the points, and the
/// samples do not move. Points in slots marked in `haloSlot` (halo cells of
/// a distributed run, owned by another process) are dropped instead. Cell c's
/// points are the slots [grid.CellStart[c], grid.CellStart[c + 1]) of the
/// members; its samples, [sampleStart[c], sampleStart[c + 1]), took the first
/// of them.
VTKASMFILTERS_EXPORT void AttachUnclaimedPoints(Coordinates xyz, const CellGrid& grid,
  const std::vector<Index>& sampleStart, SimplifyResult& result, const std::vector<char>& haloSlot,
  const Execution& execution);
} // namespace asmcore

#endif
