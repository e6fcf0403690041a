// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target of the ASM core: asmcore::Simplify (and, for small
// clouds, asmcore::CompareClouds) on point sets and parameters decoded from
// the fuzz input, checking the invariants every run must meet:
//
// - no crash, no sanitizer report (ASan + UBSan), no abort;
// - exactly min(N_s, finite points) samples;
// - positions and normals finite; every position inside the bounding box of
//   the finite input points (a centroid of some of them); snapped positions
//   are input points exactly;
// - the samples' member lists partition the finite point ids, and each
//   sample's representative is one of the members that place it;
// - AKPE <= MKPE, both finite;
// - the same result when the core's parallel loops are cut into single
//   iterations run in reverse order (what vtkSMPTools may do);
// - CompareClouds: finite, non-negative figures, one error per point.
// - EstimateCurvature at the samples (the filter's curvature arrays), with 6
//   and 20 neighbours: min(k, points) neighbours each; where a quadric was
//   fitted a finite mean curvature, else 0; a surface variation in
//   [0, 1/3] and a unit normal; the same bits with the reversed single
//   steps.
//
// Input layout (missing bytes read as 0):
//   header (16 bytes), then points of 7 bytes: a flag byte and 3 x int16.
//   header[0]   mode bits: 0 snap, 1 surface-variation weight, 2-3 degenerate
//               shape (none, coplanar, collinear, one point), 4 float
//               coordinates, 5 input normals, 6 paper mode (else
//               feature-preserving), 7 the feature-preserving options of
//               header[12-15] (else their defaults); new core modes go in
//               ApplyModeBits, one line each
//   header[1-2] N_s (uint16)              header[3] cell size (0: automatic)
//   header[4]   alpha (-0.05 .. 0.55)     header[5] error tolerance (0: off)
//   header[6]   samples per cell (0..32)  header[7] random seed (and the
//               comparison's plane neighbours and distance measure)
//   header[8]   extent scale 1e-30..1e30  header[9] offset from the origin, up to 1e15
//   header[10]  link factor               header[11] curvature weight
//   header[12-15] with mode bit 7: the feature-preserving mode's options,
//               each over the range its vtkASMSimplify property accepts, 0
//               bits giving the default (ApplyFeatureOptions)
//   flag % 16   0 NaN, 1 +Inf, 2 -Inf (coordinate flag/16 % 3), 3 the previous
//               point again, 4 an earlier point again, 5 far outlier (x 1e12),
//               6 tiny (x 1e-300), else a plain point.
#include "Core/Curvature.h"
#include "Core/Grid.h"
#include "Core/Metrics.h"
#include "Core/Neighbors.h"
#include "Core/Simplify.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace
{
using asmcore::Index;

constexpr std::size_t HeaderSize = 16;
constexpr std::size_t PointSize = 7;
constexpr std::size_t MaxPoints = 4096;

#define FUZZ_CHECK(condition)                                                                      \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::fprintf(stderr, "invariant violated: %s (%s:%d)\n", #condition, __FILE__, __LINE__);    \
      std::abort();                                                                                \
    }                                                                                              \
  } while (false)

struct Reader
{
  const std::uint8_t* Data;
  std::size_t Size;
  std::uint8_t Byte(std::size_t i) const { return i < this->Size ? this->Data[i] : 0; }
  std::int16_t Int16(std::size_t i) const
  {
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(this->Byte(i)) |
      static_cast<std::uint16_t>(this->Byte(i + 1) << 8));
  }
};

// The core's options selected by the mode byte. A new mode of
// SimplifyParameters is one more line here (bit 7 is free).
void ApplyModeBits(std::uint8_t mode, asmcore::SimplifyParameters& p)
{
  p.Snap = (mode & 1) != 0;
  p.Weight = (mode & 2) ? asmcore::WeightMode::SurfaceVariation : asmcore::WeightMode::Uniform;
  p.Mode = (mode & 64) ? asmcore::SimplifyMode::Paper : asmcore::SimplifyMode::FeaturePreserving;
}

// The feature-preserving mode's options (SimplifyParameters' defaults where
// the bits are 0), over the values vtkASMSimplify's properties accept:
//   b12: each set bit switches one fix off: 0 FillHoles, 1 CoverEveryCell,
//        2 ValidateKeyPoints, 3 InPlaneKeyPoints, 4 ExtremeKeyPoints,
//        5 InputPointSamples, 6 BoundSnappedHoles, 7 ReserveFreeSample
//   b13: bits 0-1 LloydIterations {4, 0, 1, 20}, 2-3 CrossCellIterations
//        {1, 0, 2, 4}, 4-5 FinalLloydIterations {2, 0, 1, 8}, 6
//        SparseCellKeyPoints off, 7 CoveringRounds 2
//   b14: bits 0-3 BudgetExponent (0: 0.5, else (v - 1) / 14 in [0, 1]),
//        4-7 FeatureSamplesPerCell (0: 4, 15: -1 (SamplesPerCell), else
//        2^(v - 7): 1/64 .. 128)
//   b15: bits 0-3 HoleFillFraction (0: 0.02, else v / 30, up to 0.5), 4-5
//        LloydVariationWeight {0.75, 0, 4, 100}, 6-7 VariationBudget and
//        VariationCap {(1, 4), (0, 4), (10, 0: no cap), (1, 0.5)}
void ApplyFeatureOptions(const std::uint8_t b[4], asmcore::SimplifyParameters& p)
{
  p.FillHoles = !(b[0] & 1);
  p.CoverEveryCell = !(b[0] & 2);
  p.ValidateKeyPoints = !(b[0] & 4);
  p.InPlaneKeyPoints = !(b[0] & 8);
  p.ExtremeKeyPoints = !(b[0] & 16);
  p.InputPointSamples = !(b[0] & 32);
  p.BoundSnappedHoles = !(b[0] & 64);
  p.ReserveFreeSample = !(b[0] & 128);
  static const int lloyd[4] = { 4, 0, 1, 20 }, cross[4] = { 1, 0, 2, 4 }, final[4] = { 2, 0, 1, 8 };
  p.LloydIterations = lloyd[b[1] & 3];
  p.CrossCellIterations = cross[(b[1] >> 2) & 3];
  p.FinalLloydIterations = final[(b[1] >> 4) & 3];
  p.SparseCellKeyPoints = !(b[1] & 64);
  p.CoveringRounds = (b[1] & 128) ? 2 : 0;
  const int exponent = b[2] & 15, perCell = b[2] >> 4;
  p.BudgetExponent = exponent == 0 ? 0.5 : (exponent - 1) / 14.0;
  p.FeatureSamplesPerCell = perCell == 0 ? 4.0
    : perCell == 15                      ? -1.0
                                         : std::ldexp(1.0, perCell - 7);
  const int fraction = b[3] & 15;
  p.HoleFillFraction = fraction == 0 ? 0.02 : fraction / 30.0;
  static const double lloydWeight[4] = { 0.75, 0.0, 4.0, 100.0 };
  static const double budget[4][2] = { { 1.0, 4.0 }, { 0.0, 4.0 }, { 10.0, 0.0 }, { 1.0, 0.5 } };
  p.LloydVariationWeight = lloydWeight[(b[3] >> 4) & 3];
  p.VariationBudget = budget[b[3] >> 6][0];
  p.VariationCap = budget[b[3] >> 6][1];
}

struct Case
{
  std::vector<double> Xyz;
  std::vector<double> Normals;
  asmcore::SimplifyParameters Parameters;
  bool UseNormals = false;
};

Case Decode(const Reader& in)
{
  Case k;
  const std::uint8_t mode = in.Byte(0);
  asmcore::SimplifyParameters& p = k.Parameters;
  ApplyModeBits(mode, p);
  if (mode & 128)
  {
    const std::uint8_t options[4] = { in.Byte(12), in.Byte(13), in.Byte(14), in.Byte(15) };
    ApplyFeatureOptions(options, p);
  }
  const double scale = std::pow(10.0, static_cast<double>(in.Byte(8) % 61) - 30.0);
  const std::uint8_t off = in.Byte(9);
  const double offset = off < 128 ? 0.0 : (off & 1 ? -1.0 : 1.0) * std::pow(10.0, (off >> 1) % 16);
  p.NumberOfSamples = static_cast<Index>(in.Byte(1) | (in.Byte(2) << 8));
  const std::uint8_t cell = in.Byte(3);
  p.CellSize = cell == 0 ? 0.0 : cell == 255 ? -1.0 : scale * std::pow(2.0, (cell - 128) / 8.0);
  p.Alpha = in.Byte(4) / 255.0 * 0.6 - 0.05;
  const std::uint8_t tol = in.Byte(5);
  p.ErrorTolerance = tol == 0 ? 0.0 : scale * std::pow(2.0, (tol - 200) / 8.0);
  p.SamplesPerCell = in.Byte(6) / 8.0;
  p.RandomSeed = in.Byte(7);
  p.LinkFactor = in.Byte(10) / 64.0;
  p.CurvatureWeight = in.Byte(11) / 16.0;
  const bool asFloat = (mode & 16) != 0;
  p.CoordinateEpsilon = asFloat ? FLT_EPSILON : DBL_EPSILON;
  k.UseNormals = (mode & 32) != 0;

  const std::size_t n =
    std::min(MaxPoints, in.Size > HeaderSize ? (in.Size - HeaderSize) / PointSize : 0);
  const int shape = (mode >> 2) & 3;
  k.Xyz.resize(3 * n);
  k.Normals.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t at = HeaderSize + i * PointSize;
    const std::uint8_t flag = in.Byte(at);
    double v[3];
    for (int a = 0; a < 3; ++a)
    {
      v[a] = in.Int16(at + 1 + 2 * a) / 32767.0;
      k.Normals[3 * i + a] = v[(a + 1) % 3];
    }
    if (shape == 1)
    {
      v[2] = 0.0; // coplanar
    }
    else if (shape == 2)
    {
      v[1] = v[0]; // collinear
      v[2] = -v[0];
    }
    else if (shape == 3)
    {
      v[0] = v[1] = v[2] = 0.25; // one point, many times
    }
    double* q = &k.Xyz[3 * i];
    for (int a = 0; a < 3; ++a)
    {
      q[a] = offset + scale * v[a];
    }
    switch (flag % 16)
    {
      case 0:
        q[(flag / 16) % 3] = std::nan("");
        break;
      case 1:
        q[(flag / 16) % 3] = HUGE_VAL;
        break;
      case 2:
        q[(flag / 16) % 3] = -HUGE_VAL;
        break;
      case 3:
        if (i > 0)
        {
          std::copy(q - 3, q, q);
        }
        break;
      case 4:
        if (i > 0)
        {
          const std::size_t j = static_cast<std::uint16_t>(in.Int16(at + 1)) % i;
          std::copy(&k.Xyz[3 * j], &k.Xyz[3 * j] + 3, q);
        }
        break;
      case 5:
        for (int a = 0; a < 3; ++a)
        {
          q[a] = offset + 1e12 * scale * v[a];
        }
        break;
      case 6:
        for (int a = 0; a < 3; ++a)
        {
          q[a] = offset + 1e-300 * v[a];
        }
        break;
      default:
        break;
    }
    if (asFloat)
    {
      for (int a = 0; a < 3; ++a)
      {
        q[a] = static_cast<double>(static_cast<float>(q[a]));
      }
    }
  }
  return k;
}

// Cuts every parallel loop into single iterations, run last to first.
asmcore::Execution ReversedSingleSteps()
{
  asmcore::Execution e;
  e.For = [](Index begin, Index end, const std::function<void(Index, Index)>& body) {
    for (Index i = end - 1; i >= begin; --i)
    {
      body(i, i + 1);
    }
  };
  return e;
}

bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

void CheckSimplify(const Case& k, asmcore::IdView ids, const asmcore::SimplifyResult& r)
{
  const Index total = static_cast<Index>(ids.size());
  const Index expected = std::max<Index>(0, std::min(k.Parameters.NumberOfSamples, total));
  FUZZ_CHECK(!r.Aborted);
  FUZZ_CHECK(static_cast<Index>(r.Samples.size()) == expected);
  if (expected == 0)
  {
    return;
  }
  const asmcore::Bounds b = asmcore::ComputeBounds(k.Xyz.data(), ids);
  double magnitude = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    magnitude = std::max({ magnitude, std::abs(b.Min[a]), std::abs(b.Max[a]) });
  }
  const double slack = 1e-9 * b.MaxExtent() + 64.0 * DBL_EPSILON * magnitude;

  FUZZ_CHECK(static_cast<Index>(r.Members.size()) == total);
  std::vector<char> finite(k.Xyz.size() / 3, 0);
  for (Index id : ids)
  {
    finite[id] = 1;
  }
  std::vector<char> seen(k.Xyz.size() / 3, 0);
  std::vector<char> slotUsed(r.Members.size(), 0);
  Index keys = 0;
  double maxKeyError = 0.0;
  for (const asmcore::Sample& s : r.Samples)
  {
    // Paper mode: every sample has members, the first CoreSize of which
    // place it. The feature-preserving mode leaves CoreSize at 0 (its
    // clusters are the points nearest each sample, possibly none).
    FUZZ_CHECK(s.ClusterSize >= 0 && s.CoreSize >= 0 && s.CoreSize <= s.ClusterSize);
    if (k.Parameters.Mode == asmcore::SimplifyMode::Paper)
    {
      FUZZ_CHECK(s.ClusterSize >= 1 && s.CoreSize >= 1);
    }
    FUZZ_CHECK(s.Representative >= 0 && s.Representative < static_cast<Index>(finite.size()) &&
      finite[s.Representative]);
    FUZZ_CHECK(s.MemberBegin >= 0 && s.MemberBegin + s.ClusterSize <= total);
    bool representativeIsMember = false;
    for (Index m = s.MemberBegin; m < s.MemberBegin + s.ClusterSize; ++m)
    {
      FUZZ_CHECK(!slotUsed[m]);
      slotUsed[m] = 1;
      const Index id = r.Members[m];
      FUZZ_CHECK(id >= 0 && id < static_cast<Index>(finite.size()) && finite[id]);
      FUZZ_CHECK(!seen[id]);
      seen[id] = 1;
      // The representative is one of the members that place the sample.
      representativeIsMember |= id == s.Representative && m < s.MemberBegin + s.CoreSize;
    }
    FUZZ_CHECK(representativeIsMember || s.CoreSize == 0);
    for (int a = 0; a < 3; ++a)
    {
      FUZZ_CHECK(std::isfinite(s.Position[a]));
      FUZZ_CHECK(std::isfinite(s.Normal[a]));
      FUZZ_CHECK(s.Position[a] >= b.Min[a] - slack && s.Position[a] <= b.Max[a] + slack);
    }
    if (k.Parameters.Snap || (s.CoreSize == 1 && s.ClusterSize == 1))
    {
      for (int a = 0; a < 3; ++a)
      {
        FUZZ_CHECK(SameBits(s.Position[a], k.Xyz[3 * s.Representative + a]));
      }
    }
    FUZZ_CHECK(std::isfinite(s.KeyError) && s.KeyError >= 0.0);
    if (s.Key)
    {
      ++keys;
      maxKeyError = std::max(maxKeyError, s.KeyError);
    }
  }
  for (Index id : ids)
  {
    FUZZ_CHECK(seen[id]);
  }
  FUZZ_CHECK(keys == r.NumberOfKeyPoints);
  FUZZ_CHECK(std::isfinite(r.AKPE) && std::isfinite(r.MKPE));
  FUZZ_CHECK(r.AKPE <= r.MKPE * (1.0 + 1e-12));
  FUZZ_CHECK(r.MKPE == maxKeyError);
  FUZZ_CHECK(std::isfinite(r.CellSize) && r.CellSize > 0.0);
}

void CheckSameResult(const asmcore::SimplifyResult& a, const asmcore::SimplifyResult& b)
{
  FUZZ_CHECK(a.Samples.size() == b.Samples.size());
  FUZZ_CHECK(a.Members == b.Members);
  for (std::size_t s = 0; s < a.Samples.size(); ++s)
  {
    const asmcore::Sample& x = a.Samples[s];
    const asmcore::Sample& y = b.Samples[s];
    for (int c = 0; c < 3; ++c)
    {
      FUZZ_CHECK(SameBits(x.Position[c], y.Position[c]));
      FUZZ_CHECK(SameBits(x.Normal[c], y.Normal[c]));
    }
    FUZZ_CHECK(x.Representative == y.Representative && x.ClusterSize == y.ClusterSize &&
      x.CoreSize == y.CoreSize && x.MemberBegin == y.MemberBegin && x.Key == y.Key);
  }
  FUZZ_CHECK(SameBits(a.MKPE, b.MKPE) && SameBits(a.AKPE, b.AKPE));
}

void CheckCompare(const Case& k, asmcore::IdView ids, const asmcore::SimplifyResult& r)
{
  if (ids.empty() || r.Samples.empty() || ids.size() > 1024)
  {
    return;
  }
  std::vector<double> simplified;
  for (const asmcore::Sample& s : r.Samples)
  {
    simplified.insert(simplified.end(), s.Position, s.Position + 3);
  }
  const std::vector<Index> sids =
    asmcore::FinitePointIds(simplified.data(), static_cast<Index>(r.Samples.size()));
  FUZZ_CHECK(sids.size() == r.Samples.size());
  const asmcore::Neighbors tree(k.Xyz.data(), ids);
  asmcore::ComparisonOptions options;
  options.Rule.Alpha = k.Parameters.Alpha;
  options.Rule.CoordinateEpsilon = k.Parameters.CoordinateEpsilon;
  options.CellSize = k.Parameters.CellSize;
  options.SamplesPerCell = k.Parameters.SamplesPerCell;
  // vtkKeyPointError's own options, from the seed byte: PlaneNeighbors in
  // 3 .. 1000 (the property's range; more than the samples too), the squared
  // distance of the paper's Eq. 3 every other seed.
  static const int planeNeighbors[4] = { 8, 3, 17, 1000 };
  options.PlaneNeighbors = planeNeighbors[k.Parameters.RandomSeed % 4];
  options.Measure = (k.Parameters.RandomSeed & 4) ? asmcore::KeyPointDistance::Squared
                                                  : asmcore::KeyPointDistance::Euclidean;
  const asmcore::Comparison c =
    asmcore::CompareClouds(k.Xyz.data(), ids, tree, simplified.data(), sids, options);
  FUZZ_CHECK(!c.Aborted);
  FUZZ_CHECK(c.SimplifiedError.size() == sids.size());
  const double figures[] = { c.AKPE, c.MKPE, c.Diagonal, c.Hausdorff, c.OriginalToSimplified.Max,
    c.SimplifiedToOriginal.Max, c.PointToPlane.Mean };
  for (double f : figures)
  {
    FUZZ_CHECK(std::isfinite(f) && f >= 0.0);
  }
}
void CheckCurvature(const Case& k, asmcore::IdView ids, const asmcore::SimplifyResult& r)
{
  if (ids.empty() || r.Samples.empty() || ids.size() > 1024)
  {
    return;
  }
  std::vector<double> positions, normals;
  for (const asmcore::Sample& s : r.Samples)
  {
    positions.insert(positions.end(), s.Position, s.Position + 3);
    normals.insert(normals.end(), s.Normal, s.Normal + 3);
  }
  const auto count = static_cast<Index>(r.Samples.size());
  const asmcore::Neighbors tree(k.Xyz.data(), ids);
  for (int neighbors : { 6, asmcore::DefaultCurvatureNeighbors })
  {
    const std::vector<asmcore::CurvatureEstimate> e = asmcore::EstimateCurvature(
      k.Xyz.data(), ids, tree, positions.data(), count, normals.data(), neighbors, {});
    const std::vector<asmcore::CurvatureEstimate> again = asmcore::EstimateCurvature(k.Xyz.data(),
      ids, tree, positions.data(), count, normals.data(), neighbors, ReversedSingleSteps());
    FUZZ_CHECK(static_cast<Index>(e.size()) == count && again.size() == e.size());
    const int expected = static_cast<int>(std::min<std::size_t>(neighbors, ids.size()));
    for (std::size_t i = 0; i < e.size(); ++i)
    {
      const asmcore::CurvatureEstimate& x = e[i];
      FUZZ_CHECK(x.NumberOfNeighbors == expected);
      FUZZ_CHECK(x.QuadricFit ? std::isfinite(x.MeanCurvature) : x.MeanCurvature == 0.0);
      FUZZ_CHECK(x.SurfaceVariation >= 0.0 && x.SurfaceVariation <= 1.0 / 3.0 + 1e-12);
      const double norm2 =
        x.Normal[0] * x.Normal[0] + x.Normal[1] * x.Normal[1] + x.Normal[2] * x.Normal[2];
      FUZZ_CHECK(std::abs(norm2 - 1.0) <= 1e-9);
      const asmcore::CurvatureEstimate& y = again[i];
      FUZZ_CHECK(SameBits(x.MeanCurvature, y.MeanCurvature) &&
        SameBits(x.SurfaceVariation, y.SurfaceVariation) && x.QuadricFit == y.QuadricFit);
      for (int a = 0; a < 3; ++a)
      {
        FUZZ_CHECK(SameBits(x.Normal[a], y.Normal[a]));
      }
    }
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const Case k = Decode(Reader{ data, size });
  const Index n = static_cast<Index>(k.Xyz.size() / 3);
  const std::vector<Index> ids = asmcore::FinitePointIds(k.Xyz.data(), n);
  const double* normals = k.UseNormals ? k.Normals.data() : nullptr;

  const asmcore::SimplifyResult r = asmcore::Simplify(k.Xyz.data(), ids, normals, k.Parameters);
  CheckSimplify(k, ids, r);
  const asmcore::SimplifyResult again =
    asmcore::Simplify(k.Xyz.data(), ids, normals, k.Parameters, ReversedSingleSteps());
  CheckSameResult(r, again);
  CheckCompare(k, ids, r);
  CheckCurvature(k, ids, r);
  return 0;
}
