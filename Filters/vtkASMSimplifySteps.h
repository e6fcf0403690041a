// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   vtkASMSimplifySteps.h
 * @brief  The steps of vtkASMSimplify::RequestData that translate between
 *         VTK and the core: the filter's properties as the core's parameters,
 *         the input normals as the core reads them, and the core's samples as
 *         the output's points and generated arrays.
 *
 * Private to the module (not wrapped, not installed).
 */
#ifndef vtkASMSimplifySteps_h
#define vtkASMSimplifySteps_h

#include "Core/Simplify.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"
#include "vtkUnsignedCharArray.h"

#include <memory>

class vtkASMSimplify;
class vtkAlgorithm;
class vtkPointData;
class vtkPolyData;

namespace asmvtk
{
/// The core's parameters for a run of `filter` to `target` output points:
/// every property of the filter, as it is set. What depends on the run
/// (ErrorTolerance relative to the cloud's diagonal, CoordinateEpsilon, the
/// distributed run's grid, budgets and hooks) is the caller's to add.
/// (Exported for the profiling harness, Benchmarks/Profile.)
VTKASMFILTERS_EXPORT asmcore::SimplifyParameters CoreParameters(
  vtkASMSimplify* filter, vtkIdType target);

/// The input normals (3 components, at least `numberOfPoints` tuples) as the
/// core reads them: float and double arrays in place, other types copied
/// into `copy` as doubles. Empty when the input has no such normals.
asmcore::NormalField InputNormals(
  vtkPointData* pd, vtkIdType numberOfPoints, std::unique_ptr<double[]>& copy);

/// The arrays vtkASMSimplify generates for each output point.
struct SampleArrays
{
  vtkSmartPointer<vtkUnsignedCharArray> KeyPoint;   ///< "KeyPoint": 1 for key points
  vtkSmartPointer<vtkIdTypeArray> ClusterSize;      ///< "ClusterSize": input points represented
  vtkSmartPointer<vtkDoubleArray> SurfaceVariation; ///< "SurfaceVariation" of the sample's cell
  vtkSmartPointer<vtkIdTypeArray> OriginalIds;      ///< "vtkOriginalPointIds": the representative
  vtkSmartPointer<vtkFloatArray> Normals;           ///< the cell's PCA normal, oriented
};

/// Sets the output's points (one per sample, double or float, with one
/// vertex cell each) and returns the generated arrays, not yet added to its
/// point data. The normals are named `normalsName`; a representative's id
/// is `sourceIds[Representative]` when `sourceIds` is given (a distributed
/// run: its id on the process that read it), else Representative.
SampleArrays WriteSamples(const asmcore::SimplifyResult& result, bool doublePrecision,
  const long long* sourceIds, const char* normalsName, bool threads, vtkPolyData* output);

/// Adds the curvature arrays (AddCurvatureArrays) at the samples' positions,
/// from the k nearest points of the original cloud (xyz, ids), signed by
/// the samples' normals. Releases result.Samples first (room for the k-d
/// tree). Progress from 0.72 to 0.95 of `filter`'s. Returns false if
/// aborted.
bool AddSampleCurvature(vtkPointData* pd, asmcore::SimplifyResult& result, asmcore::Coordinates xyz,
  asmcore::IdView ids, int k, vtkAlgorithm* filter, bool threads);
} // namespace asmvtk

#endif
