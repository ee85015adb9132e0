// Jet formation without the explosive (validation label): the shaped charge's liner
// (examples/shaped_charge: a 60-degree copper cone, 2 mm wall) alone, every particle started
// at V0 = 1500 m/s normal to the wall, inward and forward. Each element then collapses at the
// cone's half angle, beta = alpha, and the steady collapse theory (Birkhoff, MacDougall, Pugh &
// Taylor 1948; PER's formulas with no Taylor deflection, docs/explosives.md) gives every element
// the same jet velocity, V0 / tan(alpha / 2) = 5598 m/s, the slug V0 tan(alpha / 2) = 402 m/s,
// and a collapse point running along the axis at V0 / sin(alpha) = 3000 m/s. The liner's flow
// speed into the collapse point, V0 / tan(alpha) = 2598 m/s, is below copper's sound speed, so
// a coherent jet is expected.
//
// What it shows: how well the MPM forms a jet where the drive is known exactly, apart from the
// explosive (the V9 shaped charge's tip velocity falls with the cell, docs/validation.md). The
// jet is the liner moving along the axis faster than the collapse point.
// - Its mean velocity (momentum over mass) at 14 us, when the collapse point has passed the
//   liner's base (the base's inner edge reaches the axis at 13.6 us, its outer at 15.4 us),
//   within 5 % of V0 / tan(alpha / 2) at 0.75 and 0.5 mm cells, changing by less than 1 %
//   between them. Measured 2026-12-03 (this test, 1 thread beside other runs, 453 s): 5824 and
//   5850 m/s (+4.0, +4.5 %; change +0.45 %); a scratch form of the run at 0.4 mm 5828 m/s; without
//   splitting 5767, 5794 and 5791 m/s at 0.75, 0.5 and 0.4 mm.
// - Not asserted, printed: its velocity's 10th, 50th and 90th percentiles (by mass; the steady
//   theory has one velocity, the run a spread from the apex's start-up, whose fastest tenth
//   falls with the cell: 8093, 7651 and, at 0.4 mm, 7516 m/s) and its share of the liner's
//   mass (4.4-4.7 % against the theory's sin^2(alpha / 2) = 6.7 % of what collapses: the
//   velocity threshold is not the theory's split into jet and slug).
// - Energy balance within 1 % (what leaves through the outflow faces booked). The 5 % and 1 %
//   marks were set after the scratch runs above.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "afemp/energies.hpp"
#include "core/scene.hpp"
#include "example_text.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

constexpr double v0 = 1500.0;                     // m/s
constexpr double alpha = std::numbers::pi / 6.0;  // the cone's half angle

struct JetAt14 {
  double mass = 0.0, liner_mass = 0.0;
  double mean_vz = 0.0;  // m/s
  double p10 = 0.0, p50 = 0.0, p90 = 0.0;
  double energy_error = 0.0;
};

JetAt14 collapse(const std::string& cell) {
  // The example's liner, its copper and its [mpm] table (scheme, splitting), taken from
  // examples/shaped_charge/scene.toml; the grid runs to z = 180 mm, beyond the jet's body at
  // 14 us (a few of the apex's fastest particles reach it by 10 us and leave, booked as
  // outflow).
  const std::string example = test::example_text("shaped_charge/scene.toml");
  const std::string text = R"([run]
units = "mm-ms-g"
end_time = 0.014
[grid]
cell = )" + cell + R"(
min = [0, 0, 10]
max = [24, 24, 180]
boundary = { xmin = "symmetric", ymin = "symmetric", xmax = "outflow", ymax = "outflow", zmin = "outflow", zmax = "outflow" }
)" + test::table(example, "[mpm]") +
                           test::table(example, "[materials.copper]") +
                           test::table(example, "[[bodies]]", "name = \"liner\"");
  const core::Scene scene = core::parse_scene(text, "birkhoff.toml");
  Particles start = generate_particles(scene);
  for (std::size_t i = 0; i < start.size(); ++i) {  // V0 along the wall's inward normal
    const Vec3& x = start.position[i];
    const double r = std::hypot(x.x, x.y);
    const double c = r > 0.0 ? v0 * std::cos(alpha) / r : 0.0;
    start.velocity[i] = {-c * x.x, -c * x.y, v0 * std::sin(alpha)};
  }
  MpmSolver solver(scene, std::move(start));
  const Particles& p = solver.particles();
  JetAt14 jet;
  for (std::size_t i = 0; i < p.size(); ++i) jet.liner_mass += p.mass[i];
  const core::Energies e0 = solver.energies();
  double max_kinetic = e0.kinetic;
  while (solver.time() < 0.014 - 1e-12) {
    solver.step(std::min(solver.stable_time_step(), 0.014 - solver.time()));
    max_kinetic = std::max(max_kinetic, solver.energies().kinetic);
  }
  jet.energy_error = core::energy_balance_error(solver.energies(), e0, max_kinetic);
  const double collapse_point = v0 / std::sin(alpha);
  std::vector<std::pair<double, double>> by_speed;  // (vz, mass) of the jet's particles
  double momentum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.velocity[i].z <= collapse_point) continue;
    jet.mass += p.mass[i], momentum += p.mass[i] * p.velocity[i].z;
    by_speed.emplace_back(p.velocity[i].z, p.mass[i]);
  }
  std::sort(by_speed.begin(), by_speed.end());
  auto percentile = [&](double f) {
    double below = 0.0;
    for (const auto& [vz, m] : by_speed)
      if ((below += m) >= f * jet.mass) return vz;
    return by_speed.empty() ? 0.0 : by_speed.back().first;
  };
  jet.mean_vz = jet.mass > 0.0 ? momentum / jet.mass : 0.0;
  jet.p10 = percentile(0.1), jet.p50 = percentile(0.5), jet.p90 = percentile(0.9);
  return jet;
}

TEST(BirkhoffJet, MeanJetVelocityConvergesWithin5PercentOfTheSteadyTheory) {
  const double theory = v0 / std::tan(0.5 * alpha);
  const JetAt14* coarser = nullptr;
  JetAt14 runs[2];
  int k = 0;
  for (const char* cell : {"0.75", "0.5"}) {
    const JetAt14& jet = runs[k++] = collapse(cell);
    std::printf(
        "%s mm: the jet (faster than the collapse point, %.0f m/s) %.3f g, %.2f %% of the liner's "
        "mass (steady theory %.2f %% of what collapses); mean vz %.0f m/s, %+.1f %% of V0 / "
        "tan(alpha / 2) = %.0f m/s; vz by mass p10/p50/p90 %.0f/%.0f/%.0f m/s; balance %+.2f %%\n",
        cell, v0 / std::sin(alpha), jet.mass, 100.0 * jet.mass / jet.liner_mass,
        100.0 * std::pow(std::sin(0.5 * alpha), 2), jet.mean_vz,
        100.0 * (jet.mean_vz / theory - 1.0), theory, jet.p10, jet.p50, jet.p90,
        100.0 * jet.energy_error);
    std::fflush(stdout);
    EXPECT_NEAR(jet.mean_vz, theory, 0.05 * theory) << cell << " mm";
    EXPECT_LT(std::abs(jet.energy_error), 0.01) << cell << " mm";
    if (coarser) {
      EXPECT_LT(std::abs(jet.mean_vz / coarser->mean_vz - 1.0), 0.01) << cell << " mm";
    }
    coarser = &jet;
  }
}

}  // namespace
}  // namespace afemp::mpm
