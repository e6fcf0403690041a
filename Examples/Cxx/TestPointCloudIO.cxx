// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the example's readers (PointCloudIO): small files written
// here, in the directory given as the first argument.
//   TestPointCloudIO <scratch-dir>
#include "PointCloudIO.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
int Failures = 0;
std::string Dir = ".";

#define CHECK(condition)                                                                           \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": CHECK failed: " #condition "\n";              \
      ++Failures;                                                                                  \
    }                                                                                              \
  } while (false)

std::string Write(const std::string& name, const std::string& content)
{
  const std::string path = Dir + "/" + name;
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

bool Near(double a, double b)
{
  return std::abs(a - b) < 1e-6;
}

bool PointIs(vtkPolyData* cloud, vtkIdType i, double x, double y, double z)
{
  double p[3];
  cloud->GetPoint(i, p);
  return Near(p[0], x) && Near(p[1], y) && Near(p[2], z);
}

void TestText()
{
  std::string error;
  // Named columns in any order and case; separators , ; and blanks; comments.
  auto cloud = pcio::ReadPointCloud(Write("named.csv",
                                      "# exported by a scanner\n"
                                      "intensity,Z,Y,X\n"
                                      "0.5, 3, 2, 1\n"
                                      "\n"
                                      "0.25;6;5;4  # trailing comment\n"),
    error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 2 && cloud->GetNumberOfVerts() == 2);
  if (cloud)
  {
    CHECK(PointIs(cloud, 0, 1, 2, 3) && PointIs(cloud, 1, 4, 5, 6));
    vtkDataArray* intensity = cloud->GetPointData()->GetArray("intensity");
    CHECK(intensity && Near(intensity->GetTuple1(1), 0.25));
  }
  // No header: the first three columns, extra ones named Column<i>.
  cloud = pcio::ReadText(Write("plain.xyz", "1 2 3 7 8\n4 5 6 9 10\n"), error);
  CHECK(cloud && PointIs(cloud, 1, 4, 5, 6));
  CHECK(cloud && cloud->GetPointData()->GetArray("Column4") &&
    Near(cloud->GetPointData()->GetArray("Column4")->GetTuple1(0), 8));
  // A bad row names its line.
  cloud = pcio::ReadText(Write("bad.xyz", "x y z\n1 2 3\n4 five 6\n"), error);
  CHECK(!cloud && error.find("bad.xyz:3:") != std::string::npos);
  cloud = pcio::ReadText(Write("short.xyz", "1 2\n"), error);
  CHECK(!cloud && error.find("at least 3 numbers") != std::string::npos);
  cloud = pcio::ReadText(Write("empty.txt", "# nothing\n"), error);
  CHECK(!cloud && error.find("no points") != std::string::npos);
}

std::string PCDHeader(const std::string& fields, const std::string& sizes, const std::string& types,
  const std::string& counts, int n, const std::string& data)
{
  return "# .PCD v0.7\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes + "\nTYPE " + types +
    "\nCOUNT " + counts + "\nWIDTH " + std::to_string(n) +
    "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(n) + "\nDATA " + data + "\n";
}

template <typename T>
void Append(std::string& bytes, T value)
{
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

float PackedColor(std::uint32_t r, std::uint32_t g, std::uint32_t b)
{
  const std::uint32_t packed = (r << 16) | (g << 8) | b;
  float f;
  std::memcpy(&f, &packed, 4);
  return f;
}

void TestPCD()
{
  std::string error;
  // ASCII with an integer-packed rgb and a 3-component field.
  auto cloud = pcio::ReadPointCloud(
    Write("a.pcd",
      PCDHeader("x y z rgb normal", "4 4 4 4 4", "F F F U F", "1 1 1 1 3", 2, "ascii") + "1 2 3 " +
        std::to_string((10u << 16) | (20u << 8) | 30u) + " 0 0 1\n" + "4 5 6 0 1 0 0\n"),
    error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 2);
  if (cloud)
  {
    CHECK(PointIs(cloud, 0, 1, 2, 3) && PointIs(cloud, 1, 4, 5, 6));
    vtkDataArray* rgb = cloud->GetPointData()->GetArray("RGB");
    CHECK(rgb && rgb->GetNumberOfComponents() == 3 && rgb->GetComponent(0, 0) == 10 &&
      rgb->GetComponent(0, 1) == 20 && rgb->GetComponent(0, 2) == 30);
    vtkDataArray* normal = cloud->GetPointData()->GetArray("normal");
    CHECK(normal && normal->GetNumberOfComponents() == 3 && normal->GetComponent(1, 0) == 1);
  }

  // Binary: float x y z, float-packed rgb, uint16 intensity, 2 bytes padding "_".
  std::string bytes =
    PCDHeader("x y z rgb intensity _", "4 4 4 4 2 1", "F F F F U U", "1 1 1 1 1 2", 3, "binary");
  const std::string header = bytes;
  for (int i = 0; i < 3; ++i)
  {
    Append<float>(bytes, 1.5f * i);
    Append<float>(bytes, -2.0f * i);
    Append<float>(bytes, 0.25f);
    Append<float>(bytes, PackedColor(255, 128, static_cast<std::uint32_t>(i)));
    Append<std::uint16_t>(bytes, static_cast<std::uint16_t>(1000 + i));
    Append<std::uint16_t>(bytes, 0xBEEF);
  }
  cloud = pcio::ReadPCD(Write("b.pcd", bytes), error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 3);
  if (cloud)
  {
    CHECK(PointIs(cloud, 2, 3.0, -4.0, 0.25));
    vtkDataArray* intensity = cloud->GetPointData()->GetArray("intensity");
    CHECK(intensity && intensity->GetDataType() == VTK_UNSIGNED_SHORT &&
      intensity->GetTuple1(2) == 1002);
    vtkDataArray* rgb = cloud->GetPointData()->GetArray("RGB");
    CHECK(rgb && rgb->GetComponent(2, 0) == 255 && rgb->GetComponent(2, 1) == 128 &&
      rgb->GetComponent(2, 2) == 2);
    CHECK(cloud->GetPointData()->GetArray("_") == nullptr);
  }
  // Truncated binary data, unsupported compression, no coordinates, not a PCD.
  cloud = pcio::ReadPCD(Write("truncated.pcd", bytes.substr(0, bytes.size() - 5)), error);
  CHECK(!cloud && error.find("ends after 2 of 3 points") != std::string::npos);
  cloud =
    pcio::ReadPCD(Write("c.pcd", PCDHeader("x y z", "4 4 4", "F F F", "1 1 1", 1, "lzma")), error);
  CHECK(!cloud && error.find("PCD DATA lzma is not supported") != std::string::npos);
  cloud = pcio::ReadPCD(
    Write("noxyz.pcd", PCDHeader("a b c", "4 4 4", "F F F", "1 1 1", 1, "ascii") + "1 2 3\n"),
    error);
  CHECK(!cloud && error.find("no x y z") != std::string::npos);
  cloud = pcio::ReadPCD(Write("text.pcd", "hello world\n"), error);
  CHECK(!cloud && error.find("not a PCD file") != std::string::npos);
  cloud = pcio::ReadPCD(
    Write("short.pcd", PCDHeader("x y z", "4 4 4", "F F F", "1 1 1", 2, "ascii") + "1 2 3\n"),
    error);
  CHECK(!cloud && error.find("ends after 1 of 2") != std::string::npos);
}

/// LZF with literal runs only (valid LZF, no compression), for the tests.
std::string LZFLiterals(const std::string& raw)
{
  std::string out;
  for (std::size_t i = 0; i < raw.size(); i += 32)
  {
    const std::size_t run = std::min<std::size_t>(32, raw.size() - i);
    out += static_cast<char>(run - 1);
    out += raw.substr(i, run);
  }
  return out;
}

void TestCompressedPCD()
{
  // A literal run "abc", then a back reference of 6 bytes at distance 3.
  const std::vector<unsigned char> lzf = { 2, 'a', 'b', 'c', (4 << 5) | 0, 2 };
  std::vector<unsigned char> out;
  CHECK(pcio::LZFDecompress(lzf, 9, out) && std::string(out.begin(), out.end()) == "abcabcabc");
  CHECK(!pcio::LZFDecompress(lzf, 8, out)); // wrong size
  CHECK(!pcio::LZFDecompress(
    { 2, 'a', 'b', 'c', (4 << 5) | 0, 5 }, 9, out)); // reference before the start
  CHECK(!pcio::LZFDecompress({ 5, 'a' }, 6, out));   // truncated literal

  // 3 points, fields x y z (F4) and intensity (U2), stored field after field.
  std::string fieldMajor;
  for (int axis = 0; axis < 3; ++axis)
    for (int i = 0; i < 3; ++i)
      Append<float>(fieldMajor, static_cast<float>(10 * i + axis));
  for (int i = 0; i < 3; ++i)
    Append<std::uint16_t>(fieldMajor, static_cast<std::uint16_t>(500 + i));
  const std::string packed = LZFLiterals(fieldMajor);
  std::string file =
    PCDHeader("x y z intensity", "4 4 4 2", "F F F U", "1 1 1 1", 3, "binary_compressed");
  Append<std::uint32_t>(file, static_cast<std::uint32_t>(packed.size()));
  Append<std::uint32_t>(file, static_cast<std::uint32_t>(fieldMajor.size()));
  file += packed;
  std::string error;
  auto cloud = pcio::ReadPointCloud(Write("compressed.pcd", file), error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 3);
  if (cloud)
  {
    CHECK(PointIs(cloud, 0, 0, 1, 2) && PointIs(cloud, 2, 20, 21, 22));
    vtkDataArray* intensity = cloud->GetPointData()->GetArray("intensity");
    CHECK(intensity && intensity->GetTuple1(1) == 501);
  }
  cloud = pcio::ReadPCD(Write("compressed-cut.pcd", file.substr(0, file.size() - 4)), error);
  CHECK(!cloud && error.find("bad binary_compressed") != std::string::npos);
}

void TestDispatchAndRoundTrip()
{
  std::string error;
  CHECK(
    !pcio::ReadPointCloud(Dir + "/does-not-exist.ply", error) && error.find("cannot open") == 0);
  CHECK(!pcio::ReadPointCloud(Write("x.obj", "v 1 2 3\n"), error) &&
    error.find("unknown extension 'obj'") != std::string::npos);
  CHECK(!pcio::ReadPointCloud(Write("garbage.ply", "not a ply file\n"), error) && !error.empty());
  CHECK(!pcio::ReadPointCloud(Write("garbage.vtp", "<nope/>\n"), error) && !error.empty());

  auto cloud = pcio::ReadText(Write("rt.xyz", "x y z w\n1 2 3 4\n5 6 7 8\n"), error);
  CHECK(cloud != nullptr);
  if (!cloud)
    return;
  CHECK(pcio::WritePointCloud(cloud, Dir + "/rt.vtp", error));
  auto back = pcio::ReadPointCloud(Dir + "/rt.vtp", error);
  CHECK(back && back->GetNumberOfPoints() == 2 && PointIs(back, 1, 5, 6, 7) &&
    back->GetPointData()->GetArray("w") && back->GetNumberOfVerts() == 2);
  CHECK(pcio::WritePointCloud(cloud, Dir + "/rt.ply", error));
  back = pcio::ReadPointCloud(Dir + "/rt.ply", error);
  CHECK(back && back->GetNumberOfPoints() == 2 && PointIs(back, 0, 1, 2, 3));
  CHECK(!pcio::WritePointCloud(cloud, Dir + "/rt.obj", error));
  CHECK(!pcio::WritePointCloud(cloud, Dir + "/no/such/dir/rt.vtp", error));
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc > 1)
  {
    Dir = argv[1];
  }
  TestText();
  TestPCD();
  TestCompressedPCD();
  TestDispatchAndRoundTrip();
  if (Failures)
  {
    std::cerr << Failures << " check(s) failed\n";
    return 1;
  }
  std::cout << "TestPointCloudIO: all checks passed\n";
  return 0;
}
