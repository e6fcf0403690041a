// SPDX-License-Identifier: BSD-3-Clause
#include "vtkASMPointDataAggregation.h"

#include "vtkASMFilterUtilities.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

namespace
{
using asmcore::Index;
using asmcore::SimplifyResult;

// Mean of each component over the finite member values, written to dst
// (renormalised for normals). `get(member, component)` reads a value;
// `touch(member)` may start loading a member's values ahead of their turn
// (members are scattered in memory).
// Returns false when the mean of a normal is zero (caller keeps the
// representative's normal).
template <typename Get, typename Touch>
bool ClusterMean(const SimplifyResult& result, const asmcore::Sample& sample, int components,
  bool renormalise, Get&& get, Touch&& touch, double* sum, Index* count)
{
  std::fill(sum, sum + components, 0.0);
  std::fill(count, count + components, Index(0));
  const Index* members = result.Members.data() + sample.MemberBegin;
  // The members that place the sample (its cluster proper), so the values
  // belong to the sample's position.
  const Index core = sample.CoreSize > 0 ? sample.CoreSize : sample.ClusterSize;
  if (core <= 0)
  {
    return false; // an empty cluster: the representative's values
  }
  // Members lie sample after sample: the look-ahead runs into the next
  // samples' members.
  constexpr Index Ahead = 16;
  const Index available = static_cast<Index>(result.Members.size()) - sample.MemberBegin;
  for (Index m = 0; m < core; ++m)
  {
    if (m + Ahead < available)
    {
      touch(members[m + Ahead]);
    }
    const Index id = members[m];
    for (int c = 0; c < components; ++c)
    {
      const double v = get(id, c);
      if (std::isfinite(v))
      {
        sum[c] += v;
        ++count[c];
      }
    }
  }
  double norm = 0.0;
  for (int c = 0; c < components; ++c)
  {
    sum[c] = count[c] > 0 ? sum[c] / static_cast<double>(count[c])
                          : std::numeric_limits<double>::quiet_NaN();
    norm += sum[c] * sum[c];
  }
  if (renormalise)
  {
    norm = std::sqrt(norm);
    if (!(norm > 0.0) || !std::isfinite(norm))
    {
      return false;
    }
    for (int c = 0; c < components; ++c)
    {
      sum[c] /= norm;
    }
  }
  return true;
}

// Floating-point arrays: cluster means. AOS arrays read and write raw memory.
struct MeanWorker
{
  template <typename ArrayT>
  void operator()(ArrayT* in, vtkDataArray* outBase, const SimplifyResult& result, bool renormalise,
    bool parallel) const
  {
    auto* out = static_cast<ArrayT*>(outBase);
    using T = vtk::GetAPIType<ArrayT>;
    const int nc = in->GetNumberOfComponents();
    const auto count = static_cast<vtkIdType>(result.Samples.size());
    auto body = [&](vtkIdType begin, vtkIdType end) {
      std::vector<double> sum(static_cast<std::size_t>(nc));
      std::vector<Index> n(static_cast<std::size_t>(nc));
      const auto inTuples = vtk::DataArrayTupleRange(in);
      auto outTuples = vtk::DataArrayTupleRange(out);
      for (vtkIdType s = begin; s < end; ++s)
      {
        const asmcore::Sample& sample = result.Samples[s];
        auto dst = outTuples[s];
        const bool ok = ClusterMean(
          result, sample, nc, renormalise,
          [&](Index id, int c) { return static_cast<double>(inTuples[id][c]); }, [](Index) {},
          sum.data(), n.data());
        if (!ok)
        {
          const auto src = inTuples[sample.Representative];
          std::copy(src.begin(), src.end(), dst.begin());
          continue;
        }
        for (int c = 0; c < nc; ++c)
        {
          dst[c] = static_cast<T>(sum[c]);
        }
      }
    };
    asmvtk::For(parallel, 0, count, body);
  }

  // The common case, with raw pointers; 1 and 3 components (scalars,
  // vectors, normals) with a compile-time count.
  template <typename T>
  void operator()(vtkAOSDataArrayTemplate<T>* in, vtkDataArray* outBase,
    const SimplifyResult& result, bool renormalise, bool parallel) const
  {
    auto* out = static_cast<vtkAOSDataArrayTemplate<T>*>(outBase);
    switch (in->GetNumberOfComponents())
    {
      case 1:
        MeanAOS<1>(in->GetPointer(0), out->GetPointer(0), 1, result, renormalise, parallel);
        break;
      case 3:
        MeanAOS<3>(in->GetPointer(0), out->GetPointer(0), 3, result, renormalise, parallel);
        break;
      default:
        MeanAOS<0>(in->GetPointer(0), out->GetPointer(0), in->GetNumberOfComponents(), result,
          renormalise, parallel);
    }
  }

  template <int NC, typename T>
  static void MeanAOS(const T* src, T* dst, int dynamicComponents, const SimplifyResult& result,
    bool renormalise, bool parallel)
  {
    const int nc = NC > 0 ? NC : dynamicComponents;
    asmvtk::For(parallel, 0, static_cast<vtkIdType>(result.Samples.size()),
      [&](vtkIdType begin, vtkIdType end) {
        std::vector<double> sum(static_cast<std::size_t>(nc));
        std::vector<Index> n(static_cast<std::size_t>(nc));
        for (vtkIdType s = begin; s < end; ++s)
        {
          const asmcore::Sample& sample = result.Samples[s];
          T* d = dst + s * nc;
          const bool ok = ClusterMean(
            result, sample, nc, renormalise,
            [&](Index id, int c) { return static_cast<double>(src[id * nc + c]); },
            [&](Index id) { asmcore::Prefetch(src + id * nc); }, sum.data(), n.data());
          if (!ok)
          {
            std::copy(src + sample.Representative * nc, src + (sample.Representative + 1) * nc, d);
            continue;
          }
          for (int c = 0; c < nc; ++c)
          {
            d[c] = static_cast<T>(sum[c]);
          }
        }
      });
  }
};

// Any AOS array: the representatives' tuples, copied as bytes.
void CopyRepresentativesAOS(
  vtkDataArray* in, vtkDataArray* out, const std::vector<vtkIdType>& representatives, bool parallel)
{
  const std::size_t bytes = static_cast<std::size_t>(in->GetDataTypeSize()) *
    static_cast<std::size_t>(in->GetNumberOfComponents());
  const auto* src = static_cast<const unsigned char*>(in->GetVoidPointer(0));
  auto* dst = static_cast<unsigned char*>(out->GetVoidPointer(0));
  asmvtk::For(parallel, 0, static_cast<vtkIdType>(representatives.size()),
    [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType s = begin; s < end; ++s)
      {
        std::memcpy(dst + static_cast<std::size_t>(s) * bytes,
          src + static_cast<std::size_t>(representatives[s]) * bytes, bytes);
      }
    });
}

// Whether an array of `pd` is averaged over the clusters (float and double
// data arrays) rather than taken from the representatives; with snapping,
// none. Global and pedigree ids are labels, whatever their type: never
// averaged (VTK's convention: ids are not interpolated).
bool Averaged(vtkPointData* pd, vtkAbstractArray* array, bool snap)
{
  const int type = array->GetDataType();
  return !snap && vtkDataArray::SafeDownCast(array) && (type == VTK_FLOAT || type == VTK_DOUBLE) &&
    array != pd->GetGlobalIds() && array != pd->GetPedigreeIds();
}

// -1, 0 or 1: values a against b, NaN after every number and equal to NaN.
template <typename T>
int CompareValues(T a, T b)
{
  const bool nanA = a != a, nanB = b != b; // NOLINT (NaN test for any T)
  if (nanA || nanB)
  {
    return int(nanA) - int(nanB);
  }
  return a < b ? -1 : (b < a ? 1 : 0);
}

// Whether an input array is carried to the output: a tuple for every point.
bool Carried(vtkAbstractArray* array, Index numberOfPoints)
{
  return array && array->GetNumberOfTuples() >= numberOfPoints &&
    array->GetNumberOfComponents() >= 1;
}

bool IsAOS(vtkAbstractArray* a)
{
  return a->GetArrayType() == vtkAbstractArray::AoSDataArrayTemplate &&
    a->GetDataType() != VTK_BIT && vtkDataArray::SafeDownCast(a) != nullptr;
}
} // namespace

namespace asmvtk
{
int CompareTuples(vtkAbstractArray* array, vtkIdType a, vtkIdType b)
{
  const int nc = array->GetNumberOfComponents();
  auto* data = vtkDataArray::SafeDownCast(array);
  if (data && data->HasStandardMemoryLayout() && data->GetDataType() != VTK_BIT)
  {
    switch (data->GetDataType())
    {
      vtkTemplateMacro(const auto* values = static_cast<const VTK_TT*>(data->GetVoidPointer(0));
                       for (int c = 0; c < nc; ++c) {
                         const int order = CompareValues(values[a * nc + c], values[b * nc + c]);
                         if (order != 0)
                         {
                           return order;
                         }
                       });
    }
    return 0;
  }
  if (data)
  {
    for (int c = 0; c < nc; ++c)
    {
      const int order = CompareValues(data->GetComponent(a, c), data->GetComponent(b, c));
      if (order != 0)
      {
        return order;
      }
    }
    return 0;
  }
  if (auto* strings = vtkStringArray::SafeDownCast(array))
  {
    for (int c = 0; c < nc; ++c)
    {
      const int order = strings->GetValue(a * nc + c).compare(strings->GetValue(b * nc + c));
      if (order != 0)
      {
        return order < 0 ? -1 : 1;
      }
    }
  }
  return 0;
}

int AggregatePointData(vtkPointData* inPD, vtkPointData* outPD, const SimplifyResult& result,
  bool snap, Index numberOfPoints, vtkObject* reporter, bool threads)
{
  const auto count = static_cast<vtkIdType>(result.Samples.size());
  std::vector<vtkIdType> representatives(static_cast<std::size_t>(count));
  for (vtkIdType s = 0; s < count; ++s)
  {
    representatives[s] = result.Samples[s].Representative;
  }
  int dropped = 0;
  for (int i = 0; i < inPD->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* in = inPD->GetAbstractArray(i);
    if (!Carried(in, numberOfPoints))
    {
      vtkWarningWithObjectMacro(
        reporter, << "Point-data array " << (in && in->GetName() ? in->GetName() : "(unnamed)")
                  << " has " << (in ? in->GetNumberOfTuples() : 0) << " tuples for "
                  << numberOfPoints << " points: not carried to the output.");
      ++dropped;
      continue;
    }
    vtkSmartPointer<vtkAbstractArray> out = vtk::TakeSmartPointer(in->NewInstance());
    out->SetName(in->GetName());
    out->SetNumberOfComponents(in->GetNumberOfComponents());
    out->CopyComponentNames(in);
    out->SetNumberOfTuples(count);
    auto* inData = vtkDataArray::SafeDownCast(in);
    auto* outData = vtkDataArray::SafeDownCast(out);
    if (Averaged(inPD, in, snap))
    {
      const bool renormalise = inData == inPD->GetNormals() && in->GetNumberOfComponents() == 3;
      MeanWorker worker;
      using Reals = vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>;
      if (!Reals::Execute(inData, worker, outData, result, renormalise, threads))
      {
        worker(inData, outData, result, renormalise, false); // generic API, one thread
      }
    }
    else if (IsAOS(in) && IsAOS(out))
    {
      CopyRepresentativesAOS(inData, outData, representatives, threads);
    }
    else
    {
      // Bit, string, variant and other array layouts: the generic API, a
      // tuple at a time (VTK 9.2's vtkStringArray::GetTuples(vtkIdList*)
      // takes the ids as value indices: a 2-component array got the wrong
      // strings).
      for (vtkIdType s = 0; s < count; ++s)
      {
        out->SetTuple(s, representatives[s], in);
      }
    }
    const int index = outPD->AddArray(out);
    for (int attribute = 0; attribute < vtkDataSetAttributes::NUM_ATTRIBUTES; ++attribute)
    {
      if (inPD->GetAbstractAttribute(attribute) == in)
      {
        outPD->SetActiveAttribute(index, attribute);
      }
    }
  }
  return dropped;
}

void ChooseAmongDuplicates(vtkPointData* inPD, Index numberOfPoints, SimplifyResult& result,
  bool snap, bool threads, std::vector<std::pair<vtkIdType, Index>>* ties)
{
  const auto& duplicates = result.RepresentativeDuplicates;
  // The arrays carried, all compared; something to do only when one of them
  // is taken from the representatives (with snapping: all of them), or when
  // the ties are asked for.
  std::vector<vtkAbstractArray*> arrays;
  bool copied = false;
  for (int i = 0; i < inPD->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* array = inPD->GetAbstractArray(i);
    if (Carried(array, numberOfPoints))
    {
      copied = copied || !Averaged(inPD, array, snap);
      arrays.push_back(array);
    }
  }
  // Numeric arrays first, then string, variant and bit arrays, each in the
  // order of inPD: the order a distributed run compares them in (the others
  // are read at the representatives after the run, to break the numeric
  // arrays' ties: FetchRepresentativeValues), so both choose alike.
  std::stable_partition(arrays.begin(), arrays.end(), [](vtkAbstractArray* array) {
    return vtkDataArray::SafeDownCast(array) && array->GetDataType() != VTK_BIT;
  });
  if (ties)
  {
    ties->clear();
  }
  if (duplicates.empty() || (!copied && !ties))
  {
    return;
  }
  auto compare = [&arrays](Index a, Index b) {
    for (vtkAbstractArray* array : arrays)
    {
      if (const int order = CompareTuples(array, a, b))
      {
        return order;
      }
    }
    return 0;
  };
  // A group of duplicates holding several samples' representatives is
  // listed once, under its lead (the first of them: ListDuplicatesOnce);
  // every sample of the group chooses over the lead and its list (the lead's
  // own sample may not be in the result: a distributed run's halo sample).
  using Pair = std::pair<Index, Index>;
  const auto sampleCount = static_cast<vtkIdType>(result.Samples.size());
  std::vector<Index> lead(static_cast<std::size_t>(sampleCount));
  std::vector<std::pair<Index, vtkIdType>> sampleOf(static_cast<std::size_t>(sampleCount));
  for (vtkIdType s = 0; s < sampleCount; ++s)
  {
    lead[s] = result.Samples[s].Representative;
    sampleOf[s] = { lead[s], s };
  }
  std::sort(sampleOf.begin(), sampleOf.end());
  for (const Pair& pair : duplicates)
  {
    // (Every sample of that representative: two samples may share one.)
    for (auto it = std::lower_bound(sampleOf.begin(), sampleOf.end(),
           std::make_pair(pair.second, std::numeric_limits<vtkIdType>::min()));
         it != sampleOf.end() && it->first == pair.second; ++it)
    {
      lead[it->second] = pair.first;
    }
  }
  std::mutex tiesMutex;
  asmvtk::For(threads, 0, sampleCount, [&](vtkIdType begin, vtkIdType end) {
    std::vector<std::pair<vtkIdType, Index>> found;
    for (vtkIdType s = begin; s < end; ++s)
    {
      asmcore::Sample& sample = result.Samples[s];
      const Index r = lead[s];
      const auto first = std::lower_bound(
        duplicates.begin(), duplicates.end(), Pair(r, std::numeric_limits<Index>::min()));
      auto last = first;
      while (last != duplicates.end() && last->first == r)
      {
        ++last;
      }
      sample.Representative = r;
      for (auto it = first; it != last; ++it)
      {
        const int order = compare(it->second, sample.Representative);
        if (order < 0 || (order == 0 && it->second < sample.Representative))
        {
          sample.Representative = it->second;
        }
      }
      if (ties)
      {
        // The points at its position with the same values as the one chosen.
        auto tied = [&](Index p) {
          if (p != sample.Representative && compare(p, sample.Representative) == 0)
          {
            found.emplace_back(s, p);
          }
        };
        tied(r);
        for (auto it = first; it != last; ++it)
        {
          tied(it->second);
        }
      }
    }
    if (!found.empty())
    {
      const std::lock_guard<std::mutex> lock(tiesMutex);
      ties->insert(ties->end(), found.begin(), found.end());
    }
  });
  if (ties)
  {
    std::sort(ties->begin(), ties->end());
  }
}
//------------------------------------------------------------------------------
void CopyArrayInformation(vtkPointData* from, vtkPointData* to)
{
  for (int i = 0; i < from->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* in = from->GetAbstractArray(i);
    vtkAbstractArray* out =
      in && in->GetName() && in->HasInformation() ? to->GetAbstractArray(in->GetName()) : nullptr;
    if (!out || out == in)
    {
      continue;
    }
    // The keys without the cached ranges (CopyInformation drops them), added
    // to those `out` has: an array with no keys of its own (an information
    // object is made by a range query) takes nothing away.
    vtkSmartPointer<vtkAbstractArray> keys = vtk::TakeSmartPointer(in->NewInstance());
    keys->CopyInformation(in->GetInformation());
    out->GetInformation()->Append(keys->GetInformation(), 1);
  }
}

} // namespace asmvtk
