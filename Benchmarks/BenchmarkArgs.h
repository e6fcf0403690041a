// SPDX-License-Identifier: BSD-3-Clause
/**
 * The command-line parsing the benchmark programs share (asm_quality_benchmark,
 * asm_speed_benchmark, Profile/asm_profile, Profile/asm_partition): header
 * only, so that asm_profile uses it without the benchmarks' support library.
 *
 * Every parser throws UsageError, whose message names the option and the
 * value ("--runs: \"0\" is not an integer >= 1"); the programs print it on one
 * line and exit with status 2 before any work.
 */
#ifndef asm_BenchmarkArgs_h
#define asm_BenchmarkArgs_h

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace asmbench
{
/// A bad command line (exit status 2).
class UsageError : public std::runtime_error
{
public:
  explicit UsageError(const std::string& message)
    : std::runtime_error(message)
  {
  }
};

/// The largest point count of a synthetic input or of asm_profile's --points
/// (2^31: vtkIdType arrays of 3 components stay within 2^33 values, 24 GB of doubles).
constexpr std::int64_t MaxPointCount = std::int64_t(1) << 31;

/// The value after option argv[i] (i is advanced to it); throws when there is none.
inline std::string OptionValue(int argc, char* argv[], int& i)
{
  if (i + 1 >= argc)
  {
    throw UsageError(std::string(argv[i]) + ": missing value");
  }
  return argv[++i];
}

/// `"text"` for messages.
inline std::string Quoted(const std::string& text)
{
  return "\"" + text + "\"";
}

/// Splits "a,b,c" keeping empty items (",": two empty items).
inline std::vector<std::string> SplitItems(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
  {
    items.push_back(item);
  }
  if (!text.empty() && text.back() == ',')
  {
    items.push_back(std::string());
  }
  return items;
}

/// An integer in [lo, hi] (the whole text, decimal).
inline long ParseInteger(const std::string& option, const std::string& text, long lo,
  long hi = std::numeric_limits<int>::max())
{
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno == ERANGE || value < lo || value > hi)
  {
    throw UsageError(option + ": " + Quoted(text) + " is not an integer in [" + std::to_string(lo) +
      ", " + std::to_string(hi) + "]");
  }
  return value;
}

/// A fraction in (0, 1].
inline double ParseFraction(const std::string& option, const std::string& text)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(value > 0.0 && value <= 1.0))
  {
    throw UsageError(option + ": " + Quoted(text) + " is not a fraction in (0, 1]");
  }
  return value;
}

/// A point count such as "100k", "1M", "14M", "2.5e5" or "5000", at most
/// MaxPointCount; -1 when invalid, -2 when too large.
inline std::int64_t ParseCount(const std::string& text)
{
  if (text.empty())
  {
    return -1;
  }
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str())
  {
    return -1;
  }
  double scale = 1.0;
  const std::string suffix(end);
  if (suffix == "k" || suffix == "K")
  {
    scale = 1e3;
  }
  else if (suffix == "M" || suffix == "m")
  {
    scale = 1e6;
  }
  else if (!suffix.empty())
  {
    return -1;
  }
  if (!(value > 0.0) || !std::isfinite(value))
  {
    return std::isinf(value) && value > 0.0 ? -2 : -1;
  }
  if (value * scale > static_cast<double>(MaxPointCount))
  {
    return -2;
  }
  const auto n = static_cast<std::int64_t>(std::llround(value * scale));
  return n > 0 ? n : -1;
}

/// Why ParseCount(text) failed, for messages.
inline std::string CountError(const std::string& text)
{
  return ParseCount(text) == -2
    ? Quoted(text) + " is more than " + std::to_string(MaxPointCount) + " points"
    : Quoted(text) + " is not a point count (e.g. 5000, 100k, 1M)";
}

/// A comma-separated list, none of its items empty or repeated, each
/// parsed by `parse(option, item)`; throws on an empty list.
template <typename Parse>
auto ParseList(const std::string& option, const std::string& text, const Parse& parse)
  -> std::vector<decltype(parse(option, text))>
{
  std::vector<decltype(parse(option, text))> values;
  std::set<std::string> seen;
  for (const std::string& item : SplitItems(text))
  {
    if (item.empty())
    {
      throw UsageError(option + ": " + Quoted(text) + " has an empty item");
    }
    values.push_back(parse(option, item));
    if (!seen.insert(item).second)
    {
      throw UsageError(option + ": " + Quoted(item) + " is given twice");
    }
  }
  if (values.empty())
  {
    throw UsageError(option + ": " + Quoted(text) + " is an empty list");
  }
  return values;
}

/// Integers in [lo, hi], distinct.
inline std::vector<long> ParseIntegerList(const std::string& option, const std::string& text,
  long lo, long hi = std::numeric_limits<int>::max())
{
  const std::vector<long> values = ParseList(option, text,
    [lo, hi](const std::string& o, const std::string& t) { return ParseInteger(o, t, lo, hi); });
  if (std::set<long>(values.begin(), values.end()).size() != values.size())
  {
    throw UsageError(option + ": " + Quoted(text) + " repeats a value");
  }
  return values;
}

/// Fractions in (0, 1], distinct.
inline std::vector<double> ParseFractionList(const std::string& option, const std::string& text)
{
  const std::vector<double> values = ParseList(option, text, ParseFraction);
  if (std::set<double>(values.begin(), values.end()).size() != values.size())
  {
    throw UsageError(option + ": " + Quoted(text) + " repeats a value");
  }
  return values;
}

/// Point counts (ParseCount), distinct.
inline std::vector<std::int64_t> ParseCountList(const std::string& option, const std::string& text)
{
  const std::vector<std::int64_t> values =
    ParseList(option, text, [](const std::string& o, const std::string& t) {
      const std::int64_t n = ParseCount(t);
      if (n <= 0)
      {
        throw UsageError(o + ": " + CountError(t));
      }
      return n;
    });
  if (std::set<std::int64_t>(values.begin(), values.end()).size() != values.size())
  {
    throw UsageError(option + ": " + Quoted(text) + " repeats a value");
  }
  return values;
}
} // namespace asmbench

#endif
