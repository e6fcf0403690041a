// SPDX-License-Identifier: BSD-3-Clause
// VTK-side helpers shared by the filter tests.
#ifndef asm_FilterHelpers_h
#define asm_FilterHelpers_h

#include "FeatureShapes.h"
#include "TestHelpers.h"

#include "vtkASMSimplify.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMP.h" // VTK_SMP_ENABLE_*: the backends this VTK was built with
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace asmtest
{
inline vtkSmartPointer<vtkPolyData> ReadPLY(const std::string& name)
{
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(DataFile(name).c_str());
  reader->Update();
  vtkSmartPointer<vtkPolyData> data = reader->GetOutput();
  return data;
}

inline vtkSmartPointer<vtkPolyData> ToPolyData(const Cloud& c, int type = VTK_DOUBLE)
{
  vtkNew<vtkPoints> points;
  points->SetDataType(type);
  points->SetNumberOfPoints(static_cast<vtkIdType>(c.size() / 3));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    points->SetPoint(i, c.data() + 3 * i);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  return pd;
}

/// The points of `c` rounded to floats, in a double array (as an upstream
/// filter that widens float points gives them). (Through a float array: GCC
/// 12's -O3 may drop a double -> float -> double rounding done in registers.)
inline vtkSmartPointer<vtkPolyData> FloatsInDoubles(const Cloud& c)
{
  vtkSmartPointer<vtkPolyData> floats = ToPolyData(c, VTK_FLOAT);
  vtkNew<vtkPoints> widened;
  widened->SetDataTypeToDouble();
  widened->SetNumberOfPoints(floats->GetNumberOfPoints());
  for (vtkIdType i = 0; i < floats->GetNumberOfPoints(); ++i)
  {
    widened->SetPoint(i, floats->GetPoint(i));
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(widened);
  return pd;
}

/// A box (FeatureShapes.h's Box) turned so that the float rounding of its
/// flat faces is off their planes.
inline Cloud TurnedBox(std::size_t n)
{
  Cloud c = Box(n).Points;
  const Eigen::Matrix3d turn =
    Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  for (std::size_t i = 0; i < c.size(); i += 3)
  {
    Eigen::Map<Eigen::Vector3d>(c.data() + i) = turn * Eigen::Vector3d(c[i], c[i + 1], c[i + 2]);
  }
  return c;
}

/// Asserts that every output point is finite.
inline void ExpectAllFinite(vtkPolyData* out)
{
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    ASSERT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) << i;
  }
}

// Largest | |p - centre| - radius | over the output points (with KeyPoint ==
// 1 only when keysOnly).
inline double SphereDeviation(
  vtkPolyData* out, const double centre[3], double radius, bool keysOnly)
{
  auto* keys = out->GetPointData()->GetArray("KeyPoint");
  double worst = 0.0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    if (keysOnly && keys->GetTuple1(i) != 1.0)
    {
      continue;
    }
    double p[3];
    out->GetPoint(i, p);
    const double r = std::hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]);
    worst = std::max(worst, std::abs(r - radius));
  }
  return worst;
}

/// The same points, in the same order, bit for bit.
inline ::testing::AssertionResult SamePoints(vtkPointSet* a, vtkPointSet* b)
{
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints())
  {
    return ::testing::AssertionFailure()
      << a->GetNumberOfPoints() << " points against " << b->GetNumberOfPoints();
  }
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double pa[3], pb[3];
    a->GetPoint(i, pa);
    b->GetPoint(i, pb);
    for (int c = 0; c < 3; ++c)
    {
      if (pa[c] != pb[c])
      {
        return ::testing::AssertionFailure() << "point " << i << " differs";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

/// One vertex cell per point, cell i holding point i alone (what ParaView
/// renders), and no other cells.
inline ::testing::AssertionResult OneVertexPerPoint(vtkPolyData* out)
{
  const vtkIdType n = out->GetNumberOfPoints();
  if (out->GetNumberOfVerts() != n || out->GetNumberOfCells() != n)
  {
    return ::testing::AssertionFailure() << out->GetNumberOfVerts() << " vertices, "
                                         << out->GetNumberOfCells() << " cells, " << n << " points";
  }
  vtkCellArray* verts = out->GetVerts();
  for (vtkIdType i = 0; i < n; ++i)
  {
    vtkIdType size = 0;
    const vtkIdType* points = nullptr;
    verts->GetCellAtId(i, size, points);
    if (size != 1 || points[0] != i)
    {
      return ::testing::AssertionFailure() << "vertex " << i << " holds " << size << " points";
    }
  }
  return ::testing::AssertionSuccess();
}

inline double FieldValue(vtkDataSet* ds, const char* name)
{
  vtkDataArray* a = ds->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : std::nan("");
}

/// Counts warnings and errors instead of printing them.
class MessageCounter : public vtkCommand
{
public:
  static MessageCounter* New() { return new MessageCounter; }
  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings)++;
    this->LastMessage = callData ? static_cast<const char*>(callData) : "";
  }
  int Warnings = 0;
  int Errors = 0;
  std::string LastMessage; ///< the text of the last warning or error
};

/// A filter whose warnings and errors are counted.
template <typename FilterT>
struct ObservedFilter
{
  vtkNew<FilterT> Filter;
  vtkNew<MessageCounter> Messages;
  ObservedFilter()
  {
    this->Filter->AddObserver(vtkCommand::WarningEvent, this->Messages);
    this->Filter->AddObserver(vtkCommand::ErrorEvent, this->Messages);
  }
};

/// A vtkASMSimplify whose warnings and errors are counted.
struct FilterRun : ObservedFilter<vtkASMSimplify>
{
  vtkPolyData* Execute(vtkDataObject* input)
  {
    this->Filter->SetInputData(input);
    this->Filter->Update();
    return this->Filter->GetOutput();
  }
  void Count(vtkIdType n)
  {
    this->Filter->SetTargetModeToNumberOfOutputPoints();
    this->Filter->SetNumberOfOutputPoints(n);
  }
};

/// Restores vtkSMPTools' backend and thread count when it goes out of scope
/// (a test that picks them leaves the next test what it found).
class SMPScope
{
public:
  SMPScope()
    : Backend(vtkSMPTools::GetBackend())
  {
  }
  ~SMPScope()
  {
    vtkSMPTools::SetBackend(this->Backend.c_str());
    vtkSMPTools::Initialize(0);
  }
  SMPScope(const SMPScope&) = delete;
  SMPScope& operator=(const SMPScope&) = delete;

private:
  std::string Backend;
};

/// The threaded vtkSMPTools backends this VTK was built with: STDThread,
/// and TBB or OpenMP where present (VTK 9.1 of Debian defaults to TBB).
inline std::vector<std::string> ThreadedSMPBackends()
{
  std::vector<std::string> backends;
#if VTK_SMP_ENABLE_STDTHREAD
  backends.emplace_back("STDThread");
#endif
#if VTK_SMP_ENABLE_TBB
  backends.emplace_back("TBB");
#endif
#if VTK_SMP_ENABLE_OPENMP
  backends.emplace_back("OpenMP");
#endif
  return backends;
}

/// One run of a threading test: its backend and thread count ("TBB, 2
/// threads") and what it output, flattened.
struct ThreadingRun
{
  std::string Label;
  std::vector<double> Output;
};

/// Calls run() (returning std::vector<double>) with every threaded backend of
/// this VTK, with 1 and then 2 threads each, for the tests that the output
/// does not depend on the threading; restores the backend and thread count
/// found.
template <class Run>
std::vector<ThreadingRun> RunForEachThreading(Run&& run)
{
  SMPScope restore;
  std::vector<ThreadingRun> runs;
  for (const std::string& backend : ThreadedSMPBackends())
  {
    if (!vtkSMPTools::SetBackend(backend.c_str()))
    {
      ADD_FAILURE() << "vtkSMP.h lists the " << backend << " backend, SetBackend refuses it";
      continue;
    }
    for (int threads : { 1, 2 })
    {
      vtkSMPTools::Initialize(threads);
      runs.push_back(
        { backend + ", " + std::to_string(threads) + (threads == 1 ? " thread" : " threads"),
          run() });
    }
  }
  return runs;
}

/// Two runs or more, the first with some output, and every one's output
/// equal to the first's, bit for bit.
inline ::testing::AssertionResult SameOutputs(const std::vector<ThreadingRun>& runs)
{
  if (runs.size() < 2 || runs[0].Output.empty())
  {
    return ::testing::AssertionFailure() << runs.size() << " runs, nothing to compare";
  }
  for (const ThreadingRun& other : runs)
  {
    if (other.Output != runs[0].Output)
    {
      return ::testing::AssertionFailure() << runs[0].Label << " and " << other.Label << " differ";
    }
  }
  return ::testing::AssertionSuccess();
}
} // namespace asmtest

#endif
