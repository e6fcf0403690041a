// SPDX-License-Identifier: BSD-3-Clause
#include "PointCloudIO.h"
#include "PointCloudIOInternal.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cctype>
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
/// Parses every field of `fields` as a double; false if one is not a number.
bool ParseRow(const std::vector<std::string>& fields, std::vector<double>& row)
{
  row.resize(fields.size());
  for (std::size_t i = 0; i < fields.size(); ++i)
  {
    if (!ParseDouble(fields[i], row[i]))
    {
      return false;
    }
  }
  return true;
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
  for (std::size_t lineNumber = 1; std::getline(in, line); ++lineNumber)
  {
    const auto hash = line.find('#');
    if (hash != std::string::npos)
    {
      line.erase(hash);
    }
    const auto fields = Fields(line);
    if (fields.empty())
    {
      continue;
    }
    const bool numeric = ParseRow(fields, row);
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
  if (ext == "ply" || ext == "vtp")
  {
    vtkNew<ErrorCatcher> errors;
    vtkSmartPointer<vtkAlgorithm> reader;
    if (ext == "ply")
    {
      auto ply = vtkSmartPointer<vtkPLYReader>::New();
      ply->SetFileName(path.c_str());
      reader = ply;
    }
    else
    {
      auto xml = vtkSmartPointer<vtkXMLPolyDataReader>::New();
      xml->SetFileName(path.c_str());
      reader = xml;
    }
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
    cloud = ReadText(path, error);
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
    vtkNew<vtkPLYWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetFileTypeToBinary();
    writer->SetInputData(cloud);
    writer->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, quiet);
    ok = writer->Write();
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
