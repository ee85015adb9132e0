// Crater and hole measures (analysis/crater_metrics.hpp) on point sets of known geometry: a flat
// plate of lattice points with a spherical-cap crater of depth d0 and rim radius a cut into its
// top, and a plate with a round hole. References: the cap's depth d0 and its rim diameter 2a
// for a threshold far below d0 (the drop reaches 0 at r = a), the cap's radius where its drop
// equals a given threshold (closed form of the sphere), and the hole's diameter less the
// lattice's sampling of its edge.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/crater_metrics.hpp"

namespace afemp::analysis {
namespace {

constexpr double spacing = 0.25;           // lattice spacing
constexpr double depth0 = 2.0, rim = 4.0;  // crater depth and rim radius
// The sphere through the rim circle and the bottom point: radius (a^2 + d^2) / (2 d).
const double sphere = (rim * rim + depth0 * depth0) / (2.0 * depth0);

// A plate 20 x 20 x 6 about the z axis, top at z = 0, with the cap removed: points whose
// height lies below the cap's surface z_c(r) = -(depth0 - (sphere - sqrt(sphere^2 - r^2))).
std::vector<Vec3> cratered_plate(bool ejecta) {
  std::vector<Vec3> points;
  const int n = static_cast<int>(10.0 / spacing);
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = 0; k <= static_cast<int>(6.0 / spacing); ++k) {
        const Vec3 x{i * spacing, j * spacing, -k * spacing};
        const double r = std::hypot(x.x, x.y);
        const double cap =
            r < rim ? -(depth0 - (sphere - std::sqrt(sphere * sphere - r * r))) : 0.0;
        if (x.z <= cap + 1e-12) points.push_back(x);
      }
  if (ejecta)  // a debris cloud flying up the axis, well clear of the floor
    for (int k = 0; k < 5; ++k) points.push_back({0.05 * k, 0.0, 3.0 + 0.1 * k});
  return points;
}

TEST(CraterMetrics, SphericalCapGivesItsDepthAndRimDiameter) {
  const std::vector<Vec3> points = cratered_plate(false);
  const Vec3 point{0, 0, 0}, normal{0, 0, 1};
  const double level = surface_level(points, point, normal);
  EXPECT_DOUBLE_EQ(level, 0.0);
  // A threshold of a tenth of a spacing: the crater ends where the drop vanishes, at r = rim.
  const CraterMeasures m = measure_crater(points, point, normal, level, spacing, 0.1 * spacing);
  std::printf("crater depth %.4f (ref %.4f), diameter %.4f (ref %.4f)\n", m.depth, depth0,
              m.diameter, 2 * rim);
  // Depth: the lattice's top point within one ring of the axis lies within a spacing of the
  // cap's bottom (it can only be below the cap's surface).
  EXPECT_NEAR(m.depth, depth0, spacing);
  EXPECT_GE(m.depth, depth0 - 1e-12);
  EXPECT_NEAR(m.diameter, 2.0 * rim, 2.0 * spacing);
}

TEST(CraterMetrics, DiameterAtAThresholdFollowsTheSphereAndEjectaAreNotTheFloor) {
  const std::vector<Vec3> points = cratered_plate(true);
  const Vec3 point{0, 0, -1}, unit{0, 0, 1};  // any point on the axis
  const double level = surface_level(cratered_plate(false), point, unit);
  const double threshold = 1.0;
  // The cap's drop at r: depth0 - (sphere - sqrt(sphere^2 - r^2)) = threshold.
  const double s = sphere - depth0 + threshold;
  const double radius = std::sqrt(sphere * sphere - s * s);
  const CraterMeasures m = measure_crater(points, point, unit, level, spacing, threshold);
  std::printf("crater diameter at drop %.2f: %.4f (ref %.4f); depth with ejecta %.4f\n", threshold,
              m.diameter, 2 * radius, m.depth);
  EXPECT_NEAR(m.depth, depth0, spacing);
  EXPECT_NEAR(m.diameter, 2.0 * radius, 2.0 * spacing);
}

TEST(CraterMetrics, AnUntouchedSurfaceHasNoCraterAndAPerforatedOneNoDepth) {
  std::vector<Vec3> flat;
  for (int i = 0; i < 40; ++i)
    for (int k = 0; k < 4; ++k) flat.push_back({i * spacing, 0.0, -k * spacing});
  const CraterMeasures m = measure_crater(flat, {0, 0, 0}, {0, 0, 1}, 0.0, spacing, 0.1);
  EXPECT_DOUBLE_EQ(m.depth, 0.0);
  EXPECT_DOUBLE_EQ(m.diameter, 0.0);
  std::vector<Vec3> holed;
  for (const Vec3& x : flat)
    if (x.x > 1.0) holed.push_back(x);
  const CraterMeasures h = measure_crater(holed, {0, 0, 0}, {0, 0, 1}, 0.0, spacing, 0.1);
  EXPECT_TRUE(std::isnan(h.depth));
  // Every ring out to r = 1.25 is empty (an infinite drop); the first holding material, from
  // r = 1.25 on, is not dropped: the crater's edge is that ring's inner edge.
  EXPECT_DOUBLE_EQ(h.diameter, 2.0 * 1.25);
}

TEST(CraterMetrics, HoleDiameterIsTheLargestFreeCircleInTheMidPlaneSlab) {
  // A plate 2 thick about z = 5 with a hole of radius 1.5 through it, and a plug pushed out
  // below the plate (outside the slab) and a petal bent up at r = 0.5 above it.
  const double hole = 1.5;
  std::vector<Vec3> points;
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j)
      for (int k = 0; k <= 8; ++k) {
        const Vec3 x{i * spacing, j * spacing, 4.0 + k * spacing};
        if (std::hypot(x.x, x.y) >= hole) points.push_back(x);
      }
  points.push_back({0.0, 0.0, 0.5});  // the plug
  points.push_back({0.5, 0.0, 7.5});  // the petal
  const double d = measure_hole(points, {0, 0, 5}, {0, 0, 1}, 1.0);
  // The lattice's nearest point to the axis outside r = 1.5: (1.5, 0), on the hole's edge.
  EXPECT_NEAR(d, 2.0 * hole, 1e-12);
  // A slab that reaches the petal sees it.
  EXPECT_NEAR(measure_hole(points, {0, 0, 5}, {0, 0, 1}, 2.6), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(measure_hole(points, {0, 0, 50}, {0, 0, 1}, 1.0)));
}

}  // namespace
}  // namespace afemp::analysis
