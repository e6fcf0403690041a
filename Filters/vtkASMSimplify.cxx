// SPDX-License-Identifier: BSD-3-Clause
#include "vtkASMSimplify.h"

#include "Core/CellNeighbors.h"
#include "Core/Grid.h"
#include "Core/Simplify.h"
#include "vtkASMCompositeInput.h"
#include "vtkASMDistributed.h"
#include "vtkASMFilterUtilities.h"
#include "vtkASMPointDataAggregation.h"
#include "vtkASMSimplifySteps.h"

#include "vtkCompositeDataSet.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <limits>
#include <memory>
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
  // Every floating-point property (a clamped setter lets NaN through).
  const double values[] = { this->OutputFraction, this->CellSize, this->SamplesPerCell, this->Alpha,
    this->ErrorTolerance, this->CurvatureWeight, this->FeatureSamplesPerCell, this->VariationBudget,
    this->VariationCap, this->KeyPointRadius, this->KeyPointProminence, this->BudgetExponent,
    this->HoleFillFraction, this->LloydVariationWeight };
  const char* names[] = { "OutputFraction", "CellSize", "SamplesPerCell", "Alpha", "ErrorTolerance",
    "CurvatureWeight", "FeatureSamplesPerCell", "VariationBudget", "VariationCap", "KeyPointRadius",
    "KeyPointProminence", "BudgetExponent", "HoleFillFraction", "LloydVariationWeight" };
  static_assert(sizeof(values) / sizeof(values[0]) == sizeof(names) / sizeof(names[0]),
    "a name for every value");
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
    std::vector<std::string> dropped, skipped;
    merged = asmvtk::MergeLeaves(composite, asmvtk::LeafData::ArraysAndOrigins, dropped, &skipped);
    for (const std::string& leaf : skipped)
    {
      vtkWarningMacro(<< asmvtk::SkippedLeafWarning(leaf));
    }
    for (const std::string& name : dropped)
    {
      vtkWarningMacro(<< asmvtk::DroppedArrayWarning(name));
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
    numberOfPoints >= asmvtk::MinimumPointsForThreads(this->MinimumPointsForThreads);

  // Coordinates, finite points, and the requested output size.
  std::unique_ptr<double[]> coordinateCopy;
  asmcore::PointIds idList; // (empty when every point is valid: ids is the identity)
  asmcore::IdView ids;
  // A float cloud is read in place, widened as it is read (the default
  // mode into its cell-ordered copy, the paper mode cell by cell): no double
  // copy of 24 bytes per point. MPI runs send doubles on.
  const bool floatsInPlace = !distributed;
  double largest = 0.0; // |coordinate|
  asmcore::Coordinates xyz = numberOfPoints > 0
    ? asmvtk::PrepareCoordinates(
        input->GetPoints(), coordinateCopy, idList, ids, largest, threads, floatsInPlace)
    : asmcore::Coordinates();
  vtkIdType skipped = numberOfPoints - static_cast<vtkIdType>(ids.size());
  // Duplicate ghost points (another piece's, in a partitioned dataset) are
  // not this input's to simplify, nor are hidden (blanked) ones.
  asmvtk::DropGhostPoints(input, ids, idList);
  vtkIdType valid = static_cast<vtkIdType>(ids.size());
  int pointsType = numberOfPoints > 0 ? input->GetPoints()->GetDataType() : VTK_FLOAT;
  double coordinateEpsilon = numberOfPoints > 0 ? asmvtk::CoordinateEpsilon(input->GetPoints())
                                                : std::numeric_limits<float>::epsilon();
  if (distributed)
  {
    valid = comm.Sum(static_cast<Index>(ids.size()));
    skipped = comm.Sum(static_cast<Index>(skipped));
    pointsType = comm.Max(pointsType == VTK_DOUBLE ? 1.0 : 0.0) > 0.0 ? VTK_DOUBLE : VTK_FLOAT;
    coordinateEpsilon = -comm.Max(-coordinateEpsilon); // a double's if any process needs it
    largest = comm.Max(largest);
  }
  if (skipped > 0)
  {
    vtkWarningMacro(<< skipped
                    << " input points have NaN or infinite coordinates; they are ignored.");
  }
  if (valid == 0)
  {
    vtkWarningMacro(<< "The input has no points to simplify: the output is empty.");
    return 1;
  }
  if (!asmcore::CoordinateRange::Holds(largest))
  {
    vtkErrorMacro(<< asmvtk::OutOfRangeMessage("The input", largest));
    return 1;
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
                    << "): every input point is kept, one sample each.");
    target = valid;
  }

  if (this->Mode != PAPER &&
    target > static_cast<vtkIdType>(std::numeric_limits<asmcore::SampleId>::max()))
  {
    vtkErrorMacro(<< "The feature-preserving mode keeps at most "
                  << std::numeric_limits<asmcore::SampleId>::max() << " output points (asked: "
                  << target << "); use the paper mode (Mode = PAPER) or a smaller target.");
    return 1;
  }

  asmcore::SimplifyParameters parameters = asmvtk::CoreParameters(this, target);
  // The bound is the largest hole of the whole cloud: distributed runs take
  // it after the core's run, over all processes (BoundSnappedHolesAcross).
  parameters.BoundSnappedHoles = parameters.BoundSnappedHoles && !distributed;
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
    asmvtk::RunOnShare(share, parameters);
  }

  // The input normals are read where they are (float or double arrays).
  std::unique_ptr<double[]> normalCopy;
  const asmcore::NormalField normals = asmvtk::InputNormals(inPD, numberOfPoints, normalCopy);

  if (this->RelativeErrorTolerance && this->ErrorTolerance > 0.0)
  {
    parameters.ErrorTolerance *=
      distributed ? share.Diagonal : asmcore::ComputeBounds(xyz, ids).Diagonal();
  }
  parameters.CoordinateEpsilon = coordinateEpsilon;

  asmvtk::CollectiveChannel channel(comm);
  if (distributed && parameters.Mode == asmcore::SimplifyMode::FeaturePreserving)
  {
    parameters.SumOverProcesses = channel.SumHook();
    parameters.GatherOverProcesses = channel.GatherHook();
    parameters.ShareSamples = channel.ShareHook(share, asmvtk::HaloRingsFor(parameters));
  }
  asmcore::SimplifyResult result = asmcore::Simplify(xyz, ids, normals, parameters,
    asmvtk::SMPExecution(
      this, distributed ? 0.2 : 0.0, this->GenerateCurvature ? 0.7 : 0.9, threads));
  if (distributed)
  {
    if (parameters.SumOverProcesses)
    {
      channel.Finish(); // (with the processes still running, if any)
    }
    asmvtk::CombineFigures(comm, share, result); // of the whole cloud
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
  // Which of exact duplicates each sample stands for: by value, not by id.
  // (A distributed run's string, variant and bit arrays, read from the
  // processes holding the points, decide among those that tie on the rest.)
  std::vector<std::pair<vtkIdType, asmcore::Index>> ties;
  const bool fetching = distributed && !share.Cloud.Fetched.empty();
  asmvtk::ChooseAmongDuplicates(
    inPD, numberOfPoints, result, this->SnapToInputPoints, threads, fetching ? &ties : nullptr);
  vtkNew<vtkPointData> fetchedPD;
  if (distributed &&
    !asmvtk::FetchRepresentativeValues(
      comm, input->GetPointData(), share.Cloud, ties, result, fetchedPD))
  {
    vtkWarningMacro(<< "The string, variant and bit arrays could not be read from the other "
                       "processes: they are not passed on.");
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

  // Points (one vertex cell each) and the generated arrays.
  bool doublePrecision = this->OutputPointsPrecision == vtkAlgorithm::DOUBLE_PRECISION ||
    (this->OutputPointsPrecision == vtkAlgorithm::DEFAULT_PRECISION && pointsType == VTK_DOUBLE);
  if (!doublePrecision && pointsType == VTK_DOUBLE &&
    (largest > std::numeric_limits<float>::max() ||
      (largest > 0.0 && largest < std::numeric_limits<float>::min())))
  {
    vtkWarningMacro(<< "The coordinates reach " << largest
                    << ", beyond a float's normal range: the output points are double, not "
                       "single precision as OutputPointsPrecision asks.");
    doublePrecision = true;
  }
  vtkAbstractArray* inputNamedNormals = inPD->GetAbstractArray("Normals");
  const bool nameTaken = // by an input array that is carried (see AggregatePointData)
    inputNamedNormals && inputNamedNormals->GetNumberOfTuples() >= numberOfPoints;
  const asmvtk::SampleArrays generated = asmvtk::WriteSamples(result, doublePrecision,
    distributed ? share.Cloud.SourceId.data() : nullptr, nameTaken ? "PCANormals" : "Normals",
    threads, output);
  this->UpdateProgress(this->GenerateCurvature ? 0.72 : 0.95);

  // Point data: the input's arrays aggregated, then the generated ones.
  vtkPointData* outPD = output->GetPointData();
  asmvtk::AggregatePointData(
    inPD, outPD, result, this->SnapToInputPoints, numberOfPoints, this, threads);
  if (distributed)
  {
    asmvtk::AddFetchedArrays(fetchedPD, share.Cloud, outPD);
  }
  // (A distributed run's arrays were rebuilt from their types: the keys
  // come from this process's input, as a serial run's do.)
  asmvtk::CopyArrayInformation(input->GetPointData(), outPD);
  asmcore::PointArray<asmcore::Index>().swap(
    result.Members); // used up: room for the curvature's tree
  outPD->AddArray(generated.KeyPoint);
  outPD->AddArray(generated.ClusterSize);
  outPD->AddArray(generated.SurfaceVariation);
  outPD->AddArray(generated.OriginalIds); // (replacing an input's: ids into this input)
  // An input's own origin arrays (an earlier run's) pair with the
  // vtkOriginalPointIds just replaced: only this run's are kept.
  if (!merged)
  {
    outPD->RemoveArray("vtkOriginalBlockIds");
  }
  if (!distributed)
  {
    outPD->RemoveArray("vtkOriginalProcessIds");
  }
  if (merged)
  {
    // A composite input: the ids in the representative's own block (which
    // "vtkOriginalBlockIds" names), not in the merged cloud.
    if (vtkDataArray* leafIds = outPD->GetArray(asmvtk::LeafPointIdsName))
    {
      for (vtkIdType s = 0; s < count; ++s)
      {
        generated.OriginalIds->SetValue(s, static_cast<vtkIdType>(leafIds->GetComponent(s, 0)));
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
  if (outPD->GetNormals()) // the input's, carried: the PCA normals beside them
  {
    outPD->AddArray(generated.Normals);
  }
  else
  {
    outPD->SetNormals(generated.Normals);
  }
  if (this->GenerateCurvature)
  {
    // At the output points, from the original cloud, signed by the output
    // normals (the PCA normals, oriented).
    if (!asmvtk::AddSampleCurvature(
          outPD, result, xyz, ids, this->CurvatureNeighbors, this, threads))
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
  os << indent
     << "WeightMode: " << (this->WeightMode == UNIFORM_WEIGHT ? "Uniform" : "SurfaceVariation")
     << "\n";
  os << indent << "CurvatureWeight: " << this->CurvatureWeight << "\n";
  os << indent << "RandomSeed: " << this->RandomSeed << "\n";
  os << indent << "SnapToInputPoints: " << this->SnapToInputPoints << "\n";
  os << indent << "GenerateCurvature: " << this->GenerateCurvature << "\n";
  os << indent << "CurvatureNeighbors: " << this->CurvatureNeighbors << "\n";
  os << indent << "OutputPointsPrecision: " << this->OutputPointsPrecision << "\n";
  os << indent << "MinimumPointsForThreads: "
     << asmvtk::DescribeMinimumPointsForThreads(this->MinimumPointsForThreads) << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "AlwaysDistribute: " << this->AlwaysDistribute << "\n";
}
