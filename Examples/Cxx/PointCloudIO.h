// SPDX-License-Identifier: BSD-3-Clause
/**
 * Reading and writing the point-cloud formats scan users have, for the
 * asm_simplify example (not part of the ASM module):
 *
 * - PLY, read by ReadPLY and written by WritePLY (below; not VTK's
 *   vtkPLYReader/vtkPLYWriter, which crash on malformed files and drop
 *   arrays), and VTP (VTK XML polydata),
 * - XYZ/CSV text (.xyz .txt .csv .pts .asc): one point per line, fields
 *   separated by white space, commas or semicolons; in a line with a
 *   semicolon, only semicolons and white space separate and a comma is a
 *   decimal comma ("1,5;2,5;3,5"); '#' starts a comment; every data line
 *   has as many numbers as the first one (else an error naming the line);
 *   lines before the first numeric line are headers (the last one, if it has
 *   as many fields as the data, names the columns; one naming x, y and z
 *   but not as many fields as the data is an error); the columns named x, y, z
 *   (any case) or else the first three are the coordinates, every other
 *   column becomes a double point-data array; in .pts files (Leica) lines
 *   holding a single integer, the point count of the file or of a scan, are
 *   skipped,
 * - PCD (Point Cloud Library), DATA ascii, binary and binary_compressed
 *   (LZF; little endian): fields x y z plus others as point-data arrays of
 *   their own type (I8 and U8 exactly, as 64-bit integer arrays); a packed
 *   rgb/rgba field (SIZE 4, COUNT 1) becomes an unsigned char RGB array (in
 *   ascii, an unsigned integer value is the packed 0xAARRGGBB, as PCL writes
 *   it even for TYPE F; another value of a TYPE F field gives the bits of the
 *   float; TYPE I may also be a negative int32). The header is checked
 *   strictly: SIZE 1 2 4 8 (F: 4 8), TYPE F I U, COUNT 1 to 2^20, WIDTH,
 *   HEIGHT, POINTS whole numbers >= 0 without trailing junk; WIDTH x HEIGHT
 *   must be POINTS when both are given; each header line but VERSION and
 *   VIEWPOINT (not used) at most once; field
 *   names unique (x, y, z, rgb in any case, rgba counting as rgb; other names
 *   case-sensitive; the padding "_" may repeat). POINTS is checked against
 *   the size of the file before anything is allocated; ascii values must be
 *   values of their field's type (integers in range, floats within the float
 *   range; "nan" is allowed for F), one line per point holding exactly the
 *   values of the fields, else an error naming the line and field. Data after
 *   the declared points (non-blank lines, or bytes after binary data) is an
 *   error, not ignored as PCL does (it means the header does not describe
 *   the data).
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

/// Reads the `vertex` element of a PLY file, format ascii 1.0,
/// binary_little_endian 1.0 or binary_big_endian 1.0, wherever it is among
/// the elements (the others are skipped or, after it, not read; so are list
/// properties). Properties x, y, z are required; the points are double if
/// one of them is double, int or uint, else float. nx ny nz become a
/// "Normals" array (the normals); uchar red green blue (and alpha) an
/// unsigned char "RGB" (or "RGBA") array (the scalars); colours of other
/// types, and every other property, become one-component arrays named after
/// the property, of its own type. The header (at most 1 MiB, 4096
/// properties an element) is checked strictly, element counts against the
/// size of the file, ascii values against their type (one record a line);
/// a file shorter than its vertices (and the elements before them) need is
/// an error; the elements after the vertices (faces) are not read.
vtkSmartPointer<vtkPolyData> ReadPLY(const std::string& path, std::string& error);

/// Writes binary little-endian PLY: element vertex with x y z (float, or
/// double unless the points are float), nx ny nz (from the normals or a
/// 3-component "Normals" array, float or double), red green blue [alpha]
/// (uchar, from an unsigned char "RGB" or "RGBA" array), then every other
/// numeric point-data array, one property per component (NAME, or NAME_0,
/// NAME_1, ... for several components), of its own type; 64-bit integers are
/// written as int or uint when their values fit, else as double. Names get
/// '_' for blanks, and a suffix _2, _3, ... if taken. No faces.
bool WritePLY(vtkPolyData* cloud, const std::string& path, std::string& error);

/// Reads any supported format, chosen by extension; the result has one
/// vertex cell per point and at least one point.
vtkSmartPointer<vtkPolyData> ReadPointCloud(const std::string& path, std::string& error);

/// Writes `cloud` as binary PLY (.ply) or VTK XML polydata (.vtp).
bool WritePointCloud(vtkPolyData* cloud, const std::string& path, std::string& error);
} // namespace pcio

#endif
