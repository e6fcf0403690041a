// SPDX-License-Identifier: BSD-3-Clause
#include "vtkASMSimplify.h"

#include "Core/CellNeighbors.h"
#include "Core/Grid.h"
#include "vtkASMDistributed.h"
#include "Core/Neighbors.h"
#include "Core/Simplify.h"
#include "vtkASMCompositeInput.h"
#include "vtkASMFilterUtilities.h"
#include "vtkASMPointDataAggregation.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkASMSimplify);
vtkCxxSetObjectMacro(vtkASMSimplify, Controller, vtkMultiProcessController);

namespace
{
using asmcore::Index;
} // namespace

//------------------------------------------------------------------------------
vtkASMSimplify::vtkASMSimplify()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

//------------------------------------------------------------------------------
vtkASMSimplify::~vtkASMSimplify()
{
  this->SetController(nullptr);
}

//------------------------------------------------------------------------------
int vtkASMSimplify::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  // A composite input is one cloud (vtkASMCompositeInput.h), not one run per leaf.
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

//------------------------------------------------------------------------------
bool vtkASMSimplify::CheckParameters()
{
  const double values[] = { this->OutputFraction, this->CellSize, this->SamplesPerCell, this->Alpha,
    this->ErrorTolerance, this->CurvatureWeight, this->FeatureSamplesPerCell, this->VariationBudget,
    this->VariationCap };
  const char* names[] = { "OutputFraction", "CellSize", "SamplesPerCell", "Alpha",
    "ErrorTolerance", "CurvatureWeight", "FeatureSamplesPerCell", "VariationBudget",
    "VariationCap" };
  for (std::size_t i = 0; i < sizeof(values) / sizeof(values[0]); ++i)
  {
    if (!std::isfinite(values[i]))
    {
      vtkErrorMacro(<< names[i] << " is not a finite number (" << values[i] << ").");
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkASMSimplify::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // An abort (ParaView's Cancel) stops one run; VTK 9.2's executive never
  // clears the flag, so without this every later run would abort at once.
  this->AbortExecute = 0;
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  vtkSmartPointer<vtkPolyData> merged; // a composite input's leaves as one cloud
  if (auto* composite = vtkCompositeDataSet::GetData(inputVector[0]))
  {
    std::vector<std::string> dropped;
    merged = asmvtk::MergeLeaves(composite, asmvtk::LeafData::ArraysAndOrigins, dropped);
    for (const std::string& name : dropped)
    {
      vtkWarningMacro(<< "Point array " << name << " is not on every block with points: it is not passed on.");
    }
    input = merged;
  }
  if (!input || !output)
  {
    vtkErrorMacro(<< "Input must be a vtkPointSet or a composite dataset of them.");
    return 0;
  }
  output->GetFieldData()->PassData(input->GetFieldData());
  if (!this->CheckParameters())
  {
    return 1; // empty output
  }
  vtkIdType numberOfPoints = input->GetPoints() ? input->GetNumberOfPoints() : 0;
  // MPI runs (vtkASMDistributed.h): every process takes part in the
  // collectives, with or without points of its own.
  const bool distributed = asmvtk::IsDistributed(this->Controller, this->AlwaysDistribute);
  const asmvtk::Communication comm(distributed ? this->Controller : nullptr);
  if (numberOfPoints == 0 && !distributed)
  {
    vtkWarningMacro(<< "The input has no points: the output is empty.");
    return 1;
  }

  // Small clouds on the calling thread (MinimumPointsForThreads).
  const bool threads =
    this->MinimumPointsForThreads <= 0 || numberOfPoints >= this->MinimumPointsForThreads;

  // Coordinates, finite points, and the requested output size.
  std::unique_ptr<double[]> coordinateCopy;
  asmcore::PointIds idList; // (empty when every point is valid: ids is the identity)
  asmcore::IdView ids;
  // A float cloud is read in place, widened as it is read (the default
  // mode into its cell-ordered copy, the paper mode cell by cell): no double
  // copy of 24 bytes per point. MPI runs send doubles on.
  const bool floatsInPlace = !distributed;
  asmcore::Coordinates xyz = numberOfPoints > 0
    ? asmvtk::PrepareCoordinates(
        input->GetPoints(), coordinateCopy, idList, ids, threads, floatsInPlace)
    : asmcore::Coordinates();
  vtkIdType valid = static_cast<vtkIdType>(ids.size());
  vtkIdType skipped = numberOfPoints - valid;
  int pointsType = numberOfPoints > 0 ? input->GetPoints()->GetDataType() : VTK_FLOAT;
  if (distributed)
  {
    asmvtk::DropDuplicateGhosts(input, ids, idList);
    valid = comm.Sum(static_cast<Index>(ids.size()));
    skipped = comm.Sum(static_cast<Index>(skipped));
    pointsType = comm.Max(pointsType == VTK_DOUBLE ? 1.0 : 0.0) > 0.0 ? VTK_DOUBLE : VTK_FLOAT;
    if (valid == 0)
    {
      vtkWarningMacro(<< "The input has no points: the output is empty.");
      return 1;
    }
  }
  if (skipped > 0)
  {
    vtkWarningMacro(<< skipped << " input points have NaN or infinite coordinates; they are ignored.");
  }
  vtkIdType target = this->TargetMode == OUTPUT_FRACTION
    ? static_cast<vtkIdType>(std::llround(this->OutputFraction * static_cast<double>(valid)))
    : this->NumberOfOutputPoints;
  if (target <= 0)
  {
    vtkWarningMacro(<< "The requested number of output points is 0: the output is empty.");
    return 1;
  }
  if (target >= valid)
  {
    vtkWarningMacro(<< "The requested number of output points (" << target
                    << ") is not smaller than the number of input points (" << valid
                    << "): the input points are passed through.");
    target = valid;
  }

  if (this->Mode != PAPER && target > static_cast<vtkIdType>(std::numeric_limits<asmcore::SampleId>::max()))
  {
    vtkErrorMacro(<< "The feature-preserving mode keeps at most "
                  << std::numeric_limits<asmcore::SampleId>::max() << " output points (asked: "
                  << target << "); use the paper mode (Mode = PAPER) or a smaller target.");
    return 1;
  }

  asmcore::SimplifyParameters parameters;
  parameters.Mode = this->Mode == PAPER ? asmcore::SimplifyMode::Paper
                                        : asmcore::SimplifyMode::FeaturePreserving;
  parameters.NumberOfSamples = target;
  parameters.CellSize = this->CellSize;
  parameters.SamplesPerCell = this->SamplesPerCell;
  parameters.Weight = this->WeightMode == SURFACE_VARIATION_WEIGHT
    ? asmcore::WeightMode::SurfaceVariation
    : asmcore::WeightMode::Uniform;
  parameters.CurvatureWeight = this->CurvatureWeight;
  // Options of the feature mode that the distributed budget rule and halo
  // width depend on.
  parameters.CoverEveryCell = this->CoverEveryCell;
  parameters.BudgetExponent = this->BudgetExponent;
  parameters.CrossCellIterations = this->CrossCellIterations;
  // Hole filling ranks the samples and points of the whole cloud: distributed
  // runs gather their rankings (GatherOverProcesses).
  parameters.FillHoles = this->FillHoles;
  parameters.FeatureSamplesPerCell = this->FeatureSamplesPerCell;
  parameters.VariationBudget = this->VariationBudget;
  parameters.VariationCap = this->VariationCap;
  parameters.ReserveFreeSample = this->ReserveFreeSample;
  // Local steps (a wider halo in distributed runs: HaloRingsFor); the mean
  // of their weights is summed over the processes (SumOverProcesses).
  parameters.FinalLloydIterations = this->FinalLloydIterations;
  parameters.LloydVariationWeight = this->LloydVariationWeight;
  // (Local: each sample moves within its own cluster.)
  parameters.CoveringRounds = this->CoveringRounds;
  parameters.SparseCellKeyPoints = this->SparseCellKeyPoints;
  // The bound is the largest hole of the whole cloud: distributed runs take
  // it after the core's run, over all processes (BoundSnappedHolesAcross).
  parameters.BoundSnappedHoles = distributed ? false : this->BoundSnappedHoles;
  vtkPointData* inPD = input->GetPointData();
  asmvtk::SimplifyShare share;
  if (distributed)
  {
    // One grid, owners, halo, budgets; then the core runs on this process's
    // cells (owned and halo) as if they were the whole input.
    // (The grid, the redistribution and the budgets: progress only; an
    // abort waits for the core, whose processes agree on it.)
    this->UpdateProgress(0.0);
    // (Threads only: its progress is reported around it.)
    share = asmvtk::PrepareSimplify(
      comm, input, xyz.Doubles, ids, parameters, asmvtk::SMPExecution(this, 0.0, 0.0, threads));
    this->UpdateProgress(0.2);
    for (const std::string& dropped : share.Cloud.Dropped)
    {
      vtkWarningMacro(<< "Point array " << dropped << " is not passed on in a distributed run.");
    }
    xyz = share.Cloud.Xyz.data();
    idList = asmcore::PointIds(); // (the share's points are 0 .. n-1)
    ids = share.Cloud.Ids();
    coordinateCopy.reset(); // the share holds this process's points now
    numberOfPoints = static_cast<vtkIdType>(ids.size());
    inPD = share.Cloud.PointData;
    parameters.Grid = &share.Grid;
    parameters.Cells = &share.Cloud.Cells;
    if (parameters.Mode == asmcore::SimplifyMode::Paper)
    {
      parameters.CellBudget = [&share](std::uint64_t key) { return share.BudgetOf(key); };
    }
    else
    {
      // Halo cells are simplified too, with their true budgets, as context
      // for the cross-cell steps; only the owned cells' samples are output.
      parameters.CellBudget = [&share](std::uint64_t key) { return share.TrueBudgetOf(key); };
      parameters.OutputCell = [&share](std::uint64_t key) { return share.Owns(key); };
    }
    parameters.CloudCentroid = share.Centroid;
  }

  // The input normals are read where they are (float or double arrays);
  // other layouts are copied as doubles.
  std::unique_ptr<double[]> normalCopy;
  asmcore::NormalField normals;
  if (vtkDataArray* inNormals = inPD->GetNormals())
  {
    if (inNormals->GetNumberOfComponents() == 3 && inNormals->GetNumberOfTuples() >= numberOfPoints)
    {
      if (auto* floats = vtkArrayDownCast<vtkAOSDataArrayTemplate<float>>(inNormals))
      {
        normals = asmcore::NormalField(floats->GetPointer(0));
      }
      else if (auto* doubles = vtkArrayDownCast<vtkAOSDataArrayTemplate<double>>(inNormals))
      {
        normals = asmcore::NormalField(doubles->GetPointer(0));
      }
      else
      {
        normals = asmvtk::TuplesAsDoubles(inNormals, normalCopy);
      }
    }
  }

  parameters.Alpha = this->Alpha;
  parameters.ErrorTolerance = this->ErrorTolerance;
  if (this->RelativeErrorTolerance && this->ErrorTolerance > 0.0)
  {
    parameters.ErrorTolerance *=
      distributed ? share.Diagonal : asmcore::ComputeBounds(xyz, ids).Diagonal();
  }
  parameters.RandomSeed = static_cast<std::uint64_t>(static_cast<std::uint32_t>(this->RandomSeed));
  parameters.Snap = this->SnapToInputPoints;
  parameters.ValidateKeyPoints = this->ValidateKeyPoints;
  parameters.KeyPointRadius = this->KeyPointRadius;
  parameters.KeyPointProminence = this->KeyPointProminence;
  parameters.InPlaneKeyPoints = this->InPlaneKeyPoints;
  parameters.ExtremeKeyPoints = this->ExtremeKeyPoints;
  parameters.LloydIterations = this->LloydIterations;
  parameters.InputPointSamples = this->InputPointSamples;
  parameters.HoleFillFraction = this->HoleFillFraction;
  parameters.CoordinateEpsilon = pointsType == VTK_DOUBLE
    ? std::numeric_limits<double>::epsilon()
    : std::numeric_limits<float>::epsilon();

  asmvtk::CollectiveChannel channel(comm);
  if (distributed && parameters.Mode == asmcore::SimplifyMode::FeaturePreserving)
  {
    parameters.SumOverProcesses = channel.SumHook();
    parameters.GatherOverProcesses = channel.GatherHook();
    parameters.ShareSamples = channel.ShareHook(share, asmvtk::HaloRingsFor(parameters));
  }
  asmcore::SimplifyResult result = asmcore::Simplify(xyz, ids, normals, parameters,
    asmvtk::SMPExecution(this, distributed ? 0.2 : 0.0, this->GenerateCurvature ? 0.7 : 0.9, threads));
  if (distributed)
  {
    if (parameters.SumOverProcesses)
    {
      channel.Finish(); // (with the processes still running, if any)
    }
    // Figures of the whole cloud: sums and maxima over the processes.
    const Index keys = comm.Sum(result.NumberOfKeyPoints);
    const double sum = comm.Sum(result.AKPE * static_cast<double>(result.NumberOfKeyPoints));
    result.MKPE = comm.Max(result.MKPE);
    result.AKPE = keys > 0 ? sum / static_cast<double>(keys) : 0.0;
    result.NumberOfKeyPoints = keys;
    result.CellSize = share.Grid.CellSize;
    result.Aborted = comm.Max(result.Aborted ? 1.0 : 0.0) > 0.0;
  }
  if (result.Aborted)
  {
    if (this->GetAbortExecute())
    {
      vtkWarningMacro(<< "Aborted: the output is empty.");
    }
    else // (the core's own limits: 32-bit cell and sample numbers)
    {
      vtkErrorMacro(<< "The grid has more than " << asmcore::CellNeighborTable::MaxTableCells
                    << " non-empty cells (or this process more samples), more than the "
                       "feature-preserving mode can number; use a larger CellSize or the paper "
                       "mode (Mode = PAPER). The output is empty.");
    }
    return 1;
  }
  if (distributed && parameters.Mode == asmcore::SimplifyMode::FeaturePreserving &&
    this->BoundSnappedHoles && this->InputPointSamples && !this->SnapToInputPoints)
  {
    // (Collective: every process got here, none aborted.)
    const double at = this->GenerateCurvature ? 0.7 : 0.9;
    asmvtk::BoundSnappedHolesAcross(comm, xyz, result, asmvtk::SMPExecution(this, at, at, threads));
  }
  if (this->CellSize > 0.0 && result.CellSize > this->CellSize)
  {
    vtkWarningMacro(<< "CellSize " << this->CellSize << " would make more than "
                    << asmcore::GridSpec::MaxDim << " cells along an axis; using "
                    << result.CellSize << ".");
  }
  const auto count = static_cast<vtkIdType>(result.Samples.size());
  // From here on the coordinates and ids serve the curvature estimates only:
  // released before the output is laid out when those are off.
  normalCopy.reset();
  if (!this->GenerateCurvature)
  {
    coordinateCopy.reset();
    asmcore::PointIds().swap(idList);
    ids = asmcore::IdView();
    xyz = asmcore::Coordinates();
  }

  // Points and one vertex cell each.
  vtkNew<vtkPoints> points;
  const bool doublePrecision = this->OutputPointsPrecision == vtkAlgorithm::DOUBLE_PRECISION ||
    (this->OutputPointsPrecision == vtkAlgorithm::DEFAULT_PRECISION &&
      pointsType == VTK_DOUBLE);
  points->SetDataType(doublePrecision ? VTK_DOUBLE : VTK_FLOAT);
  points->SetNumberOfPoints(count);
  auto keyFlags = asmvtk::NewArray<vtkUnsignedCharArray>("KeyPoint", 1, count);
  auto clusterSizes = asmvtk::NewArray<vtkIdTypeArray>("ClusterSize", 1, count);
  auto variation = asmvtk::NewArray<vtkDoubleArray>("SurfaceVariation", 1, count);
  auto originalIds = asmvtk::NewArray<vtkIdTypeArray>("vtkOriginalPointIds", 1, count);
  vtkAbstractArray* inputNamedNormals = inPD->GetAbstractArray("Normals");
  const bool nameTaken = // by an input array that is carried (see AggregatePointData)
    inputNamedNormals && inputNamedNormals->GetNumberOfTuples() >= numberOfPoints;
  auto pcaNormals = asmvtk::NewArray<vtkFloatArray>(nameTaken ? "PCANormals" : "Normals", 3, count);
  {
    // Straight into the arrays, in parallel (each sample writes its slots).
    void* xyzOut = points->GetData()->GetVoidPointer(0);
    unsigned char* key = keyFlags->GetPointer(0);
    vtkIdType* size = clusterSizes->GetPointer(0);
    double* sv = variation->GetPointer(0);
    vtkIdType* original = originalIds->GetPointer(0);
    float* normal = pcaNormals->GetPointer(0);
    asmvtk::For(threads, 0, count, [&](vtkIdType first, vtkIdType last) {
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
        original[s] = distributed ? share.Cloud.SourceId[sample.Representative] : sample.Representative;
      }
    });
  }
  output->SetPoints(points);
  output->SetVerts(asmvtk::VertexCells(count, threads));
  this->UpdateProgress(this->GenerateCurvature ? 0.72 : 0.95);

  // Point data: the input's arrays aggregated, then the generated ones.
  vtkPointData* outPD = output->GetPointData();
  asmvtk::AggregatePointData(inPD, outPD, result, this->SnapToInputPoints, numberOfPoints, this);
  asmcore::PointArray<asmcore::Index>().swap(result.Members); // used up: room for the curvature's tree
  outPD->AddArray(keyFlags);
  outPD->AddArray(clusterSizes);
  outPD->AddArray(variation);
  outPD->AddArray(originalIds);
  if (merged)
  {
    // A composite input: the ids in the representative's own block (which
    // "vtkOriginalBlockIds" names), not in the merged cloud.
    if (vtkDataArray* leafIds = outPD->GetArray(asmvtk::LeafPointIdsName))
    {
      for (vtkIdType s = 0; s < count; ++s)
      {
        originalIds->SetValue(s, static_cast<vtkIdType>(leafIds->GetComponent(s, 0)));
      }
      outPD->RemoveArray(asmvtk::LeafPointIdsName);
    }
  }
  if (distributed)
  {
    // Which process's input vtkOriginalPointIds refers to.
    auto processIds = asmvtk::NewArray<vtkIdTypeArray>("vtkOriginalProcessIds", 1, count);
    for (vtkIdType s = 0; s < count; ++s)
    {
      processIds->SetValue(s, share.Cloud.SourceRank[result.Samples[s].Representative]);
    }
    outPD->AddArray(processIds);
  }
  if (nameTaken || outPD->GetNormals())
  {
    outPD->AddArray(pcaNormals);
  }
  else
  {
    outPD->SetNormals(pcaNormals);
  }
  if (this->GenerateCurvature)
  {
    // At the output points, from the original cloud, signed by the output
    // normals (the PCA normals, oriented).
    std::vector<double> positions(static_cast<std::size_t>(3 * count));
    std::vector<double> orientation(static_cast<std::size_t>(3 * count));
    for (vtkIdType s = 0; s < count; ++s)
    {
      std::copy(result.Samples[s].Position, result.Samples[s].Position + 3, &positions[3 * s]);
      std::copy(result.Samples[s].Normal, result.Samples[s].Normal + 3, &orientation[3 * s]);
    }
    asmcore::UnwrittenArray<asmcore::Sample>().swap(result.Samples); // room for the tree
    const asmcore::Neighbors tree(xyz, ids, asmvtk::SMPExecution(this, 0.72, 0.75, threads));
    if (!asmvtk::AddCurvatureArrays(outPD, xyz, ids, tree, positions.data(), count,
          orientation.data(), this->CurvatureNeighbors, asmvtk::SMPExecution(this, 0.75, 0.95, threads)))
    {
      vtkWarningMacro(<< "Aborted: the output is empty.");
      output->Initialize();
      return 1;
    }
  }
  if (!outPD->GetScalars())
  {
    outPD->SetActiveScalars(this->GenerateCurvature ? "MeanCurvature" : "SurfaceVariation");
  }

  vtkFieldData* fd = output->GetFieldData();
  asmvtk::AddFieldValue(fd, "AKPE", result.AKPE);
  asmvtk::AddFieldValue(fd, "MKPE", result.MKPE);
  asmvtk::AddFieldValue(fd, "NumberOfKeyPoints", static_cast<double>(result.NumberOfKeyPoints));
  asmvtk::AddFieldValue(fd, "CellSize", result.CellSize);
  asmvtk::AddFieldValue(fd, "NumberOfSkippedPoints", static_cast<double>(skipped));
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkASMSimplify::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << (this->Mode == PAPER ? "Paper" : "FeaturePreserving") << "\n";
  os << indent << "ValidateKeyPoints: " << this->ValidateKeyPoints << "\n";
  os << indent << "KeyPointRadius: " << this->KeyPointRadius << "\n";
  os << indent << "KeyPointProminence: " << this->KeyPointProminence << "\n";
  os << indent << "InPlaneKeyPoints: " << this->InPlaneKeyPoints << "\n";
  os << indent << "ExtremeKeyPoints: " << this->ExtremeKeyPoints << "\n";
  os << indent << "CoverEveryCell: " << this->CoverEveryCell << "\n";
  os << indent << "BudgetExponent: " << this->BudgetExponent << "\n";
  os << indent << "LloydIterations: " << this->LloydIterations << "\n";
  os << indent << "CrossCellIterations: " << this->CrossCellIterations << "\n";
  os << indent << "InputPointSamples: " << this->InputPointSamples << "\n";
  os << indent << "FillHoles: " << this->FillHoles << "\n";
  os << indent << "HoleFillFraction: " << this->HoleFillFraction << "\n";
  os << indent << "FeatureSamplesPerCell: " << this->FeatureSamplesPerCell << "\n";
  os << indent << "VariationBudget: " << this->VariationBudget << "\n";
  os << indent << "VariationCap: " << this->VariationCap << "\n";
  os << indent << "ReserveFreeSample: " << this->ReserveFreeSample << "\n";
  os << indent << "FinalLloydIterations: " << this->FinalLloydIterations << "\n";
  os << indent << "LloydVariationWeight: " << this->LloydVariationWeight << "\n";
  os << indent << "CoveringRounds: " << this->CoveringRounds << "\n";
  os << indent << "BoundSnappedHoles: " << this->BoundSnappedHoles << "\n";
  os << indent << "SparseCellKeyPoints: " << this->SparseCellKeyPoints << "\n";
  os << indent << "TargetMode: "
     << (this->TargetMode == OUTPUT_FRACTION ? "OutputFraction" : "NumberOfOutputPoints") << "\n";
  os << indent << "OutputFraction: " << this->OutputFraction << "\n";
  os << indent << "NumberOfOutputPoints: " << this->NumberOfOutputPoints << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
  os << indent << "SamplesPerCell: " << this->SamplesPerCell << "\n";
  os << indent << "Alpha: " << this->Alpha << "\n";
  os << indent << "ErrorTolerance: " << this->ErrorTolerance << "\n";
  os << indent << "RelativeErrorTolerance: " << this->RelativeErrorTolerance << "\n";
  os << indent << "WeightMode: "
     << (this->WeightMode == UNIFORM_WEIGHT ? "Uniform" : "SurfaceVariation") << "\n";
  os << indent << "CurvatureWeight: " << this->CurvatureWeight << "\n";
  os << indent << "RandomSeed: " << this->RandomSeed << "\n";
  os << indent << "SnapToInputPoints: " << this->SnapToInputPoints << "\n";
  os << indent << "GenerateCurvature: " << this->GenerateCurvature << "\n";
  os << indent << "CurvatureNeighbors: " << this->CurvatureNeighbors << "\n";
  os << indent << "OutputPointsPrecision: " << this->OutputPointsPrecision << "\n";
  os << indent << "MinimumPointsForThreads: " << this->MinimumPointsForThreads << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "AlwaysDistribute: " << this->AlwaysDistribute << "\n";
}
