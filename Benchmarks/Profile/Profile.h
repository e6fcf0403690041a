// SPDX-License-Identifier: BSD-3-Clause
/**
 * asm_profile's parts (see asm_profile.cxx): the clocks and the timings of
 * --stages and --floor (ProfileStages.cxx) and --loops (ProfileLoops.cxx).
 */
#ifndef asm_profile_Profile_h
#define asm_profile_Profile_h

#include "Core/Common.h"
#include "vtkASMFilterUtilities.h"

#include "vtkPolyData.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

class vtkASMSimplify;

namespace asmprofile
{
/// Wall-clock time, in seconds.
inline double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU time of the whole process (all threads): robust to a loaded machine.
inline double Cpu()
{
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/// The median of `v` (NaN when empty).
inline double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return std::nan("");
  }
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// An input's coordinates and finite ids as vtkASMSimplify reads them
/// (asmvtk::PrepareCoordinates, with its two switches).
struct InputCoordinates
{
  std::unique_ptr<double[]> Copy;
  asmcore::PointIds IdList;
  asmcore::IdView Ids;
  asmcore::Coordinates Xyz;
  double Largest = 0.0; ///< the largest |coordinate|
  explicit InputCoordinates(vtkPolyData* input, bool threads = true, bool floatsInPlace = false)
  {
    this->Xyz = asmvtk::PrepareCoordinates(input->GetPoints(), this->Copy, this->IdList, this->Ids,
      this->Largest, threads, floatsInPlace);
  }
};

/// The core's stages one by one, one thread (mirrors asmcore::Simplify),
/// then the curvature's parts (--stages).
void TimeStages(vtkPolyData* input, double fraction, int mode);

/// The floor of a grid simplifier with a target count (--floor).
void TimeFloor(vtkPolyData* input, double fraction);

/// asmcore::Simplify's parallel loops by call site with each thread count
/// (--loops); `settings` applies --set to a filter (false: rejected).
void TimeLoops(vtkPolyData* input, double fraction, int mode, int runs,
  const std::vector<long>& threadCounts, const std::function<bool(vtkASMSimplify*)>& settings);
} // namespace asmprofile

#endif
