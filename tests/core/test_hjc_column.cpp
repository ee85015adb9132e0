// End to end: a 1 x 1 x 10 mm column of the 48 MPa HJC concrete hits a rigid wall at 20 m/s
// with its sides held in uniaxial strain, once as MPM particles (symmetric grid faces, a
// "wall" face) and once as one-point hexahedra (fixed lateral planes, a rigid wall). The wall
// crushes the concrete near it and the release from the free end unloads it; at the end every
// point must carry the compaction law's pressure for its own density and compaction history,
// a deviator on or inside the HJC yield surface, and the crushed ones permanent compaction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/materials/holmquist_johnson_cook.hpp"
#include "core/materials/material.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp {
namespace {

// C = 0: the rate factor is 1, so the yield stress of a point is known from its state alone.
const std::string kConcrete = R"(
[materials.concrete]
density = 2440
G = 14.86e9
strength = { model = "holmquist-johnson-cook", A = 0.79, B = 1.60, N = 0.61, C = 0.0, fc = 48e6, T = 4e6, EFMIN = 0.01, SFMAX = 7.0, D1 = 0.04, D2 = 1.0 }
eos = { model = "hjc-compaction", PC = 16e6, muc = 0.001, PL = 800e6, mul = 0.10, K1 = 85e9, K2 = -171e9, K3 = 208e9 }
)";

constexpr double kEndTime = 6e-6;  // the release from the free end has passed the wall

// One point's state after the last step, with its damage before that step.
struct PointCheck {
  core::SymTensor stress;
  double density, damage_before, max_compaction, plastic_increment;
};

// Runs the solver to the end time and returns its points' damage and plastic strain as they
// were before the last step (the yield check uses the damage the step started with).
// `points(solver)` gives the solver's point storage (particles or hexahedra).
template <class Solver, class Points>
std::pair<std::vector<double>, std::vector<double>> run_keeping_last_history(Solver& solver,
                                                                             Points&& points) {
  std::vector<double> damage, plastic;
  while (solver.time() < kEndTime) {
    damage = points(solver).damage;
    plastic = points(solver).plastic_strain;
    solver.step(solver.stable_time_step());
  }
  return {damage, plastic};
}

// Compares every point with the closed forms; some must have been crushed and unloaded.
void check_points(const char* label, const core::Material& m, const std::vector<PointCheck>& pts) {
  const auto& s = std::get<core::HolmquistJohnsonCook>(m.strength);
  const auto& eos = std::get<core::HjcCompaction>(m.eos);
  int crushed = 0, unloaded = 0, flowing = 0;
  double worst_p = 0.0, worst_q = 0.0;
  for (const PointCheck& pt : pts) {
    const double mu = pt.density / m.density - 1.0;
    ASSERT_GE(pt.max_compaction, mu - 1e-15);
    // Pressure: P = max(P(mu, mu_max), -T (1 - D)); 1e-9 of PC.
    const double p_ref = std::max(eos.pressure(mu, pt.max_compaction),
                                  -s.tensile_strength * (1.0 - pt.damage_before));
    const double p = core::pressure(pt.stress);
    worst_p = std::max(worst_p, std::abs(p - p_ref));
    EXPECT_NEAR(p, p_ref, 1e-9 * 16e6) << label << " mu " << mu;
    // Deviator: q <= fc sigma*(P*, D), equal where the point flowed in the last step.
    const double q_yield = s.compressive_strength *
                           s.normalised_strength(p / s.compressive_strength, pt.damage_before, 0.0);
    const double q = core::von_mises(pt.stress);
    EXPECT_LE(q, q_yield * (1.0 + 1e-9)) << label;
    if (pt.plastic_increment > 0.0) {
      ++flowing;
      worst_q = std::max(worst_q, std::abs(q - q_yield) / q_yield);
      EXPECT_NEAR(q, q_yield, 1e-9 * q_yield) << label;
    }
    if (pt.max_compaction > eos.crush_strain()) {
      ++crushed;
      EXPECT_GT(pt.damage_before, 0.0) << label << ": crushing damages";
    }
    if (pt.max_compaction > eos.crush_strain() && pt.max_compaction - mu > 1e-4) ++unloaded;
  }
  std::printf(
      "HJC column %s: %zu points, %d crushed, %d unloaded from a crush, %d flowing in "
      "the last step; largest |P - closed form| %.3g Pa, |q / q_yield - 1| %.3g\n",
      label, pts.size(), crushed, unloaded, flowing, worst_p, worst_q);
  EXPECT_GT(crushed, 0) << label;
  EXPECT_GT(unloaded, 0) << label;
}

TEST(HjcColumn, MpmParticlesFollowCompactionLawAndYieldSurface) {
  const core::Scene scene = core::parse_scene(R"([run]
end_time = 6e-6
[grid]
cell = 5e-4
min = [0, 0, 0]
max = [0.001, 0.001, 0.0115]
boundary = { xmin = "symmetric", xmax = "symmetric", ymin = "symmetric", ymax = "symmetric", zmin = "wall" }
)" + kConcrete + R"(
[[bodies]]
name = "column"
material = "concrete"
shape = { box = { min = [0, 0, 0], max = [0.001, 0.001, 0.01] } }
velocity = [0, 0, -20]
)",
                                              "hjc_column_mpm.toml");
  mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
  const auto [damage, plastic] = run_keeping_last_history(
      solver, [](const mpm::MpmSolver& s) -> auto& { return s.particles(); });
  const mpm::Particles& p = solver.particles();
  std::vector<PointCheck> pts;
  for (std::size_t i = 0; i < p.size(); ++i)
    pts.push_back({p.stress[i], p.mass[i] / p.volume[i], damage[i],
                   p.history[i * p.history_count + core::kMaxCompaction],
                   p.plastic_strain[i] - plastic[i]});
  check_points("MPM", scene.materials.at(0), pts);
}

TEST(HjcColumn, HexahedraFollowCompactionLawAndYieldSurface) {
  std::string lateral;
  for (const char* plane :
       {"point = [0, 0, 0], normal = [1, 0, 0]", "point = [0.001, 0, 0], normal = [1, 0, 0]"})
    lateral += std::string("[[constraints]]\nnodes = { plane = { ") + plane +
               ", tolerance = 1e-9 } }\nfixed = [\"x\"]\n";
  for (const char* plane :
       {"point = [0, 0, 0], normal = [0, 1, 0]", "point = [0, 0.001, 0], normal = [0, 1, 0]"})
    lateral += std::string("[[constraints]]\nnodes = { plane = { ") + plane +
               ", tolerance = 1e-9 } }\nfixed = [\"y\"]\n";
  const core::Scene scene = core::parse_scene("[run]\nend_time = 6e-6\n" + kConcrete + R"(
[[bodies]]
name = "column"
discretisation = "hexahedra"
material = "concrete"
shape = { box = { min = [0, 0, 0], max = [0.001, 0.001, 0.01] } }
mesh = { divisions = [2, 2, 40] }
velocity = [0, 0, -20]

[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
)" + lateral,
                                              "hjc_column_fe.toml");
  fem::FeSolver solver(scene);
  const auto [damage, plastic] = run_keeping_last_history(
      solver, [](const fem::FeSolver& s) -> auto& { return s.hexahedra(); });
  const fem::HexElements& h = solver.hexahedra();
  std::vector<PointCheck> pts;
  for (std::size_t i = 0; i < h.stress.size(); ++i)
    pts.push_back({h.stress[i], h.density[i], damage[i],
                   h.history[i * h.history_count + core::kMaxCompaction],
                   h.plastic_strain[i] - plastic[i]});
  check_points("FE", scene.materials.at(0), pts);
}

}  // namespace
}  // namespace afemp
