// W1: a stress wave in a free bar. A steel bar moving at v0 meets a fixed end at t = 0: a
// compressive front runs along it at the bar speed c = sqrt(E / rho) with stress rho c v0
// behind it; at the free end it reflects as a tensile wave that cancels the stress and
// reverses the velocity. Run with each update scheme.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

constexpr double young = 200e3, density = 7.85e-3, v0 = 10.0, length = 60.0;

std::string bar_scene(const char* scheme) {
  // Quarter of a 2 x 2 mm bar, 60 mm long, cell 0.5; units mm, ms, g, N, MPa.
  return std::string(R"(
[run]
end_time = 0.02
[grid]
cell = 0.5
min = [0, 0, 0]
max = [3, 3, 61]
boundary = { xmin = "symmetric", ymin = "symmetric", zmin = "fixed" }
[mpm]
scheme = ")") +
         scheme + R"("
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
[[bodies]]
name = "bar"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [1, 1, 60] } }
velocity = [0, 0, -10]
)";
}

// Mean axial stress and velocity of the particles in the slab |z - z0| < half.
struct Slab {
  double stress = 0.0, velocity = 0.0;
};
Slab slab(const Particles& p, double z0, double half) {
  Slab s;
  int n = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (std::abs(p.position[i].z - z0) >= half) continue;
    s.stress += p.stress[i].zz;
    s.velocity += p.velocity[i].z;
    ++n;
  }
  s.stress /= n;
  s.velocity /= n;
  return s;
}

class WaveInBar : public ::testing::TestWithParam<const char*> {};

TEST_P(WaveInBar, FrontRunsAtBarSpeedAndReflectsAsTensionAtTheFreeEnd) {
  const core::Scene scene = core::parse_scene(bar_scene(GetParam()), "w1.toml");
  MpmSolver solver(scene, generate_particles(scene));
  const double c = std::sqrt(young / density);
  const double plateau = -density * c * v0;  // stress behind the front
  const double stations[2] = {10.0, 40.0};
  double arrival[2] = {-1.0, -1.0};
  double prev_time = 0.0, prev_stress[2] = {0.0, 0.0};
  // Sample until the reflected wave is back at mid-length: t = 1.5 L / c.
  const double t_end = 1.5 * length / c;
  Slab near_free_end;
  while (solver.time() < t_end) {
    solver.step(solver.stable_time_step());
    for (int k = 0; k < 2; ++k) {
      const double s = slab(solver.particles(), stations[k], 0.5).stress;
      // Arrival: the first crossing of half the plateau, interpolated in time.
      if (arrival[k] < 0.0 && s <= 0.5 * plateau)
        arrival[k] = prev_time + (solver.time() - prev_time) * (0.5 * plateau - prev_stress[k]) /
                                     (s - prev_stress[k]);
      prev_stress[k] = s;
    }
    prev_time = solver.time();
  }
  near_free_end = slab(solver.particles(), 54.0, 4.0);
  ASSERT_GT(arrival[0], 0.0);
  ASSERT_GT(arrival[1], 0.0);
  const double measured = (stations[1] - stations[0]) / (arrival[1] - arrival[0]);
  std::printf(
      "W1 %s: front speed %.1f m/s, theory %.1f (%+.2f %%); behind the reflected wave: "
      "stress %.1f MPa (plateau %.1f), velocity %.2f m/s (v0 %.1f toward the wall)\n",
      GetParam(), measured, c, 100.0 * (measured / c - 1.0), near_free_end.stress, plateau,
      near_free_end.velocity, v0);
  // Reference: c = sqrt(E / rho), pass mark 2 % (VALIDATION W1).
  EXPECT_NEAR(measured, c, 0.02 * c);
  // Reference: behind the reflected front the free-end reflection (tension, opposite sign to
  // the incident compression) cancels the stress and reverses the velocity to +v0; allow
  // 10 % of the plateau and of v0 for the dispersion of a 3D bar.
  EXPECT_NEAR(near_free_end.stress, 0.0, 0.1 * std::abs(plateau));
  EXPECT_NEAR(near_free_end.velocity, v0, 0.1 * v0);
}

INSTANTIATE_TEST_SUITE_P(Schemes, WaveInBar, ::testing::Values("USF", "USL", "MUSL"));

}  // namespace
}  // namespace afemp::mpm
