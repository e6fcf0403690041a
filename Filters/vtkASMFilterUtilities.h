// SPDX-License-Identifier: BSD-3-Clause
/**
 * Private helpers shared by the ASM filters (not wrapped, not installed):
 * coordinates as doubles, the vtkSMPTools execution of the core, field
 * values, and the curvature arrays.
 */
#ifndef vtkASMFilterUtilities_h
#define vtkASMFilterUtilities_h

#include "Core/Common.h"
#include "Core/Curvature.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h> // madvise
#endif

namespace asmvtk
{
/// Whether loops asked to run on threads should go through vtkSMPTools:
/// only when it has more than one thread. With one (the Sequential backend,
/// or vtkSMPTools::Initialize(1)), VTK 9.2's STDThread backend would still
/// start a thread for every loop while the calling thread waits (about 0.1
/// ms each: 10-15 % of a run on 100 k points); the calling thread runs the
/// loop itself instead. The output is the same either way.
inline bool UseThreads(bool threads)
{
  return threads && vtkSMPTools::GetEstimatedNumberOfThreads() > 1;
}

/// vtkASMSimplify::MinimumPointsForThreads as it applies: a value >= 0 as
/// it is; automatic (< 0): 50000 with the STDThread backend, whose loops in
/// VTK 9.1-9.2 start their threads anew (a second thread does not pay below
/// about 50 k points on 2 cores), 0 with the backends that keep their
/// threads between loops (TBB, OpenMP).
inline vtkIdType MinimumPointsForThreads(vtkIdType value)
{
  if (value >= 0)
  {
    return value;
  }
  return std::string(vtkSMPTools::GetBackend()) == "STDThread" ? 50000 : 0;
}

/// A MinimumPointsForThreads value and what it means here, for PrintSelf:
/// "-1 (automatic: 50000 with the STDThread backend)".
inline std::string DescribeMinimumPointsForThreads(vtkIdType value)
{
  return std::to_string(value) + (value < 0 ? " (automatic: " : " (") +
    std::to_string(MinimumPointsForThreads(value)) + " with the " + vtkSMPTools::GetBackend() +
    " backend)";
}

/// vtkSMPTools::For(begin, end, body), or body(begin, end) on the calling
/// thread when `threads` is false (small clouds: see
/// vtkASMSimplify::MinimumPointsForThreads) or vtkSMPTools has one thread.
template <typename Body>
void For(bool threads, vtkIdType begin, vtkIdType end, Body&& body)
{
  if (UseThreads(threads))
  {
    vtkSMPTools::For(begin, end, body);
  }
  else if (begin < end)
  {
    body(begin, end);
  }
}

/// The coordinates of `points` as N x 3 doubles: the array itself when it
/// already is one, else a copy in `copy`.
inline const double* CoordinatesAsDoubles(vtkPoints* points, std::vector<double>& copy)
{
  vtkDataArray* data = points->GetData();
  if (auto* doubles = vtkDoubleArray::SafeDownCast(data))
  {
    return doubles->GetPointer(0);
  }
  copy.resize(static_cast<std::size_t>(3 * points->GetNumberOfPoints()));
  const auto range = vtk::DataArrayValueRange<3>(data);
  std::copy(range.begin(), range.end(), copy.begin());
  return copy.data();
}

/// The ghost flags of `data` that the filters read (vtkGhostType: an
/// unsigned char array with a value for each point), or null: another
/// array of that name is an array as any other.
inline vtkUnsignedCharArray* GhostFlags(vtkPointSet* data)
{
  auto* ghosts = vtkUnsignedCharArray::SafeDownCast(
    data->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
  return ghosts && ghosts->GetNumberOfTuples() >= data->GetNumberOfPoints() ? ghosts : nullptr;
}

/// The relative precision of the coordinates of `points` (the key point
/// rule's CoordinateEpsilon): a double's for double arrays, unless every
/// coordinate would fit in a float unchanged (doubles made from floats, as an
/// upstream filter that converts its points gives them); a float's for float
/// and integer arrays. So the same values give the same key points whatever
/// array holds them. Reads doubles until the first that a float cannot hold.
inline double CoordinateEpsilon(vtkPoints* points)
{
  auto* doubles = points ? vtkDoubleArray::FastDownCast(points->GetData()) : nullptr;
  if (points && points->GetDataType() == VTK_DOUBLE)
  {
    if (!doubles)
    {
      return std::numeric_limits<double>::epsilon(); // (another layout: not read)
    }
    const double* v = doubles->GetPointer(0);
    const double* end = v + 3 * doubles->GetNumberOfTuples();
    const bool floats = std::all_of(v, end, [](double x) {
      return static_cast<double>(static_cast<float>(x)) == x || x != x; // NOLINT (NaN)
    });
    if (!floats)
    {
      return std::numeric_limits<double>::epsilon();
    }
  }
  return std::numeric_limits<float>::epsilon();
}

/// Asks the kernel to back [data, data + bytes) with huge pages where it can
/// (Linux; a hint, no effect elsewhere). For large arrays read in random
/// order, e.g. the coordinates gathered cell by cell: far fewer TLB misses
/// and page faults. Call before the memory is first written.
inline void AdviseHugePages(void* data, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::uintptr_t huge = std::uintptr_t(1) << 21;
  if (bytes < 4 * huge)
  {
    return;
  }
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + huge - 1) & ~(huge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(huge - 1);
  if (end > begin)
  {
    madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
#else
  (void)data;
  (void)bytes;
#endif
}

/// The coordinates of `points`, and in `ids` the ids of the points whose
/// coordinates are finite, ascending: IdView::Identity(N) when all are (no
/// list), else a view of `idList`, which holds them. Doubles are used in
/// place, and so are floats with `floatsInPlace` (the core widens them as it
/// reads them); other types are converted into `copy` as doubles (not
/// zero-filled first). `largest`: the largest |coordinate| of the finite
/// points (0 for none; see asmcore::CoordinateRange), found in the same
/// pass. Both passes run in parallel (vtkSMPTools) over fixed blocks: the
/// result does not depend on the thread count.
inline asmcore::Coordinates PrepareCoordinates(vtkPoints* points, std::unique_ptr<double[]>& copy,
  asmcore::PointIds& idList, asmcore::IdView& ids, double& largest, bool threads,
  bool floatsInPlace = false)
{
  using asmcore::Index;
  vtkDataArray* data = points->GetData();
  const Index n = points->GetNumberOfPoints();
  asmcore::Coordinates xyz;
  auto* floats = vtkFloatArray::SafeDownCast(data);
  if (auto* doubles = vtkDoubleArray::SafeDownCast(data))
  {
    xyz = doubles->GetPointer(0);
  }
  else if (floats && floatsInPlace)
  {
    xyz = floats->GetPointer(0);
    floats = nullptr; // (nothing to convert)
  }
  else
  {
    copy.reset(new double[static_cast<std::size_t>(3 * n)]);
    AdviseHugePages(copy.get(), static_cast<std::size_t>(3 * n) * sizeof(double));
    xyz = copy.get();
  }
  const Index blockSize = Index(1) << 15;
  const Index blocks = (n + blockSize - 1) / blockSize;
  std::vector<Index> finite(static_cast<std::size_t>(blocks) + 1, 0);
  std::vector<double> blockLargest(static_cast<std::size_t>(blocks), 0.0);
  For(threads, 0, blocks, [&](vtkIdType first, vtkIdType last) {
    for (Index k = first; k < last; ++k)
    {
      const Index begin = k * blockSize;
      const Index end = std::min(n, begin + blockSize);
      double* out = copy ? copy.get() : nullptr;
      if (floats)
      {
        const float* in = floats->GetPointer(0);
        for (Index i = 3 * begin; i < 3 * end; ++i)
        {
          out[i] = static_cast<double>(in[i]);
        }
      }
      else if (out)
      {
        // (A value range: its bounds count values, three per point.)
        const auto range = vtk::DataArrayValueRange<3>(data, 3 * begin, 3 * end);
        std::copy(range.begin(), range.end(), out + 3 * begin);
      }
      Index count = 0;
      double blockMax = 0.0;
      for (Index i = begin; i < end; ++i)
      {
        double p[3];
        xyz.Get(i, p);
        const bool isFinite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
        count += isFinite ? 1 : 0;
        const double m = std::max({ std::abs(p[0]), std::abs(p[1]), std::abs(p[2]) });
        blockMax = isFinite && m > blockMax ? m : blockMax;
      }
      finite[k + 1] = count;
      blockLargest[k] = blockMax;
    }
  });
  largest = 0.0;
  for (Index k = 0; k < blocks; ++k)
  {
    finite[k + 1] += finite[k];
    largest = std::max(largest, blockLargest[k]);
  }
  idList.clear();
  if (finite[blocks] == n)
  {
    ids = asmcore::IdView::Identity(static_cast<std::size_t>(n));
    return xyz;
  }
  idList.resize(static_cast<std::size_t>(finite[blocks]));
  ids = idList;
  For(threads, 0, blocks, [&](vtkIdType first, vtkIdType last) {
    for (Index k = first; k < last; ++k)
    {
      const Index begin = k * blockSize;
      const Index end = std::min(n, begin + blockSize);
      Index* out = idList.data() + finite[k];
      if (finite[k + 1] - finite[k] == end - begin)
      {
        for (Index i = begin; i < end; ++i)
        {
          *out++ = i;
        }
        continue;
      }
      for (Index i = begin; i < end; ++i)
      {
        double p[3];
        xyz.Get(i, p);
        if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
        {
          *out++ = i;
        }
      }
    }
  });
  return xyz;
}

/// The error for a cloud whose largest |coordinate| is out of
/// asmcore::CoordinateRange (`what`: "The input", "The original cloud"...).
inline std::string OutOfRangeMessage(const char* what, double largest)
{
  std::ostringstream text;
  text << what << "'s coordinates reach " << largest
       << ", beyond what their squared distances can hold in double precision (the largest "
          "|coordinate| must be 0 or within [1e-100, 1e100]): scale the cloud into that range "
          "(e.g. with vtkTransformFilter) and the results back. The output is empty.";
  return text.str();
}

/// The 3-component array `data` as N x 3 doubles in `copy` (float and double
/// arrays copied directly, in parallel; others through the generic API).
inline const double* TuplesAsDoubles(vtkDataArray* data, std::unique_ptr<double[]>& copy)
{
  const vtkIdType n = data->GetNumberOfTuples();
  copy.reset(new double[static_cast<std::size_t>(3 * n)]);
  double* out = copy.get();
  auto* floats = vtkFloatArray::SafeDownCast(data);
  auto* doubles = vtkDoubleArray::SafeDownCast(data);
  For(true, 0, n, [&](vtkIdType begin, vtkIdType end) {
    if (floats)
    {
      const float* in = floats->GetPointer(0);
      std::copy(in + 3 * begin, in + 3 * end, out + 3 * begin);
    }
    else if (doubles)
    {
      const double* in = doubles->GetPointer(0);
      std::copy(in + 3 * begin, in + 3 * end, out + 3 * begin);
    }
    else
    {
      // (A value range: its bounds count values, three per tuple.)
      const auto range = vtk::DataArrayValueRange<3>(data, 3 * begin, 3 * end);
      std::copy(range.begin(), range.end(), out + 3 * begin);
    }
  });
  return out;
}

/// Runs the core's loops with vtkSMPTools (on the calling thread alone when
/// `threads` is false or vtkSMPTools has one thread: UseThreads); progress
/// goes to `algorithm`, scaled into [from, to], and its AbortExecute flag
/// aborts.
inline asmcore::Execution SMPExecution(
  vtkAlgorithm* algorithm, double from, double to, bool threads)
{
  asmcore::Execution execution;
  if (UseThreads(threads))
  {
    execution.For = [](asmcore::Index begin, asmcore::Index end,
                      const std::function<void(asmcore::Index, asmcore::Index)>& body) {
      vtkSMPTools::For(begin, end, [&body](vtkIdType b, vtkIdType e) { body(b, e); });
    };
  }
  execution.Progress = [algorithm, from, to](double fraction) {
    algorithm->UpdateProgress(from + (to - from) * fraction);
    return algorithm->GetAbortExecute() != 0;
  };
  return execution;
}

/// A new array of `tuples` x `components`.
template <typename ArrayT>
vtkSmartPointer<ArrayT> NewArray(const char* name, int components, vtkIdType tuples)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

/// One vertex cell per point, for n points: what ParaView renders.
inline vtkSmartPointer<vtkCellArray> VertexCells(vtkIdType n, bool threads)
{
  auto offsets = NewArray<vtkIdTypeArray>(nullptr, 1, n + 1);
  auto connectivity = NewArray<vtkIdTypeArray>(nullptr, 1, n);
  vtkIdType* offset = offsets->GetPointer(0);
  vtkIdType* point = connectivity->GetPointer(0);
  For(threads, 0, n, [offset, point](vtkIdType first, vtkIdType last) {
    for (vtkIdType i = first; i < last; ++i)
    {
      offset[i] = i;
      point[i] = i;
    }
  });
  offset[n] = n;
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  verts->SetData(offsets, connectivity);
  return verts;
}

/// Adds (or replaces) a one-value double array in `fd`.
inline void AddFieldValue(vtkFieldData* fd, const char* name, double value)
{
  auto array = NewArray<vtkDoubleArray>(name, 1, 1);
  array->SetValue(0, value);
  fd->AddArray(array);
}

/// Adds "MeanCurvature" (1/length, positive where the surface bends away
/// from the normal) and "NeighborhoodSurfaceVariation" to `pd`, estimated at
/// the positions `queries` (n x 3) from the k nearest points of the original
/// cloud (xyz, ids, tree), signs following `normals` (n x 3, may be null).
/// Returns false if aborted.
inline bool AddCurvatureArrays(vtkPointData* pd, asmcore::Coordinates xyz, asmcore::IdView ids,
  const asmcore::Neighbors& tree, const double* queries, vtkIdType n, const double* normals, int k,
  const asmcore::Execution& execution)
{
  const auto estimates =
    asmcore::EstimateCurvature(xyz, ids, tree, queries, n, normals, k, execution);
  if (static_cast<vtkIdType>(estimates.size()) != n)
  {
    return false;
  }
  auto mean = NewArray<vtkDoubleArray>("MeanCurvature", 1, n);
  auto variation = NewArray<vtkDoubleArray>("NeighborhoodSurfaceVariation", 1, n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    mean->SetValue(i, estimates[i].MeanCurvature);
    variation->SetValue(i, estimates[i].SurfaceVariation);
  }
  pd->AddArray(mean);
  pd->AddArray(variation);
  return true;
}
} // namespace asmvtk

#endif
