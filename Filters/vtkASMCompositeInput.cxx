// SPDX-License-Identifier: BSD-3-Clause
#include "vtkASMCompositeInput.h"

#include "vtkASMFilterUtilities.h"
#include "vtkASMPointDataAggregation.h"

#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArrayRange.h"
#include "vtkDataSetAttributesFieldList.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <set>

namespace asmvtk
{
const char* const LeafPointIdsName = "vtkASMLeafPointIds";

vtkSmartPointer<vtkPolyData> MergeLeaves(vtkCompositeDataSet* input, LeafData what,
  std::vector<std::string>& dropped, std::vector<std::string>* skipped)
{
  struct Leaf
  {
    vtkPointSet* Points;
    unsigned int FlatIndex;
  };
  std::vector<Leaf> leaves;
  vtkIdType total = 0;
  bool floats = true;
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(input->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    vtkDataObject* object = it->GetCurrentDataObject();
    auto* leaf = vtkPointSet::SafeDownCast(object);
    if (leaf && leaf->GetPoints() && leaf->GetNumberOfPoints() > 0)
    {
      leaves.push_back({ leaf, it->GetCurrentFlatIndex() });
      total += leaf->GetNumberOfPoints();
      floats = floats && leaf->GetPoints()->GetDataType() == VTK_FLOAT;
    }
    else if (!leaf && skipped && object)
    {
      auto* data = vtkDataSet::SafeDownCast(object);
      if (!data || data->GetNumberOfPoints() > 0)
      {
        skipped->push_back("block " + std::to_string(it->GetCurrentFlatIndex()) + " (" +
          object->GetClassName() + ")");
      }
    }
  }
  auto merged = vtkSmartPointer<vtkPolyData>::New();
  merged->GetFieldData()->PassData(input->GetFieldData()); // (the composite's own)
  if (leaves.empty())
  {
    return merged;
  }

  vtkNew<vtkPoints> points;
  points->SetDataType(floats ? VTK_FLOAT : VTK_DOUBLE);
  points->SetNumberOfPoints(total);
  vtkDataSetAttributes::FieldList fields(static_cast<int>(leaves.size()));
  std::vector<vtkSmartPointer<vtkPointData>> leafData; // each leaf's arrays that can be merged
  std::set<std::string> names;
  // The ghost flags travel apart from the other arrays: a leaf without them
  // (ghosts are often given only where there are some) has none flagged,
  // where the intersection below would drop every leaf's flags.
  bool anyGhosts = false;
  for (const Leaf& leaf : leaves)
  {
    anyGhosts = anyGhosts || GhostFlags(leaf.Points);
  }
  vtkNew<vtkUnsignedCharArray> ghosts;
  ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
  ghosts->SetNumberOfTuples(anyGhosts ? total : 0);
  vtkIdType at = 0;
  for (std::size_t k = 0; k < leaves.size(); ++k)
  {
    vtkPointSet* leaf = leaves[k].Points;
    vtkDataArray* data = leaf->GetPoints()->GetData();
    auto copyTo = [&](auto* to) {
      // (Raw pointers for the usual arrays; the value range reads any other.)
      if (auto* f = vtkFloatArray::FastDownCast(data))
      {
        std::copy_n(f->GetPointer(0), 3 * f->GetNumberOfTuples(), to);
      }
      else if (auto* d = vtkDoubleArray::FastDownCast(data))
      {
        std::copy_n(d->GetPointer(0), 3 * d->GetNumberOfTuples(), to);
      }
      else
      {
        const auto from = vtk::DataArrayValueRange<3>(data);
        std::copy(from.begin(), from.end(), to);
      }
    };
    if (floats)
    {
      copyTo(static_cast<vtkFloatArray*>(points->GetData())->GetPointer(3 * at));
    }
    else
    {
      copyTo(static_cast<vtkDoubleArray*>(points->GetData())->GetPointer(3 * at));
    }
    if (anyGhosts)
    {
      vtkUnsignedCharArray* flags = GhostFlags(leaf);
      for (vtkIdType i = 0; i < leaf->GetNumberOfPoints(); ++i)
      {
        ghosts->SetValue(at + i, flags ? flags->GetValue(i) : 0);
      }
    }
    at += leaf->GetNumberOfPoints();
    // The leaf's arrays with a tuple for each of its points (a shorter one
    // is left out, as an array that some leaf lacks is).
    vtkPointData* pd = leafData.emplace_back(vtkSmartPointer<vtkPointData>::New());
    pd->ShallowCopy(leaf->GetPointData());
    if (GhostFlags(leaf)) // (merged above; another vtkGhostType is an array as any other)
    {
      pd->RemoveArray(vtkDataSetAttributes::GhostArrayName());
    }
    for (int a = pd->GetNumberOfArrays() - 1; a >= 0; --a)
    {
      if (const char* name = pd->GetArrayName(a))
      {
        names.insert(name);
      }
      if (pd->GetAbstractArray(a)->GetNumberOfTuples() < leaf->GetNumberOfPoints())
      {
        pd->RemoveArray(a);
      }
    }
    if (k == 0)
    {
      fields.InitializeFieldList(pd);
    }
    else
    {
      fields.IntersectFieldList(pd);
    }
  }
  merged->SetPoints(points);
  if (what == LeafData::PointsOnly)
  {
    if (anyGhosts)
    {
      merged->GetPointData()->AddArray(ghosts);
    }
    return merged;
  }

  vtkPointData* out = merged->GetPointData();
  out->CopyGlobalIdsOn(); // (off by default: the leaves' global ids would be dropped)
  out->CopyAllocate(fields, total);
  at = 0;
  for (std::size_t k = 0; k < leaves.size(); ++k)
  {
    const vtkIdType n = leaves[k].Points->GetNumberOfPoints();
    out->CopyData(fields, leafData[k], static_cast<int>(k), at, n, 0);
    at += n;
  }
  if (anyGhosts)
  {
    out->AddArray(ghosts);
  }
  for (std::size_t k = leaves.size(); k-- > 0;) // (the first leaf's keys last: they win)
  {
    CopyArrayInformation(leaves[k].Points->GetPointData(), out);
  }
  for (const std::string& name : names)
  {
    if (!out->GetAbstractArray(name.c_str()))
    {
      dropped.push_back(name);
    }
  }

  if (what == LeafData::ArraysAndOrigins)
  {
    vtkNew<vtkIdTypeArray> block, id;
    block->SetName("vtkOriginalBlockIds");
    id->SetName(LeafPointIdsName);
    block->SetNumberOfTuples(total);
    id->SetNumberOfTuples(total);
    at = 0;
    for (const Leaf& leaf : leaves)
    {
      for (vtkIdType i = 0; i < leaf.Points->GetNumberOfPoints(); ++i, ++at)
      {
        block->SetValue(at, leaf.FlatIndex);
        id->SetValue(at, i);
      }
    }
    out->AddArray(block);
    out->AddArray(id);
  }
  return merged;
}

std::string SkippedLeafWarning(const std::string& leaf, const char* whose)
{
  return "The composite input's " + leaf + whose +
    " is not a point set (vtkPointSet): it is left out.";
}

std::string DroppedArrayWarning(const std::string& name, const char* whose)
{
  return "Point array " + name + whose +
    " is not on every block with points, with a value for each point: it is not passed on.";
}

} // namespace asmvtk
