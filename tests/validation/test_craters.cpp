// V3 and V4 (label `validation`): craters in a thick copper target (Ma 2005, §3.2.1-3.2.2) on
// a grid sized to the region of interest. examples/hypervelocity/crater_sphere.toml (a 0.5 g
// copper sphere at 6 km/s, crater at 32 us) and crater_cylinder.toml (a copper cylinder d 5,
// h 4 at 4, 5, 6, 7 km/s, crater at 45 us): quarter models, cells of 1 mm, 8 particles per
// cell as in Ma 2005, a grid that holds the 40 mm target (half width 40) and 10 mm above it
// with outflow faces all round, so the back-spray leaves the run. The crater is measured on
// the target's particles (analysis/crater_metrics.hpp, rings of 1 mm, threshold 1 mm).
// References: V3, the experiment, depth 14 and diameter 25.4; V4, MPM3D's table (Ma 2005),
// diameter/depth 24/12, 25/14, 28/16, 30/17; pass mark (VALIDATION): within 15 %, the depth
// growing with speed, no energy created (balance within 3 %, outflow booked) and mass + outflow
// mass constant to 1e-12. V3 is also run on the large grid the crater runs needed without
// outflow (300 x 300 x 220 mm around the target: 150 x 150 x 220 in the quarter model), and
// the two craters must agree within 2 %; the wall times are printed, not asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/crater_metrics.hpp"
#include "analysis/reference_checks.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "example_text.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::mpm {
namespace {

using test::replaced;

struct Crater {
  double depth = 0.0, diameter = 0.0;
  core::RunSummary summary;
  double mass_drift = 0.0;  // |mass + outflow mass - initial mass| / initial mass
};

Crater run_crater(const std::string& text, const std::string& name) {
  const core::Scene scene = core::parse_scene(text, name);
  MpmModel model(scene);
  const int target = 1;
  const Vec3 point{0.0, 0.0, 0.0}, normal{0.0, 0.0, 1.0};
  const double level = analysis::surface_level(model.body_points(target).position, point, normal);
  Crater c;
  c.summary = analysis::run(model, scene, {});
  const analysis::CraterMeasures m =
      analysis::measure_crater(model.body_points(target).position, point, normal, level, 1.0, 1.0);
  c.depth = m.depth;
  c.diameter = m.diameter;
  double m0 = 0.0, m1 = c.summary.final.outflow_mass;
  for (const core::BodySums& b : c.summary.initial.bodies) m0 += b.mass;
  for (const core::BodySums& b : c.summary.final.bodies) m1 += b.mass;
  c.mass_drift = std::abs(m1 - m0) / m0;
  std::printf(
      "%s: depth %.2f, diameter %.2f mm; %ld steps, %.1f s wall on %d thread(s), %zu "
      "particles; energy error %+.2f %% (largest %.2f %%), outflow %.3g g (%.2f %% of "
      "the kinetic energy), mass drift %.1e\n",
      name.c_str(), c.depth, c.diameter, c.summary.steps, c.summary.wall_seconds,
      core::thread_count(), c.summary.particles, 100.0 * c.summary.energy_error,
      100.0 * c.summary.max_energy_error, c.summary.final.outflow_mass,
      100.0 * c.summary.final.outflow / c.summary.initial.kinetic, c.mass_drift);
  return c;
}

void expect_balanced(const Crater& c) {
  EXPECT_LT(c.summary.max_energy_error, 0.03);
  EXPECT_LT(c.mass_drift, 1e-12);
}

TEST(Craters, V3SphereAtSixKilometresPerSecondOnAGridSizedToTheTarget) {
  const std::string text = test::example_text("hypervelocity/crater_sphere.toml");
  const Crater small = run_crater(text, "V3, outflow grid 41 x 41 x 51");
  EXPECT_NEAR(small.depth, 14.0, 0.15 * 14.0);
  EXPECT_NEAR(small.diameter, 25.4, 0.15 * 25.4);
  EXPECT_GE(small.depth, 12.0);  // VALIDATION's band: depth 12-16, diameter 22-29
  EXPECT_LE(small.depth, 16.0);
  EXPECT_GE(small.diameter, 22.0);
  EXPECT_LE(small.diameter, 29.0);
  expect_balanced(small);
  EXPECT_GT(small.summary.final.outflow_mass, 0.0);  // the back-spray left through the faces

  // The same run on the large grid, every face free: nothing reaches its faces by 32 us.
  std::string large = replaced(text, "min = [0, 0, -41]", "min = [0, 0, -60]");
  large = replaced(large, "max = [41, 41, 10]", "max = [150, 150, 160]");
  large = replaced(
      large,
      R"(boundary = { xmin = "symmetric", ymin = "symmetric", xmax = "outflow", ymax = "outflow", zmin = "outflow", zmax = "outflow" })",
      R"(boundary = { xmin = "symmetric", ymin = "symmetric" })");
  const Crater big = run_crater(large, "V3, large grid 150 x 150 x 220");
  EXPECT_NEAR(small.depth, big.depth, 0.02 * big.depth);
  EXPECT_NEAR(small.diameter, big.diameter, 0.02 * big.diameter);
  std::printf("V3 wall time: %.1f s on the outflow grid, %.1f s on the large grid\n",
              small.summary.wall_seconds, big.summary.wall_seconds);
}

TEST(Craters, V4CylinderAtFourToSevenKilometresPerSecond) {
  const std::string text = test::example_text("hypervelocity/crater_cylinder.toml");
  const double speed[4] = {4000, 5000, 6000, 7000};
  const double diameter[4] = {24, 25, 28, 30}, depth[4] = {12, 14, 16, 17};  // MPM3D
  double previous_depth = 0.0;
  for (int k = 0; k < 4; ++k) {
    char velocity[64], name[64];
    std::snprintf(velocity, sizeof velocity, "velocity = [0, 0, -%g]", speed[k]);
    std::snprintf(name, sizeof name, "V4 at %g km/s", speed[k] / 1000.0);
    const Crater c = run_crater(replaced(text, "velocity = [0, 0, -6000]", velocity), name);
    std::printf("  against MPM3D: depth %.2f / %g (%+.1f %%), diameter %.2f / %g (%+.1f %%)\n",
                c.depth, depth[k], 100.0 * (c.depth / depth[k] - 1.0), c.diameter, diameter[k],
                100.0 * (c.diameter / diameter[k] - 1.0));
    EXPECT_NEAR(c.depth, depth[k], 0.15 * depth[k]) << name;
    EXPECT_NEAR(c.diameter, diameter[k], 0.15 * diameter[k]) << name;
    EXPECT_GT(c.depth, previous_depth) << name;
    previous_depth = c.depth;
    expect_balanced(c);
  }
}

}  // namespace
}  // namespace afemp::mpm
