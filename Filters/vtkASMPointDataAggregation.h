// SPDX-License-Identifier: BSD-3-Clause
/**
 * Private helper of vtkASMSimplify (not wrapped, not installed): the input's
 * point-data arrays carried to the samples, so no attribute is lost.
 *
 * One output array per input array, same class, name (or no name), number
 * of components, component names and attribute role, one tuple per sample:
 *
 * - floating-point arrays (float, double): the mean over the sample's
 *   cluster (the members that place it, asmcore::Sample::CoreSize; not the
 *   points that only joined it), component by component, ignoring NaN values (NaN only when
 *   every member is NaN); the normals attribute (3 components) is
 *   renormalised (the representative's normal when the mean is zero);
 * - every other array (signed/unsigned 8- to 64-bit integers, char,
 *   vtkIdType, bit, string, variant arrays): the tuple of the sample's
 *   representative input point, the member nearest the cluster centroid
 *   (the id in "vtkOriginalPointIds"). Labels, classes, flags and ids are
 *   never averaged into values no input point has;
 * - with snapping, every array takes the snapped point's tuple.
 *
 * One linear pass per array over the members, parallel over samples with
 * vtkSMPTools (each sample writes its own tuple: deterministic), dispatched
 * on the concrete array type (raw pointers for AOS arrays, no virtual call
 * per value). Arrays with fewer tuples than the input has points are not
 * carried (a warning names them).
 */
#ifndef vtkASMPointDataAggregation_h
#define vtkASMPointDataAggregation_h

#include "Core/Simplify.h"

class vtkObject;
class vtkPointData;

namespace asmvtk
{
/// Adds to `outPD` one array per array of `inPD` (see above), for the
/// samples of `result`, taken from an input of `numberOfPoints` points.
/// Warnings go to `reporter`. The loops run on the calling thread alone
/// when `threads` is false (asmvtk::For). Returns the number of arrays not
/// carried.
int AggregatePointData(vtkPointData* inPD, vtkPointData* outPD,
  const asmcore::SimplifyResult& result, bool snap, asmcore::Index numberOfPoints,
  vtkObject* reporter, bool threads = true);
} // namespace asmvtk

#endif
