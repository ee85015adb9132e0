// V5 (label `validation`): a copper sphere (d 8) through a copper plate (t 2) at 2-6 km/s
// (Ma 2005, §3.1.1), examples/hypervelocity/plate_sphere.toml: quarter model, cells of 0.5 mm,
// 2 particles per cell direction, Johnson-Cook damage (OFHC copper), outflow faces all round.
// The hole is read on the plate's particles in a 1 mm slab about its mid-plane
// (analysis::measure_hole) at the scene's end time, 16 us, and every 2 us before it to show
// that the rim has stopped growing by then. References: the three empirical laws Ma 2005
// (§3.1.1, Fig. 3.2) compares with, v in km/s for A and B:
//   A (Maiden, as Ma quotes it)  Dc/d = 0.45 v (t/d)^(2/3) + 0.9
//   B                            Dc/d = 1.66 (v - 1)^0.5 (t/d)^0.5
//   C (strength and density)     Dc/d = 1.68 ln(v / sqrt(Y / rho)) - 1.91, the plate's Y, rho.
// Ma reports his own MPM holes between them, near A and B only at high speed. Pass mark
// (VALIDATION V5): at every speed the hole lies between min(A, B) and C and grows with speed;
// at 6 km/s within 25 % of max(A, B); no energy created (balance within 3 %, outflow booked)
// and mass + outflow mass constant to 1e-12; the rim stopped (below). Wall times are printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <variant>
#include <vector>

#include "analysis/crater_metrics.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "example_text.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::mpm {
namespace {

using test::replaced;

constexpr double sphere_d = 8.0, plate_t = 2.0;  // mm
constexpr double sample_every = 0.002;           // ms: the hole's history, every 2 us
// The rim has stopped when the hole grows by less than 0.5 mm over the last 4 us: the hole is
// twice the smallest radius of the slab's particles, so one particle moving by a spacing
// (0.25 mm: 0.5 mm cells, 2 particles per cell direction) moves it by 0.5 mm; the rim while
// still opening grows by 1.5 mm from 4 to 8 us at 2 km/s. One-sided: once the rim has stopped,
// by about 10 us, the reading falls at some speeds (by 1.4 mm from 10 to 16 us at 3 km/s; the
// cause is not established), and the mark is about the rim no longer opening.
constexpr double settle_window = 0.004, settle_bound = 0.5;

// Ma 2005 §3.1.1's laws, diameters in mm; v in m/s (the scene's unit), Y in MPa, rho in g/mm^3.
double law_a(double v) {
  return sphere_d * (0.45 * v / 1000.0 * std::cbrt(std::pow(plate_t / sphere_d, 2.0)) + 0.9);
}
double law_b(double v) {
  return sphere_d * 1.66 * std::sqrt(v / 1000.0 - 1.0) * std::sqrt(plate_t / sphere_d);
}
// sqrt(Y / rho) with Y in N/mm^2 and rho in g/mm^3 is in m/s.
double law_c(double v, double yield, double rho) {
  return sphere_d * (1.68 * std::log(v / std::sqrt(yield / rho)) - 1.91);
}

struct Hole {
  std::vector<double> times, diameters;  // every sample_every, the last at the end time
  core::RunSummary summary;
  double mass_drift = 0.0;  // |mass + outflow mass - initial mass| / initial mass
  double diameter() const { return diameters.back(); }
  // The growth of the hole over the last settle_window (< 0: it fell).
  double late_growth() const {
    const double t0 = times.back() - settle_window;
    for (std::size_t k = 0; k < times.size(); ++k)
      if (times[k] >= t0 - 1e-9) return diameters.back() - diameters[k];
    return diameters.back();
  }
};

Hole run_hole(const core::Scene& scene, int plate) {
  MpmModel model(scene);
  const Vec3 point{0.0, 0.0, -0.5 * plate_t}, normal{0.0, 0.0, 1.0};
  const double band = 0.5;
  Hole h;
  auto sample = [&] {
    h.times.push_back(model.time());
    h.diameters.push_back(
        analysis::measure_hole(model.body_points(plate).position, point, normal, band));
  };
  double next = sample_every;
  core::TimeLoop loop(model, scene, {});
  // Each sample at the first step at or past its time (a step is about 15 ns), so that the
  // run steps exactly as `afemp run` and the study do.
  loop.run([&] {
    if (model.time() >= next * (1.0 - 1e-9) && !loop.finished()) {
      sample();
      next += sample_every;
    }
  });
  h.summary = loop.finish();
  sample();
  double m0 = 0.0, m1 = h.summary.final.outflow_mass;
  for (const core::BodySums& b : h.summary.initial.bodies) m0 += b.mass;
  for (const core::BodySums& b : h.summary.final.bodies) m1 += b.mass;
  h.mass_drift = std::abs(m1 - m0) / m0;
  return h;
}

TEST(Hole, V5SphereThroughAThinPlateAtTwoToSixKilometresPerSecond) {
  const std::string text = test::example_text("hypervelocity/plate_sphere.toml");
  const double speeds[5] = {2000, 3000, 4000, 5000, 6000};
  double previous = 0.0, wall = 0.0;
  for (double v : speeds) {
    char velocity[64], name[64];
    std::snprintf(velocity, sizeof velocity, "velocity = [0, 0, -%g]", v);
    std::snprintf(name, sizeof name, "V5 at %g km/s", v / 1000.0);
    const core::Scene scene =
        core::parse_scene(replaced(text, "velocity = [0, 0, -2000]", velocity), name);
    const auto plate = std::find_if(scene.bodies.begin(), scene.bodies.end(),
                                    [](const core::BodySpec& b) { return b.name == "plate"; });
    ASSERT_NE(plate, scene.bodies.end());
    const core::Material& copper = scene.materials[static_cast<std::size_t>(plate->material)];
    const auto* j2 = std::get_if<J2Plasticity>(&copper.strength);
    ASSERT_NE(j2, nullptr);
    const double a = law_a(v), b = law_b(v), c = law_c(v, j2->yield_stress, copper.density);
    const double low = std::min(a, b), high = std::max(a, b);

    const Hole h = run_hole(scene, static_cast<int>(plate - scene.bodies.begin()));
    wall += h.summary.wall_seconds;
    std::printf("%s: hole %.2f mm at %.0f us; band [min(A, B), C] = [%.2f, %.2f] (A %.2f, B %.2f)",
                name, h.diameter(), 1000.0 * h.times.back(), low, c, a, b);
    if (v == 6000)
      std::printf("; %+.1f %% from max(A, B), tolerance 25 %%",
                  100.0 * (h.diameter() / high - 1.0));
    std::printf("\n  hole against time (us: mm):");
    for (std::size_t k = 0; k < h.times.size(); ++k)
      std::printf(" %.0f: %.2f", 1000.0 * h.times[k], h.diameters[k]);
    std::printf(
        "\n  last %.0f us: %+.2f mm (bound +%.2f); %ld steps, %.1f s wall on %d thread(s), %zu "
        "particles; energy error %+.2f %% (largest %.2f %%, bound 3 %%), outflow %.3g g, mass "
        "drift %.1e\n",
        1000.0 * settle_window, h.late_growth(), settle_bound, h.summary.steps,
        h.summary.wall_seconds, core::thread_count(), h.summary.particles,
        100.0 * h.summary.energy_error, 100.0 * h.summary.max_energy_error,
        h.summary.final.outflow_mass, h.mass_drift);

    EXPECT_GE(h.diameter(), low) << name;
    EXPECT_LE(h.diameter(), c) << name;
    EXPECT_GT(h.diameter(), previous) << name;
    previous = h.diameter();
    if (v == 6000) {
      EXPECT_NEAR(h.diameter(), high, 0.25 * high) << name;
    }
    EXPECT_LT(h.late_growth(), settle_bound) << name;
    EXPECT_LT(h.summary.max_energy_error, 0.03) << name;
    EXPECT_LT(h.mass_drift, 1e-12) << name;
  }
  std::printf("V5 wall time: %.1f s for the five speeds on %d thread(s)\n", wall,
              core::thread_count());
}

}  // namespace
}  // namespace afemp::mpm
