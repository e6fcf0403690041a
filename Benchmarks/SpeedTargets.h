// SPDX-License-Identifier: BSD-3-Clause
// The speed benchmark's measured rows and issue 8's targets checked on them
// (asm_speed_benchmark's targets block).
#ifndef asm_SpeedTargets_h
#define asm_SpeedTargets_h

#include "vtkType.h"

#include <cmath>
#include <string>
#include <vector>

namespace asmbench
{
/// One measured row, kept for the targets block.
struct Record
{
  std::string Input;
  vtkIdType N = 0;
  double Fraction = 0.0;
  std::string Method;
  bool IsASM = false;
  int Threads = 1;
  double Median = NAN;
  double Memory = NAN; ///< bytes per input point beyond input and output (first thread count)
};

/// The row of `method` on `input` at `fraction` with `threads` threads, or null.
const Record* Find(const std::vector<Record>& records, const std::string& input, double fraction,
  const std::string& method, int threads);

/// Prints issue 8's targets as PASS / FAIL / n/a (the run lacks the data),
/// each with the figures it was decided on: "ASM paper" >= 20 and "ASM
/// default" >= 10 M input pt/s at 5 % with 1 thread on bumps-4M and -14M,
/// >= 1.7x from 1 to 2 threads there, both modes faster than vtkVoxelGrid
/// on every row, time per point within 25 % over the synthetic sizes, and
/// <= 48 B/pt beyond input and output.
void PrintTargets(const std::vector<Record>& records, const std::vector<int>& threads);
} // namespace asmbench

#endif
