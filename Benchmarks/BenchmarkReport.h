// SPDX-License-Identifier: BSD-3-Clause
/**
 * Small helpers shared by the benchmark programs: a text / Markdown table,
 * number formatting, medians, comma-separated option lists, and the peak
 * memory of one run measured in a forked child.
 */
#ifndef asm_BenchmarkReport_h
#define asm_BenchmarkReport_h

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace asmbench
{
/// Rows of cells printed as aligned text or as a Markdown table.
class Table
{
public:
  explicit Table(std::vector<std::string> header)
    : Header(std::move(header))
  {
  }
  void Add(std::vector<std::string> row) { this->Rows.push_back(std::move(row)); }
  bool Empty() const { return this->Rows.empty(); }
  void Print(std::ostream& os, bool markdown) const;

private:
  std::vector<std::string> Header;
  std::vector<std::vector<std::string>> Rows;
};

/// `value` with `digits` significant digits ("-" when not finite).
std::string Format(double value, int digits = 3);
/// Fixed notation with `decimals` decimals.
std::string Fixed(double value, int decimals);

double Median(std::vector<double> values);

/// Splits "a,b,c".
std::vector<std::string> SplitList(const std::string& text);

/// Peak resident memory (bytes) added while `run` executes, measured in a
/// forked child (the parent's memory is untouched), on a thread of the
/// child's own (a new malloc arena, not the heap inherited from the parent
/// with its free space): it makes malloc
/// return large blocks to the system at once, runs once to warm up, resets
/// its high-water mark (/proc/self/clear_refs "5"), runs again and reports
/// VmHWM - VmRSS(before) - run()'s own return value (bytes to exclude, e.g.
/// the output's). Negative when not measurable (not Linux, fork failed).
double PeakExtraBytes(const std::function<double()>& run);
} // namespace asmbench

#endif
