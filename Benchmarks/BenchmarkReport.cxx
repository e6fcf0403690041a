// SPDX-License-Identifier: BSD-3-Clause
#include "BenchmarkReport.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <thread>

#if defined(__linux__)
#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace asmbench
{
void Table::Print(std::ostream& os, bool markdown) const
{
  std::vector<std::size_t> width(this->Header.size(), 0);
  auto measure = [&width](const std::vector<std::string>& row) {
    for (std::size_t i = 0; i < row.size() && i < width.size(); ++i)
    {
      width[i] = std::max(width[i], row[i].size());
    }
  };
  measure(this->Header);
  for (const auto& row : this->Rows)
  {
    measure(row);
  }
  auto line = [&](const std::vector<std::string>& row) {
    for (std::size_t i = 0; i < width.size(); ++i)
    {
      const std::string cell = i < row.size() ? row[i] : "";
      if (markdown)
      {
        os << "| " << cell << " ";
      }
      else
      {
        // First column left-aligned, numbers right-aligned.
        os << (i == 0 ? std::left : std::right) << std::setw(static_cast<int>(width[i])) << cell
           << (i + 1 < width.size() ? "  " : "");
      }
    }
    os << (markdown ? "|\n" : "\n");
  };
  line(this->Header);
  if (markdown)
  {
    for (std::size_t i = 0; i < width.size(); ++i)
    {
      os << (i == 0 ? "|---" : "|---:");
    }
    os << "|\n";
  }
  for (const auto& row : this->Rows)
  {
    line(row);
  }
  os << std::left;
}

std::string Format(double value, int digits)
{
  if (!std::isfinite(value))
  {
    return "-";
  }
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*g", digits, value);
  return buffer;
}

std::string Fixed(double value, int decimals)
{
  if (!std::isfinite(value))
  {
    return "-";
  }
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value);
  return buffer;
}

double Median(std::vector<double> values)
{
  if (values.empty())
  {
    return std::nan("");
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::vector<std::string> SplitList(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
  {
    if (!item.empty())
    {
      items.push_back(item);
    }
  }
  return items;
}

#if defined(__linux__)
namespace
{
/// A "VmRSS:" / "VmHWM:" line of /proc/self/status, in bytes (-1: absent).
double StatusBytes(const char* key)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(status, line))
  {
    if (line.compare(0, prefix.size(), prefix) == 0)
    {
      return 1024.0 * std::stod(line.substr(prefix.size()));
    }
  }
  return -1.0;
}
} // namespace

double PeakExtraBytes(const std::function<double()>& run)
{
  int fds[2];
  if (pipe(fds) != 0)
  {
    return -1.0;
  }
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child < 0)
  {
    close(fds[0]);
    close(fds[1]);
    return -1.0;
  }
  if (child == 0)
  {
    close(fds[0]);
    double extra = -1.0;
    // Large blocks straight from and back to the system (no dynamic mmap
    // threshold), and a first run so that code pages and small-object pools
    // are in place: the second run's growth is its own working memory.
    mallopt(M_MMAP_THRESHOLD, 64 * 1024);
    mallopt(M_TRIM_THRESHOLD, 128 * 1024);
    // Both runs on a thread of their own, whose malloc arena is new: the
    // parent's heap, inherited with whatever free space its earlier work
    // left (resident or not), would otherwise take some of the runs' small
    // blocks, and the figure would depend on what the parent did before
    // (1 thread, 1 M points, 20 %: 45 to 57 B/pt by the rows measured
    // before; see Profile README, round 29).
    std::thread([&]() {
      run();
      malloc_trim(0);
      {
        std::ofstream reset("/proc/self/clear_refs");
        reset << "5";
      }
      const double before = StatusBytes("VmRSS");
      const double exclude = run();
      const double peak = StatusBytes("VmHWM");
      if (before >= 0.0 && peak >= 0.0)
      {
        extra = peak - before - exclude;
      }
    }).join();
    const ssize_t written = write(fds[1], &extra, sizeof(extra));
    (void)written;
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  double extra = -1.0;
  if (read(fds[0], &extra, sizeof(extra)) != static_cast<ssize_t>(sizeof(extra)))
  {
    extra = -1.0;
  }
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return extra;
}
#else
double PeakExtraBytes(const std::function<double()>&)
{
  return -1.0;
}
#endif
} // namespace asmbench
