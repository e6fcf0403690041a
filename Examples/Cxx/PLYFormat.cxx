// SPDX-License-Identifier: BSD-3-Clause
// A small, strict reader of the vertices of a PLY file (ascii 1.0,
// binary_little_endian 1.0, binary_big_endian 1.0): see ReadPLY in
// PointCloudIO.h. Every count and size read from the file is checked
// against the bytes that follow before anything is allocated or read.
#include "PLYFormatInternal.h"
#include "PointCloudIO.h"
#include "PointCloudIOInternal.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"

#include <cerrno>
#include <cfloat>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <stdexcept>

namespace pcio
{
namespace
{
using namespace detail::ply;

/// The file, its header and the reading position.
class Reader
{
public:
  Reader(const std::string& path)
    : Path(path)
  {
  }

  void Open()
  {
    this->In.open(this->Path, std::ios::binary);
    if (!this->In)
    {
      throw Failure("cannot open " + this->Path);
    }
    this->In.seekg(0, std::ios::end);
    const auto size = this->In.tellg();
    this->In.seekg(0);
    if (!this->In || size < 0)
    {
      throw Failure("cannot read " + this->Path);
    }
    this->FileSize = static_cast<std::uint64_t>(size);
  }

  void ReadHeader()
  {
    const Header header = detail::ply::ReadHeader(this->In, this->Path);
    this->DataFormat = header.DataFormat;
    this->Elements = header.Elements;
    this->Position = header.Bytes;
    this->Line = header.Lines;
  }
  vtkSmartPointer<vtkPolyData> ReadVertices();

private:
  [[noreturn]] void Fail(const std::string& message) const
  {
    throw Failure(this->Path + ": " + message);
  }
  std::uint64_t Remaining() const
  {
    return this->Position < this->FileSize ? this->FileSize - this->Position : 0;
  }
  void CheckCount(const Element& element);
  void ReadBinary(char* data, std::size_t size, const Element& element, std::uint64_t record);
  double BinaryValue(Type type, const Element& element, std::uint64_t record);
  /// Calls store(property, value) for each scalar property of one record.
  template <typename Store>
  void ReadRecord(const Element& element, std::uint64_t record, Store&& store);
  double AsciiValue(const std::string& token, Type type, const Element& element, std::uint64_t r);

  std::string Path;
  std::ifstream In;
  std::uint64_t FileSize = 0;
  std::uint64_t Position = 0; // binary: the offset of the next byte to read
  std::uint64_t Line = 0;
  Format DataFormat = Format::Ascii;
  std::vector<Element> Elements;
  // ascii: the tokens of the current line and the next one to use.
  std::vector<std::string> Fields;
  std::size_t Next = 0;
};

/// Fails unless `element`'s records can fit in the bytes left.
void Reader::CheckCount(const Element& element)
{
  std::uint64_t minimum = 0; // bytes of the smallest record
  for (const auto& property : element.Properties)
  {
    if (this->DataFormat == Format::Ascii)
    {
      minimum += 2; // a digit and a separator
    }
    else
    {
      minimum += Size(property.IsList ? property.CountType : property.ValueType);
    }
  }
  const std::uint64_t remaining = this->Remaining() + (this->DataFormat == Format::Ascii ? 1 : 0);
  if (minimum > 0 && element.Count > remaining / minimum)
  {
    this->Fail("the header declares " + std::to_string(element.Count) + " " + element.Name +
      " records, but the " + std::to_string(this->Remaining()) +
      " bytes after the header hold at most " + std::to_string(remaining / minimum) +
      " (file truncated or header wrong)");
  }
}

void Reader::ReadBinary(char* data, std::size_t size, const Element& element, std::uint64_t record)
{
  if (size > this->Remaining() || !this->In.read(data, static_cast<std::streamsize>(size)))
  {
    this->Fail("premature end of file: read " + std::to_string(record) + " of " +
      std::to_string(element.Count) + " " + element.Name + " records");
  }
  this->Position += size;
}

double Reader::BinaryValue(Type type, const Element& element, std::uint64_t record)
{
  char bytes[8];
  this->ReadBinary(bytes, Size(type), element, record);
  return Decode(bytes, type, (this->DataFormat == Format::BinaryBig) == HostIsLittleEndian());
}

double Reader::AsciiValue(
  const std::string& token, Type type, const Element& element, std::uint64_t record)
{
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  double value = 0;
  bool ok = false;
  if (IsInteger(type))
  {
    const long long integer = std::strtoll(begin, &end, 10);
    value = static_cast<double>(integer);
    ok = end != begin && *end == '\0' && errno == 0 && InRange(value, type);
  }
  else
  {
    value = std::strtod(begin, &end);
    const bool overflow = errno == ERANGE && std::abs(value) > 1;
    ok = end != begin && *end == '\0' && !overflow &&
      (type == Type::Double || !(std::abs(value) > FLT_MAX) || std::isinf(value));
  }
  if (!ok)
  {
    this->Fail("line " + std::to_string(this->Line) + " (" + element.Name + " " +
      std::to_string(record) + "): '" + token.substr(0, 40) + "' is not a " + Name(type) +
      " value");
  }
  return value;
}

template <typename Store>
void Reader::ReadRecord(const Element& element, std::uint64_t record, Store&& store)
{
  const bool ascii = this->DataFormat == Format::Ascii;
  if (ascii)
  {
    std::string line;
    do
    {
      ++this->Line;
      if (!std::getline(this->In, line))
      {
        this->Fail("premature end of file: read " + std::to_string(record) + " of " +
          std::to_string(element.Count) + " " + element.Name + " records");
      }
      this->Position += line.size() + 1;
      this->Fields = Tokens(line);
    } while (this->Fields.empty());
    this->Next = 0;
  }
  auto value = [&](Type type) {
    if (!ascii)
    {
      return this->BinaryValue(type, element, record);
    }
    if (this->Next >= this->Fields.size())
    {
      this->Fail("line " + std::to_string(this->Line) + " (" + element.Name + " " +
        std::to_string(record) + "): too few values (" + std::to_string(this->Fields.size()) + ")");
    }
    return this->AsciiValue(this->Fields[this->Next++], type, element, record);
  };
  for (std::size_t p = 0; p < element.Properties.size(); ++p)
  {
    const Property& property = element.Properties[p];
    if (!property.IsList)
    {
      store(p, value(property.ValueType));
      continue;
    }
    const double count = value(property.CountType);
    if (count < 0)
    {
      this->Fail(element.Name + " " + std::to_string(record) + ": negative list length");
    }
    const auto n = static_cast<std::uint64_t>(count);
    if (!ascii)
    {
      const std::uint64_t bytes = n * Size(property.ValueType);
      if (bytes > this->Remaining())
      {
        this->Fail(element.Name + " " + std::to_string(record) + ": a list of " +
          std::to_string(n) + " items runs past the end of the file");
      }
      this->In.seekg(static_cast<std::streamoff>(bytes), std::ios::cur);
      this->Position += bytes;
      continue;
    }
    for (std::uint64_t i = 0; i < n; ++i)
    {
      value(property.ValueType);
    }
  }
  if (ascii && this->Next != this->Fields.size())
  {
    this->Fail("line " + std::to_string(this->Line) + " (" + element.Name + " " +
      std::to_string(record) + "): " + std::to_string(this->Fields.size()) + " values, expected " +
      std::to_string(this->Next));
  }
}

vtkSmartPointer<vtkPolyData> Reader::ReadVertices()
{
  std::size_t v = 0;
  while (v < this->Elements.size() && this->Elements[v].Name != "vertex")
  {
    ++v;
  }
  if (v == this->Elements.size())
  {
    this->Fail("no 'vertex' element in the header");
  }
  const Element& vertex = this->Elements[v];
  auto find = [&vertex](const char* name) {
    for (std::size_t p = 0; p < vertex.Properties.size(); ++p)
    {
      if (vertex.Properties[p].Name == name && !vertex.Properties[p].IsList)
      {
        return static_cast<int>(p);
      }
    }
    return -1;
  };
  const int xyz[3] = { find("x"), find("y"), find("z") };
  for (int axis = 0; axis < 3; ++axis)
  {
    if (xyz[axis] < 0)
    {
      this->Fail(std::string("the vertex element has no '") + "xyz"[axis] + "' property");
    }
  }
  // Skip the elements before the vertices, record by record (lists have
  // their own lengths) or in one go (binary records of fixed size).
  for (std::size_t e = 0; e < v; ++e)
  {
    const Element& element = this->Elements[e];
    this->CheckCount(element);
    std::uint64_t fixed = 0;
    bool lists = false;
    for (const auto& property : element.Properties)
    {
      lists = lists || property.IsList;
      fixed += Size(property.ValueType);
    }
    if (element.Properties.empty())
    {
      continue; // records of nothing
    }
    if (this->DataFormat != Format::Ascii && !lists)
    {
      this->In.seekg(static_cast<std::streamoff>(fixed * element.Count), std::ios::cur);
      this->Position += fixed * element.Count;
      continue;
    }
    for (std::uint64_t r = 0; r < element.Count; ++r)
    {
      this->ReadRecord(element, r, [](std::size_t, double) {});
    }
  }
  this->CheckCount(vertex);
  const auto n = static_cast<vtkIdType>(vertex.Count);
  const auto& properties = vertex.Properties;

  // Where each property goes: a component of the points, of Normals, of
  // RGB(A), or an array of its own.
  // (Smart pointers: an array stays alive whatever later happens to the point data.)
  std::vector<std::pair<vtkSmartPointer<vtkDataArray>, int>> targets(
    properties.size(), { nullptr, 0 });
  vtkNew<vtkPoints> points;
  points->SetDataType(NeedsDouble(properties[xyz[0]].ValueType, properties[xyz[1]].ValueType,
                        properties[xyz[2]].ValueType)
      ? VTK_DOUBLE
      : VTK_FLOAT);
  points->SetNumberOfPoints(n);
  for (int axis = 0; axis < 3; ++axis)
  {
    targets[xyz[axis]] = { points->GetData(), axis };
  }
  auto cloud = detail::MakeCloud(points);
  vtkPointData* pointData = cloud->GetPointData();
  const int normal[3] = { find("nx"), find("ny"), find("nz") };
  if (normal[0] >= 0 && normal[1] >= 0 && normal[2] >= 0)
  {
    auto normals = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(
      NeedsDouble(properties[normal[0]].ValueType, properties[normal[1]].ValueType,
        properties[normal[2]].ValueType)
        ? VTK_DOUBLE
        : VTK_FLOAT));
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n);
    pointData->SetNormals(normals);
    for (int c = 0; c < 3; ++c)
    {
      targets[normal[c]] = { normals, c };
    }
  }
  int colour[4] = { find("red"), find("green"), find("blue"), find("alpha") };
  const auto isUChar = [&](int p) { return p >= 0 && properties[p].ValueType == Type::UChar; };
  if (isUChar(colour[0]) && isUChar(colour[1]) && isUChar(colour[2]))
  {
    const int components = isUChar(colour[3]) ? 4 : 3;
    auto rgb = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(VTK_UNSIGNED_CHAR));
    rgb->SetName(components == 4 ? "RGBA" : "RGB");
    rgb->SetNumberOfComponents(components);
    rgb->SetNumberOfTuples(n);
    pointData->SetScalars(rgb);
    for (int c = 0; c < components; ++c)
    {
      targets[colour[c]] = { rgb, c };
    }
  }
  for (std::size_t p = 0; p < properties.size(); ++p)
  {
    if (targets[p].first || properties[p].IsList)
    {
      continue;
    }
    auto array =
      vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(VtkType(properties[p].ValueType)));
    std::string name = properties[p].Name;
    // Not to replace the normals, the colours or an array added before
    // (a property "Normals" renamed "Normals_" next to a property "Normals_").
    while (pointData->GetAbstractArray(name.c_str()))
    {
      name += "_";
    }
    array->SetName(name.c_str());
    array->SetNumberOfTuples(n);
    pointData->AddArray(array);
    targets[p] = { array, 0 };
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    this->ReadRecord(vertex, static_cast<std::uint64_t>(i), [&](std::size_t p, double value) {
      targets[p].first->SetComponent(i, targets[p].second, value);
    });
  }
  for (const auto& target : targets)
  {
    if (target.first)
    {
      target.first->Modified(); // written behind the arrays' back
    }
  }
  return cloud;
}
} // namespace

vtkSmartPointer<vtkPolyData> ReadPLY(const std::string& path, std::string& error)
{
  try
  {
    Reader reader(path);
    reader.Open();
    reader.ReadHeader();
    return reader.ReadVertices();
  }
  catch (const Failure& failure)
  {
    error = failure.what();
  }
  catch (const std::bad_alloc&)
  {
    error = path + ": out of memory";
  }
  catch (const std::exception& e)
  {
    error = path + ": " + e.what();
  }
  return nullptr;
}
} // namespace pcio
