// SPDX-License-Identifier: BSD-3-Clause
/**
 * Inputs of the benchmarks (Benchmarks/asm_*_benchmark): seeded synthetic
 * clouds generated in memory, and PLY scans read from disk.
 *
 * Synthetic clouds (all deterministic for a given seed, whatever the number
 * of threads: they are generated in fixed chunks of points, each with its
 * own seed):
 *  - "bumps": a unit sphere with 12 Gaussian bumps, sampled uniformly by
 *    area (rejection on the area element of the radial surface), with
 *    normal noise of 2e-4 (0.02 % of the radius); the speed inputs;
 *  - "spikes": a unit sphere with 12 sharp conical spikes (tips at radius
 *    1.6, along the icosahedron's vertices); features = the 12 tips;
 *  - "bracket": an L-shaped bracket (a CAD part: planar faces, creases);
 *    features = its 12 corners;
 *  - "terrain": a 1 x 1 height field with a gentle slope and 9 Gaussian
 *    peaks, sampled uniformly by area; features = the 9 summits.
 */
#ifndef asm_BenchmarkData_h
#define asm_BenchmarkData_h

#include "BenchmarkArgs.h" // ParseCount

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <string>
#include <vector>

namespace asmbench
{
/// One benchmark input: its points (float, as scans are stored) and, for
/// the synthetic shapes, the known feature points.
struct Input
{
  std::string Name;
  vtkSmartPointer<vtkPolyData> Data; ///< points only (no cells, no arrays) for synthetic clouds
  std::vector<double> Features;      ///< x y z of each known feature point (may be empty)
  std::int64_t NumberOfPoints() const { return this->Data ? this->Data->GetNumberOfPoints() : 0; }
};

/// The bumpy sphere with n points.
Input MakeBumpySphere(std::int64_t n, std::uint64_t seed = 1);
/// The sphere with 12 spikes, n points; features: the spike tips.
Input MakeSpikes(std::int64_t n, std::uint64_t seed = 2);
/// The L-bracket, n points; features: its 12 corners.
Input MakeBracket(std::int64_t n, std::uint64_t seed = 3);
/// The terrain with 9 peaks, n points; features: the summits.
Input MakeTerrain(std::int64_t n, std::uint64_t seed = 4);

/// A PLY file (vertices; name = file name without directory). Empty Data
/// (with a message on stderr) when it cannot be read.
Input ReadPLY(const std::string& path);

/// An input given on the command line: a path to a .ply file, or
/// "bumps:1M", "spikes:100k", "bracket:100k", "terrain:100k" (at most
/// MaxPointCount points). Empty Data (with a message on stderr naming the
/// input) when it cannot be read or made.
Input MakeInput(const std::string& spec);

/// Whether `spec` can be an input: a synthetic spec must name a shape and a
/// valid count (`error` says why not, naming the spec); a path is checked
/// when it is read (MakeInput). The programs check their inputs with it
/// before any work.
bool CheckInputSpec(const std::string& spec, std::string& error);

/// CheckInputSpec on `inputs` then `extra`: the first refusal's message, or
/// "" when every spec can be an input.
std::string CheckInputSpecs(
  const std::vector<std::string>& inputs, const std::vector<std::string>& extra);

/// Leaves out the points of `input` with a NaN or infinite coordinate (a
/// copy of the others replaces input.Data when there are any); returns how
/// many were left out.
std::int64_t DropNonFinite(Input& input);

/// The coordinates of a point set as x y z doubles.
std::vector<double> Coordinates(vtkPointSet* data);

/// Diagonal of the bounding box of the points x y z.
double BoundingBoxDiagonal(const std::vector<double>& xyz);
} // namespace asmbench

#endif
