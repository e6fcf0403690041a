// SPDX-License-Identifier: BSD-3-Clause
// The header of a PLY file, parsed strictly and with limits, for the PLY
// reader of the asm_simplify example (PLYFormat.cxx).
#include "PLYFormatInternal.h"

#include <set>

namespace pcio
{
namespace detail
{
namespace ply
{
namespace
{
bool Blank(char c)
{
  return c == ' ' || c == '\t' || c == '\r';
}
} // namespace

std::vector<std::string> Tokens(const std::string& line)
{
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < line.size())
  {
    while (i < line.size() && Blank(line[i]))
    {
      ++i;
    }
    const std::size_t start = i;
    while (i < line.size() && !Blank(line[i]))
    {
      ++i;
    }
    if (i > start)
    {
      tokens.push_back(line.substr(start, i - start));
    }
  }
  return tokens;
}

namespace
{
/// A non-negative decimal integer, digits only, at most `max`.
bool ParseCount(const std::string& text, std::uint64_t max, std::uint64_t& value)
{
  if (text.empty() || text.size() > 19)
  {
    return false;
  }
  value = 0;
  for (char c : text)
  {
    if (c < '0' || c > '9')
    {
      return false;
    }
    value = value * 10 + static_cast<std::uint64_t>(c - '0');
  }
  return value <= max;
}

/// Reads lines of the header and fails with the line number.
struct HeaderReader
{
  std::istream& In;
  const std::string& Path;
  Header Result;

  bool Line(std::string& line);
  [[noreturn]] void Fail(const std::string& message) const
  {
    throw Failure(this->Path + ": " + message);
  }
  [[noreturn]] void FailHeader(const std::string& message) const
  {
    this->Fail("header line " + std::to_string(this->Result.Lines) + ": " + message);
  }
};

/// One header line without its line end; false at the end of the file.
bool HeaderReader::Line(std::string& line)
{
  line.clear();
  ++this->Result.Lines;
  while (true)
  {
    const int c = this->In.get();
    if (c == std::char_traits<char>::eof())
    {
      return false;
    }
    if (++this->Result.Bytes > MaxHeaderBytes)
    {
      this->Fail("no end_header in the first " + std::to_string(MaxHeaderBytes) + " bytes");
    }
    if (c == '\n')
    {
      break;
    }
    line += static_cast<char>(c);
  }
  if (!line.empty() && line.back() == '\r')
  {
    line.pop_back();
  }
  return true;
}
} // namespace

Header ReadHeader(std::istream& in, const std::string& path)
{
  HeaderReader reader{ in, path, {} };
  std::string line;
  if (!reader.Line(line) || Tokens(line) != std::vector<std::string>{ "ply" })
  {
    reader.Fail("not a PLY file (the first line is not 'ply')");
  }
  bool formatSeen = false;
  std::set<std::string> elementNames, propertyNames; // (of the last element)
  while (true)
  {
    if (!reader.Line(line))
    {
      reader.Fail("the file ends inside the header (no end_header line)");
    }
    const auto tokens = Tokens(line);
    if (tokens.empty())
    {
      continue;
    }
    const std::string& keyword = tokens[0];
    if (keyword == "comment" || keyword == "obj_info")
    {
      continue;
    }
    if (keyword == "end_header" && tokens.size() == 1)
    {
      break;
    }
    if (keyword == "format")
    {
      if (formatSeen)
      {
        reader.FailHeader("a second format line");
      }
      formatSeen = true;
      if (tokens.size() != 3 || tokens[2] != "1.0")
      {
        reader.FailHeader("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      }
      if (tokens[1] == "ascii")
      {
        reader.Result.DataFormat = Format::Ascii;
      }
      else if (tokens[1] == "binary_little_endian")
      {
        reader.Result.DataFormat = Format::BinaryLittle;
      }
      else if (tokens[1] == "binary_big_endian")
      {
        reader.Result.DataFormat = Format::BinaryBig;
      }
      else
      {
        reader.FailHeader("unknown format '" + tokens[1] + "'");
      }
    }
    else if (keyword == "element")
    {
      Element element;
      if (tokens.size() != 3 || !ParseCount(tokens[2], MaxCount, element.Count))
      {
        reader.FailHeader("expected 'element NAME COUNT' with COUNT a non-negative integer");
      }
      element.Name = tokens[1];
      if (!elementNames.insert(element.Name).second)
      {
        reader.FailHeader("a second element '" + element.Name + "'");
      }
      propertyNames.clear();
      reader.Result.Elements.push_back(element);
    }
    else if (keyword == "property")
    {
      if (reader.Result.Elements.empty())
      {
        reader.FailHeader("a property before the first element");
      }
      Property property;
      bool ok = false;
      if (tokens.size() == 3)
      {
        ok = ParseType(tokens[1], property.ValueType);
        property.Name = tokens[2];
      }
      else if (tokens.size() == 5 && tokens[1] == "list")
      {
        property.IsList = true;
        ok = ParseType(tokens[2], property.CountType) && ParseType(tokens[3], property.ValueType) &&
          IsInteger(property.CountType);
        property.Name = tokens[4];
      }
      if (!ok)
      {
        reader.FailHeader("expected 'property TYPE NAME' or 'property list INTTYPE TYPE NAME' "
                          "with TYPE one of char uchar short ushort int uint float double "
                          "(or int8 uint8 int16 uint16 int32 uint32 float32 float64)");
      }
      if (propertyNames.size() == MaxProperties)
      {
        reader.FailHeader("more than " + std::to_string(MaxProperties) +
          " properties in element '" + reader.Result.Elements.back().Name + "'");
      }
      if (!propertyNames.insert(property.Name).second)
      {
        reader.FailHeader("a second property '" + property.Name + "'");
      }
      reader.Result.Elements.back().Properties.push_back(property);
    }
    else
    {
      reader.FailHeader("unknown keyword '" + keyword.substr(0, 40) + "' (or no end_header line)");
    }
  }
  if (!formatSeen)
  {
    reader.Fail("no format line in the header");
  }
  return reader.Result;
}
} // namespace ply
} // namespace detail
} // namespace pcio
