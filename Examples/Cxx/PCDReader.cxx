// SPDX-License-Identifier: BSD-3-Clause
// The PCD reader of PointCloudIO.h: DATA ascii, binary and binary_compressed (LZF).
#include "PointCloudIO.h"
#include "PointCloudIOInternal.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace pcio
{
using detail::Fields;
using detail::Lower;
using detail::MakeCloud;
using detail::ParseDouble;

namespace
{
std::string PCDTypeName(char type, int size)
{
  return std::string(1, type) + std::to_string(size);
}

/// A PCD field: name, size in bytes, type letter (F, I, U), count.
struct PCDField
{
  std::string Name;
  int Size = 4;
  char Type = 'F';
  int Count = 1;
  vtkSmartPointer<vtkDataArray> Array; // nullptr for x, y, z and padding
  bool PackedColor = false;            // rgb / rgba stored in 4 bytes
};

vtkSmartPointer<vtkDataArray> NewPCDArray(const PCDField& f)
{
  vtkSmartPointer<vtkDataArray> array;
  const std::string t = PCDTypeName(f.Type, f.Size);
  if (t == "F4")
    array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_FLOAT));
  else if (t == "F8")
    array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_DOUBLE));
  else if (t == "I1")
    array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_SIGNED_CHAR));
  else if (t == "U1")
    array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_UNSIGNED_CHAR));
  else if (t == "I2")
    array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_SHORT));
  else if (t == "U2")
    array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_UNSIGNED_SHORT));
  else if (t == "I4")
    array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_INT));
  else if (t == "U4")
    array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_UNSIGNED_INT));
  else if (t == "I8")
    array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_LONG_LONG));
  else if (t == "U8")
    array =
      vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_UNSIGNED_LONG_LONG));
  return array;
}

/// The value of one binary field component (little endian, as written by PCL on x86).
double DecodeBinary(const unsigned char* p, char type, int size)
{
  switch (size)
  {
    case 1:
      return type == 'I' ? static_cast<double>(static_cast<std::int8_t>(*p))
                         : static_cast<double>(*p);
    case 2:
    {
      std::uint16_t u;
      std::memcpy(&u, p, 2);
      return type == 'I' ? static_cast<double>(static_cast<std::int16_t>(u))
                         : static_cast<double>(u);
    }
    case 4:
    {
      if (type == 'F')
      {
        float f;
        std::memcpy(&f, p, 4);
        return f;
      }
      std::uint32_t u;
      std::memcpy(&u, p, 4);
      return type == 'I' ? static_cast<double>(static_cast<std::int32_t>(u))
                         : static_cast<double>(u);
    }
    default:
    {
      if (type == 'F')
      {
        double d;
        std::memcpy(&d, p, 8);
        return d;
      }
      std::uint64_t u;
      std::memcpy(&u, p, 8);
      return type == 'I' ? static_cast<double>(static_cast<std::int64_t>(u))
                         : static_cast<double>(u);
    }
  }
}

/// PCL's packed colour: the bytes of a float (or uint32) read as 0x00RRGGBB.
void StorePackedColor(vtkDataArray* rgb, vtkIdType point, const unsigned char* bytes)
{
  std::uint32_t packed;
  std::memcpy(&packed, bytes, 4);
  rgb->SetComponent(point, 0, (packed >> 16) & 0xff);
  rgb->SetComponent(point, 1, (packed >> 8) & 0xff);
  rgb->SetComponent(point, 2, packed & 0xff);
}
} // namespace

bool LZFDecompress(
  const std::vector<unsigned char>& in, std::size_t size, std::vector<unsigned char>& out)
{
  out.clear();
  out.reserve(size);
  std::size_t i = 0;
  while (i < in.size())
  {
    const unsigned ctrl = in[i++];
    if (ctrl < 32) // a literal run of ctrl + 1 bytes
    {
      if (i + ctrl + 1 > in.size() || out.size() + ctrl + 1 > size)
        return false;
      out.insert(out.end(), in.begin() + static_cast<std::ptrdiff_t>(i),
        in.begin() + static_cast<std::ptrdiff_t>(i + ctrl + 1));
      i += ctrl + 1;
      continue;
    }
    // A back reference: length (ctrl >> 5) + 2, extended by a byte when 7;
    // distance ((ctrl & 31) << 8 | next byte) + 1 back from the end.
    std::size_t length = ctrl >> 5;
    if (length == 7)
    {
      if (i >= in.size())
        return false;
      length += in[i++];
    }
    length += 2;
    if (i >= in.size())
      return false;
    const std::size_t distance = (static_cast<std::size_t>(ctrl & 31) << 8 | in[i++]) + 1;
    if (distance > out.size() || out.size() + length > size)
      return false;
    for (std::size_t k = 0, from = out.size() - distance; k < length; ++k)
    {
      out.push_back(out[from + k]); // may overlap what it appends
    }
  }
  return out.size() == size;
}

vtkSmartPointer<vtkPolyData> ReadPCD(const std::string& path, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    error = "cannot open " + path;
    return nullptr;
  }
  std::vector<PCDField> fields;
  std::vector<int> sizes, counts;
  std::vector<char> types;
  long long points = -1, width = -1, height = 1;
  std::string data;
  std::string line;
  while (data.empty() && std::getline(in, line))
  {
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    std::istringstream words(line);
    std::string key;
    if (!(words >> key) || key[0] == '#')
    {
      continue;
    }
    key = Lower(key);
    std::vector<std::string> values;
    for (std::string v; words >> v;)
    {
      values.push_back(v);
    }
    if (key == "fields")
    {
      for (const auto& v : values)
      {
        fields.push_back(PCDField{ v });
      }
    }
    else if (key == "size")
    {
      for (const auto& v : values)
        sizes.push_back(std::atoi(v.c_str()));
    }
    else if (key == "type")
    {
      for (const auto& v : values)
        types.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(v[0]))));
    }
    else if (key == "count")
    {
      for (const auto& v : values)
        counts.push_back(std::atoi(v.c_str()));
    }
    else if (key == "width" && !values.empty())
      width = std::atoll(values[0].c_str());
    else if (key == "height" && !values.empty())
      height = std::atoll(values[0].c_str());
    else if (key == "points" && !values.empty())
      points = std::atoll(values[0].c_str());
    else if (key == "data" && !values.empty())
      data = Lower(values[0]);
    else if (key != "version" && key != "viewpoint")
    {
      error = path + ": not a PCD file (unknown header line '" + line.substr(0, 40) + "')";
      return nullptr;
    }
  }
  if (data.empty())
  {
    error = path + ": not a PCD file (no DATA line)";
    return nullptr;
  }
  if (data != "ascii" && data != "binary" && data != "binary_compressed")
  {
    error = path + ": PCD DATA " + data + " is not supported (ascii, binary, binary_compressed)";
    return nullptr;
  }
  if (points < 0)
  {
    points = width * height;
  }
  if (fields.empty() || sizes.size() != fields.size() || types.size() != fields.size() ||
    (!counts.empty() && counts.size() != fields.size()) || points < 0)
  {
    error = path + ": bad PCD header (FIELDS, SIZE, TYPE, COUNT and POINTS must agree)";
    return nullptr;
  }
  int coordinate[3] = { -1, -1, -1 };
  std::size_t stride = 0;
  for (std::size_t f = 0; f < fields.size(); ++f)
  {
    PCDField& field = fields[f];
    field.Size = sizes[f];
    field.Type = types[f];
    field.Count = counts.empty() ? 1 : counts[f];
    const std::string type = PCDTypeName(field.Type, field.Size);
    if (field.Count < 1 || (field.Type != 'F' && field.Type != 'I' && field.Type != 'U') ||
      (field.Size != 1 && field.Size != 2 && field.Size != 4 && field.Size != 8) ||
      (field.Type == 'F' && field.Size < 4))
    {
      error = path + ": bad PCD field " + field.Name + " (type " + type + ", count " +
        std::to_string(field.Count) + ")";
      return nullptr;
    }
    stride += static_cast<std::size_t>(field.Size * field.Count);
    const std::string name = Lower(field.Name);
    if ((name == "x" || name == "y" || name == "z") && field.Count == 1)
    {
      coordinate[name[0] - 'x'] = static_cast<int>(f);
    }
    else if ((name == "rgb" || name == "rgba") && field.Size == 4 && field.Count == 1)
    {
      field.PackedColor = true;
      field.Array = vtkSmartPointer<vtkUnsignedCharArray>::New();
      field.Array->SetName("RGB");
      field.Array->SetNumberOfComponents(3);
    }
    else if (name != "_")
    {
      field.Array = NewPCDArray(field);
      field.Array->SetName(field.Name.c_str());
      field.Array->SetNumberOfComponents(field.Count);
    }
  }
  if (coordinate[0] < 0 || coordinate[1] < 0 || coordinate[2] < 0)
  {
    error = path + ": the PCD file has no x y z fields";
    return nullptr;
  }
  const auto n = static_cast<vtkIdType>(points);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(n);
  for (auto& field : fields)
  {
    if (field.Array)
    {
      field.Array->SetNumberOfTuples(n);
    }
  }
  std::vector<unsigned char> record(stride);
  // binary_compressed: LZF-compressed, one field after the other (all x,
  // then all y, ...); unpacked here into records as in DATA binary.
  std::vector<unsigned char> records;
  if (data == "binary_compressed")
  {
    std::uint32_t sizes2[2] = { 0, 0 }; // compressed, uncompressed
    std::vector<unsigned char> packed;
    if (in.read(reinterpret_cast<char*>(sizes2), 8))
    {
      packed.resize(sizes2[0]);
      in.read(reinterpret_cast<char*>(packed.data()), static_cast<std::streamsize>(packed.size()));
    }
    std::vector<unsigned char> fieldMajor;
    if (!in || sizes2[1] != static_cast<std::uint64_t>(n) * stride ||
      !LZFDecompress(packed, sizes2[1], fieldMajor))
    {
      error = path + ": bad binary_compressed PCD data (truncated, or not " + std::to_string(n) +
        " points of " + std::to_string(stride) + " bytes)";
      return nullptr;
    }
    records.resize(fieldMajor.size());
    std::size_t fieldStart = 0, recordOffset = 0;
    for (const auto& field : fields)
    {
      const std::size_t bytes = static_cast<std::size_t>(field.Size * field.Count);
      for (vtkIdType i = 0; i < n; ++i)
      {
        std::memcpy(records.data() + i * stride + recordOffset,
          fieldMajor.data() + fieldStart + i * bytes, bytes);
      }
      fieldStart += bytes * static_cast<std::size_t>(n);
      recordOffset += bytes;
    }
    data = "binary";
  }
  std::string text;
  double xyz[3];
  for (vtkIdType i = 0; i < n; ++i)
  {
    std::vector<std::string> words;
    if (!records.empty())
    {
      std::memcpy(record.data(), records.data() + i * stride, stride);
    }
    else if (data == "binary")
    {
      if (!in.read(reinterpret_cast<char*>(record.data()), static_cast<std::streamsize>(stride)))
      {
        error = path + ": the binary PCD data ends after " + std::to_string(i) + " of " +
          std::to_string(n) + " points";
        return nullptr;
      }
    }
    else
    {
      do
      {
        if (!std::getline(in, text))
        {
          error = path + ": the ASCII PCD data ends after " + std::to_string(i) + " of " +
            std::to_string(n) + " points";
          return nullptr;
        }
        words = Fields(text);
      } while (words.empty());
    }
    std::size_t offset = 0; // bytes (binary) or words (ascii) into the record
    for (std::size_t f = 0; f < fields.size(); ++f)
    {
      const PCDField& field = fields[f];
      for (int c = 0; c < field.Count; ++c)
      {
        double value = 0;
        if (data == "binary")
        {
          value = DecodeBinary(record.data() + offset, field.Type, field.Size);
          if (field.PackedColor)
          {
            StorePackedColor(field.Array, i, record.data() + offset);
          }
          offset += static_cast<std::size_t>(field.Size);
        }
        else
        {
          if (offset >= words.size() || !ParseDouble(words[offset], value))
          {
            // PCL writes "nan" for missing points, which strtod reads; anything else is an error.
            error = path + ": point " + std::to_string(i) + ": bad or missing value of field " +
              field.Name;
            return nullptr;
          }
          if (field.PackedColor)
          {
            float packed = static_cast<float>(value);
            unsigned char bytes[4];
            std::memcpy(bytes, &packed, 4);
            if (field.Type != 'F') // written as an integer
            {
              const auto u = static_cast<std::uint32_t>(value);
              std::memcpy(bytes, &u, 4);
            }
            StorePackedColor(field.Array, i, bytes);
          }
          ++offset;
        }
        if (static_cast<int>(f) == coordinate[0])
          xyz[0] = value;
        else if (static_cast<int>(f) == coordinate[1])
          xyz[1] = value;
        else if (static_cast<int>(f) == coordinate[2])
          xyz[2] = value;
        else if (field.Array && !field.PackedColor)
          field.Array->SetComponent(i, c, value);
      }
    }
    pts->SetPoint(i, xyz);
  }
  if (n == 0)
  {
    error = "no points in " + path;
    return nullptr;
  }
  auto cloud = MakeCloud(pts);
  for (const auto& field : fields)
  {
    if (field.Array)
    {
      cloud->GetPointData()->AddArray(field.Array);
    }
  }
  return cloud;
}
} // namespace pcio
