// SPDX-License-Identifier: BSD-3-Clause
// Tests of the example's PLY reader and writer (ReadPLY, WritePLY): the
// malformed files that crashed or fooled vtkPLYReader, precision, arrays and
// round trips, and the scans of Testing/Data read as vtkPLYReader read them.
//   TestPLYFormat <scratch-dir> <Testing/Data>
#include "PointCloudIO.h"
#include "TestCheck.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
using exampletest::Dir;
using exampletest::Failures;
using exampletest::Write;
std::string DataDir = ".";

/// Appends the bytes of `value`, little endian (or big if `big`).
template <typename T>
void Put(std::string& out, T value, bool big = false)
{
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  const std::uint16_t one = 1;
  const bool hostLittle = *reinterpret_cast<const unsigned char*>(&one) == 1;
  for (std::size_t i = 0; i < sizeof(T); ++i)
  {
    out += bytes[big == hostLittle ? sizeof(T) - 1 - i : i];
  }
}

/// Reads `content` as `name`; the error (empty on success) goes to `error`.
vtkSmartPointer<vtkPolyData> Read(
  const std::string& name, const std::string& content, std::string& error)
{
  error.clear();
  return pcio::ReadPLY(Write(name, content), error);
}

bool Fails(const std::string& name, const std::string& content, const std::string& message)
{
  std::string error;
  const bool failed = !Read(name, content, error) && error.find(message) != std::string::npos;
  if (!failed)
  {
    std::cerr << name << ": expected an error with '" << message << "', got '" << error << "'\n";
  }
  return failed;
}

const std::string XYZ = "property float x\nproperty float y\nproperty float z\n";

std::string Ascii(int n, const std::string& properties, const std::string& data)
{
  return "ply\nformat ascii 1.0\ncomment test\nelement vertex " + std::to_string(n) + "\n" +
    properties + "end_header\n" + data;
}

/// A binary little-endian file of `n` float points (i, 2i, 3i) with a face element.
std::string Binary(int declared, int n)
{
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " +
    std::to_string(declared) + "\n" + XYZ +
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < n; ++i)
  {
    Put<float>(ply, i), Put<float>(ply, 2.f * i), Put<float>(ply, 3.f * i);
    ply += "\x01\x02\x03";
  }
  ply += '\x03';
  for (int i : { 0, 1, 99 })
  {
    Put<std::int32_t>(ply, i);
  }
  return ply;
}

// Each case crashed, hung or misread with vtkPLYReader (VTK 9.2).
void TestMalformed()
{
  std::string error;
  CHECK(Fails(
    "short-row.ply", Ascii(2, XYZ, "1.5 2.5 3.5\n4 5\n"), "line 10 (vertex 1): too few values"));
  CHECK(Fails("long-row.ply", Ascii(1, XYZ, "1 2 3 4\n"), "4 values, expected 3"));
  CHECK(Fails("junk.ply", Ascii(2, XYZ, "1 abc 3\n4 5 6\n"), "'abc' is not a float value"));
  CHECK(Fails("range.ply", Ascii(1, XYZ + "property uchar red\n", "1 2 3 300\n"),
    "'300' is not a uchar value"));
  CHECK(Fails("int.ply", Ascii(1, XYZ + "property int i\n", "1 2 3 1.5\n"), "not a int value"));
  CHECK(Fails("no-z.ply", Ascii(1, "property float x\nproperty float y\n", "1 2\n"),
    "the vertex element has no 'z' property"));
  CHECK(
    Fails("no-vertex.ply", "ply\nformat ascii 1.0\nelement point 1\n" + XYZ + "end_header\n1 2 3\n",
      "no 'vertex' element"));
  CHECK(Fails("no-end-header.ply", "ply\nformat ascii 1.0\nelement vertex 1\n" + XYZ + "1 2 3\n",
    "unknown keyword '1' (or no end_header line)"));
  CHECK(Fails("header-eof.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty fl",
    "the file ends inside the header"));
  CHECK(Fails("negative.ply", Ascii(-5, XYZ, "1 2 3\n"), "COUNT a non-negative integer"));
  CHECK(Fails("count-junk.ply",
    "ply\nformat ascii 1.0\nelement vertex 1x\n" + XYZ + "end_header\n1 2 3\n",
    "COUNT a non-negative integer"));
  CHECK(Fails("unknown-type.ply", Ascii(1, XYZ + "property int64 t\n", "1 2 3 4\n"),
    "expected 'property TYPE NAME'"));
  CHECK(Fails(
    "duplicate.ply", Ascii(1, "property float x\n" + XYZ, "1 1 2 3\n"), "a second property 'x'"));
  CHECK(Fails("magic.ply", "not a ply\n", "not a PLY file"));
  CHECK(Fails("two-formats.ply", "ply\nformat ascii 1.0\nformat ascii 1.0\nend_header\n",
    "a second format line"));
  CHECK(Fails("no-format.ply", "ply\nelement vertex 0\n" + XYZ + "end_header\n", "no format line"));
  CHECK(Fails("big-header.ply", "ply\n" + std::string(2 << 20, 'c'), "no end_header in the first"));
  CHECK(
    Fails("ascii-eof.ply", Ascii(2, XYZ, "1.5 2.5 3.5\n"), "premature end of file: read 1 of 2"));
  // 10 declared, 4 present: not 10 points with copies of the last one.
  CHECK(Fails("fewer.ply", Binary(10, 4), "declares 10 vertex records, but the "));
  // 2e8 and 1e12 declared in a tiny file: refused before allocating.
  const auto start = std::chrono::steady_clock::now();
  CHECK(Fails("huge.ply", Binary(200000000, 4), "declares 200000000 vertex"));
  CHECK(Fails("huger.ply",
    "ply\nformat ascii 1.0\nelement vertex 1000000000000\n" + XYZ + "end_header\n1 2 3\n",
    "declares 1000000000000 vertex records"));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));
  // Faces with bad indices or huge list lengths: the vertices are read, the
  // faces (after them) are not.
  auto cloud = Read("faces.ply", Binary(4, 4), error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 4 && cloud->GetNumberOfVerts() == 4);
  // Truncated anywhere in the header or vertices: an error, never a crash.
  const std::string whole = Binary(4, 4);
  const std::size_t faces = whole.size() - 13;
  for (std::size_t size = 0; size < whole.size(); ++size)
  {
    cloud = Read("truncated.ply", whole.substr(0, size), error);
    CHECK(size >= faces ? cloud && cloud->GetNumberOfPoints() == 4 : !cloud && !error.empty());
  }
  // A list in the vertex element whose length runs past the end.
  std::string list = "ply\nformat binary_little_endian 1.0\nelement vertex 1\n" + XYZ +
    "property list int float extra\nend_header\n";
  Put<float>(list, 1), Put<float>(list, 2), Put<float>(list, 3), Put<std::int32_t>(list, 1 << 30);
  CHECK(Fails("list-eof.ply", list, "runs past the end of the file"));
  list.resize(list.size() - 4);
  Put<std::int32_t>(list, -1);
  CHECK(Fails("list-negative.ply", list, "negative list length"));
}

// Valid files that vtkPLYReader crashed on (long names, many properties,
// an element before the vertices) or misread (precision, float colours).
void TestValid()
{
  std::string error;
  const std::string longName(5000, 'a');
  auto cloud =
    Read("long-name.ply", Ascii(1, XYZ + "property float " + longName + "\n", "1 2 3 4\n"), error);
  CHECK(cloud && cloud->GetPointData()->GetArray(longName.c_str()) &&
    cloud->GetPointData()->GetArray(longName.c_str())->GetTuple1(0) == 4);
  std::string properties = XYZ, row = "1 2 3";
  for (int i = 0; i < 3000; ++i)
  {
    properties += "property ushort p" + std::to_string(i) + "\n";
    row += " " + std::to_string(i);
  }
  cloud = Read("many.ply", Ascii(1, properties, row + "\n"), error);
  CHECK(cloud && cloud->GetPointData()->GetNumberOfArrays() == 3000 &&
    cloud->GetPointData()->GetArray("p2999")->GetTuple1(0) == 2999);

  // UTM-size coordinates: double (or int) stays double.
  cloud = Read("double.ply",
    Ascii(2, "property double x\nproperty double y\nproperty float z\n",
      "500000.123456 5400000.654321 1.5\n-1e-3 2 3\n"),
    error);
  CHECK(cloud && cloud->GetPoints()->GetDataType() == VTK_DOUBLE &&
    cloud->GetPoint(0)[0] == 500000.123456 && cloud->GetPoint(0)[1] == 5400000.654321);
  cloud = Read("int.ply",
    Ascii(
      1, "property int x\nproperty int y\nproperty int z\n", "16777217 -2147483648 2147483647\n"),
    error);
  CHECK(cloud && cloud->GetPoint(0)[0] == 16777217 && cloud->GetPoint(0)[1] == -2147483648.0);
  // Renamed properties do not replace arrays ("Normals" is taken by nx ny nz,
  // and "Normals_" by the property of that name: freed while still written to).
  for (const char* taken : { "Normals", "RGB" })
  {
    const std::string t = taken;
    const std::string extra = t == "Normals"
      ? "property float nx\nproperty float ny\nproperty float nz\n"
      : "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    cloud = Read("taken-" + t + ".ply",
      Ascii(1, XYZ + extra + "property float " + t + "_\nproperty float " + t + "\n",
        "1 2 3 0 0 1 7 8\n"),
      error);
    CHECK(cloud && cloud->GetPointData()->GetNumberOfArrays() == 3 &&
      cloud->GetPointData()->GetArray((t + "_").c_str())->GetTuple1(0) == 7 &&
      cloud->GetPointData()->GetArray((t + "__").c_str())->GetTuple1(0) == 8);
  }
  cloud = Read("float.ply", Ascii(1, XYZ, "0.1 2 3\n"), error);
  CHECK(cloud && cloud->GetPoints()->GetDataType() == VTK_FLOAT);

  // Float colours stay float arrays (not RGB 0 0 1); uchar ones are RGB(A).
  cloud = Read("float-rgb.ply",
    Ascii(1, XYZ + "property float red\nproperty float green\nproperty float blue\n",
      "1 2 3 0.5 0.25 1.0\n"),
    error);
  CHECK(cloud && !cloud->GetPointData()->GetArray("RGB") &&
    cloud->GetPointData()->GetArray("red")->GetTuple1(0) == 0.5 &&
    cloud->GetPointData()->GetArray("green")->GetTuple1(0) == 0.25);
  cloud = Read("rgba.ply",
    Ascii(1,
      XYZ + "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n",
      "1 2 3 10 20 30 40\n"),
    error);
  vtkDataArray* rgba = cloud ? cloud->GetPointData()->GetScalars() : nullptr;
  CHECK(rgba && std::string(rgba->GetName()) == "RGBA" && rgba->GetComponent(0, 3) == 40);

  // An element (with lists) before the vertices, a list among the vertex
  // properties, CRLF line ends; the same in all three formats.
  const std::string header = "element material 2\nproperty list uchar int ids\n"
                             "property float shine\nelement vertex 2\nproperty double x\n"
                             "property list uchar float extra\nproperty float y\nproperty short z\n"
                             "property float nx\nproperty float ny\nproperty float nz\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string ascii = "ply\r\nformat ascii 1.0\r\n" + header + "2 7 8 0.5\n0 1.5\n" +
    "0.125 1 9 -1 2 0 0 1\r\n\n2.5 0 3 300 1 0 0\n3 0 1 2\n";
  for (bool big : { false, true })
  {
    std::string binary =
      std::string("ply\nformat binary_") + (big ? "big" : "little") + "_endian 1.0\n" + header;
    binary += '\x02', Put<std::int32_t>(binary, 7, big), Put<std::int32_t>(binary, 8, big);
    Put<float>(binary, 0.5f, big), binary += '\0', Put<float>(binary, 1.5f, big);
    Put<double>(binary, 0.125, big), binary += '\x01', Put<float>(binary, 9, big);
    Put<float>(binary, -1, big), Put<std::int16_t>(binary, 2, big);
    Put<float>(binary, 0, big), Put<float>(binary, 0, big), Put<float>(binary, 1, big);
    Put<double>(binary, 2.5, big), binary += '\0', Put<float>(binary, 3, big);
    Put<std::int16_t>(binary, 300, big);
    Put<float>(binary, 1, big), Put<float>(binary, 0, big), Put<float>(binary, 0, big);
    for (const std::string* content : { &ascii, static_cast<const std::string*>(&binary) })
    {
      cloud = Read("before.ply", *content, error);
      CHECK(cloud && cloud->GetNumberOfPoints() == 2 && cloud->GetNumberOfVerts() == 2);
      if (cloud)
      {
        CHECK(cloud->GetPoints()->GetDataType() == VTK_DOUBLE);
        CHECK(cloud->GetPoint(0)[0] == 0.125 && cloud->GetPoint(0)[1] == -1 &&
          cloud->GetPoint(1)[2] == 300);
        vtkDataArray* normals = cloud->GetPointData()->GetNormals();
        CHECK(normals && normals->GetComponent(1, 0) == 1 && normals->GetComponent(0, 2) == 1);
        CHECK(cloud->GetPointData()->GetNumberOfArrays() == 1); // the list is skipped
      }
    }
  }
}

vtkSmartPointer<vtkPolyData> Cloud(int type)
{
  vtkNew<vtkPoints> points;
  points->SetDataType(type);
  points->InsertNextPoint(500000.123456, 5400000.654321, 12.5);
  points->InsertNextPoint(-1, 0.1, 3);
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  return cloud.Get();
}

// WritePLY keeps the points' precision and every numeric array.
void TestRoundTrip()
{
  std::string error;
  auto cloud = Cloud(VTK_DOUBLE);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->InsertNextTuple3(0, 0, 1), normals->InsertNextTuple3(0.6, 0.8, 0);
  cloud->GetPointData()->SetNormals(normals);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  rgb->InsertNextTuple3(255, 128, 0), rgb->InsertNextTuple3(1, 2, 3);
  cloud->GetPointData()->AddArray(rgb);
  vtkNew<vtkDoubleArray> curvature;
  curvature->SetName("Mean Curvature");
  curvature->InsertNextValue(0.1), curvature->InsertNextValue(-1e300);
  cloud->GetPointData()->AddArray(curvature);
  vtkNew<vtkUnsignedCharArray> key;
  key->SetName("KeyPoint");
  key->InsertNextValue(1), key->InsertNextValue(0);
  cloud->GetPointData()->AddArray(key);
  vtkNew<vtkIdTypeArray> size, big;
  size->SetName("ClusterSize");
  size->InsertNextValue(7), size->InsertNextValue(-2);
  big->SetName("x"); // a taken name, and a value beyond int32
  big->InsertNextValue(1), big->InsertNextValue(vtkIdType(1) << 40);
  cloud->GetPointData()->AddArray(size);
  cloud->GetPointData()->AddArray(big);
  vtkNew<vtkFloatArray> pair;
  pair->SetName("uv");
  pair->SetNumberOfComponents(2);
  pair->InsertNextTuple2(0.25, 0.5), pair->InsertNextTuple2(1, 2);
  cloud->GetPointData()->AddArray(pair);
  const std::string path = Dir + "/round-trip.ply";
  CHECK(pcio::WritePointCloud(cloud, path, error));
  auto back = pcio::ReadPointCloud(path, error);
  CHECK(back && back->GetNumberOfPoints() == 2 && back->GetNumberOfVerts() == 2);
  if (!back)
  {
    return;
  }
  vtkPointData* data = back->GetPointData();
  CHECK(back->GetPoints()->GetDataType() == VTK_DOUBLE);
  CHECK(back->GetPoint(0)[0] == 500000.123456 && back->GetPoint(0)[1] == 5400000.654321);
  CHECK(data->GetNormals() && data->GetNormals()->GetDataType() == VTK_FLOAT &&
    data->GetNormals()->GetComponent(1, 1) == 0.8f);
  CHECK(data->GetScalars() && std::string(data->GetScalars()->GetName()) == "RGB" &&
    data->GetScalars()->GetComponent(0, 1) == 128 && data->GetScalars()->GetComponent(1, 2) == 3);
  vtkDataArray* c = data->GetArray("Mean_Curvature");
  CHECK(c && c->GetDataType() == VTK_DOUBLE && c->GetTuple1(0) == 0.1 && c->GetTuple1(1) == -1e300);
  vtkDataArray* k = data->GetArray("KeyPoint");
  CHECK(k && k->GetDataType() == VTK_UNSIGNED_CHAR && k->GetTuple1(0) == 1);
  vtkDataArray* s = data->GetArray("ClusterSize");
  CHECK(s && s->GetDataType() == VTK_INT && s->GetTuple1(1) == -2);
  vtkDataArray* x = data->GetArray("x_2");
  CHECK(x && x->GetDataType() == VTK_DOUBLE && x->GetTuple1(1) == std::ldexp(1.0, 40));
  CHECK(data->GetArray("uv_0") && data->GetArray("uv_1")->GetTuple1(1) == 2);
  CHECK(data->GetNumberOfArrays() == 8);

  // Float points are written as float; an empty cloud as an empty file.
  CHECK(pcio::WritePLY(Cloud(VTK_FLOAT), path, error));
  back = pcio::ReadPLY(path, error);
  CHECK(back && back->GetPoints()->GetDataType() == VTK_FLOAT &&
    back->GetPoint(1)[1] == static_cast<double>(0.1f));
  vtkNew<vtkPolyData> empty;
  CHECK(pcio::WritePLY(empty, path, error));
  back = pcio::ReadPLY(path, error);
  CHECK(back && back->GetNumberOfPoints() == 0);
  CHECK(!pcio::WritePLY(empty, Dir + "/no-such-dir/x.ply", error) && !error.empty());

  // Short normals and colours are not written (they were read past their end).
  cloud = Cloud(VTK_FLOAT);
  vtkNew<vtkFloatArray> shortNormals;
  shortNormals->SetName("Normals");
  shortNormals->SetNumberOfComponents(3);
  shortNormals->InsertNextTuple3(0, 0, 1);
  cloud->GetPointData()->SetNormals(shortNormals);
  vtkNew<vtkUnsignedCharArray> shortRGB;
  shortRGB->SetName("RGB");
  shortRGB->SetNumberOfComponents(3);
  shortRGB->InsertNextTuple3(1, 2, 3);
  cloud->GetPointData()->AddArray(shortRGB);
  CHECK(pcio::WritePLY(cloud, path, error));
  back = pcio::ReadPLY(path, error);
  CHECK(back && back->GetNumberOfPoints() == 2 && back->GetPointData()->GetNumberOfArrays() == 0);
  // Names cut to 200 characters (vtkPLYReader misreads lines of ~4090).
  cloud = Cloud(VTK_FLOAT);
  vtkNew<vtkFloatArray> longNamed;
  longNamed->SetName(std::string(4100, 'n').c_str());
  longNamed->InsertNextValue(1), longNamed->InsertNextValue(2);
  cloud->GetPointData()->AddArray(longNamed);
  CHECK(pcio::WritePLY(cloud, path, error));
  back = pcio::ReadPLY(path, error);
  CHECK(back && back->GetPointData()->GetArray(std::string(200, 'n').c_str()));
  // More properties than ReadPLY accepts: an error, no file ReadPLY would refuse.
  vtkNew<vtkFloatArray> wide;
  wide->SetName("wide");
  wide->SetNumberOfComponents(5000);
  wide->SetNumberOfTuples(2);
  wide->Fill(0);
  cloud->GetPointData()->AddArray(wide);
  CHECK(
    !pcio::WritePLY(cloud, path, error) && error.find("more than the 4096") != std::string::npos);
}

// The scans read exactly as vtkPLYReader read them (sums printed by a
// program that read them with vtkPLYReader, same order of summation).
void TestData()
{
  const struct
  {
    const char* Name;
    vtkIdType N;
    double Sum[3];
    const char* Array;
    double ArraySum;
  } files[] = {
    { "bunny.ply", 35947, { -961.93848469303748, 3422.7317016422749, 321.62192779389454 }, nullptr,
      0 },
    { "fandisk.ply", 7229, { 18199.368908461787, 107859.29209709167, -6660.8132145745685 }, nullptr,
      0 },
    { "kitten.ply", 5210, { -68.928915565891657, -112.5683919742296, -168.42901495921069 },
      "Normals", 30.00276751110141 },
    { "laurana.ply", 27861, { -541394.29898745532, -4548124.8204673557, -44652500.576904297 },
      "RGB", 11480979 },
  };
  for (const auto& file : files)
  {
    std::string error;
    auto cloud = pcio::ReadPointCloud(DataDir + "/" + file.Name, error);
    CHECK(cloud && cloud->GetNumberOfPoints() == file.N && cloud->GetNumberOfVerts() == file.N);
    if (!cloud)
    {
      continue;
    }
    CHECK(cloud->GetPoints()->GetDataType() == VTK_FLOAT);
    double sum[3] = { 0, 0, 0 };
    for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        sum[c] += cloud->GetPoint(i)[c];
      }
    }
    CHECK(sum[0] == file.Sum[0] && sum[1] == file.Sum[1] && sum[2] == file.Sum[2]);
    CHECK(cloud->GetPointData()->GetNumberOfArrays() == (file.Array ? 1 : 0));
    if (file.Array)
    {
      vtkDataArray* array = cloud->GetPointData()->GetArray(file.Array);
      double arraySum = 0;
      for (vtkIdType i = 0; array && i < array->GetNumberOfTuples(); ++i)
      {
        for (int c = 0; c < array->GetNumberOfComponents(); ++c)
        {
          arraySum += array->GetComponent(i, c);
        }
      }
      CHECK(array && arraySum == file.ArraySum);
      CHECK(array == cloud->GetPointData()->GetNormals() ||
        array == cloud->GetPointData()->GetScalars());
    }
  }
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc > 1)
  {
    Dir = argv[1];
  }
  if (argc > 2)
  {
    DataDir = argv[2];
  }
  TestMalformed();
  TestValid();
  TestRoundTrip();
  TestData();
  if (Failures > 0)
  {
    std::cerr << Failures << " check(s) failed\n";
    return 1;
  }
  std::cout << "all PLY checks passed\n";
  return 0;
}
