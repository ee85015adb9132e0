// Tangent-ogive nose geometry (core/ogive_nose.hpp) against closed forms: a CRH 0.5 nose is a
// hemisphere, and the nose volume formula matches a numerical integral of pi r(t)^2.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "afemp/ogive_nose.hpp"

namespace afemp::core {
namespace {

TEST(OgiveNose, HalfCaliberHeadIsAHemisphere) {
  // Reference: CRH 0.5 gives S = R: length R, r(t) = sqrt(R^2 - t^2), volume 2/3 pi R^3 (1e-12).
  const OgiveNose nose{0.5, 0.0};
  const double r = 2.5;
  EXPECT_NEAR(ogive_nose_length(nose, r), r, 1e-12 * r);
  for (double t : {0.0, 0.7, 1.9, 2.5})
    EXPECT_NEAR(ogive_radius(nose, r, t), std::sqrt(r * r - t * t), 1e-12 * r) << t;
  EXPECT_NEAR(ogive_nose_volume(nose, r), 2.0 / 3.0 * std::numbers::pi * r * r * r,
              1e-12 * r * r * r);
}

TEST(OgiveNose, ThreeCaliberNoseWithMeplatMatchesItsArc) {
  // Hanchak's projectile: R = 12.7 mm, CRH 3 (S = 76.2 mm), here with a 4 mm meplat.
  // References: the sharp nose is R sqrt(4 psi - 1) = 42.12 mm long; the cut nose ends where
  // r = 2 mm; the arc is tangent to the shank (r'(0) = 0, checked by a difference over 1e-6);
  // the volume equals Simpson's rule on pi r^2 with 2000 intervals to 1e-9.
  const double r = 12.7;
  EXPECT_NEAR(ogive_nose_length({3.0, 0.0}, r), r * std::sqrt(11.0), 1e-12 * r);
  const OgiveNose nose{3.0, 4.0};
  const double length = ogive_nose_length(nose, r);
  EXPECT_LT(length, r * std::sqrt(11.0));
  EXPECT_NEAR(ogive_radius(nose, r, 0.0), r, 1e-12 * r);
  EXPECT_NEAR(ogive_radius(nose, r, length), 2.0, 1e-9);
  EXPECT_NEAR((ogive_radius(nose, r, 1e-6) - r) / 1e-6, 0.0, 1e-5);
  // Past the tip the radius stays the meplat's (the profile is clamped to the nose).
  EXPECT_NEAR(ogive_radius(nose, r, length + 1.0), 2.0, 1e-9);
  const int n = 2000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double t = length * i / n, rr = ogive_radius(nose, r, t);
    sum += (i == 0 || i == n ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0)) * rr * rr;
  }
  const double simpson = std::numbers::pi * sum * length / (3.0 * n);
  EXPECT_NEAR(ogive_nose_volume(nose, r), simpson, 1e-9 * simpson);
}

}  // namespace
}  // namespace afemp::core
