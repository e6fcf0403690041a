// SPDX-License-Identifier: BSD-3-Clause
#include "vtkKeyPointError.h"

#include "Core/Grid.h"
#include "Core/Metrics.h"
#include "Core/Neighbors.h"
#include "vtkASMCompositeInput.h"
#include "vtkASMDistributedMetrics.h"
#include "vtkASMFilterUtilities.h"

#include "vtkCellArray.h"
#include "vtkCompositeDataSet.h"
#include "vtkDoubleArray.h"
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
#include "vtkTable.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkKeyPointError);
vtkCxxSetObjectMacro(vtkKeyPointError, Controller, vtkMultiProcessController);

namespace
{
using asmcore::Index;

// A cloud's coordinates as doubles and its finite points that are neither
// duplicate ghosts (another piece's points) nor hidden: vtkASMSimplify
// skips them too.
struct Cloud
{
  std::vector<double> Copy;
  const double* Xyz = nullptr;
  std::vector<Index> Ids;
  vtkIdType Skipped = 0; // (non-finite)

  explicit Cloud(vtkPointSet* data)
  {
    if (data->GetPoints() && data->GetNumberOfPoints() > 0)
    {
      this->Xyz = asmvtk::CoordinatesAsDoubles(data->GetPoints(), this->Copy);
      this->Ids = asmcore::FinitePointIds(this->Xyz, data->GetNumberOfPoints());
      this->Skipped = data->GetNumberOfPoints() - static_cast<vtkIdType>(this->Ids.size());
      asmcore::IdView ids(this->Ids);
      asmcore::PointIds owned;
      asmvtk::DropGhostPoints(data, ids, owned);
      if (ids.size() != this->Ids.size())
      {
        this->Ids.assign(ids.begin(), ids.end());
      }
    }
  }
};

// Whether the boxes overlap, or nearly: apart by at most 1e-6 of the larger
// diagonal plus 16 roundings (`epsilon`, the coarser of the clouds'
// precisions) of the largest |coordinate| (a centroid of coplanar points can
// leave their plane by a rounding; the warning is about unrelated clouds).
// (Before 2026-11-29 the slack was 1e-6 of the largest |coordinate|: 5 m
// 5e6 m from the origin, so that two 1 m clouds 4 m apart passed.)
bool Overlap(const asmcore::Bounds& a, const asmcore::Bounds& b, double epsilon)
{
  const double slack = 1e-6 * std::max(a.Diagonal(), b.Diagonal()) +
    16.0 * epsilon * std::max(a.LargestMagnitude(), b.LargestMagnitude());
  for (int k = 0; k < 3; ++k)
  {
    if (a.Max[k] + slack < b.Min[k] || b.Max[k] + slack < a.Min[k])
    {
      return false;
    }
  }
  return true;
}
} // namespace

//------------------------------------------------------------------------------
vtkKeyPointError::vtkKeyPointError()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

//------------------------------------------------------------------------------
vtkKeyPointError::~vtkKeyPointError()
{
  this->SetController(nullptr);
}

//------------------------------------------------------------------------------
int vtkKeyPointError::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  // A composite input is one cloud (vtkASMCompositeInput.h), as vtkASMSimplify takes it.
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkKeyPointError::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

//------------------------------------------------------------------------------
vtkTable* vtkKeyPointError::GetFiguresOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkKeyPointError::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // An abort (ParaView's Cancel) stops one run; VTK 9.2's executive never
  // clears the flag, so without this every later run would abort at once.
  this->AbortExecute = 0;
  vtkPointSet* original = vtkPointSet::GetData(inputVector[0]);
  vtkPointSet* simplified = vtkPointSet::GetData(inputVector[1]);
  // Composite inputs: their leaves as one cloud each (the original's points
  // only; the simplified cloud's arrays are passed to the output).
  vtkSmartPointer<vtkPolyData> merged[2];
  for (int port = 0; port < 2; ++port)
  {
    if (auto* composite = vtkCompositeDataSet::GetData(inputVector[port]))
    {
      std::vector<std::string> dropped, skipped;
      merged[port] = asmvtk::MergeLeaves(composite,
        port == 0 ? asmvtk::LeafData::PointsOnly : asmvtk::LeafData::Arrays, dropped, &skipped);
      (port == 0 ? original : simplified) = merged[port];
      for (const std::string& leaf : skipped)
      {
        vtkWarningMacro(<< asmvtk::SkippedLeafWarning(
                          leaf, port == 0 ? " (original, port 0)" : " (simplified, port 1)"));
      }
      for (const std::string& name : dropped) // (port 1's: passed to the output)
      {
        vtkWarningMacro(<< asmvtk::DroppedArrayWarning(name, " of the simplified (port 1) cloud"));
      }
    }
  }
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  if (!original || !simplified || !output || !table)
  {
    vtkErrorMacro(
      << "Needs two point sets: the original (port 0) and a simplified cloud (port 1).");
    return 0;
  }
  const std::pair<const char*, double> parameters[] = { { "Alpha", this->Alpha },
    { "CellSize", this->CellSize }, { "SamplesPerCell", this->SamplesPerCell } };
  for (const auto& parameter : parameters)
  {
    if (!std::isfinite(parameter.second)) // (a clamped setter lets NaN through)
    {
      vtkErrorMacro(<< parameter.first << " is not a finite number (" << parameter.second << ").");
      return 1;
    }
  }
  const Cloud orig(original);
  const Cloud simp(simplified);
  const bool distributed = asmvtk::IsDistributed(this->Controller, false);
  const asmvtk::Communication comm(distributed ? this->Controller : nullptr);
  if (distributed &&
    (comm.Sum(static_cast<Index>(orig.Ids.size())) == 0 ||
      comm.Sum(static_cast<Index>(simp.Ids.size())) == 0))
  {
    // (A warning, as vtkASMSimplify's: an upstream clip or time step that
    // leaves nothing is not an error.)
    vtkWarningMacro(<< "One of the clouds has no finite points (not flagged as ghosts or hidden) "
                       "on any process: nothing to measure, the outputs are empty.");
    return 1;
  }
  if (!distributed && (orig.Ids.empty() || simp.Ids.empty()))
  {
    vtkWarningMacro(<< "The " << (orig.Ids.empty() ? "original (port 0)" : "simplified (port 1)")
                    << " cloud has no finite points (not flagged as ghosts or hidden): nothing "
                       "to measure, the outputs are empty.");
    return 1;
  }
  if (orig.Skipped + simp.Skipped > 0)
  {
    vtkWarningMacro(<< orig.Skipped << " original and " << simp.Skipped
                    << " simplified points have NaN or infinite coordinates; they are ignored.");
  }
  if (!distributed && simp.Ids.size() > orig.Ids.size())
  {
    vtkWarningMacro(<< "The simplified cloud has more points (" << simp.Ids.size()
                    << ") than the original (" << orig.Ids.size() << "): check the inputs' order.");
  }
  const asmcore::Bounds origBounds = asmcore::ComputeBounds(orig.Xyz, orig.Ids);
  const asmcore::Bounds simpBounds = asmcore::ComputeBounds(simp.Xyz, simp.Ids);
  const double largest[2] = { comm.Max(origBounds.LargestMagnitude()),
    comm.Max(simpBounds.LargestMagnitude()) };
  for (int port = 0; port < 2; ++port)
  {
    if (!asmcore::CoordinateRange::Holds(largest[port]))
    {
      vtkErrorMacro(<< asmvtk::OutOfRangeMessage(
                      port == 0 ? "The original (port 0) cloud" : "The simplified (port 1) cloud",
                      largest[port]));
      return 1;
    }
  }
  // The coordinates' precision, of the whole original cloud, as
  // vtkASMSimplify takes it (asmvtk::CoordinateEpsilon: a double's when any
  // process holds double values that a float cannot hold). A process without
  // points (an empty piece, a composite whose leaves are empty here: no
  // vtkPoints at all) has no say.
  vtkPoints* originalPoints = original->GetPoints();
  double coordinateEpsilon = originalPoints && original->GetNumberOfPoints() > 0
    ? asmvtk::CoordinateEpsilon(originalPoints)
    : std::numeric_limits<float>::epsilon();
  if (distributed)
  {
    coordinateEpsilon = -comm.Max(-coordinateEpsilon);
  }
  if (!distributed &&
    !Overlap(origBounds, simpBounds,
      std::max(coordinateEpsilon, asmvtk::CoordinateEpsilon(simplified->GetPoints()))))
  {
    vtkWarningMacro(<< "The two clouds' bounding boxes do not overlap: the distances are those "
                       "between unrelated clouds.");
  }

  // The planes' precision: the coarser of the two clouds' (a float cloud's
  // line is off its line by its roundings, and no plane).
  vtkPoints* simplifiedPoints = simplified->GetPoints();
  double surfaceEpsilon = std::max(coordinateEpsilon,
    simplifiedPoints && simplified->GetNumberOfPoints() > 0
      ? asmvtk::CoordinateEpsilon(simplifiedPoints)
      : 0.0);
  if (distributed)
  {
    surfaceEpsilon = comm.Max(surfaceEpsilon);
  }

  asmcore::ComparisonOptions options;
  options.Rule.Alpha = this->Alpha;
  options.Rule.CoordinateEpsilon = coordinateEpsilon;
  options.SurfaceEpsilon = surfaceEpsilon;
  options.CellSize = this->CellSize;
  options.SamplesPerCell = this->SamplesPerCell;
  options.Measure = this->DistanceMeasure == SQUARED_DISTANCE
    ? asmcore::KeyPointDistance::Squared
    : asmcore::KeyPointDistance::Euclidean;
  options.PlaneNeighbors = this->PlaneNeighbors;
  // Small clouds on the calling thread (MinimumPointsForThreads).
  const bool threads = static_cast<vtkIdType>(orig.Ids.size()) >=
    asmvtk::MinimumPointsForThreads(this->MinimumPointsForThreads);
  // The simplified cloud's normals sign the curvature: only a 3-component
  // array with a tuple for every point.
  const vtkIdType n = simplified->GetNumberOfPoints();
  vtkDataArray* inNormals = simplified->GetPointData()->GetNormals();
  const bool useNormals =
    inNormals && inNormals->GetNumberOfComponents() == 3 && inNormals->GetNumberOfTuples() >= n;
  if (this->GenerateCurvature && inNormals && !useNormals)
  {
    vtkWarningMacro(<< "The simplified cloud's normals (" << inNormals->GetNumberOfTuples()
                    << " tuples of " << inNormals->GetNumberOfComponents()
                    << " components) do not give each of its " << n
                    << " points a normal: they do not sign the curvature.");
  }
  asmvtk::DistributedComparison shared;
  if (distributed)
  {
    // Figures of the whole clouds (vtkASMDistributedMetrics.h). (Without
    // usable normals on a process that holds simplified points, no
    // process uses normals: CompareDistributed agrees on it.)
    std::vector<double> normals;
    if (useNormals)
    {
      for (Index id : simp.Ids)
      {
        const double* v = inNormals->GetTuple3(id);
        normals.insert(normals.end(), v, v + 3);
      }
    }
    shared = asmvtk::CompareDistributed(comm, orig.Xyz, orig.Ids, simp.Xyz, simp.Ids,
      useNormals ? normals.data() : nullptr, options,
      this->GenerateCurvature ? this->CurvatureNeighbors : 0,
      asmvtk::SMPExecution(this, 0.0, 0.8, threads));
  }
  const asmcore::Neighbors originalTree = distributed
    ? asmcore::Neighbors()
    : asmcore::Neighbors(orig.Xyz, orig.Ids, asmvtk::SMPExecution(this, 0.0, 0.0, threads));
  const asmcore::Comparison result = distributed
    ? shared.Figures
    : asmcore::CompareClouds(orig.Xyz, orig.Ids, originalTree, simp.Xyz, simp.Ids, options,
        asmvtk::SMPExecution(this, 0.0, 0.8, threads));
  if (result.Aborted)
  {
    vtkWarningMacro(<< "Aborted: the output is empty.");
    return 1;
  }

  // The simplified cloud, one vertex per point, its arrays, and the errors.
  output->SetPoints(simplified->GetPoints());
  output->SetVerts(asmvtk::VertexCells(n, threads));
  vtkPointData* pd = output->GetPointData();
  pd->PassData(simplified->GetPointData());
  auto error = asmvtk::NewArray<vtkDoubleArray>("Error", 1, n);
  error->Fill(std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < simp.Ids.size(); ++i)
  {
    error->SetValue(simp.Ids[i], result.SimplifiedError[i]);
  }
  pd->AddArray(error);

  if (this->GenerateCurvature && distributed)
  {
    auto mean = asmvtk::NewArray<vtkDoubleArray>("MeanCurvature", 1, n);
    auto variation = asmvtk::NewArray<vtkDoubleArray>("NeighborhoodSurfaceVariation", 1, n);
    mean->Fill(std::numeric_limits<double>::quiet_NaN());
    variation->Fill(std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < simp.Ids.size(); ++i)
    {
      mean->SetValue(simp.Ids[i], shared.Curvature[i].MeanCurvature);
      variation->SetValue(simp.Ids[i], shared.Curvature[i].SurfaceVariation);
    }
    pd->AddArray(mean);
    pd->AddArray(variation);
  }
  else if (this->GenerateCurvature)
  {
    // Estimated at the finite simplified points, signed by their normals.
    std::vector<double> queries, normals;
    for (Index id : simp.Ids)
    {
      queries.insert(queries.end(), simp.Xyz + 3 * id, simp.Xyz + 3 * id + 3);
      if (useNormals)
      {
        const double* v = inNormals->GetTuple3(id);
        normals.insert(normals.end(), v, v + 3);
      }
    }
    vtkNew<vtkPointData> finite;
    if (!asmvtk::AddCurvatureArrays(finite, orig.Xyz, orig.Ids, originalTree, queries.data(),
          static_cast<vtkIdType>(simp.Ids.size()), useNormals ? normals.data() : nullptr,
          this->CurvatureNeighbors, asmvtk::SMPExecution(this, 0.8, 0.95, threads)))
    {
      vtkWarningMacro(<< "Aborted: the output is empty.");
      output->Initialize();
      return 1;
    }
    for (int a = 0; a < finite->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* compact = finite->GetArray(a);
      auto full = asmvtk::NewArray<vtkDoubleArray>(compact->GetName(), 1, n);
      full->Fill(std::numeric_limits<double>::quiet_NaN());
      for (std::size_t i = 0; i < simp.Ids.size(); ++i)
      {
        full->SetValue(simp.Ids[i], compact->GetTuple1(static_cast<vtkIdType>(i)));
      }
      pd->AddArray(full);
    }
  }

  // The figures: field data of the output (on every process), and a one-row
  // table. A distributed run's figures are those of the whole clouds, the
  // same on every process: as ParaView's global reductions do (e.g.
  // vtkIntegrateAttributes), process 0 alone outputs them, so that the
  // table gathered from the processes (spreadsheet view, SaveData) has one
  // row; the other processes' tables have the same columns and no row.
  const vtkIdType rows = !distributed || comm.Rank() == 0 ? 1 : 0;
  // Eq. 1 and 2 over no key point (a flat original, or one too sparse for
  // its cells) are undefined, not a perfect 0; so are the relative figures
  // of an original at one position (a diagonal of 0).
  const double undefined = std::numeric_limits<double>::quiet_NaN();
  const bool noKeys = result.OriginalKeyPoints == 0;
  const double akpe = noKeys ? undefined : result.AKPE;
  const double mkpe = noKeys ? undefined : result.MKPE;
  if (noKeys)
  {
    if (rows > 0)
    {
      vtkWarningMacro("The original cloud has no key point (flat, or too sparse for the grid's "
                      "cells): AKPE and MKPE are undefined (NaN).");
    }
  }
  const double diagonal = result.Diagonal > 0.0 ? result.Diagonal : undefined;
  const double keyScale =
    this->DistanceMeasure == SQUARED_DISTANCE ? diagonal * diagonal : diagonal;
  const std::vector<std::pair<const char*, double>> figures = {
    { "NumberOfOriginalPoints",
      static_cast<double>(
        distributed ? shared.OriginalPoints : static_cast<Index>(orig.Ids.size())) },
    { "NumberOfSimplifiedPoints",
      static_cast<double>(
        distributed ? shared.SimplifiedPoints : static_cast<Index>(simp.Ids.size())) },
    { "CellSize", result.CellSize },
    { "NumberOfOriginalKeyPoints", static_cast<double>(result.OriginalKeyPoints) },
    { "NumberOfSimplifiedKeyPoints", static_cast<double>(result.SimplifiedKeyPoints) },
    { "AKPE", akpe },
    { "MKPE", mkpe },
    { "AKPERelative", akpe / keyScale },
    { "MKPERelative", mkpe / keyScale },
    { "HausdorffDistance", result.Hausdorff },
    { "HausdorffDistanceRelative", result.Hausdorff / diagonal },
    { "MeanDistanceOriginalToSimplified", result.OriginalToSimplified.Mean },
    { "RMSDistanceOriginalToSimplified", result.OriginalToSimplified.RMS },
    { "MaxDistanceOriginalToSimplified", result.OriginalToSimplified.Max },
    { "MeanDistanceSimplifiedToOriginal", result.SimplifiedToOriginal.Mean },
    { "RMSDistanceSimplifiedToOriginal", result.SimplifiedToOriginal.RMS },
    { "MaxDistanceSimplifiedToOriginal", result.SimplifiedToOriginal.Max },
    { "PointToPlaneMean", result.PointToPlane.Mean },
    { "PointToPlaneRMS", result.PointToPlane.RMS },
    { "PointToPlaneMax", result.PointToPlane.Max },
    { "PointToPlaneMeanRelative", result.PointToPlane.Mean / diagonal },
    { "BoundingBoxDiagonal", result.Diagonal },
  };
  vtkFieldData* fd = output->GetFieldData();
  fd->PassData(simplified->GetFieldData());
  for (const auto& figure : figures)
  {
    asmvtk::AddFieldValue(fd, figure.first, figure.second);
    auto column = asmvtk::NewArray<vtkDoubleArray>(figure.first, 1, rows);
    if (rows > 0)
    {
      column->SetValue(0, figure.second);
    }
    table->AddColumn(column);
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkKeyPointError::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Alpha: " << this->Alpha << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
  os << indent << "SamplesPerCell: " << this->SamplesPerCell << "\n";
  os << indent << "DistanceMeasure: "
     << (this->DistanceMeasure == EUCLIDEAN_DISTANCE ? "Euclidean" : "Squared") << "\n";
  os << indent << "PlaneNeighbors: " << this->PlaneNeighbors << "\n";
  os << indent << "GenerateCurvature: " << this->GenerateCurvature << "\n";
  os << indent << "CurvatureNeighbors: " << this->CurvatureNeighbors << "\n";
  os << indent << "MinimumPointsForThreads: "
     << asmvtk::DescribeMinimumPointsForThreads(this->MinimumPointsForThreads) << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
