// SPDX-License-Identifier: BSD-3-Clause
/**
 * The simplifiers the benchmarks compare, each configured to give (about) the
 * same output count N_s on a given input:
 *  - vtkASMSimplify in each configuration of AsmConfigurations() (exact count);
 *  - vtkVoxelGrid, its cubic leaf size searched (not timed) so that its output
 *    count is within 1 % of N_s (the closest reachable count otherwise);
 *  - vtkMaskPoints: random sampling (Vitter, exact count) and spatially
 *    stratified random sampling (Woodring et al.);
 *  - when built with CGAL (ASM_BENCHMARK_HAVE_CGAL): grid_simplify_point_set
 *    (cell size searched) and hierarchy_simplify_point_set (cluster size,
 *    then maximum variation, searched), both within 1 % of N_s.
 */
#ifndef asm_BenchmarkMethods_h
#define asm_BenchmarkMethods_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

class vtkASMSimplify;

namespace asmbench
{
/// The pipeline of vtkASMSimplify.
enum class AsmMode
{
  Paper,            ///< the paper's literal pipeline
  FeaturePreserving ///< the feature-preserving default (issue 7)
};

/// One configuration of vtkASMSimplify: THE table of what is benchmarked.
struct AsmConfig
{
  std::string Name;
  AsmMode Mode;
  bool Curvature;       ///< GenerateCurvature
  std::string Settings; ///< more properties, "Name=value,..." (ApplyAsmSettings)
  /// A user's variant (--asm): measured and reported, but not one of the
  /// methods the targets compare the modes with.
  bool Variant = false;
};

/// Both modes, curvature off and on.
const std::vector<AsmConfig>& AsmConfigurations();

/// Sets properties of `filter` from "Name=value,..." (e.g.
/// "FillHoles=0,FinalLloydIterations=1"): any numeric or on/off property of
/// vtkASMSimplify (AsmSettingNames), booleans as 0/1, Mode as paper or
/// feature. An unknown name, a value that is not a number or one the
/// property clamps to another value is an error (returned in `error`; that
/// property keeps its value, and no later setting is applied).
bool ApplyAsmSettings(vtkASMSimplify* filter, const std::string& settings, std::string& error);

/// The property names ApplyAsmSettings knows, comma separated.
std::string AsmSettingNames();

/// The names of the peers' methods (Method::Name of MakeVoxelGrid,
/// MakeMaskPoints, MakeCgalGrid, MakeCgalHierarchy).
const std::vector<std::string>& PeerMethodNames();

/// A variant from "NAME:SETTINGS" (--asm): the default mode (or the paper
/// mode with Mode=paper) with those settings, curvature off. NAME must not
/// be the name of a standard configuration or of a peer (PeerMethodNames).
bool ParseAsmVariant(const std::string& spec, AsmConfig& config, std::string& error);

/// The programs' --asm: ParseAsmVariant(spec) appended to `configs`; false
/// (the error printed to stderr) when the variant is refused, or when a
/// configuration of that name is in `configs` already.
bool AddAsmVariant(const std::string& spec, std::vector<AsmConfig>& configs);

/// Whether this build's vtkASMSimplify can run `mode`: PAPER always (before
/// the Mode property exists, the one pipeline is the paper's), the others only
/// when vtkASMSimplify has SetModeToPaper()/SetModeToFeaturePreserving().
bool AsmModeAvailable(AsmMode mode);

/// One run of a method: output count, wall time of the simplification
/// alone (seconds), and the output's memory (bytes).
struct RunResult
{
  vtkIdType Count = 0;
  double Seconds = 0.0;
  double OutputBytes = 0.0;
  std::vector<double> Xyz; ///< output points, when asked for
};

/// A simplifier configured for one input and one N_s.
struct Method
{
  std::string Name;
  bool IsASM = false;
  std::string Note; ///< how it was driven to N_s (cell size, ...)
  /// Runs once; fills RunResult::Xyz when `keepPoints`.
  std::function<RunResult(bool keepPoints)> Run;
  /// Random methods only (empty for the others): reseeds the generator the
  /// next Run draws from (seed >= 1), so that a draw is reproducible.
  std::function<void(unsigned seed)> Reseed;
};

Method MakeAsm(vtkPolyData* input, vtkIdType target, const AsmConfig& config);
/// vtkVoxelGrid allocates memory for every bin, empty or not (its locator's
/// offsets and its bin map, 12-16 bytes per bin), and the products overflow
/// past 2^31 bins: the benchmarks never give it more than MaxVoxelBins bins
/// (2^28, about 4 GB); an N_s it cannot reach within them is marked "*".
constexpr double MaxVoxelBins = 268435456.0;
/// Whether divisions d are all >= 1 and their product is <= MaxVoxelBins.
bool DivisionsFit(const std::array<int, 3>& d);
/// Divisions of the box `bounds` (xmin xmax ymin ymax zmin zmax) for a cubic
/// cell of edge s: round(range / s) per axis, each in [1, 2^20], the cell
/// grown until the product fits MaxVoxelBins; s not finite or <= 0 gives the finest / coarsest
/// grid.
std::array<int, 3> VoxelDivisions(const double bounds[6], double s);

/// Leaf size searched with the real filter (an empty Run when no grid within MaxVoxelBins works) so
/// that the count is within 1 % of target.
Method MakeVoxelGrid(vtkPolyData* input, vtkIdType target);
/// randomModeType: 1 random sampling, 2 spatially stratified (vtkMaskPoints).
Method MakeMaskPoints(vtkPolyData* input, vtkIdType target, int randomModeType);

/// Whether the CGAL peers are built in.
bool HaveCGAL();
/// CGAL peers (empty Run when !HaveCGAL()).
Method MakeCgalGrid(vtkPolyData* input, vtkIdType target);
Method MakeCgalHierarchy(vtkPolyData* input, vtkIdType target);

/// Searches a scale s > 0 such that count(s) (decreasing in s, about as
/// s^-exponent) is within `tolerance` (relative) of target; returns the best
/// s found in at most maxEvaluations calls (and its count in `found`), then,
/// if still outside the tolerance, up to `probes` more calls at s * (1 +/-
/// 0.25 % k) around the best (grid counts jump, and are not monotone).
double SearchScale(const std::function<vtkIdType(double)>& count, vtkIdType target, double initial,
  double exponent, double tolerance, int maxEvaluations, vtkIdType& found, int probes = 0);

/// Wall-clock seconds since an arbitrary origin.
double Now();
} // namespace asmbench

#endif
