// SPDX-License-Identifier: BSD-3-Clause
/**
 * Reading and writing the point-cloud formats scan users have, for the
 * asm_simplify example (not part of the ASM module):
 *
 * - PLY (vtkPLYReader/vtkPLYWriter) and VTP (VTK XML polydata),
 * - XYZ/CSV text (.xyz .txt .csv .pts .asc): one point per line, fields
 *   separated by white space, commas or semicolons; '#' starts a comment;
 *   lines before the first numeric line are headers (the last one, if it has
 *   as many fields as the data, names the columns); the columns named x, y, z
 *   (any case) or else the first three are the coordinates, every other
 *   column becomes a double point-data array,
 * - PCD (Point Cloud Library), DATA ascii, binary and binary_compressed
 *   (LZF; little endian): fields x y z plus others as point-data arrays of
 *   their own type; a packed rgb/rgba float field becomes an unsigned char
 *   RGB array.
 *
 * The readers return nullptr and set `error` to a one-line message when a
 * file cannot be read; they never throw.
 */
#ifndef PointCloudIO_h
#define PointCloudIO_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstddef>
#include <string>
#include <vector>

namespace pcio
{
/// Lower-case extension of `path` without the dot ("" if none).
std::string Extension(const std::string& path);

/// Reads XYZ/CSV text (see the file comment).
vtkSmartPointer<vtkPolyData> ReadText(const std::string& path, std::string& error);

/// Decompresses LZF data (the format of PCD's binary_compressed) that must
/// expand to exactly `size` bytes; false on corrupt input.
bool LZFDecompress(
  const std::vector<unsigned char>& in, std::size_t size, std::vector<unsigned char>& out);

/// Reads a PCD file, DATA ascii, binary or binary_compressed.
vtkSmartPointer<vtkPolyData> ReadPCD(const std::string& path, std::string& error);

/// Reads any supported format, chosen by extension; the result has one
/// vertex cell per point and at least one point.
vtkSmartPointer<vtkPolyData> ReadPointCloud(const std::string& path, std::string& error);

/// Writes `cloud` as binary PLY (.ply) or VTK XML polydata (.vtp).
bool WritePointCloud(vtkPolyData* cloud, const std::string& path, std::string& error);
} // namespace pcio

#endif
