// SPDX-License-Identifier: BSD-3-Clause
// Writes a point cloud as a binary little-endian PLY vertex element with all
// its numeric point-data arrays: see WritePLY in PointCloudIO.h.
#include "PLYFormatInternal.h"
#include "PointCloudIO.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <set>
#include <vector>

namespace pcio
{
namespace
{
using namespace detail::ply;

/// One PLY property: component `Component` of `Array`, written as `Type`.
struct Column
{
  std::string Name;
  vtkDataArray* Array;
  int Component;
  Type ValueType;
};

/// The PLY type of an array, or false if it has none; 64-bit integers become
/// int or uint when all their values fit, else double.
bool PlyType(vtkDataArray* array, Type& type)
{
  switch (array->GetDataType())
  {
    case VTK_CHAR: // (signed or not, as the platform's char)
      type = std::numeric_limits<char>::is_signed ? Type::Char : Type::UChar;
      return true;
    case VTK_SIGNED_CHAR:
      type = Type::Char;
      return true;
    case VTK_UNSIGNED_CHAR:
      type = Type::UChar;
      return true;
    case VTK_SHORT:
      type = Type::Short;
      return true;
    case VTK_UNSIGNED_SHORT:
      type = Type::UShort;
      return true;
    case VTK_INT:
      type = Type::Int;
      return true;
    case VTK_UNSIGNED_INT:
      type = Type::UInt;
      return true;
    case VTK_FLOAT:
      type = Type::Float;
      return true;
    case VTK_DOUBLE:
      type = Type::Double;
      return true;
    case VTK_LONG:
    case VTK_LONG_LONG:
    case VTK_ID_TYPE:
    case VTK_UNSIGNED_LONG:
    case VTK_UNSIGNED_LONG_LONG:
    {
      const bool isSigned = array->GetDataType() == VTK_LONG ||
        array->GetDataType() == VTK_LONG_LONG || array->GetDataType() == VTK_ID_TYPE;
      type = isSigned ? Type::Int : Type::UInt;
      for (int c = 0; c < array->GetNumberOfComponents(); ++c)
      {
        double range[2];
        array->GetRange(range, c);
        if (array->GetNumberOfTuples() > 0 &&
          (!InRange(range[0], type) || !InRange(range[1], type)))
        {
          type = Type::Double;
        }
      }
      return true;
    }
    default:
      return false;
  }
}

/// `name` with white space and control characters replaced by '_', and cut
/// to 200 characters (VTK 9.2's vtkPLYReader misreads lines of about 4090).
std::string SafeName(const std::string& name)
{
  std::string safe = name.empty() ? "array" : name.substr(0, 200);
  for (char& c : safe)
  {
    if (std::isspace(static_cast<unsigned char>(c)) || std::iscntrl(static_cast<unsigned char>(c)))
    {
      c = '_';
    }
  }
  return safe;
}
} // namespace

bool WritePLY(vtkPolyData* cloud, const std::string& path, std::string& error)
{
  try
  {
    vtkPoints* points = cloud ? cloud->GetPoints() : nullptr;
    const vtkIdType n = points ? points->GetNumberOfPoints() : 0;
    std::vector<Column> columns;
    std::set<std::string> used;
    auto add = [&](const std::string& name, vtkDataArray* array, int component, Type type) {
      std::string unique = SafeName(name);
      for (int k = 2; used.count(unique); ++k)
      {
        unique = SafeName(name) + "_" + std::to_string(k);
      }
      used.insert(unique);
      columns.push_back({ unique, array, component, type });
    };
    const Type pointType =
      points && points->GetDataType() != VTK_FLOAT ? Type::Double : Type::Float;
    for (int c = 0; c < 3; ++c) // no points: x y z anyway, for 0 vertices
    {
      add(std::string(1, static_cast<char>('x' + c)), points ? points->GetData() : nullptr, c,
        pointType);
    }
    vtkPointData* pointData = cloud ? cloud->GetPointData() : nullptr;
    vtkDataArray* normals = pointData ? pointData->GetNormals() : nullptr;
    if (pointData && !normals)
    {
      normals = pointData->GetArray("Normals");
    }
    if (normals && normals->GetNumberOfComponents() == 3 && normals->GetNumberOfTuples() == n)
    {
      const Type type = normals->GetDataType() == VTK_FLOAT ? Type::Float : Type::Double;
      for (int c = 0; c < 3; ++c)
      {
        add(std::string("n") + static_cast<char>('x' + c), normals, c, type);
      }
    }
    else
    {
      normals = nullptr;
    }
    vtkDataArray* colours = nullptr;
    for (const char* name : { "RGB", "RGBA" })
    {
      vtkDataArray* array = pointData ? pointData->GetArray(name) : nullptr;
      if (!colours && array && array->GetDataType() == VTK_UNSIGNED_CHAR &&
        array->GetNumberOfComponents() == static_cast<int>(std::strlen(name)) &&
        array->GetNumberOfTuples() == n)
      {
        colours = array;
        const char* channels[] = { "red", "green", "blue", "alpha" };
        for (int c = 0; c < array->GetNumberOfComponents(); ++c)
        {
          add(channels[c], array, c, Type::UChar);
        }
      }
    }
    for (int a = 0; pointData && a < pointData->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* array = pointData->GetArray(a);
      Type type;
      if (!array || array == normals || array == colours || !PlyType(array, type) ||
        array->GetNumberOfTuples() != n)
      {
        continue;
      }
      const std::string name = array->GetName() ? array->GetName() : "array" + std::to_string(a);
      const int components = array->GetNumberOfComponents();
      for (int c = 0; c < components; ++c)
      {
        add(components == 1 ? name : name + "_" + std::to_string(c), array, c, type);
      }
    }

    if (columns.size() > MaxProperties) // (ReadPLY would refuse the file)
    {
      error = "cannot write " + path + ": " + std::to_string(columns.size()) +
        " properties, more than the " + std::to_string(MaxProperties) +
        " a PLY vertex may have here (write .vtp)";
      return false;
    }
    std::ofstream out(path, std::ios::binary);
    if (!out)
    {
      error = "cannot write " + path;
      return false;
    }
    out << "ply\nformat binary_little_endian 1.0\ncomment written by asm_simplify\n"
        << "element vertex " << n << "\n";
    std::size_t record = 0;
    for (const auto& column : columns)
    {
      out << "property " << Name(column.ValueType) << " " << column.Name << "\n";
      record += Size(column.ValueType);
    }
    out << "end_header\n";
    std::vector<char> buffer;
    const vtkIdType chunk = 65536;
    for (vtkIdType begin = 0; begin < n && out; begin += chunk)
    {
      const vtkIdType end = std::min(n, begin + chunk);
      buffer.resize(static_cast<std::size_t>(end - begin) * record);
      char* p = buffer.data();
      for (vtkIdType i = begin; i < end; ++i)
      {
        for (const auto& column : columns)
        {
          EncodeLittle(column.Array->GetComponent(i, column.Component), column.ValueType, p);
          p += Size(column.ValueType);
        }
      }
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    }
    out.close();
    if (!out)
    {
      error = "cannot write " + path + " (disk full?)";
      return false;
    }
    return true;
  }
  catch (const std::bad_alloc&)
  {
    error = "cannot write " + path + ": out of memory";
  }
  return false;
}
} // namespace pcio
