// SPDX-License-Identifier: BSD-3-Clause
// The PLY value types, shared by the PLY reader and writer (PLYFormat.cxx,
// PLYWriter.cxx) of the asm_simplify example.
#ifndef PLYFormatInternal_h
#define PLYFormatInternal_h

#include "vtkType.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace pcio
{
namespace detail
{
namespace ply
{
/// A header longer than this is refused (real headers are a few hundred bytes).
constexpr std::uint64_t MaxHeaderBytes = 1 << 20;
/// At most this many properties per element (each may become an array).
constexpr std::size_t MaxProperties = 4096;
/// The largest element count accepted (before comparing with the file size).
constexpr std::uint64_t MaxCount = static_cast<std::uint64_t>(VTK_ID_MAX);

enum class Type
{
  Char,
  UChar,
  Short,
  UShort,
  Int,
  UInt,
  Float,
  Double
};

inline bool ParseType(const std::string& text, Type& type)
{
  static const struct
  {
    const char* Name;
    const char* Alias;
    Type Value;
  } types[] = { { "char", "int8", Type::Char }, { "uchar", "uint8", Type::UChar },
    { "short", "int16", Type::Short }, { "ushort", "uint16", Type::UShort },
    { "int", "int32", Type::Int }, { "uint", "uint32", Type::UInt },
    { "float", "float32", Type::Float }, { "double", "float64", Type::Double } };
  for (const auto& t : types)
  {
    if (text == t.Name || text == t.Alias)
    {
      type = t.Value;
      return true;
    }
  }
  return false;
}

inline const char* Name(Type type)
{
  static const char* const names[] = { "char", "uchar", "short", "ushort", "int", "uint", "float",
    "double" };
  return names[static_cast<int>(type)];
}

inline std::size_t Size(Type type)
{
  static const std::size_t sizes[] = { 1, 1, 2, 2, 4, 4, 4, 8 };
  return sizes[static_cast<int>(type)];
}

inline int VtkType(Type type)
{
  static const int types[] = { VTK_SIGNED_CHAR, VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_UNSIGNED_SHORT,
    VTK_INT, VTK_UNSIGNED_INT, VTK_FLOAT, VTK_DOUBLE };
  return types[static_cast<int>(type)];
}

inline bool IsInteger(Type type)
{
  return type != Type::Float && type != Type::Double;
}

struct Property
{
  std::string Name;
  Type ValueType = Type::Float;
  bool IsList = false;
  Type CountType = Type::UChar;
};

struct Element
{
  std::string Name;
  std::uint64_t Count = 0;
  std::vector<Property> Properties;
};

enum class Format
{
  Ascii,
  BinaryLittle,
  BinaryBig
};

/// A failure with its message (thrown inside the reader, caught by ReadPLY).
struct Failure : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// What the header says, and where it ends (bytes and lines).
struct Header
{
  Format DataFormat = Format::Ascii;
  std::vector<Element> Elements;
  std::uint64_t Bytes = 0;
  std::uint64_t Lines = 0;
};

/// Reads the header of a PLY file from `in`, positioned at its start; throws
/// Failure("path: ...") if it is not a valid header (PLYHeader.cxx).
Header ReadHeader(std::istream& in, const std::string& path);

/// The words of a line, separated by blanks, tabs (and a CR before the LF).
std::vector<std::string> Tokens(const std::string& line);

/// Whether `value` (an integer) fits in the integer `type`.
inline bool InRange(double value, Type type)
{
  static const double limits[][2] = { { -128, 127 }, { 0, 255 }, { -32768, 32767 }, { 0, 65535 },
    { -2147483648.0, 2147483647.0 }, { 0, 4294967295.0 } };
  const auto* limit = limits[static_cast<int>(type)];
  return value >= limit[0] && value <= limit[1];
}

/// Coordinates of these types need double: float holds integers up to 2^24.
inline bool NeedsDouble(Type a, Type b, Type c)
{
  for (Type t : { a, b, c })
  {
    if (t == Type::Double || t == Type::Int || t == Type::UInt)
    {
      return true;
    }
  }
  return false;
}

inline bool HostIsLittleEndian()
{
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

/// f(T{}) with T the C++ type of `type`.
template <typename F>
auto WithType(Type type, F&& f)
{
  switch (type)
  {
    case Type::Char:
      return f(std::int8_t{});
    case Type::UChar:
      return f(std::uint8_t{});
    case Type::Short:
      return f(std::int16_t{});
    case Type::UShort:
      return f(std::uint16_t{});
    case Type::Int:
      return f(std::int32_t{});
    case Type::UInt:
      return f(std::uint32_t{});
    case Type::Float:
      return f(float{});
    case Type::Double:
    default:
      return f(double{});
  }
}

/// The value of `type` stored at `bytes` (byte order reversed if `swap`).
inline double Decode(const char* bytes, Type type, bool swap)
{
  char b[8];
  const std::size_t size = Size(type);
  for (std::size_t i = 0; i < size; ++i)
  {
    b[i] = bytes[swap ? size - 1 - i : i];
  }
  return WithType(type, [&b](auto tag) {
    decltype(tag) value;
    std::memcpy(&value, b, sizeof(value));
    return static_cast<double>(value);
  });
}

/// Stores `value` (representable in `type`) as little-endian bytes.
inline void EncodeLittle(double value, Type type, char* bytes)
{
  char b[8];
  WithType(type, [&b, value](auto tag) {
    const auto v = static_cast<decltype(tag)>(value);
    std::memcpy(b, &v, sizeof(v));
    return 0;
  });
  const std::size_t size = Size(type);
  const bool swap = !HostIsLittleEndian();
  for (std::size_t i = 0; i < size; ++i)
  {
    bytes[i] = b[swap ? size - 1 - i : i];
  }
}
} // namespace ply
} // namespace detail
} // namespace pcio

#endif
