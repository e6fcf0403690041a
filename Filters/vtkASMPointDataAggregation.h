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
 *   points that only joined it), component by component, ignoring NaN and
 *   infinite values (NaN when no member has a finite value); the normals
 *   attribute (3 components) is renormalised (the representative's normal
 *   when the mean is zero);
 * - every other array (signed/unsigned 8- to 64-bit integers, char,
 *   vtkIdType, bit, string, variant arrays): the tuple of the sample's
 *   representative input point (the id in "vtkOriginalPointIds": see
 *   vtkASMSimplify.h). Labels, classes, flags and ids are
 *   never averaged into values no input point has;
 * - with snapping, every array takes the snapped point's tuple.
 *
 * One linear pass per array over the members, parallel over samples with
 * vtkSMPTools (each sample writes its own tuple: deterministic), dispatched
 * on the concrete array type (raw pointers for AOS arrays, no virtual call
 * per value). Arrays with fewer tuples than the input has points are not
 * carried (a warning names them).
 *
 * Which of exact duplicates a sample stands for (ChooseAmongDuplicates) does
 * not depend on the points' ids either: the one whose values come first.
 */
#ifndef vtkASMPointDataAggregation_h
#define vtkASMPointDataAggregation_h

#include "Core/Simplify.h"

#include "vtkType.h"

#include <utility>
#include <vector>

class vtkAbstractArray;
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
  vtkObject* reporter, bool threads);

/// Exact duplicates (points at the same position, such as the overlap of
/// merged scans) may carry different values. A sample's representative
/// input point becomes, among the points at exactly its position
/// (SimplifyResult::RepresentativeDuplicates), the one whose point data
/// comes first (the same point for every sample at that position): array by
/// array, the numeric ones in the order of `inPD`, then the string, variant
/// and bit arrays in that order (as a distributed run compares them: these
/// break the numeric arrays' ties there) (those carried: with a
/// tuple for each of the `numberOfPoints` points), component by
/// component, by value (CompareTuples), then the lower id. So the tuples
/// copied from representatives (and, with `snap`, every array) do not depend
/// on the input's order or on the number of MPI processes. Nothing to do
/// when no representative has a duplicate or no array is taken from the
/// representatives (`snap` off, floating-point arrays only), unless `ties`
/// is given: it then also receives, as (sample, point) pairs in increasing
/// order, the other points at each sample's position with the same values
/// in every array of `inPD` (a distributed run's string arrays, which are
/// not in `inPD`, decide among them: FetchRepresentativeValues).
void ChooseAmongDuplicates(vtkPointData* inPD, asmcore::Index numberOfPoints,
  asmcore::SimplifyResult& result, bool snap, bool threads,
  std::vector<std::pair<vtkIdType, asmcore::Index>>* ties = nullptr);

/// The information keys (units, GUI hints, ...) of each array of `from`
/// that has some, added to those of the array of the same name in `to`
/// (replacing the same keys), as VTK's point-subsetting filters keep them
/// (the cached range keys excepted: vtkDataArray::CopyInformation drops
/// them).
void CopyArrayInformation(vtkPointData* from, vtkPointData* to);

/// -1, 0 or 1: the tuple of point a against that of point b in `array`,
/// component by component, by value (NaN after every number and equal to
/// NaN; strings by their bytes; other arrays, such as variant arrays, tie).
int CompareTuples(vtkAbstractArray* array, vtkIdType a, vtkIdType b);
} // namespace asmvtk

#endif
