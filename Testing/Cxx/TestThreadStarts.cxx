// SPDX-License-Identifier: BSD-3-Clause
// Which clouds the filters run on threads of their own (MinimumPointsForThreads),
// observed from outside: the test binary counts the threads the process
// starts. VTK 9.1-9.2's STDThread backend starts its threads anew in every
// parallel loop, so a filter that ignored its threshold would start threads
// on a small cloud. Linux with glibc only (pthread_create is interposed
// here, exported by the link: Testing/Cxx/CMakeLists.txt).
#include "FilterHelpers.h"

#include "vtkASMSimplify.h"
#include "vtkFloatArray.h"
#include "vtkKeyPointError.h"
#include "vtkPointData.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <thread>

#if defined(__linux__) && defined(__GLIBC__)
#include <cerrno>
#include <dlfcn.h>
#include <pthread.h>

namespace
{
std::atomic<long> ThreadStarts{ 0 };
}

// Counts, then starts the thread through the next definition (glibc's, or a
// sanitizer's interceptor).
extern "C" int pthread_create(pthread_t* thread, const pthread_attr_t* attributes,
  void* (*start)(void*), void* argument) noexcept
{
  ThreadStarts.fetch_add(1, std::memory_order_relaxed);
  using Create = int (*)(pthread_t*, const pthread_attr_t*, void* (*)(void*), void*);
  static const auto next = reinterpret_cast<Create>(dlsym(RTLD_NEXT, "pthread_create"));
  // (No next definition, as in a static link: no thread, an error the
  // caller reports, instead of a call through a null pointer.)
  return next ? next(thread, attributes, start, argument) : EAGAIN;
}
#define ASM_COUNTS_THREAD_STARTS 1
#endif

namespace
{
#ifdef ASM_COUNTS_THREAD_STARTS
// The threads `work` starts.
long ThreadsStartedBy(const std::function<void()>& work)
{
  const long before = ThreadStarts.load();
  work();
  return ThreadStarts.load() - before;
}

// Sets STDThread with 2 threads (call it within an asmtest::SMPScope);
// false when this VTK's STDThread keeps its threads between loops (VTK >=
// 9.3), which the count cannot see.
bool StartsThreadsPerLoop()
{
  if (!vtkSMPTools::SetBackend("STDThread"))
  {
    return false;
  }
  vtkSMPTools::Initialize(2);
  auto loop = []() { vtkSMPTools::For(0, 1000, [](vtkIdType, vtkIdType) {}); };
  loop(); // (a pool that is kept starts here)
  return ThreadsStartedBy(loop) > 0;
}
#endif

// A float sphere with a scan's usual point data (normals, RGB colour, an
// intensity), so that the arrays' aggregation is among the loops counted.
vtkSmartPointer<vtkPolyData> SphereCloud(std::size_t n)
{
  vtkSmartPointer<vtkPolyData> cloud = asmtest::ToPolyData(asmtest::Sphere(n, 1.0, 11), VTK_FLOAT);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(cloud->GetNumberOfPoints());
  vtkNew<vtkUnsignedCharArray> colour;
  colour->SetName("RGB");
  colour->SetNumberOfComponents(3);
  colour->SetNumberOfTuples(cloud->GetNumberOfPoints());
  vtkNew<vtkFloatArray> intensity;
  intensity->SetName("Intensity");
  intensity->SetNumberOfTuples(cloud->GetNumberOfPoints());
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    double p[3];
    cloud->GetPoint(i, p); // on the unit sphere: its own normal
    normals->SetTuple(i, p);
    colour->SetTuple3(i, i % 256, (3 * i) % 256, (7 * i) % 256);
    intensity->SetValue(i, static_cast<float>(p[2]));
  }
  cloud->GetPointData()->SetNormals(normals);
  cloud->GetPointData()->SetScalars(colour);
  cloud->GetPointData()->AddArray(intensity);
  return cloud;
}
} // namespace

// The interposition itself: a thread started here is counted.
TEST(ThreadStarts, CountsTheThreadsThisProcessStarts)
{
#ifdef ASM_COUNTS_THREAD_STARTS
  EXPECT_EQ(ThreadsStartedBy([]() { std::thread([]() {}).join(); }), 1);
  EXPECT_EQ(ThreadsStartedBy([]() {}), 0);
#else
  GTEST_SKIP() << "counted on Linux with glibc only";
#endif
}

// vtkASMSimplify, both modes: below the automatic threshold (50000 points
// with STDThread) no thread is started; with the threshold at 0, or above
// it, the loops run on vtkSMPTools' threads.
TEST(ThreadStarts, SimplifyStartsThreadsOnlyFromTheThreshold)
{
#ifdef ASM_COUNTS_THREAD_STARTS
  asmtest::SMPScope restore;
  if (!StartsThreadsPerLoop())
  {
    GTEST_SKIP() << "this VTK's STDThread keeps its threads: starts cannot be counted";
  }
  const vtkSmartPointer<vtkPolyData> small = SphereCloud(20000);
  const vtkSmartPointer<vtkPolyData> large = SphereCloud(60000);
  for (int mode : { vtkASMSimplify::PAPER, vtkASMSimplify::FEATURE_PRESERVING })
  {
    auto startsFor = [mode](vtkPolyData* input, vtkIdType minimum) {
      vtkNew<vtkASMSimplify> filter;
      filter->SetMode(mode);
      filter->SetOutputFraction(0.05);
      filter->SetMinimumPointsForThreads(minimum);
      filter->SetInputData(input);
      const long starts = ThreadsStartedBy([&]() { filter->Update(); });
      EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), input->GetNumberOfPoints() / 20);
      EXPECT_TRUE(filter->GetOutput()->GetPointData()->GetArray("Intensity")); // carried
      EXPECT_TRUE(filter->GetOutput()->GetPointData()->GetArray("MeanCurvature"));
      return starts;
    };
    EXPECT_EQ(startsFor(small, -1), 0) << "mode " << mode << ", 20000 points, automatic";
    EXPECT_EQ(startsFor(large, 60001), 0) << "mode " << mode << ", 60000 points, threshold 60001";
    EXPECT_GT(startsFor(small, 0), 0) << "mode " << mode << ", 20000 points, threshold 0";
    EXPECT_GT(startsFor(large, -1), 0) << "mode " << mode << ", 60000 points, automatic";
  }
#else
  GTEST_SKIP() << "counted on Linux with glibc only";
#endif
}

// vtkKeyPointError follows the same rule, on the original cloud's size.
TEST(ThreadStarts, KeyPointErrorStartsThreadsOnlyFromTheThreshold)
{
#ifdef ASM_COUNTS_THREAD_STARTS
  asmtest::SMPScope restore;
  if (!StartsThreadsPerLoop())
  {
    GTEST_SKIP() << "this VTK's STDThread keeps its threads: starts cannot be counted";
  }
  auto startsFor = [](std::size_t n, vtkIdType minimum) {
    const vtkSmartPointer<vtkPolyData> original = SphereCloud(n);
    vtkNew<vtkASMSimplify> simplify;
    simplify->SetOutputFraction(0.05);
    simplify->SetMinimumPointsForThreads(n + 1); // its own threads are not counted here
    simplify->SetInputData(original);
    simplify->Update();
    vtkNew<vtkKeyPointError> error;
    error->SetMinimumPointsForThreads(minimum);
    error->SetInputData(original);
    error->SetSimplifiedData(simplify->GetOutput());
    const long starts = ThreadsStartedBy([&]() { error->Update(); });
    auto* figures = vtkTable::SafeDownCast(error->GetOutputDataObject(1));
    EXPECT_TRUE(figures && figures->GetNumberOfRows() > 0);
    return starts;
  };
  EXPECT_EQ(startsFor(20000, -1), 0) << "20000 points, automatic";
  EXPECT_GT(startsFor(20000, 0), 0) << "20000 points, threshold 0";
  EXPECT_GT(startsFor(60000, -1), 0) << "60000 points, automatic";
#else
  GTEST_SKIP() << "counted on Linux with glibc only";
#endif
}
