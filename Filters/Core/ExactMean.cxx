// SPDX-License-Identifier: BSD-3-Clause
#include "ExactMean.h"

#include <algorithm>
#include <cmath>

namespace asmcore
{
void ExactMean::Add(double value)
{
  constexpr double largest = 4096.0;
  const double v = value > 0.0 ? std::min(value, largest) : 0.0; // (NaN: 0)
  // At most 2^52: the high and the low 26 bits, each summed over fewer than
  // 2^37 terms without overflow.
  auto q = static_cast<long long>(std::llround(std::ldexp(v, 40)));
  q = std::min(q, (1LL << 52) - 1);
  this->Sums[0] += q >> 26;
  this->Sums[1] += q & ((1LL << 26) - 1);
  this->Sums[2] += 1;
}

double ExactMean::Total() const
{
  return std::ldexp(static_cast<double>(this->Sums[0]), -14) +
    std::ldexp(static_cast<double>(this->Sums[1]), -40);
}

double ExactMean::Value() const
{
  if (this->Sums[2] <= 0)
  {
    return 0.0;
  }
  return this->Total() / static_cast<double>(this->Sums[2]);
}

} // namespace asmcore
