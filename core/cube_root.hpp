// The real cube root of a positive double, branch-free so that a loop over lanes of elements
// vectorises (std::cbrt is a library call per value, with frexp and scalbn inside: 6 % of the
// one-point hexahedron stage went to it, for the viscous hourglass factor's V^(2/3)).
// A first guess from the exponent bits (the classic bit-level estimate: the integer image of a
// double is roughly 2^52 (log2 x + 1023), so a third of it, re-biased, is a cube root within
// about 5 %), then three Halley steps y <- y (y^3 + 2x) / (2y^3 + x), each tripling the correct
// digits (5e-2 -> 1e-4 -> 1e-12 -> below rounding). Tests: tests/core/test_cube_root.cpp
// (within 1 ulp of std::cbrt over 600 decades).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

namespace afemp::core {

inline double cube_root(double x) {
  // bits(x) / 3 + (2/3) 1023 2^52, the division done in double so that it vectorises
  // (1023 2^52 (2/3) = 0x2A9F7893782DA1CE, Kahan's constant without its tuning).
  const auto bits = static_cast<double>(std::bit_cast<std::int64_t>(x));
  double y = std::bit_cast<double>(static_cast<std::int64_t>(bits * (1.0 / 3.0)) +
                                   std::int64_t{0x2A9F7893782DA1CE});
  for (int k = 0; k < 2; ++k) {
    const double y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  }
  // A last Newton step, y - (y^3 - x) / (3 y^2), with the residual y^3 - x formed exactly
  // enough (y^2 split into its rounded value and its error by fused multiply-adds) that the
  // result is the cube root rounded, or its neighbour.
  const double y2 = y * y;
  const double y2_error = std::fma(y, y, -y2);
  const double residual = std::fma(y2, y, -x) + y2_error * y;
  return y - residual / (3.0 * y2);
}

}  // namespace afemp::core
