// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the example's readers (PointCloudIO): small files written
// here, in the directory given as the first argument.
//   TestPointCloudIO <scratch-dir>
#include "PointCloudIO.h"
#include "TestCheck.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>

namespace
{
using exampletest::Dir;
using exampletest::Failures;
using exampletest::Write;

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

/// True if a read failed with an error containing `expected`; else prints what it got.
bool Fails(vtkPolyData* cloud, const std::string& error, const std::string& expected)
{
  if (cloud || error.find(expected) == std::string::npos)
  {
    std::cerr << "  expected an error with '" << expected << "', got "
              << (cloud ? "a cloud" : "'" + error + "'") << "\n";
    return false;
  }
  return true;
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
  cloud = pcio::ReadPCD(Write("compressed-more.pcd", file + "x"), error);
  CHECK(Fails(cloud, error, "more PCD data than the 3 points of the header"));
}

/// A PCD header with WIDTH and POINTS given as text (HEIGHT 1).
std::string PCDHeaderN(const std::string& fields, const std::string& sizes,
  const std::string& types, const std::string& counts, const std::string& n,
  const std::string& data)
{
  return "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes + "\nTYPE " + types + "\nCOUNT " +
    counts + "\nWIDTH " + n + "\nHEIGHT 1\nPOINTS " + n + "\nDATA " + data + "\n";
}

/// Malformed PCD headers and data (review A1-A5, A10, A11): errors, never a
/// crash, an exception or a huge allocation.
void TestPCDMalformed()
{
  std::string error;
  // A1: 12 * (2^62 + 1) wraps to 12 = the uncompressed size in 64 bits.
  std::string file =
    PCDHeaderN("x y z", "4 4 4", "F F F", "1 1 1", "4611686018427387905", "binary_compressed");
  Append<std::uint32_t>(file, 13);
  Append<std::uint32_t>(file, 12);
  file += LZFLiterals(std::string(12, '\0'));
  auto cloud = pcio::ReadPCD(Write("comp-wrap.pcd", file), error);
  CHECK(Fails(cloud, error, "not 4611686018427387905 points of 12 bytes"));
  // A2: POINTS far beyond the data, binary, ascii and compressed.
  file = PCDHeaderN("x y z", "4 4 4", "F F F", "1 1 1", "1000000000000", "binary");
  for (int i = 0; i < 7; ++i)
    Append<float>(file, 1.0f);
  cloud = pcio::ReadPCD(Write("huge-bin.pcd", file), error);
  CHECK(Fails(cloud, error, "ends after 2 of 1000000000000 points"));
  cloud = pcio::ReadPCD(
    Write("huge-ascii.pcd",
      PCDHeaderN("x y z", "4 4 4", "F F F", "1 1 1", "1000000000000", "ascii") + "1 2 3\n"),
    error);
  CHECK(Fails(cloud, error, "ends after 1 of 1000000000000 points"));
  file = PCDHeaderN("x y z", "4 4 4", "F F F", "1 1 1", "1", "binary_compressed");
  Append<std::uint32_t>(file, 0xFFFFFFF0u);
  Append<std::uint32_t>(file, 12);
  file += LZFLiterals(std::string(12, '\0'));
  cloud = pcio::ReadPCD(Write("comp-huge-csize.pcd", file), error);
  CHECK(Fails(cloud, error, "bad binary_compressed PCD data (truncated)"));
  file = PCDHeaderN("x y z", "4 4 4", "F F F", "1 1 1", "357913941", "binary_compressed");
  Append<std::uint32_t>(file, 2);
  Append<std::uint32_t>(file, 357913941u * 12u); // more than LZF can expand 2 bytes to
  file += LZFLiterals("a");
  cloud = pcio::ReadPCD(Write("comp-ratio.pcd", file), error);
  CHECK(
    Fails(cloud, error, "bad binary_compressed PCD data (more than LZF can expand 2 bytes to)"));
  // A point the data cannot hold (40 fields of 2^20 doubles in a short
  // file): refused before anything is allocated.
  {
    std::string names, sizes, types, counts;
    for (int f = 0; f < 40; ++f)
    {
      names += " f" + std::to_string(f), sizes += " 8", types += " F", counts += " 1048576";
    }
    for (const char* data : { "binary", "ascii" })
    {
      cloud = pcio::ReadPCD(Write(std::string("stride-") + data + ".pcd",
                              PCDHeaderN("x y z" + names, "4 4 4" + sizes, "F F F" + types,
                                "1 1 1" + counts, "1", data) +
                                "1 2 3\n"),
        error);
      CHECK(Fails(cloud, error, "cannot hold one point of"));
    }
  }
  // A3: absurd COUNT and SIZE.
  cloud = pcio::ReadPCD(
    Write("count-huge.pcd",
      PCDHeaderN("x y z i", "4 4 4 8", "F F F F", "1 1 1 1000000000", "1", "ascii") + "1 2 3 4\n"),
    error);
  CHECK(Fails(cloud, error, "bad PCD field i (SIZE 8, TYPE F, COUNT 1000000000"));
  cloud =
    pcio::ReadPCD(Write("count-overflow.pcd",
                    PCDHeaderN("x y z i", "4 4 4 8", "F F F F", "1 1 1 2147483647", "1", "binary") +
                      std::string(64, '\0')),
      error);
  CHECK(Fails(cloud, error, "bad PCD field i"));
  cloud = pcio::ReadPCD(
    Write("size-3.pcd", PCDHeaderN("x y z", "4 4 3", "F F F", "1 1 1", "1", "ascii") + "1 2 3\n"),
    error);
  CHECK(Fails(cloud, error, "bad PCD field z (SIZE 3"));
  cloud = pcio::ReadPCD(
    Write("count-0.pcd", PCDHeaderN("x y z", "4 4 4", "F F F", "1 0 1", "1", "ascii") + "1 2 3\n"),
    error);
  CHECK(Fails(cloud, error, "bad PCD field y"));
  // A4, A5: WIDTH x HEIGHT overflowing or not POINTS.
  std::string header = PCDHeaderN("x y z", "4 4 4", "F F F", "1 1 1", "1", "ascii");
  auto replace = [](std::string text, const std::string& from, const std::string& to) {
    return text.replace(text.find(from), from.size(), to);
  };
  cloud = pcio::ReadPCD(
    Write("wh-overflow.pcd",
      replace(replace(header, "WIDTH 1", "WIDTH 4611686018427387904"), "HEIGHT 1", "HEIGHT 4") +
        "1 2 3\n"),
    error);
  CHECK(Fails(cloud, error, "WIDTH x HEIGHT is too large"));
  cloud = pcio::ReadPCD(
    Write("wh-mismatch.pcd", replace(header, "HEIGHT 1", "HEIGHT 2") + "1 2 3\n4 5 6\n"), error);
  CHECK(Fails(cloud, error, "WIDTH x HEIGHT (1 x 2) is not POINTS (1)"));
  // Organized: WIDTH x HEIGHT = POINTS; POINTS alone; WIDTH alone.
  cloud = pcio::ReadPCD(
    Write("organized.pcd",
      replace(replace(replace(header, "HEIGHT 1", "HEIGHT 2"), "POINTS 1", "POINTS 2"), "WIDTH 1",
        "WIDTH 1") +
        "1 2 3\n4 5 6\n"),
    error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 2 && PointIs(cloud, 1, 4, 5, 6));
  cloud = pcio::ReadPCD(Write("no-width.pcd", replace(header, "WIDTH 1\n", "") + "1 2 3\n"), error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 1);
  cloud =
    pcio::ReadPCD(Write("no-points.pcd", replace(header, "POINTS 1\n", "") + "1 2 3\n"), error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 1);
  // A5: data after the declared points (ascii and binary) is an error;
  // blank lines after ascii data are not.
  cloud = pcio::ReadPCD(Write("extra.pcd", header + "1 2 3\n4 5 6\n"), error);
  CHECK(Fails(cloud, error, "more PCD data than the 1 points of the header"));
  cloud = pcio::ReadPCD(Write("blank-end.pcd", header + "1 2 3\n\n  \n"), error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 1);
  file = PCDHeaderN("x y z", "4 4 4", "F F F", "1 1 1", "1", "binary");
  for (int i = 0; i < 4; ++i)
    Append<float>(file, 1.0f);
  cloud = pcio::ReadPCD(Write("extra-bin.pcd", file), error);
  CHECK(Fails(cloud, error, "more PCD data than the 1 points"));
  // An ascii line with more values than the fields have.
  cloud = pcio::ReadPCD(Write("wide-line.pcd", header + "1 2 3 4\n"), error);
  CHECK(Fails(cloud, error, "wide-line.pcd:10: 4 values, the PCD fields have 3"));
  // A10: duplicate fields.
  cloud = pcio::ReadPCD(
    Write("dup-x.pcd",
      PCDHeaderN("x X y z", "4 4 4 4", "F F F F", "1 1 1 1", "1", "ascii") + "1 2 3 4\n"),
    error);
  CHECK(Fails(cloud, error, "the PCD field X appears twice"));
  cloud = pcio::ReadPCD(
    Write("dup-i.pcd",
      PCDHeaderN("x y z i i", "4 4 4 4 4", "F F F F F", "1 1 1 1 1", "1", "ascii") + "1 2 3 4 5\n"),
    error);
  CHECK(Fails(cloud, error, "the PCD field i appears twice"));
  cloud = pcio::ReadPCD(
    Write("dup-rgb.pcd",
      PCDHeaderN("x y z rgb RGBA", "4 4 4 4 4", "F F F F U", "1 1 1 1 1", "1", "ascii") +
        "1 2 3 4 5\n"),
    error);
  CHECK(Fails(cloud, error, "the PCD field RGBA appears twice"));
  // Fields differing only in case are distinct arrays; padding "_" may repeat.
  cloud = pcio::ReadPCD(
    Write("case.pcd",
      PCDHeaderN("x y z i I _ _", "4 4 4 4 4 1 1", "F F F F F U U", "1 1 1 1 1 1 1", "1", "ascii") +
        "1 2 3 4 5 0 0\n"),
    error);
  CHECK(cloud && cloud->GetPointData()->GetArray("i") && cloud->GetPointData()->GetArray("I") &&
    cloud->GetPointData()->GetArray("I")->GetTuple1(0) == 5);
  // A11: junk after numbers in the header.
  cloud =
    pcio::ReadPCD(Write("size-junk.pcd",
                    PCDHeaderN("x y z", "4abc 4 4", "F F F", "1 1 1", "1", "ascii") + "1 2 3\n"),
      error);
  CHECK(Fails(cloud, error, "bad PCD field x (SIZE 4abc"));
  cloud =
    pcio::ReadPCD(Write("type-junk.pcd",
                    PCDHeaderN("x y z", "4 4 4", "Float F F", "1 1 1", "1", "ascii") + "1 2 3\n"),
      error);
  CHECK(Fails(cloud, error, "bad PCD field x"));
  cloud = pcio::ReadPCD(
    Write("points-junk.pcd", replace(header, "POINTS 1", "POINTS 1.5") + "1 2 3\n"), error);
  CHECK(Fails(cloud, error, "points-junk.pcd:8: bad PCD points '1.5'"));
  cloud = pcio::ReadPCD(
    Write("width-neg.pcd", replace(header, "WIDTH 1", "WIDTH -1") + "1 2 3\n"), error);
  CHECK(Fails(cloud, error, "bad PCD width '-1'"));
  cloud = pcio::ReadPCD(
    Write("two-fields.pcd", replace(header, "SIZE", "FIELDS a\nSIZE") + "1 2 3\n"), error);
  CHECK(Fails(cloud, error, "a second fields line"));
}

/// ASCII PCD values checked against their type (review A6-A9).
void TestPCDValues()
{
  std::string error;
  // A subnormal double (an underflow of strtod) is a value; an overflow is not.
  auto tiny =
    pcio::ReadPCD(Write("f8-subnormal.pcd",
                    PCDHeaderN("x y z", "8 8 8", "F F F", "1 1 1", "1", "ascii") + "1e-310 2 3\n"),
      error);
  CHECK(tiny && tiny->GetPoint(0)[0] == 1e-310);
  tiny =
    pcio::ReadPCD(Write("f8-overflow.pcd",
                    PCDHeaderN("x y z", "8 8 8", "F F F", "1 1 1", "1", "ascii") + "1e400 2 3\n"),
      error);
  CHECK(!tiny);
  // A6: a packed colour written by PCL as an unsigned integer, TYPE F or U;
  // a float token gives the bits of the float; TYPE I may be negative.
  auto cloud =
    pcio::ReadPCD(Write("rgb-int.pcd",
                    PCDHeaderN("x y z rgb", "4 4 4 4", "F F F F", "1 1 1 1", "3", "ascii") +
                      "1 2 3 4294934528\n4 5 6 4278255360\n7 8 9 1.5\n"),
      error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 3);
  if (cloud)
  {
    vtkDataArray* rgb = cloud->GetPointData()->GetArray("RGB");
    CHECK(rgb && rgb->GetComponent(0, 0) == 255 && rgb->GetComponent(0, 1) == 128 &&
      rgb->GetComponent(0, 2) == 0);
    CHECK(rgb && rgb->GetComponent(1, 0) == 0 && rgb->GetComponent(1, 1) == 255 &&
      rgb->GetComponent(1, 2) == 0);
    CHECK(rgb && rgb->GetComponent(2, 0) == 0xC0 && rgb->GetComponent(2, 1) == 0 &&
      rgb->GetComponent(2, 2) == 0); // 1.5f is 0x3FC00000
  }
  cloud = pcio::ReadPCD(
    Write("rgb-i4.pcd",
      PCDHeaderN("x y z rgba", "4 4 4 4", "F F F I", "1 1 1 1", "1", "ascii") + "1 2 3 -32768\n"),
    error);
  CHECK(cloud && cloud->GetPointData()->GetArray("RGB") &&
    cloud->GetPointData()->GetArray("RGB")->GetComponent(0, 0) == 255 &&
    cloud->GetPointData()->GetArray("RGB")->GetComponent(0, 1) == 128);
  // A7: a packed colour out of range.
  const std::string rgbU = PCDHeaderN("x y z rgb", "4 4 4 4", "F F F U", "1 1 1 1", "1", "ascii");
  const std::string rgbF = PCDHeaderN("x y z rgb", "4 4 4 4", "F F F F", "1 1 1 1", "1", "ascii");
  cloud = pcio::ReadPCD(Write("rgb-neg.pcd", rgbU + "1 2 3 -5\n"), error);
  CHECK(Fails(cloud, error, "rgb-neg.pcd:10: bad value '-5' of PCD field rgb (U4 packed colour)"));
  cloud = pcio::ReadPCD(Write("rgb-big.pcd", rgbU + "1 2 3 4294967296\n"), error);
  CHECK(Fails(cloud, error, "bad value '4294967296' of PCD field rgb"));
  cloud = pcio::ReadPCD(Write("rgb-1e300.pcd", rgbF + "1 2 3 1e300\n"), error);
  CHECK(Fails(cloud, error, "bad value '1e300' of PCD field rgb"));
  // A8: integer fields out of range or not integers; the line is named.
  const std::string u1 = PCDHeaderN("x y z i", "4 4 4 1", "F F F U", "1 1 1 1", "2", "ascii");
  for (const char* bad : { "300", "-1", "nan", "1.5", "2x" })
  {
    cloud = pcio::ReadPCD(Write("u1.pcd", u1 + "0 0 0 255\n\n1 2 3 " + bad + "\n"), error);
    CHECK(
      Fails(cloud, error, "u1.pcd:12: bad value '" + std::string(bad) + "' of PCD field i (U1)"));
  }
  const std::string i2 = PCDHeaderN("x y z i", "4 4 4 2", "F F F I", "1 1 1 1", "1", "ascii");
  cloud = pcio::ReadPCD(Write("i2.pcd", i2 + "1 2 3 -32769\n"), error);
  CHECK(Fails(cloud, error, "bad value '-32769' of PCD field i (I2)"));
  cloud = pcio::ReadPCD(Write("i2-ok.pcd", i2 + "1 2 3 -32768\n"), error);
  CHECK(cloud && cloud->GetPointData()->GetArray("i")->GetTuple1(0) == -32768);
  cloud = pcio::ReadPCD(Write("f4-range.pcd", rgbF + "1e39 2 3 0\n"), error);
  CHECK(Fails(cloud, error, "bad value '1e39' of PCD field x (F4)"));
  // A9: 64-bit integers exactly, ascii and binary.
  const std::uint64_t big = (std::uint64_t(1) << 53) + 1;
  const std::int64_t negative = -static_cast<std::int64_t>(big);
  std::string file = PCDHeaderN("x y z id n", "4 4 4 8 8", "F F F U I", "1 1 1 1 1", "2", "ascii") +
    "1 2 3 " + std::to_string(big) + " " + std::to_string(negative) +
    "\n1 2 3 18446744073709551615 -9223372036854775808\n";
  for (int binary = 0; binary < 2; ++binary)
  {
    if (binary)
    {
      file = PCDHeaderN("x y z id n", "4 4 4 8 8", "F F F U I", "1 1 1 1 1", "2", "binary");
      for (int i = 0; i < 2; ++i)
      {
        for (int c = 0; c < 3; ++c)
          Append<float>(file, 1.0f);
        Append<std::uint64_t>(file, i ? ~std::uint64_t(0) : big);
        Append<std::int64_t>(file, i ? std::numeric_limits<std::int64_t>::min() : negative);
      }
    }
    cloud = pcio::ReadPCD(Write("int64.pcd", file), error);
    vtkDataArray* id = cloud ? cloud->GetPointData()->GetArray("id") : nullptr;
    vtkDataArray* n = cloud ? cloud->GetPointData()->GetArray("n") : nullptr;
    CHECK(id && id->GetDataTypeSize() == 8 && id->GetDataType() != VTK_DOUBLE && n &&
      n->GetDataTypeSize() == 8 && n->GetDataType() != VTK_DOUBLE);
    if (id && n && id->GetDataTypeSize() == 8 && n->GetDataTypeSize() == 8)
    {
      std::uint64_t ids[2];
      std::int64_t ns[2];
      std::memcpy(ids, id->GetVoidPointer(0), 16);
      std::memcpy(ns, n->GetVoidPointer(0), 16);
      CHECK(ids[0] == big && ids[1] == ~std::uint64_t(0));
      CHECK(ns[0] == negative && ns[1] == std::numeric_limits<std::int64_t>::min());
    }
  }
  cloud = pcio::ReadPCD(Write("u8-over.pcd",
                          PCDHeaderN("x y z id", "4 4 4 8", "F F F U", "1 1 1 1", "1", "ascii") +
                            "1 2 3 18446744073709551616\n"),
    error);
  CHECK(Fails(cloud, error, "bad value '18446744073709551616' of PCD field id (U8)"));
}

/// Leica .pts count lines, decimal commas with ';' (review C1, C2).
void TestTextFormats()
{
  std::string error;
  // C1: a .pts file starts with its point count, and each scan with its own.
  auto cloud = pcio::ReadPointCloud(Write("leica.pts",
                                      "3\n1 2 3 50 255 0 0\n4 5 6 50 0 255 0\n7 8 9 50 0 0 255\n"
                                      "1\n10 11 12 50 1 1 1\n"),
    error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 4 && PointIs(cloud, 3, 10, 11, 12));
  // ... but not in .xyz files.
  cloud = pcio::ReadPointCloud(Write("count.xyz", "1\n1 2 3\n"), error);
  CHECK(Fails(cloud, error, "count.xyz:1: a point needs at least 3 numbers"));
  // C2: ';' separates the fields, ',' is then a decimal comma.
  cloud = pcio::ReadPointCloud(Write("euro.csv", "x;y;z;w\n1,5;2,5;3,5;-0,25\n4;5;6;7\n"), error);
  CHECK(cloud && cloud->GetNumberOfPoints() == 2 && PointIs(cloud, 0, 1.5, 2.5, 3.5) &&
    PointIs(cloud, 1, 4, 5, 6));
  CHECK(cloud && cloud->GetPointData()->GetArray("w") &&
    Near(cloud->GetPointData()->GetArray("w")->GetTuple1(0), -0.25));
  // A header naming x y z that does not have as many fields as the data.
  cloud = pcio::ReadPointCloud(Write("euro-comma.csv", "x,y,z\n1,5,2,5,3,5\n"), error);
  CHECK(Fails(cloud, error, "euro-comma.csv:2: 6 numbers, but the header names 3 columns"));
  // A row of another width names its line.
  cloud = pcio::ReadPointCloud(Write("ragged.csv", "1;2;3\n4;5;6;7\n"), error);
  CHECK(Fails(cloud, error, "ragged.csv:2: expected 3 numbers"));
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
  TestPCDMalformed();
  TestPCDValues();
  TestTextFormats();
  TestDispatchAndRoundTrip();
  if (Failures)
  {
    std::cerr << Failures << " check(s) failed\n";
    return 1;
  }
  std::cout << "TestPointCloudIO: all checks passed\n";
  return 0;
}
