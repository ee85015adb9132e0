// core::cube_root (core/cube_root.hpp), the cube root the viscous hourglass factor V^(2/3)
// takes in place of std::cbrt. Reference: the cube root rounded from long double (cbrtl, 64-bit
// mantissa, 11 bits beyond a double's); the bound is 1 ulp. Perfect cubes come out exact.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/cube_root.hpp"

namespace afemp::core {
namespace {

TEST(CubeRoot, WithinOneUlpOfTheRoundedRootOverSixHundredDecades) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  double worst = 0.0;
  for (int exponent = -1000; exponent <= 1000; exponent += 5) {
    for (int k = 0; k < 200; ++k) {
      const double x = std::ldexp(mantissa(random), exponent);
      const auto reference = static_cast<double>(cbrtl(static_cast<long double>(x)));
      const double ulp = std::nextafter(reference, INFINITY) - reference;
      worst = std::max(worst, std::fabs(cube_root(x) - reference) / ulp);
    }
  }
  EXPECT_LE(worst, 1.0);
}

TEST(CubeRoot, PerfectCubesAreExact) {
  for (double r : {1.0, 2.0, 3.0, 0.5, 0.25, 7.0, 1.0e5, 12.5}) {
    const double x = r * r * r;  // exact in double for these r
    EXPECT_EQ(cube_root(x), r) << "x = " << x;
  }
}

}  // namespace
}  // namespace afemp::core
