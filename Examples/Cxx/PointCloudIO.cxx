// SPDX-License-Identifier: BSD-3-Clause
#include "PointCloudIO.h"
#include "PointCloudIOInternal.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cctype>
#include <exception>
#include <fstream>
#include <vector>

namespace pcio
{
using detail::Fields;
using detail::Lower;
using detail::MakeCloud;
using detail::ParseDouble;

namespace
{
/// The fields of a text line: split at white space, commas and semicolons,
/// or, if the line has a semicolon, at semicolons and white space only (a
/// comma is then a decimal comma, see ParseRow).
std::vector<std::string> TextFields(const std::string& line)
{
  if (line.find(';') == std::string::npos)
  {
    return Fields(line);
  }
  std::vector<std::string> fields;
  std::string current;
  for (char c : line + ";")
  {
    if (c == ';' || std::isspace(static_cast<unsigned char>(c)))
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
  return fields;
}

/// Parses every field of `fields` as a double, ',' read as '.' (a decimal
/// comma: only lines with ';' have fields with commas); false if one is not
/// a number.
bool ParseRow(const std::vector<std::string>& fields, std::vector<double>& row)
{
  row.resize(fields.size());
  for (std::size_t i = 0; i < fields.size(); ++i)
  {
    std::string text = fields[i];
    std::replace(text.begin(), text.end(), ',', '.');
    if (!ParseDouble(text, row[i]))
    {
      return false;
    }
  }
  return true;
}

/// True if `names` has x, y and z (in any case).
bool NamesXYZ(const std::vector<std::string>& names)
{
  int found = 0;
  for (const auto& name : names)
  {
    const std::string lower = Lower(name);
    found |= lower == "x" ? 1 : lower == "y" ? 2 : lower == "z" ? 4 : 0;
  }
  return found == 7;
}

/// Turns VTK error events of a reader or writer into a message.
class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    if (this->Message.empty() && data)
    {
      // "ERROR: In file, line N\nvtkClass (0x...): text" -> "text"
      this->Message = static_cast<const char*>(data);
      const auto object = this->Message.find("): ");
      if (object != std::string::npos)
      {
        this->Message.erase(0, object + 3);
      }
      while (
        !this->Message.empty() && std::isspace(static_cast<unsigned char>(this->Message.back())))
      {
        this->Message.pop_back();
      }
    }
  }
  std::string Message;
};
} // namespace

std::string Extension(const std::string& path)
{
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return "";
  }
  return Lower(path.substr(dot + 1));
}

vtkSmartPointer<vtkPolyData> ReadText(const std::string& path, std::string& error)
{
  std::ifstream in(path);
  if (!in)
  {
    error = "cannot open " + path;
    return nullptr;
  }
  std::vector<std::string> header; // fields of the last header line
  std::vector<double> row;
  std::vector<std::vector<double>> columns;
  std::size_t width = 0;
  std::string line;
  const bool leica = Extension(path) == "pts"; // with point-count lines
  for (std::size_t lineNumber = 1; std::getline(in, line); ++lineNumber)
  {
    const auto hash = line.find('#');
    if (hash != std::string::npos)
    {
      line.erase(hash);
    }
    const auto fields = TextFields(line);
    if (fields.empty())
    {
      continue;
    }
    const bool numeric = ParseRow(fields, row);
    long long count = 0;
    if (leica && fields.size() == 1 && detail::StrictInt64(fields[0], count))
    {
      continue; // the number of points of the file or of the next scan
    }
    if (width == 0)
    {
      if (!numeric)
      {
        header = fields; // a header line, before the data
        continue;
      }
      if (row.size() < 3)
      {
        error =
          path + ":" + std::to_string(lineNumber) + ": a point needs at least 3 numbers (x y z)";
        return nullptr;
      }
      width = row.size();
      columns.assign(width, {});
      if (header.size() != width && NamesXYZ(header))
      {
        error = path + ":" + std::to_string(lineNumber) + ": " + std::to_string(width) +
          " numbers, but the header names " + std::to_string(header.size()) + " columns";
        return nullptr;
      }
    }
    if (!numeric || row.size() != width)
    {
      error = path + ":" + std::to_string(lineNumber) + ": expected " + std::to_string(width) +
        " numbers like the first data line";
      return nullptr;
    }
    for (std::size_t c = 0; c < width; ++c)
    {
      columns[c].push_back(row[c]);
    }
  }
  if (width == 0)
  {
    error = "no points in " + path;
    return nullptr;
  }
  std::vector<std::string> names(width);
  for (std::size_t c = 0; c < width; ++c)
  {
    names[c] = header.size() == width ? header[c] : "Column" + std::to_string(c);
  }
  // Coordinates: the columns named x, y, z, else the first three.
  std::size_t xyz[3] = { 0, 1, 2 };
  for (int axis = 0; axis < 3; ++axis)
  {
    const auto it = std::find_if(names.begin(), names.end(), [axis](const std::string& n) {
      return Lower(n) == std::string(1, static_cast<char>('x' + axis));
    });
    if (it == names.end())
    {
      xyz[0] = 0, xyz[1] = 1, xyz[2] = 2;
      break;
    }
    xyz[axis] = static_cast<std::size_t>(it - names.begin());
  }
  const auto n = static_cast<vtkIdType>(columns[0].size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    points->SetPoint(i, columns[xyz[0]][i], columns[xyz[1]][i], columns[xyz[2]][i]);
  }
  auto cloud = MakeCloud(points);
  for (std::size_t c = 0; c < width; ++c)
  {
    if (c == xyz[0] || c == xyz[1] || c == xyz[2])
    {
      continue;
    }
    vtkNew<vtkDoubleArray> array;
    array->SetName(names[c].c_str());
    array->SetNumberOfTuples(n);
    std::copy(columns[c].begin(), columns[c].end(), array->GetPointer(0));
    cloud->GetPointData()->AddArray(array);
  }
  return cloud;
}

vtkSmartPointer<vtkPolyData> ReadPointCloud(const std::string& path, std::string& error)
{
  if (!std::ifstream(path))
  {
    error = "cannot open " + path;
    return nullptr;
  }
  const std::string ext = Extension(path);
  vtkSmartPointer<vtkPolyData> cloud;
  if (ext == "ply")
  {
    cloud = ReadPLY(path, error); // not vtkPLYReader: see PLYFormat.cxx
  }
  else if (ext == "vtp")
  {
    vtkNew<ErrorCatcher> errors;
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    // The reader's messages become `error`; the executive's "returned
    // failure" dumps and the reader's warnings are not printed.
    vtkNew<ErrorCatcher> quiet;
    reader->AddObserver(vtkCommand::ErrorEvent, errors);
    reader->AddObserver(vtkCommand::WarningEvent, quiet);
    reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, quiet);
    reader->Update();
    cloud = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
    if (!errors->Message.empty())
    {
      error = path + ": " + errors->Message;
      return nullptr;
    }
    if (cloud && cloud->GetNumberOfPoints() > 0 && cloud->GetNumberOfCells() == 0)
    {
      vtkNew<vtkPolyData> withVertices;
      withVertices->ShallowCopy(MakeCloud(cloud->GetPoints()));
      withVertices->GetPointData()->ShallowCopy(cloud->GetPointData());
      cloud = withVertices;
    }
  }
  else if (ext == "xyz" || ext == "txt" || ext == "csv" || ext == "pts" || ext == "asc")
  {
    try // (out of memory on a huge text file: an error, as the other readers give)
    {
      cloud = ReadText(path, error);
    }
    catch (const std::exception& e)
    {
      error = path + ": " + e.what();
      return nullptr;
    }
  }
  else if (ext == "pcd")
  {
    cloud = ReadPCD(path, error);
  }
  else
  {
    error = path + ": unknown extension '" + ext + "' (known: ply vtp xyz txt csv pts asc pcd)";
    return nullptr;
  }
  if (cloud && cloud->GetNumberOfPoints() == 0)
  {
    error = "no points read from " + path + " (not a valid ." + ext + " file, or an empty one)";
    return nullptr;
  }
  return cloud;
}

bool WritePointCloud(vtkPolyData* cloud, const std::string& path, std::string& error)
{
  const std::string ext = Extension(path);
  vtkNew<ErrorCatcher> errors, quiet;
  int ok = 0;
  if (ext == "ply")
  {
    return WritePLY(cloud, path, error); // all the arrays, unlike vtkPLYWriter
  }
  else if (ext == "vtp")
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetDataModeToBinary();
    writer->SetInputData(cloud);
    writer->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, quiet);
    ok = writer->Write();
  }
  else
  {
    error = path + ": write .ply or .vtp";
    return false;
  }
  if (!ok || !errors->Message.empty())
  {
    error = "cannot write " + path + (errors->Message.empty() ? "" : ": " + errors->Message);
    return false;
  }
  return true;
}
} // namespace pcio
