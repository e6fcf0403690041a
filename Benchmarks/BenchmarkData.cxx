// SPDX-License-Identifier: BSD-3-Clause
#include "BenchmarkData.h"

#include "Core/Common.h" // asmcore::SplitMix64

#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>

namespace asmbench
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

/// The core's SplitMix64 generator with uniform and normal draws.
class Random
{
public:
  explicit Random(std::uint64_t seed)
    : Generator(seed)
  {
  }
  std::uint64_t Next() { return this->Generator.Next(); }
  /// Uniform in [0, 1).
  double Uniform() { return static_cast<double>(this->Next() >> 11) * 0x1.0p-53; }
  /// Standard normal (Box-Muller).
  double Normal()
  {
    const double u = 1.0 - this->Uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * Pi * this->Uniform());
  }
  /// Uniform unit vector.
  std::array<double, 3> Direction()
  {
    const double z = 2.0 * this->Uniform() - 1.0;
    const double phi = 2.0 * Pi * this->Uniform();
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return { s * std::cos(phi), s * std::sin(phi), z };
  }

private:
  asmcore::SplitMix64 Generator;
};

using Vec = std::array<double, 3>;
double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The SplitMix64 finaliser: a bijective 64-bit hash.
std::uint64_t Mix(std::uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// Fills n points: sample(rng, p) writes point p; chunks of 65536 points,
/// each with its own seed, generated in parallel (deterministic).
vtkSmartPointer<vtkPolyData> Generate(
  std::int64_t n, std::uint64_t seed, const std::function<void(Random&, float*)>& sample)
{
  constexpr std::int64_t chunk = 65536;
  vtkNew<vtkFloatArray> coords;
  coords->SetNumberOfComponents(3);
  coords->SetNumberOfTuples(n);
  float* out = coords->GetPointer(0);
  const std::int64_t chunks = (n + chunk - 1) / chunk;
  vtkSMPTools::For(0, chunks, [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t c = b; c < e; ++c)
    {
      // Each chunk's stream starts at a hashed state: consecutive seeds of
      // SplitMix64 would give streams shifted by one draw (the same points).
      Random rng(Mix(Mix(seed) ^ Mix(static_cast<std::uint64_t>(c) + 0x632BE59BD9B4E019ULL)));
      for (std::int64_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i)
      {
        sample(rng, out + 3 * i);
      }
    }
  });
  vtkNew<vtkPoints> points;
  points->SetData(coords);
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  return data;
}

void Store(float* out, const Vec& p)
{
  out[0] = static_cast<float>(p[0]);
  out[1] = static_cast<float>(p[1]);
  out[2] = static_cast<float>(p[2]);
}

/// The 12 unit vertices of an icosahedron.
std::vector<Vec> Icosahedron()
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec> v = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t },
    { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 },
    { -t, 0, 1 } };
  for (Vec& p : v)
  {
    const double l = std::sqrt(Dot(p, p));
    p = { p[0] / l, p[1] / l, p[2] / l };
  }
  return v;
}

std::string CountName(std::int64_t n)
{
  if (n % 1000000 == 0)
  {
    return std::to_string(n / 1000000) + "M";
  }
  if (n % 1000 == 0)
  {
    return std::to_string(n / 1000) + "k";
  }
  return std::to_string(n);
}
} // namespace

Input MakeBumpySphere(std::int64_t n, std::uint64_t seed)
{
  struct Bump
  {
    Vec C;
    double A, S2;
  };
  Random setup(seed);
  std::vector<Bump> bumps(12);
  for (Bump& b : bumps)
  {
    b.C = setup.Direction();
    b.A = 0.05 + 0.1 * setup.Uniform();
    const double s = 0.15 + 0.2 * setup.Uniform();
    b.S2 = s * s;
  }
  // Radius r(u) and the area element r * sqrt(r^2 + |grad_t r|^2) per solid angle.
  auto evaluate = [&bumps](const Vec& u, double& r) {
    r = 1.0;
    Vec g = { 0, 0, 0 };
    for (const Bump& b : bumps)
    {
      const Vec d = { u[0] - b.C[0], u[1] - b.C[1], u[2] - b.C[2] };
      const double e = b.A * std::exp(-Dot(d, d) / (2.0 * b.S2));
      r += e;
      for (int k = 0; k < 3; ++k)
      {
        g[k] -= e * d[k] / b.S2;
      }
    }
    const double gu = Dot(g, u);
    const Vec gt = { g[0] - gu * u[0], g[1] - gu * u[1], g[2] - gu * u[2] };
    return r * std::sqrt(r * r + Dot(gt, gt));
  };
  double maxArea = 0.0;
  for (int i = 0; i < 100000; ++i)
  {
    double r;
    maxArea = std::max(maxArea, evaluate(setup.Direction(), r));
  }
  maxArea *= 1.1;
  Input input;
  input.Name = "bumps-" + CountName(n);
  input.Data = Generate(n, seed, [&](Random& rng, float* out) {
    for (;;)
    {
      const Vec u = rng.Direction();
      double r;
      if (rng.Uniform() * maxArea <= evaluate(u, r))
      {
        r += 2e-4 * rng.Normal();
        Store(out, { r * u[0], r * u[1], r * u[2] });
        return;
      }
    }
  });
  return input;
}

Input MakeSpikes(std::int64_t n, std::uint64_t seed)
{
  const std::vector<Vec> axes = Icosahedron();
  const double tip = 1.6, baseRadius = 0.15;
  const double baseHeight = std::sqrt(1.0 - baseRadius * baseRadius);
  const double slant = std::hypot(tip - baseHeight, baseRadius);
  const double coneArea = Pi * baseRadius * slant;
  const double sphereArea = 4.0 * Pi - 12.0 * 2.0 * Pi * (1.0 - baseHeight);
  const double coneShare = 12.0 * coneArea / (12.0 * coneArea + sphereArea);
  Input input;
  input.Name = "spikes";
  for (const Vec& a : axes)
  {
    input.Features.insert(input.Features.end(), { tip * a[0], tip * a[1], tip * a[2] });
  }
  input.Data = Generate(n, seed, [&](Random& rng, float* out) {
    if (rng.Uniform() < coneShare)
    {
      const Vec& a = axes[std::min<std::size_t>(11, static_cast<std::size_t>(rng.Uniform() * 12))];
      // An orthonormal frame (a, e1, e2).
      const Vec h = std::abs(a[0]) < 0.9 ? Vec{ 1, 0, 0 } : Vec{ 0, 1, 0 };
      Vec e1 = { a[1] * h[2] - a[2] * h[1], a[2] * h[0] - a[0] * h[2], a[0] * h[1] - a[1] * h[0] };
      const double l = std::sqrt(Dot(e1, e1));
      e1 = { e1[0] / l, e1[1] / l, e1[2] / l };
      const Vec e2 = { a[1] * e1[2] - a[2] * e1[1], a[2] * e1[0] - a[0] * e1[2],
        a[0] * e1[1] - a[1] * e1[0] };
      const double t = std::sqrt(rng.Uniform()); // 0 at the tip, 1 at the base
      const double phi = 2.0 * Pi * rng.Uniform();
      const double along = tip + t * (baseHeight - tip), radius = t * baseRadius;
      Vec p;
      for (int k = 0; k < 3; ++k)
      {
        p[k] = along * a[k] + radius * (std::cos(phi) * e1[k] + std::sin(phi) * e2[k]);
      }
      Store(out, p);
      return;
    }
    for (;;)
    {
      const Vec u = rng.Direction();
      bool inCap = false;
      for (const Vec& a : axes)
      {
        inCap = inCap || Dot(a, u) > baseHeight;
      }
      if (!inCap)
      {
        Store(out, u);
        return;
      }
    }
  });
  return input;
}

Input MakeBracket(std::int64_t n, std::uint64_t seed)
{
  // The L cross-section (counter-clockwise) in x-y, extruded along z.
  const std::vector<std::array<double, 2>> l = { { 0, 0 }, { 1, 0 }, { 1, 0.25 }, { 0.25, 0.25 },
    { 0.25, 1 }, { 0, 1 } };
  const double height = 0.6, capArea = 0.25 + 0.25 * 0.75;
  std::vector<double> cumulative; // the 6 side faces, then the two caps
  double total = 0.0;
  for (std::size_t i = 0; i < l.size(); ++i)
  {
    const auto& a = l[i];
    const auto& b = l[(i + 1) % l.size()];
    total += std::hypot(b[0] - a[0], b[1] - a[1]) * height;
    cumulative.push_back(total);
  }
  total += 2.0 * capArea;
  Input input;
  input.Name = "bracket";
  for (double z : { 0.0, height })
  {
    for (const auto& v : l)
    {
      input.Features.insert(input.Features.end(), { v[0], v[1], z });
    }
  }
  input.Data = Generate(n, seed, [&](Random& rng, float* out) {
    const double pick = rng.Uniform() * total;
    for (std::size_t i = 0; i < l.size(); ++i)
    {
      if (pick < cumulative[i])
      {
        const auto& a = l[i];
        const auto& b = l[(i + 1) % l.size()];
        const double t = rng.Uniform();
        Store(out, { a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), height * rng.Uniform() });
        return;
      }
    }
    const double z = pick < cumulative.back() + capArea ? 0.0 : height;
    for (;;)
    {
      const double x = rng.Uniform(), y = rng.Uniform();
      if (x < 0.25 || y < 0.25)
      {
        Store(out, { x, y, z });
        return;
      }
    }
  });
  return input;
}

Input MakeTerrain(std::int64_t n, std::uint64_t seed)
{
  // z = slope + sum of sharp peaks h * exp(-r / s): each summit is a cusp
  // (steeper than everything around it), so it lies exactly at its centre.
  struct Peak
  {
    double X, Y, H, S;
  };
  Random setup(seed);
  std::vector<Peak> peaks;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      peaks.push_back({ 0.2 + 0.3 * i + 0.06 * (setup.Uniform() - 0.5),
        0.2 + 0.3 * j + 0.06 * (setup.Uniform() - 0.5), 0.08 + 0.08 * setup.Uniform(),
        0.04 + 0.03 * setup.Uniform() });
    }
  }
  auto height = [&peaks](double x, double y, double& gx, double& gy) {
    double z = 0.1 * x + 0.05 * y;
    gx = 0.1;
    gy = 0.05;
    for (const Peak& p : peaks)
    {
      const double dx = x - p.X, dy = y - p.Y, r = std::hypot(dx, dy);
      const double e = p.H * std::exp(-r / p.S);
      z += e;
      if (r > 0.0)
      {
        gx -= e * dx / (r * p.S);
        gy -= e * dy / (r * p.S);
      }
    }
    return z;
  };
  double maxArea = 0.0;
  for (int i = 0; i < 200000; ++i)
  {
    double gx, gy;
    height(setup.Uniform(), setup.Uniform(), gx, gy);
    maxArea = std::max(maxArea, std::sqrt(1.0 + gx * gx + gy * gy));
  }
  maxArea *= 1.2;
  Input input;
  input.Name = "terrain";
  for (const Peak& p : peaks)
  {
    double gx, gy;
    input.Features.insert(input.Features.end(), { p.X, p.Y, height(p.X, p.Y, gx, gy) });
  }
  input.Data = Generate(n, seed, [&](Random& rng, float* out) {
    for (;;)
    {
      const double x = rng.Uniform(), y = rng.Uniform();
      double gx, gy;
      const double z = height(x, y, gx, gy);
      if (rng.Uniform() * maxArea <= std::sqrt(1.0 + gx * gx + gy * gy))
      {
        Store(out, { x, y, z });
        return;
      }
    }
  });
  return input;
}

Input ReadPLY(const std::string& path)
{
  Input input;
  const std::size_t slash = path.find_last_of('/');
  input.Name = path.substr(slash == std::string::npos ? 0 : slash + 1);
  if (input.Name.size() > 4 && input.Name.substr(input.Name.size() - 4) == ".ply")
  {
    input.Name.resize(input.Name.size() - 4);
  }
  if (!std::ifstream(path).good())
  {
    std::cerr << "cannot read " << path << "\n";
    return input;
  }
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  if (reader->GetOutput()->GetNumberOfPoints() > 0)
  {
    input.Data = reader->GetOutput();
  }
  else
  {
    std::cerr << "no points read from " << path << " (not a PLY file, or empty)\n";
  }
  return input;
}

bool CheckInputSpec(const std::string& spec, std::string& error)
{
  const std::size_t colon = spec.find(':');
  if (spec.empty())
  {
    error = "an empty input";
    return false;
  }
  if (colon == std::string::npos)
  {
    return true;
  }
  const std::string shape = spec.substr(0, colon);
  if (shape != "bumps" && shape != "spikes" && shape != "bracket" && shape != "terrain")
  {
    error = Quoted(spec) + ": unknown synthetic shape " + Quoted(shape) +
      " (bumps, spikes, bracket, terrain)";
    return false;
  }
  const std::string count = spec.substr(colon + 1);
  if (ParseCount(count) <= 0)
  {
    error = Quoted(spec) + ": " + CountError(count);
    return false;
  }
  return true;
}

std::string CheckInputSpecs(
  const std::vector<std::string>& inputs, const std::vector<std::string>& extra)
{
  std::string error;
  for (const auto* list : { &inputs, &extra })
  {
    for (const std::string& spec : *list)
    {
      if (!CheckInputSpec(spec, error))
      {
        return error;
      }
    }
  }
  return "";
}

Input MakeInput(const std::string& spec)
{
  const std::size_t colon = spec.find(':');
  if (colon == std::string::npos)
  {
    return ReadPLY(spec);
  }
  const std::string shape = spec.substr(0, colon);
  const std::int64_t n = ParseCount(spec.substr(colon + 1));
  Input none;
  none.Name = spec;
  std::string error;
  if (!CheckInputSpec(spec, error))
  {
    std::cerr << "input " << error << "\n";
    return none;
  }
  Input input;
  if (shape == "bumps")
  {
    input = MakeBumpySphere(n);
  }
  else if (shape == "spikes")
  {
    input = MakeSpikes(n);
  }
  else if (shape == "bracket")
  {
    input = MakeBracket(n);
  }
  else if (shape == "terrain")
  {
    input = MakeTerrain(n);
  }
  else
  {
    std::cerr << "unknown synthetic shape " << shape << " (bumps, spikes, bracket, terrain)\n";
    return none;
  }
  if (shape != "bumps")
  {
    input.Name += "-" + CountName(n);
  }
  return input;
}

std::int64_t DropNonFinite(Input& input)
{
  const vtkIdType n = input.NumberOfPoints();
  std::vector<vtkIdType> kept;
  kept.reserve(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    input.Data->GetPoint(i, p);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      kept.push_back(i);
    }
  }
  const auto dropped = static_cast<std::int64_t>(n) - static_cast<std::int64_t>(kept.size());
  if (dropped > 0)
  {
    vtkNew<vtkFloatArray> coords;
    coords->SetNumberOfComponents(3);
    coords->SetNumberOfTuples(static_cast<vtkIdType>(kept.size()));
    for (std::size_t j = 0; j < kept.size(); ++j)
    {
      double p[3];
      input.Data->GetPoint(kept[j], p);
      coords->SetTuple(static_cast<vtkIdType>(j), p);
    }
    vtkNew<vtkPoints> points;
    points->SetData(coords);
    auto data = vtkSmartPointer<vtkPolyData>::New();
    data->SetPoints(points);
    input.Data = data;
  }
  return dropped;
}

std::vector<double> Coordinates(vtkPointSet* data)
{
  const vtkIdType n = data && data->GetPoints() ? data->GetNumberOfPoints() : 0;
  std::vector<double> xyz(static_cast<std::size_t>(3 * n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    data->GetPoint(i, xyz.data() + 3 * i);
  }
  return xyz;
}

double BoundingBoxDiagonal(const std::vector<double>& xyz)
{
  if (xyz.empty())
  {
    return 0.0;
  }
  double lo[3] = { xyz[0], xyz[1], xyz[2] }, hi[3] = { xyz[0], xyz[1], xyz[2] };
  for (std::size_t i = 0; i < xyz.size(); i += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], xyz[i + k]);
      hi[k] = std::max(hi[k], xyz[i + k]);
    }
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
    (hi[2] - lo[2]) * (hi[2] - lo[2]));
}
} // namespace asmbench
