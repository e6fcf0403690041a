// SPDX-License-Identifier: BSD-3-Clause
// VTK-side helpers shared by the filter tests.
#ifndef asm_FilterHelpers_h
#define asm_FilterHelpers_h

#include "TestHelpers.h"

#include "vtkASMSimplify.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

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
  void Execute(vtkObject*, unsigned long event, void*) override
  {
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings)++;
  }
  int Warnings = 0;
  int Errors = 0;
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
} // namespace asmtest

#endif
