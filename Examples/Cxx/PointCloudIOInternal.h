// SPDX-License-Identifier: BSD-3-Clause
// Helpers shared by the readers of PointCloudIO.cxx and PCDReader.cxx.
#ifndef PointCloudIOInternal_h
#define PointCloudIOInternal_h

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace pcio
{
namespace detail
{
inline std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

/// Splits a text line at white space, commas and semicolons.
inline std::vector<std::string> Fields(const std::string& line)
{
  std::vector<std::string> fields;
  std::string current;
  for (char c : line)
  {
    if (c == ',' || c == ';' || std::isspace(static_cast<unsigned char>(c)))
    {
      if (!current.empty())
      {
        fields.push_back(current);
      }
      current.clear();
    }
    else
    {
      current += c;
    }
  }
  if (!current.empty())
  {
    fields.push_back(current);
  }
  return fields;
}

inline bool ParseDouble(const std::string& text, double& value)
{
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  value = std::strtod(begin, &end);
  // (An underflow, a subnormal such as 1e-310, is a value; an overflow is not.)
  return end != begin && *end == '\0' && !(errno == ERANGE && std::abs(value) > 1);
}

/// A whole base-10 integer (optional sign; no blanks, no junk after it) that
/// fits a long long.
inline bool StrictInt64(const std::string& text, long long& value)
{
  if (text.empty() ||
    !(std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '-' || text[0] == '+'))
  {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(text.c_str(), &end, 10);
  return end != text.c_str() && *end == '\0' && errno != ERANGE;
}

/// A whole unsigned base-10 integer (digits only: no sign) that fits an
/// unsigned long long.
inline bool StrictUInt64(const std::string& text, unsigned long long& value)
{
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0])))
  {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  value = std::strtoull(text.c_str(), &end, 10);
  return *end == '\0' && errno != ERANGE;
}

/// One vertex per point: what ParaView and the ASM filters expect of a cloud.
inline vtkSmartPointer<vtkPolyData> MakeCloud(vtkPoints* points)
{
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    vertices->InsertNextCell(1, &i);
  }
  cloud->SetVerts(vertices);
  return cloud;
}
} // namespace detail
} // namespace pcio

#endif
