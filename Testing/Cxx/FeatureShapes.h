// SPDX-License-Identifier: BSD-3-Clause
// Synthetic shapes with known feature points, for the feature-preserving
// mode's tests and measurements.
#ifndef asm_FeatureShapes_h
#define asm_FeatureShapes_h

#include "Core/Simplify.h"
#include "TestHelpers.h"

#include <array>
#include <cmath>
#include <functional>
#include <random>

namespace asmtest
{
struct Shape
{
  Cloud Points;
  std::vector<std::array<double, 3>> Features; ///< tips, corners
  double Area = 0.0;
  double Spacing(std::size_t n) const { return std::sqrt(this->Area / static_cast<double>(n)); }
};

/// A closed cone: apex (0, 0, height), base disc of `radius` at z = 0; the
/// apex and n - 1 random points, uniform in area.
inline Shape Cone(std::size_t n, double radius = 0.3, double height = 1.0, unsigned seed = 3)
{
  Shape s;
  const double slant = std::sqrt(radius * radius + height * height);
  const double lateral = M_PI * radius * slant, base = M_PI * radius * radius;
  s.Area = lateral + base;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Add(s.Points, 0.0, 0.0, height);
  for (std::size_t i = 1; i < n; ++i)
  {
    const double t = 2.0 * M_PI * u(rng);
    const double r = radius * std::sqrt(u(rng)); // uniform on a disc / on the unrolled cone
    if (u(rng) * s.Area < lateral)
    {
      Add(s.Points, r * std::cos(t), r * std::sin(t), height * (1.0 - r / radius));
    }
    else
    {
      Add(s.Points, r * std::cos(t), r * std::sin(t), 0.0);
    }
  }
  s.Features.push_back({ 0.0, 0.0, height });
  return s;
}

/// The surface of the box [0, a] x [0, b] x [0, c]: its 8 corners (the
/// features) and n - 8 random points, uniform in area.
inline Shape Box(std::size_t n, double a = 1.0, double b = 0.7, double c = 0.4, unsigned seed = 5)
{
  Shape s;
  const double faces[3] = { b * c, a * c, a * b }; // faces normal to x, y, z
  s.Area = 2.0 * (faces[0] + faces[1] + faces[2]);
  const double size[3] = { a, b, c };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 8; ++k)
  {
    Add(s.Points, (k & 1) ? a : 0.0, (k & 2) ? b : 0.0, (k & 4) ? c : 0.0);
  }
  for (std::size_t i = 8; i < n; ++i)
  {
    double pick = u(rng) * 0.5 * s.Area;
    int axis = 0;
    while (axis < 2 && pick >= faces[axis])
    {
      pick -= faces[axis];
      ++axis;
    }
    double p[3];
    for (int k = 0; k < 3; ++k)
    {
      p[k] = size[k] * u(rng);
    }
    p[axis] = u(rng) < 0.5 ? 0.0 : size[axis];
    Add(s.Points, p[0], p[1], p[2]);
  }
  for (int k = 0; k < 8; ++k)
  {
    s.Features.push_back({ (k & 1) ? a : 0.0, (k & 2) ? b : 0.0, (k & 4) ? c : 0.0 });
  }
  return s;
}

/// n random points on the tilted plane z = 0.3 x - 0.2 y over [-1, 1]^2,
/// with Gaussian noise of `noise` along z (a plane without any would be flat).
inline Shape TiltedPlane(std::size_t n, double noise = 1e-4, unsigned seed = 9)
{
  std::normal_distribution<double> g(0.0, noise);
  Shape s;
  s.Area = 4.0 * std::sqrt(1.0 + 0.09 + 0.04);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double x = u(rng), y = u(rng);
    Add(s.Points, x, y, 0.3 * x - 0.2 * y + g(rng));
  }
  return s;
}
/// The core's simplification of `c` to `target` samples, with the default
/// parameters as changed by `configure` (if any).
inline asmcore::SimplifyResult SimplifyWith(const Cloud& c, std::int64_t target,
  const std::function<void(asmcore::SimplifyParameters&)>& configure = {})
{
  asmcore::SimplifyParameters p;
  p.NumberOfSamples = target;
  if (configure)
  {
    configure(p);
  }
  return asmcore::Simplify(c.data(), AllIds(c), nullptr, p);
}

} // namespace asmtest

#endif
