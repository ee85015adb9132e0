// Shadowed detonations (core/detonation_paths.cpp): the wave travels through explosive only,
// around inert bodies (Huygens' construction). References: points that see the detonation light
// at their straight-line distance over D, exactly; points behind a cylindrical wave shaper (an
// inert disc of radius a from z1 to z2 on the axis of a charge lit at the origin) light at the
// geodesic over its rim, (sqrt(a^2 + z1^2) + (z2 - z1) + sqrt(a^2 + (z - z2)^2)) / D, within
// 2 % (voxels of the point spacing: the path bends within about a voxel of the rim).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "core/detonation_paths.hpp"
#include "core/scene.hpp"
#include "explosive_scenes.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::core {
namespace {

constexpr double kD = 6930.0;
constexpr double kA = 4.0, kZ1 = 4.0, kZ2 = 6.0;  // the wave shaper
constexpr double kS = 0.25;                       // point spacing

// A lattice charge |x|, |y| <= 6, 0 <= z <= 16 without the shaper r < a, z1 < z < z2.
std::vector<Vec3> charge_points(bool shaper, bool cut_through = false) {
  std::vector<Vec3> x;
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 48; ++j)
      for (int i = 0; i < 48; ++i) {
        const Vec3 p{-6.0 + (i + 0.5) * kS, -6.0 + (j + 0.5) * kS, (k + 0.5) * kS};
        const bool in_band = p.z > kZ1 && p.z < kZ2;
        if (shaper && in_band && (cut_through || std::hypot(p.x, p.y) < kA)) continue;
        x.push_back(p);
      }
  return x;
}

double around_the_rim(double z) {
  return (std::hypot(kA, kZ1) + (kZ2 - kZ1) + std::hypot(kA, z - kZ2)) / kD;
}

DetonationSpec origin(bool shadow) {
  DetonationSpec d;
  d.point = {0, 0, 0};
  d.shadow = shadow;
  return d;
}

TEST(DetonationPaths, PointsThatSeeTheDetonationLightAtTheirStraightDistance) {
  const std::vector<Vec3> x = charge_points(true);
  const std::vector<double> D(x.size(), kD);
  const std::vector<DetonationSpec> det{origin(true)};
  const std::vector<double> t = lighting_times(x, D, kS, det);
  std::size_t seen = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    // The segment from the origin passes the shaper's band at radius r(z) = r_x z / z_x; it
    // clears the shaper (with a voxel to spare) where r(z1) > a + s.
    const double r = std::hypot(x[i].x, x[i].y);
    const bool clear = x[i].z < kZ1 - kS || r * kZ1 / x[i].z > kA + kS;
    if (!clear) continue;
    ++seen;
    ASSERT_NEAR(t[i], norm(x[i]) / kD, 1e-12 * norm(x[i]) / kD) << "point " << i;
  }
  EXPECT_GT(seen, x.size() / 4);  // about a third of the charge sees the detonation
}

TEST(DetonationPaths, PointsBehindAWaveShaperLightAroundItsRim) {
  const std::vector<Vec3> x = charge_points(true);
  const std::vector<double> D(x.size(), kD);
  const std::vector<DetonationSpec> shadowed{origin(true)}, straight{origin(false)};
  const std::vector<double> t = lighting_times(x, D, kS, shadowed);
  const std::vector<double> t0 = lighting_times(x, D, kS, straight);
  int checked = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (std::abs(x[i].x - 0.125) > 1e-9 || std::abs(x[i].y - 0.125) > 1e-9 || x[i].z < 8.0)
      continue;
    const double reference = around_the_rim(x[i].z);
    std::printf("z = %6.3f: lit at %.5f us, around the rim %.5f us (%+.2f %%), straight %.5f us\n",
                x[i].z, 1e3 * t[i], 1e3 * reference, 100.0 * (t[i] / reference - 1.0), 1e3 * t0[i]);
    EXPECT_NEAR(t[i], reference, 0.02 * reference) << "z " << x[i].z;
    EXPECT_NEAR(t0[i], norm(x[i]) / kD, 1e-15);  // without shadow: the straight line
    ++checked;
  }
  EXPECT_EQ(checked, 32);
}

TEST(DetonationPaths, APlaneWaveLightsEachPointAtItsDistanceFromThePlane) {
  const std::vector<Vec3> x = charge_points(false);
  const std::vector<double> D(x.size(), kD);
  DetonationSpec plane;
  plane.kind = DetonationSpec::Kind::plane;
  plane.point = {0, 0, 0};
  plane.normal = {0, 0, 1};
  plane.time = 1e-4;
  plane.shadow = true;
  const std::vector<DetonationSpec> det{plane};
  const std::vector<double> t = lighting_times(x, D, kS, det);
  for (std::size_t i = 0; i < x.size(); ++i)
    ASSERT_NEAR(t[i], 1e-4 + x[i].z / kD, 1e-12) << "point " << i;
}

TEST(DetonationPaths, ExplosiveCutOffFromTheDetonationIsNeverLit) {
  const std::vector<Vec3> x = charge_points(true, true);  // an inert slab across the charge
  const std::vector<double> D(x.size(), kD);
  const std::vector<DetonationSpec> det{origin(true)};
  const std::vector<double> t = lighting_times(x, D, kS, det);
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i].z < kZ1) {
      ASSERT_NEAR(t[i], norm(x[i]) / kD, 1e-12) << "point " << i;
    } else {
      ASSERT_EQ(t[i], std::numeric_limits<double>::infinity()) << "point " << i;
    }
  }
}

// The same wave shaper in a scene of particles: the charge is placed `outside` a steel disc.
std::string shaper_scene(const std::string& disc_max_radius_box) {
  return R"([run]
end_time = 0.001
[grid]
cell = 0.5
min = [0, 0, 0]
max = [6, 6, 16]
boundary = { xmin = "symmetric", ymin = "symmetric" }
[[bodies]]
name = "charge"
material = "tnt"
shape = { box = { min = [0, 0, 0], max = [6, 6, 16] } }
outside = ["shaper"]
[[bodies]]
name = "shaper"
material = "steel"
)" + disc_max_radius_box +
         R"(
[[detonations]]
point = [0, 0, 0]
shadow = true
)" + test::tnt_material() +
         test::steel_plate_material();
}

TEST(DetonationPaths, ParticlesBehindAWaveShaperLightAroundIt) {
  const Scene scene = parse_scene(
      shaper_scene("shape = { cylinder = { base = [0, 0, 4], radius = 4, length = 2 } }"),
      "shaper.toml");
  mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
  const mpm::Particles& p = solver.particles();
  int checked = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != 0 || std::hypot(p.position[i].x, p.position[i].y) > 0.2 ||
        p.position[i].z < 8.0)
      continue;
    const double reference = around_the_rim(p.position[i].z);
    EXPECT_NEAR(p.light_time[i], reference, 0.02 * reference) << "z " << p.position[i].z;
    ++checked;
  }
  EXPECT_EQ(checked, 32);  // 2 particles per 0.5 mm cell along z from 8 to 16
}

TEST(DetonationPaths, ACutOffParticleChargeIsAnErrorNamingTheBody) {
  const Scene scene = parse_scene(
      shaper_scene("shape = { box = { min = [0, 0, 4], max = [6, 6, 6] } }"), "cut.toml");
  try {
    mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
    FAIL() << "a charge cut off from its detonation ran";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.key(), "shadow");
    EXPECT_NE(what.find("cut.toml"), std::string::npos) << what;
    EXPECT_NE(what.find("\"charge\" are never lit"), std::string::npos) << what;
  }
}

TEST(DetonationPaths, AShadowedDetonationAwayFromTheExplosiveIsAnError) {
  const std::vector<Vec3> x = charge_points(false);
  const std::vector<double> D(x.size(), kD);
  DetonationSpec far = origin(true);
  far.point = {0, 0, -5};
  const std::vector<DetonationSpec> det{far};
  try {
    lighting_times(x, D, kS, det);
    FAIL() << "a detonation 5 mm from the explosive was taken";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "shadow");
    EXPECT_NE(std::string(e.what()).find("must lie in or on it"), std::string::npos) << e.what();
  }
}

TEST(DetonationPaths, HexahedraLightAtTheirCentresStraightDistanceWhenInSight) {
  const Scene scene = parse_scene(R"([run]
end_time = 0.001
[[bodies]]
name = "charge"
discretisation = "hexahedra"
material = "tnt"
shape = { box = { min = [0, 0, 0], max = [4, 4, 8] } }
mesh = { size = 0.5 }
[[detonations]]
point = [0, 0, 0]
shadow = true
)" + test::tnt_material(),
                                  "hex.toml");
  const fem::FeSolver solver(scene);
  const fem::HexElements& h = solver.hexahedra();
  const fem::FeNodes& n = solver.nodes();
  for (std::size_t e = 0; e < h.size(); ++e) {
    Vec3 centre;
    for (std::int32_t k : h.nodes[e]) centre += 0.125 * n.position[static_cast<std::size_t>(k)];
    ASSERT_NEAR(h.light_time[e], norm(centre) / kD, 1e-12 * norm(centre) / kD) << "element " << e;
  }
}

}  // namespace
}  // namespace afemp::core
