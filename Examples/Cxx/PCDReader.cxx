// SPDX-License-Identifier: BSD-3-Clause
// The PCD reader of PointCloudIO.h: DATA ascii, binary and binary_compressed (LZF).
#include "PointCloudIO.h"
#include "PointCloudIOInternal.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

namespace pcio
{
using detail::Fields;
using detail::Lower;
using detail::MakeCloud;
using detail::ParseDouble;
using detail::StrictInt64;
using detail::StrictUInt64;

namespace
{
constexpr long long MaxCount = 1 << 20; // components of one field
constexpr std::size_t LZFMaxRatio = 88; // 264 bytes from a 3-byte back reference
constexpr std::uint64_t MaxUInt32 = 0xffffffffu;

/// A PCD field: name, size in bytes, type letter (F, I, U), count.
struct PCDField
{
  std::string Name;
  int Size = 4;
  char Type = 'F';
  int Count = 1;
  std::size_t Offset = 0;              // of its first byte in a record
  int Axis = -1;                       // 0, 1, 2 for x, y, z
  vtkSmartPointer<vtkDataArray> Array; // nullptr for x, y, z and padding
  bool PackedColor = false;            // rgb / rgba stored in 4 bytes

  std::string TypeName() const { return std::string(1, this->Type) + std::to_string(this->Size); }
};

/// A VTK array of exactly the field's type and size, so that the bytes of a
/// record can be copied into it (I8 and U8 without going through double).
vtkSmartPointer<vtkDataArray> NewPCDArray(const PCDField& f)
{
  int type = f.Size == 8 ? VTK_TYPE_FLOAT64 : VTK_TYPE_FLOAT32;
  if (f.Type != 'F')
  {
    const int signedTypes[] = { VTK_TYPE_INT8, VTK_TYPE_INT16, VTK_TYPE_INT32, VTK_TYPE_INT64 };
    const int unsignedTypes[] = { VTK_TYPE_UINT8, VTK_TYPE_UINT16, VTK_TYPE_UINT32,
      VTK_TYPE_UINT64 };
    const int log2 = f.Size == 1 ? 0 : f.Size == 2 ? 1 : f.Size == 4 ? 2 : 3;
    type = f.Type == 'I' ? signedTypes[log2] : unsignedTypes[log2];
  }
  return vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(type));
}

/// The value of one binary field component (little endian, as written by PCL on x86).
double DecodeBinary(const unsigned char* p, char type, int size)
{
  if (type == 'F')
  {
    if (size == 4)
    {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    double d;
    std::memcpy(&d, p, 8);
    return d;
  }
  std::uint64_t u = 0;
  for (int k = size - 1; k >= 0; --k)
  {
    u = u << 8 | p[k];
  }
  if (type == 'U')
  {
    return static_cast<double>(u);
  }
  const int shift = 64 - 8 * size; // sign-extend
  return static_cast<double>(static_cast<std::int64_t>(u << shift) >> shift);
}

/// The little-endian bytes of `value`, `size` of them.
void StoreInteger(std::uint64_t value, int size, unsigned char* out)
{
  for (int k = 0; k < size; ++k, value >>= 8)
  {
    out[k] = static_cast<unsigned char>(value & 0xff);
  }
}

/// Stores the ASCII token `text` of one component of `field` as the bytes the
/// binary format would have; false if it is not a value of the field's type
/// (not a number, not an integer for I/U, out of range).
bool EncodeASCII(const std::string& text, const PCDField& field, unsigned char* out)
{
  long long s = 0;
  unsigned long long u = 0;
  if (field.PackedColor)
  {
    // PCL writes a packed colour as the unsigned integer 0xAARRGGBB even
    // when its TYPE is F; a float token gives the bits of that float.
    if (StrictUInt64(text, u))
    {
      if (u > MaxUInt32)
        return false;
      StoreInteger(u, 4, out);
      return true;
    }
    if (field.Type == 'I' && StrictInt64(text, s) && s >= std::numeric_limits<std::int32_t>::min())
    {
      StoreInteger(static_cast<std::uint64_t>(s), 4, out);
      return true;
    }
    if (field.Type != 'F')
      return false;
  }
  const int bits = 8 * field.Size;
  if (field.Type == 'I')
  {
    const long long max =
      bits == 64 ? std::numeric_limits<long long>::max() : (1LL << (bits - 1)) - 1;
    if (!StrictInt64(text, s) || s > max || s < -max - 1)
      return false;
    StoreInteger(static_cast<std::uint64_t>(s), field.Size, out);
    return true;
  }
  if (field.Type == 'U')
  {
    if (!StrictUInt64(text, u) || (bits < 64 && u >> bits != 0))
      return false;
    StoreInteger(u, field.Size, out);
    return true;
  }
  double d = 0;
  if (!ParseDouble(text, d))
    return false;
  if (field.Size == 8)
  {
    std::memcpy(out, &d, 8);
    return true;
  }
  if (std::isfinite(d) && std::abs(d) > FLT_MAX)
    return false;
  const float f = static_cast<float>(d);
  std::memcpy(out, &f, 4);
  return true;
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

/// The name under which a field must be unique: x y z rgb in any case (rgba
/// counts as rgb), other names as they are ("" for the padding "_").
std::string UniqueKey(const std::string& name)
{
  const std::string lower = Lower(name);
  if (lower == "x" || lower == "y" || lower == "z" || lower == "rgb")
    return lower;
  if (lower == "rgba")
    return "rgb";
  return name == "_" ? "" : name;
}

vtkSmartPointer<vtkPolyData> ReadPCDFile(const std::string& path, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    error = "cannot open " + path;
    return nullptr;
  }
  std::vector<PCDField> fields;
  std::vector<std::string> sizes, types, counts;
  long long points = -1, width = -1, height = 1;
  std::string data;
  std::string line;
  std::set<std::string> keys;
  std::size_t lineNumber = 0;
  const auto fail = [&](const std::string& what) {
    error = path + ": " + what;
    return nullptr;
  };
  const auto bad = [&](const std::string& what) {
    error = path + ":" + std::to_string(lineNumber) + ": " + what;
    return nullptr;
  };
  while (data.empty() && std::getline(in, line))
  {
    ++lineNumber;
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
    if (key == "version" || key == "viewpoint")
      continue;
    if (key != "fields" && key != "size" && key != "type" && key != "count" && key != "width" &&
      key != "height" && key != "points" && key != "data")
      return fail("not a PCD file (unknown header line '" + line.substr(0, 40) + "')");
    if (!keys.insert(key).second)
      return bad("bad PCD header: a second " + key + " line");
    if (key == "fields")
    {
      for (const auto& v : values)
      {
        fields.emplace_back();
        fields.back().Name = v;
      }
    }
    else if (key == "size")
      sizes = values;
    else if (key == "type")
      types = values;
    else if (key == "count")
      counts = values;
    else if (values.size() != 1)
      return bad("bad PCD header: " + key + " needs one value");
    else if (key == "data")
      data = Lower(values[0]);
    else
    {
      long long& value = key == "width" ? width : key == "height" ? height : points;
      if (!StrictInt64(values[0], value) || value < 0)
        return bad("bad PCD " + key + " '" + values[0] + "' (not an integer >= 0)");
    }
  }
  if (data.empty())
    return fail("not a PCD file (no DATA line)");
  if (data != "ascii" && data != "binary" && data != "binary_compressed")
    return fail("PCD DATA " + data + " is not supported (ascii, binary, binary_compressed)");
  if (width >= 0 && height > 0 && width > std::numeric_limits<long long>::max() / height)
    return fail("bad PCD header: WIDTH x HEIGHT is too large");
  if (width >= 0 && points >= 0 && width * height != points)
    return fail("bad PCD header: WIDTH x HEIGHT (" + std::to_string(width) + " x " +
      std::to_string(height) + ") is not POINTS (" + std::to_string(points) + ")");
  if (points < 0)
  {
    points = width * height;
  }
  if (fields.empty() || sizes.size() != fields.size() || types.size() != fields.size() ||
    (!counts.empty() && counts.size() != fields.size()) || points < 0)
    return fail("bad PCD header (FIELDS, SIZE, TYPE, COUNT and POINTS must agree)");
  int coordinate[3] = { -1, -1, -1 };
  std::size_t stride = 0, valuesPerPoint = 0;
  std::set<std::string> names;
  for (std::size_t f = 0; f < fields.size(); ++f)
  {
    PCDField& field = fields[f];
    long long size = 0, count = 1;
    const std::string& type = types[f];
    if (!StrictInt64(sizes[f], size) || (size != 1 && size != 2 && size != 4 && size != 8) ||
      type.size() != 1 || std::string("FIUfiu").find(type[0]) == std::string::npos ||
      ((type[0] == 'F' || type[0] == 'f') && size < 4) ||
      (!counts.empty() && (!StrictInt64(counts[f], count) || count < 1 || count > MaxCount)))
      return fail("bad PCD field " + field.Name + " (SIZE " + sizes[f] + ", TYPE " + type +
        ", COUNT " + (counts.empty() ? "1" : counts[f]) +
        "; SIZE 1 2 4 8, TYPE F I U, COUNT 1 to " + std::to_string(MaxCount) + ")");
    field.Size = static_cast<int>(size);
    field.Type = static_cast<char>(std::toupper(static_cast<unsigned char>(type[0])));
    field.Count = static_cast<int>(count);
    field.Offset = stride;
    stride += static_cast<std::size_t>(size * count);
    valuesPerPoint += static_cast<std::size_t>(count);
    const std::string key = UniqueKey(field.Name);
    if (!key.empty() && !names.insert(key).second)
      return fail("the PCD field " + field.Name + " appears twice" +
        (key == "rgb" ? " (rgb, rgba in any case are one colour)" : ""));
    if ((key == "x" || key == "y" || key == "z") && field.Count == 1)
    {
      field.Axis = key[0] - 'x';
      coordinate[field.Axis] = static_cast<int>(f);
    }
    else if (key == "rgb" && field.Size == 4 && field.Count == 1)
    {
      field.PackedColor = true;
      field.Array = vtkSmartPointer<vtkUnsignedCharArray>::New();
      field.Array->SetName("RGB");
      field.Array->SetNumberOfComponents(3);
    }
    else if (!key.empty())
    {
      field.Array = NewPCDArray(field);
      field.Array->SetName(field.Name.c_str());
      field.Array->SetNumberOfComponents(field.Count);
    }
  }
  if (coordinate[0] < 0 || coordinate[1] < 0 || coordinate[2] < 0)
    return fail("the PCD file has no x y z fields");
  if (points == 0)
  {
    error = "no points in " + path;
    return nullptr;
  }
  const auto n = static_cast<vtkIdType>(points);
  // Bytes after the header: no more points than they can hold are allocated.
  std::uint64_t remaining = 0; // none if the header ends the file
  const auto dataStart = in.good() ? in.tellg() : std::streampos(-1);
  if (dataStart != std::streampos(-1) && in.seekg(0, std::ios::end))
  {
    remaining = static_cast<std::uint64_t>(std::max<std::streamoff>(in.tellg() - dataStart, 0));
    in.seekg(dataStart);
  }
  // A point the data cannot hold (a short header of huge COUNTs): refused
  // before a record or an array is allocated.
  if ((data == "binary" && stride > remaining) ||
    (data == "ascii" && 2 * valuesPerPoint > remaining + 1))
    return fail("the PCD data (" + std::to_string(remaining) + " bytes) cannot hold one point of " +
      std::to_string(stride) + " bytes (" + std::to_string(valuesPerPoint) + " values)");
  // binary_compressed: LZF-compressed, one field after the other (all x,
  // then all y, ...); unpacked here into records as in DATA binary.
  std::vector<unsigned char> records;
  if (data == "binary_compressed")
  {
    std::uint32_t sizes2[2] = { 0, 0 }; // compressed, uncompressed
    const std::string what = "bad binary_compressed PCD data (";
    if (remaining < 8 || !in.read(reinterpret_cast<char*>(sizes2), 8) || sizes2[0] > remaining - 8)
      return fail(what + "truncated)");
    if (static_cast<std::uint64_t>(n) > sizes2[1] / stride || n * stride != sizes2[1])
      return fail(
        what + "not " + std::to_string(n) + " points of " + std::to_string(stride) + " bytes)");
    std::vector<unsigned char> packed(sizes2[0]), fieldMajor;
    if (sizes2[1] > LZFMaxRatio * static_cast<std::uint64_t>(sizes2[0]))
      return fail(what + "more than LZF can expand " + std::to_string(sizes2[0]) + " bytes to)");
    if (!in.read(reinterpret_cast<char*>(packed.data()), sizes2[0]) ||
      !LZFDecompress(packed, sizes2[1], fieldMajor))
      return fail(what + "corrupt LZF)");
    records.resize(fieldMajor.size());
    std::size_t fieldStart = 0;
    for (const auto& field : fields)
    {
      const std::size_t size = static_cast<std::size_t>(field.Size) * field.Count;
      for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i)
      {
        std::memcpy(records.data() + i * stride + field.Offset,
          fieldMajor.data() + fieldStart + i * size, size);
      }
      fieldStart += size * static_cast<std::size_t>(n);
    }
  }
  // A text point takes at least 2 bytes a value (a digit and a blank or
  // the newline), except the last one of the file.
  const std::uint64_t fit = !records.empty() ? static_cast<std::uint64_t>(n)
    : data == "binary"                       ? remaining / stride
                                             : (remaining + 1) / (2 * valuesPerPoint);
  const auto capacity = static_cast<vtkIdType>(std::min<std::uint64_t>(fit, n));
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(capacity);
  for (auto& field : fields)
  {
    if (field.Array)
    {
      field.Array->SetNumberOfTuples(capacity);
    }
  }
  std::vector<unsigned char> record(stride);
  std::string text;
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (!records.empty())
    {
      std::memcpy(record.data(), records.data() + static_cast<std::size_t>(i) * stride, stride);
    }
    else if (data == "binary")
    {
      if (i >= capacity ||
        !in.read(reinterpret_cast<char*>(record.data()), static_cast<std::streamsize>(stride)))
        return fail("the binary PCD data ends after " + std::to_string(i) + " of " +
          std::to_string(n) + " points");
    }
    else
    {
      std::vector<std::string> words;
      while (words.empty())
      {
        if (i >= capacity || !std::getline(in, text))
          return fail("the ASCII PCD data ends after " + std::to_string(i) + " of " +
            std::to_string(n) + " points");
        ++lineNumber;
        words = Fields(text);
      }
      if (words.size() != valuesPerPoint)
        return bad(std::to_string(words.size()) + " values, the PCD fields have " +
          std::to_string(valuesPerPoint));
      std::size_t w = 0;
      for (const auto& field : fields)
      {
        for (int c = 0; c < field.Count; ++c, ++w)
        {
          // PCL writes "nan" for missing points, which strtod reads.
          if (!EncodeASCII(words[w], field, record.data() + field.Offset + c * field.Size))
            return bad("bad value '" + words[w].substr(0, 40) + "' of PCD field " + field.Name +
              " (" + field.TypeName() + (field.PackedColor ? " packed colour)" : ")"));
        }
      }
    }
    double xyz[3];
    for (const auto& field : fields)
    {
      const unsigned char* bytes = record.data() + field.Offset;
      if (field.Axis >= 0)
      {
        xyz[field.Axis] = DecodeBinary(bytes, field.Type, field.Size);
      }
      else if (field.PackedColor)
      {
        StorePackedColor(field.Array, i, bytes);
      }
      else if (field.Array)
      {
        const std::size_t size = static_cast<std::size_t>(field.Size) * field.Count;
        std::memcpy(static_cast<unsigned char*>(field.Array->GetVoidPointer(0)) +
            static_cast<std::size_t>(i) * size,
          bytes, size);
      }
    }
    pts->SetPoint(i, xyz);
  }
  // Data after the declared points means that the header does not describe
  // the data: an error rather than a silent misreading.
  bool trailing = false;
  if (data == "ascii")
  {
    while (!trailing && std::getline(in, text))
      trailing = !Fields(text).empty();
  }
  else
  {
    trailing = in.peek() != std::char_traits<char>::eof();
  }
  if (trailing)
    return fail("more PCD data than the " + std::to_string(n) + " points of the header");
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
  try
  {
    return ReadPCDFile(path, error);
  }
  catch (const std::exception& e) // out of memory, mostly: the readers never throw
  {
    error = path + ": cannot read the PCD file (" + e.what() + ")";
    return nullptr;
  }
}
} // namespace pcio
