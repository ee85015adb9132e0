// End to end: a 1 x 1 x 10 mm column of AD995 alumina (JH-2, as usually quoted from Johnson &
// Holmquist 1994) hits a rigid wall at 300 m/s with its sides held in uniaxial strain, once as
// MPM particles (symmetric grid faces, a "wall" face) and once as one-point hexahedra (fixed
// lateral planes, a rigid wall). The impact stress, about rho c v = 9 GPa, passes the HEL
// (2.79 GPa): the ceramic yields, damages and bulks. At the end every point must carry the
// JH-2 pressure for its density and the bulking pressure it started the last step with (or the
// tension limit), a deviator on or inside the strength surface of the damage it started the
// step with, on it where it flowed, and the damaged points a bulking pressure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/materials/material.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp {
namespace {

// C = 0: the rate factor is 1, so a point's strength is known from its state alone.
const std::string kAlumina = R"(
[materials.alumina]
density = 3700
G = 90.16e9
strength = { model = "johnson-holmquist-2", A = 0.93, B = 0.31, C = 0.0, M = 0.6, N = 0.6, T = 0.2e9, HEL = 2.79e9, PHEL = 1.46e9, beta = 1.0, D1 = 0.005, D2 = 1.0 }
eos = { model = "jh2-pressure", K1 = 130.95e9 }
)";

constexpr double kEndTime = 2e-6;  // the release from the free end has passed the wall

// The state of every point before the last step: damage, plastic strain, bulking pressure.
struct Before {
  std::vector<double> damage, plastic, history;
};

template <class Solver, class Points>
Before run_keeping_last_state(Solver& solver, Points&& points) {
  Before b;
  while (solver.time() < kEndTime) {
    b = {points(solver).damage, points(solver).plastic_strain, points(solver).history};
    solver.step(solver.stable_time_step());
  }
  return b;
}

// Compares every point of `points` with the closed forms.
template <class Points>
void check_points(const char* label, const core::Material& m, const Points& pts,
                  const Before& before) {
  const auto& s = std::get<core::JohnsonHolmquist2>(m.strength);
  const auto& eos = std::get<core::Jh2Pressure>(m.eos);
  ASSERT_EQ(pts.history_count, 1u);
  int damaged = 0, bulked = 0, flowing = 0;
  double worst_p = 0.0, worst_q = 0.0;
  for (std::size_t i = 0; i < pts.stress.size(); ++i) {
    const double density = [&] {
      if constexpr (requires { pts.density; })
        return pts.density[i];
      else
        return pts.mass[i] / pts.volume[i];
    }();
    const double mu = density / m.density - 1.0;
    // Pressure: max(P(mu, dP_before), -T (1 - D_before)); 1e-9 of PHEL.
    const double p_ref = std::max(eos.pressure(mu, before.history[i]),
                                  -s.tensile_strength * (1.0 - before.damage[i]));
    const double p = core::pressure(pts.stress[i]);
    worst_p = std::max(worst_p, std::abs(p - p_ref));
    EXPECT_NEAR(p, p_ref, 1e-9 * 1.46e9) << label << " point " << i;
    // Deviator: q <= sigma_HEL sigma*(P*, D_before), equal where the point flowed.
    const double q_yield =
        s.hel_strength() * s.normalised_strength(p / s.hel_pressure, before.damage[i], 0.0);
    const double q = core::von_mises(pts.stress[i]);
    EXPECT_LE(q, q_yield * (1.0 + 1e-9) + 1e-3) << label << " point " << i;
    if (pts.plastic_strain[i] > before.plastic[i]) {
      ++flowing;
      worst_q = std::max(worst_q, std::abs(q - q_yield) / q_yield);
      EXPECT_NEAR(q, q_yield, 1e-9 * q_yield) << label << " point " << i;
    }
    if (pts.damage[i] > 0.0) {
      ++damaged;
      // Damage releases elastic energy, which bulks (beta = 1).
      bulked += pts.history[i] > 0.0;
    }
  }
  std::printf(
      "JH-2 column %s: %zu points, %d damaged, %d of them bulked, %d flowing in the last step; "
      "largest |P - closed form| %.3g Pa, |q / q_yield - 1| %.3g\n",
      label, pts.stress.size(), damaged, bulked, flowing, worst_p, worst_q);
  EXPECT_GT(damaged, 0) << label;
  EXPECT_EQ(bulked, damaged) << label;
}

TEST(Jh2Column, MpmParticlesFollowThePressureLawAndStrengthSurface) {
  const core::Scene scene = core::parse_scene(R"([run]
end_time = 2e-6

[grid]
cell = 5e-4
min = [0, 0, 0]
max = [0.001, 0.001, 0.0115]
boundary = { xmin = "symmetric", xmax = "symmetric", ymin = "symmetric", ymax = "symmetric", zmin = "wall" }
)" + kAlumina + R"(
[[bodies]]
name = "column"
material = "alumina"
shape = { box = { min = [0, 0, 0], max = [0.001, 0.001, 0.01] } }
velocity = [0, 0, -300]
)",
                                              "jh2_column_mpm.toml");
  mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
  const Before before = run_keeping_last_state(
      solver, [](const mpm::MpmSolver& s) -> auto& { return s.particles(); });
  check_points("MPM", scene.materials.at(0), solver.particles(), before);
}

TEST(Jh2Column, HexahedraFollowThePressureLawAndStrengthSurface) {
  std::string lateral;
  for (const char* plane :
       {"point = [0, 0, 0], normal = [1, 0, 0]", "point = [0.001, 0, 0], normal = [1, 0, 0]"})
    lateral += std::string("[[constraints]]\nnodes = { plane = { ") + plane +
               ", tolerance = 1e-9 } }\nfixed = [\"x\"]\n";
  for (const char* plane :
       {"point = [0, 0, 0], normal = [0, 1, 0]", "point = [0, 0.001, 0], normal = [0, 1, 0]"})
    lateral += std::string("[[constraints]]\nnodes = { plane = { ") + plane +
               ", tolerance = 1e-9 } }\nfixed = [\"y\"]\n";
  const core::Scene scene = core::parse_scene("[run]\nend_time = 2e-6\n" + kAlumina + R"(
[[bodies]]
name = "column"
discretisation = "hexahedra"
material = "alumina"
shape = { box = { min = [0, 0, 0], max = [0.001, 0.001, 0.01] } }
mesh = { divisions = [2, 2, 40] }
velocity = [0, 0, -300]

[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
)" + lateral,
                                              "jh2_column_fe.toml");
  fem::FeSolver solver(scene);
  const Before before = run_keeping_last_state(
      solver, [](const fem::FeSolver& s) -> auto& { return s.hexahedra(); });
  check_points("FE", scene.materials.at(0), solver.hexahedra(), before);
}

}  // namespace
}  // namespace afemp
