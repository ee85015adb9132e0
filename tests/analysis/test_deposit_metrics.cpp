// Deposit measures (analysis/deposit_metrics.hpp) on point sets of known geometry: a plane-strain
// deposit of lattice points under the surface h(s) = 100 for s <= 50, falling linearly to 0 at
// s = 350 (a collapsed column's shape, in mm), with grains lying loose above it. References: the
// surface's closed form at given s, and the s where it falls to a level, 350 - 3 level; the
// lattice samples the surface within one spacing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "analysis/deposit_metrics.hpp"

namespace afemp::analysis {
namespace {

constexpr double spacing = 1.25;  // lattice spacing (particles of a 2.5 mm cell, 2 per cell)

double surface(double s) {
  return s <= 50.0 ? 100.0 : std::max(0.0, 100.0 * (350.0 - s) / 300.0);
}

// Lattice points at the centres of spacing-sized squares below the surface, two layers deep in
// z (a plane-strain slab); the deposit's base at y = 0, the wall at x = 0.
std::vector<Vec3> deposit(bool loose_grains) {
  std::vector<Vec3> points;
  for (int i = 0; (i + 0.5) * spacing < 400.0; ++i)
    for (int j = 0; (j + 0.5) * spacing < 110.0; ++j)
      for (int k = 0; k < 2; ++k) {
        const Vec3 x{(i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing};
        if (x.y < surface(x.x)) points.push_back(x);
      }
  if (loose_grains)  // grains resting or bouncing well above the surface
    for (int k = 0; k < 5; ++k) points.push_back({100.0 + 40.0 * k, 105.0, 0.5});
  return points;
}

TEST(DepositMetrics, SurfaceHeightsAndRunOutFollowTheDepositsShape) {
  const std::vector<Vec3> points = deposit(false);
  const DepositProfile p =
      deposit_profile(points, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2.5, 0.5 * spacing);
  for (double s : {0.0, 100.0, 200.0, 300.0}) {
    std::printf("h(%g) = %.3f (ref %.3f)\n", s, surface_height(p, s), surface(s));
    EXPECT_NEAR(surface_height(p, s), surface(s), spacing) << s;
  }
  for (double level : {5.0, 10.0, 20.0}) {
    const double ref = 350.0 - 3.0 * level;  // the surface's slope is 1/3
    std::printf("run-out to %g: %.3f (ref %.3f)\n", level, runout_to_height(p, level), ref);
    // A spacing of height is 3 spacings along this slope.
    EXPECT_NEAR(runout_to_height(p, level), ref, 3.0 * spacing) << level;
  }
  EXPECT_NEAR(p.tip, 350.0, 3.0 * spacing);
  EXPECT_EQ(runout_to_height(p, 150.0), 0.0);         // no bin reaches it
  EXPECT_TRUE(std::isnan(surface_height(p, 390.0)));  // beyond the deposit
}

TEST(DepositMetrics, LooseGrainsAboveTheSurfaceAreNotTheSurface) {
  const std::vector<Vec3> clean = deposit(false), loose = deposit(true);
  const Vec3 origin{0, 0, 0}, along{1, 0, 0}, up{0, 1, 0};
  const DepositProfile a = deposit_profile(clean, origin, along, up, 2.5, 0.0);
  const DepositProfile b = deposit_profile(loose, origin, along, up, 2.5, 0.0);
  for (double s : {100.0, 140.0, 180.0, 220.0, 260.0})
    EXPECT_DOUBLE_EQ(surface_height(a, s), surface_height(b, s)) << s;
  EXPECT_DOUBLE_EQ(runout_to_height(a, 10.0), runout_to_height(b, 10.0));
}

TEST(DepositMetrics, MeasuresAlongAnyBaseDirection) {
  // The same deposit spreading along -y on a base normal to z, its wall at y = 20.
  std::vector<Vec3> turned;
  for (const Vec3& x : deposit(false)) turned.push_back({x.z, 20.0 - x.x, x.y});
  const DepositProfile a =
      deposit_profile(deposit(false), {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2.5, 0.0);
  const DepositProfile b = deposit_profile(turned, {0, 20, 0}, {0, -1, 0}, {0, 0, 1}, 2.5, 0.0);
  EXPECT_NEAR(runout_to_height(a, 10.0), runout_to_height(b, 10.0), 1e-9);
  EXPECT_NEAR(surface_height(a, 150.0), surface_height(b, 150.0), 1e-9);
}

}  // namespace
}  // namespace afemp::analysis
