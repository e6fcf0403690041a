// SPDX-License-Identifier: BSD-3-Clause
#include "vtkASMSimplifySteps.h"

#include "vtkASMFilterUtilities.h"
#include "vtkASMSimplify.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <vector>

namespace asmvtk
{
asmcore::SimplifyParameters CoreParameters(vtkASMSimplify* filter, vtkIdType target)
{
  asmcore::SimplifyParameters parameters;
  parameters.Mode = filter->GetMode() == vtkASMSimplify::PAPER
    ? asmcore::SimplifyMode::Paper
    : asmcore::SimplifyMode::FeaturePreserving;
  parameters.NumberOfSamples = target;
  // The grid and the budgets (Eq. 4).
  parameters.CellSize = filter->GetCellSize();
  parameters.SamplesPerCell = filter->GetSamplesPerCell();
  parameters.Weight = filter->GetWeightMode() == vtkASMSimplify::SURFACE_VARIATION_WEIGHT
    ? asmcore::WeightMode::SurfaceVariation
    : asmcore::WeightMode::Uniform;
  parameters.CurvatureWeight = filter->GetCurvatureWeight();
  parameters.CoverEveryCell = filter->GetCoverEveryCell();
  parameters.BudgetExponent = filter->GetBudgetExponent();
  parameters.FeatureSamplesPerCell = filter->GetFeatureSamplesPerCell();
  parameters.VariationBudget = filter->GetVariationBudget();
  parameters.VariationCap = filter->GetVariationCap();
  parameters.ReserveFreeSample = filter->GetReserveFreeSample();
  // Key points and the clusters of a cell.
  parameters.Alpha = filter->GetAlpha();
  parameters.ErrorTolerance = filter->GetErrorTolerance();
  parameters.RandomSeed =
    static_cast<std::uint64_t>(static_cast<std::uint32_t>(filter->GetRandomSeed()));
  parameters.Snap = filter->GetSnapToInputPoints();
  parameters.ValidateKeyPoints = filter->GetValidateKeyPoints();
  parameters.KeyPointRadius = filter->GetKeyPointRadius();
  parameters.KeyPointProminence = filter->GetKeyPointProminence();
  parameters.InPlaneKeyPoints = filter->GetInPlaneKeyPoints();
  parameters.ExtremeKeyPoints = filter->GetExtremeKeyPoints();
  parameters.SparseCellKeyPoints = filter->GetSparseCellKeyPoints();
  parameters.LloydIterations = filter->GetLloydIterations();
  parameters.InputPointSamples = filter->GetInputPointSamples();
  // The refinements across cells (the feature-preserving mode).
  parameters.CrossCellIterations = filter->GetCrossCellIterations();
  parameters.FillHoles = filter->GetFillHoles();
  parameters.HoleFillFraction = filter->GetHoleFillFraction();
  parameters.FinalLloydIterations = filter->GetFinalLloydIterations();
  parameters.LloydVariationWeight = filter->GetLloydVariationWeight();
  parameters.CoveringRounds = filter->GetCoveringRounds();
  parameters.BoundSnappedHoles = filter->GetBoundSnappedHoles();
  return parameters;
}

asmcore::NormalField InputNormals(
  vtkPointData* pd, vtkIdType numberOfPoints, std::unique_ptr<double[]>& copy)
{
  vtkDataArray* normals = pd ? pd->GetNormals() : nullptr;
  if (!normals || normals->GetNumberOfComponents() != 3 ||
    normals->GetNumberOfTuples() < numberOfPoints)
  {
    return asmcore::NormalField();
  }
  if (auto* floats = vtkArrayDownCast<vtkAOSDataArrayTemplate<float>>(normals))
  {
    return asmcore::NormalField(floats->GetPointer(0));
  }
  if (auto* doubles = vtkArrayDownCast<vtkAOSDataArrayTemplate<double>>(normals))
  {
    return asmcore::NormalField(doubles->GetPointer(0));
  }
  return TuplesAsDoubles(normals, copy);
}

SampleArrays WriteSamples(const asmcore::SimplifyResult& result, bool doublePrecision,
  const long long* sourceIds, const char* normalsName, bool threads, vtkPolyData* output)
{
  const auto count = static_cast<vtkIdType>(result.Samples.size());
  vtkNew<vtkPoints> points;
  points->SetDataType(doublePrecision ? VTK_DOUBLE : VTK_FLOAT);
  points->SetNumberOfPoints(count);
  SampleArrays arrays;
  arrays.KeyPoint = NewArray<vtkUnsignedCharArray>("KeyPoint", 1, count);
  arrays.ClusterSize = NewArray<vtkIdTypeArray>("ClusterSize", 1, count);
  arrays.SurfaceVariation = NewArray<vtkDoubleArray>("SurfaceVariation", 1, count);
  arrays.OriginalIds = NewArray<vtkIdTypeArray>("vtkOriginalPointIds", 1, count);
  arrays.Normals = NewArray<vtkFloatArray>(normalsName, 3, count);
  // Straight into the arrays, in parallel (each sample writes its slots).
  void* xyzOut = points->GetData()->GetVoidPointer(0);
  unsigned char* key = arrays.KeyPoint->GetPointer(0);
  vtkIdType* size = arrays.ClusterSize->GetPointer(0);
  double* sv = arrays.SurfaceVariation->GetPointer(0);
  vtkIdType* original = arrays.OriginalIds->GetPointer(0);
  float* normal = arrays.Normals->GetPointer(0);
  For(threads, 0, count, [&](vtkIdType first, vtkIdType last) {
    for (vtkIdType s = first; s < last; ++s)
    {
      const asmcore::Sample& sample = result.Samples[s];
      for (int a = 0; a < 3; ++a)
      {
        if (doublePrecision)
        {
          static_cast<double*>(xyzOut)[3 * s + a] = sample.Position[a];
        }
        else
        {
          static_cast<float*>(xyzOut)[3 * s + a] = static_cast<float>(sample.Position[a]);
        }
        normal[3 * s + a] = static_cast<float>(sample.Normal[a]);
      }
      key[s] = sample.Key ? 1 : 0;
      size[s] = sample.ClusterSize;
      sv[s] = sample.SurfaceVariation;
      original[s] = sourceIds ? static_cast<vtkIdType>(sourceIds[sample.Representative])
                              : sample.Representative;
    }
  });
  output->SetPoints(points);
  output->SetVerts(VertexCells(count, threads));
  return arrays;
}

bool AddSampleCurvature(vtkPointData* pd, asmcore::SimplifyResult& result, asmcore::Coordinates xyz,
  asmcore::IdView ids, int k, vtkAlgorithm* filter, bool threads)
{
  const auto count = static_cast<vtkIdType>(result.Samples.size());
  std::vector<double> positions(static_cast<std::size_t>(3 * count));
  std::vector<double> orientation(static_cast<std::size_t>(3 * count));
  for (vtkIdType s = 0; s < count; ++s)
  {
    std::copy(result.Samples[s].Position, result.Samples[s].Position + 3, &positions[3 * s]);
    std::copy(result.Samples[s].Normal, result.Samples[s].Normal + 3, &orientation[3 * s]);
  }
  asmcore::UnwrittenArray<asmcore::Sample>().swap(result.Samples); // room for the tree
  const asmcore::Neighbors tree(xyz, ids, SMPExecution(filter, 0.72, 0.75, threads));
  return AddCurvatureArrays(pd, xyz, ids, tree, positions.data(), count, orientation.data(), k,
    SMPExecution(filter, 0.75, 0.95, threads));
}
} // namespace asmvtk
