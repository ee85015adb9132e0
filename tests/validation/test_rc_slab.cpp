// V6 (label `validation`): perforation of a reinforced-concrete slab in the Hanchak et al.
// (1992) geometry, examples/rc_slab/scene.toml: a 0.5 kg, 25.4 mm, CRH 3 ogive-nosed steel rod
// (hexahedra in grid contact with the concrete, CFEMP; nose elements whose step would fall below
// 0.2 h / c become particles, AFEMP) through a 610 x 610 x 178 mm slab of 48 MPa HJC concrete
// particles with a rebar mat near each face bonded into it (HFEMP); quarter model, 8 mm cells,
// 3 particles per cell per direction.
// Each run ends when the rod's centre of mass has moved 343.7 mm ([run] terminate: its tail
// 20 mm past the rear face) and reports the residual velocity Vr, the rod's mean velocity then.
// Pass mark (VALIDATION V6): every run completes, the energy balance error stays below 5 %
// (largest over the history), Vr < Vs, and Vr rises with Vs (the published trend: perforation
// over 300-1100 m/s). The measured residual velocities of the paper are not asserted: the
// quarter model's 8 mm cells put about 1.6 cells across the rod's radius. Wall times are
// printed, not asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "afemp/simulation.hpp"
#include "analysis/reference_checks.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "coupling/coupled_model.hpp"
#include "example_text.hpp"

namespace afemp::coupling {
namespace {

using test::replaced;

std::string example() {
  return test::example_text("rc_slab/scene.toml");
}

struct Row {
  double striking = 0.0, residual = 0.0;
  core::RunSummary summary;
};

Row run_row(double striking) {
  char velocity[64];
  std::snprintf(velocity, sizeof velocity, "velocity = [0, 0, -%g]", striking);
  const std::string text = replaced(example(), "velocity = [0, 0, -1058]", velocity);
  const core::Scene scene = core::parse_scene(text, "rc_slab.toml");
  int rod = -1;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (scene.bodies[b].name == "projectile") rod = static_cast<int>(b);
  EXPECT_GE(rod, 0);
  CoupledModel model(scene);
  Row row;
  row.striking = striking;
  row.summary = analysis::run(model, scene, {});
  const core::BodySums& p = row.summary.final.bodies.at(static_cast<std::size_t>(rod));
  row.residual = -p.momentum.z / p.mass;
  const core::RunSummary& s = row.summary;
  std::printf("| %g | %.0f | %.3f | %s | %+.2f %% | %.2f %% | %.3g | %ld | %zu | %.0f | %d |\n",
              striking, row.residual, row.residual / striking, s.terminated.empty() ? "no" : "yes",
              100.0 * s.energy_error, 100.0 * s.max_energy_error, s.time, s.steps,
              s.final_particles, s.wall_seconds, core::thread_count());
  std::fflush(stdout);
  return row;
}

TEST(RcSlab, RodPerforatesWithResidualVelocityRisingWithStrikingVelocity) {
  std::printf(
      "| Vs (m/s) | Vr (m/s) | Vr/Vs | through | energy error (end) | largest |energy "
      "error| | t (ms) | steps | particles (end) | wall s | threads |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Row> rows;
  for (double vs : {434.0, 606.0, 746.0, 1058.0}) {
    rows.push_back(run_row(vs));
    const Row& r = rows.back();
    EXPECT_FALSE(r.summary.terminated.empty()) << "Vs " << vs << ": the rod did not get through";
    EXPECT_LT(r.summary.max_energy_error, 0.05) << "Vs " << vs;
    EXPECT_LT(r.residual, vs) << "Vs " << vs;
    if (rows.size() > 1) {
      EXPECT_GT(r.residual, rows[rows.size() - 2].residual) << "Vs " << vs;
    }
  }
}

// V6 preloaded (issue: implicit phases, "V6 with the slab preloaded by its own weight and the
// rebar prestressed"): examples/rc_slab/preloaded.toml, the same slab resting on a rigid rim
// under gravity with every bar prestressed to sigma_p = 300 MPa (8.48 kN a bar), brought into
// equilibrium by a relaxation phase (t 0 -> 20) before the rod strikes at 1058 m/s.
// References at the switch, in the slab's middle (x, y < 200 mm: away from the bars' anchored
// ends at 285 mm and the free edges):
// - the bars' elastic-shortening loss in biaxial compression: with equal strains in steel and
//   concrete and sigma_s A_s + sigma_c A_c = 0 each way, eps_c = sigma_c (1 - nu_c) / E_c,
//   sigma_s = sigma_p / (1 + E_s (1 - nu_c) rho / E_c), rho = A_s / A_c = 2 (pi 3^2) / (75 x 178)
//   (two mats, 75 mm apart); within 5 % (the bonded tendon along a prism of
//   tests/fem/test_static_phase.cpp comes within 2.2 %);
// - the concrete's mean sigma_xx and sigma_yy = -sigma_s rho, within 5 %;
// - the frame's vertical reaction = the weight of the quarter slab and its rebar, within 2 %.
// Then the impact: through, Vr < Vs, energy error below 5 % (V6's marks), and Vr within 5 % of
// Vs of the unloaded run's (scene.toml, run here too): 1.2 MPa of compression beside 48 MPa
// concrete and bars at 0.7 of their yield change the resistance little; a larger change would
// be a state handed on wrong.
TEST(RcSlab, PreloadedSlabStartsTheImpactFromItsRelaxedStresses) {
  const std::string text = test::example_text("rc_slab/preloaded.toml");
  const core::Scene scene = core::parse_scene(text, "preloaded.toml");
  SimulationOptions options;
  options.phase_log = &std::cout;
  Simulation sim(scene, options);
  const double switch_time = 20.0;
  sim.run_to(switch_time);
  ASSERT_DOUBLE_EQ(sim.time(), switch_time);
  const long relaxation_steps = sim.step_count();

  // Concrete: K_e = PC / muc, G from the scene; steel E_s = 200 GPa.
  const double K = 16.0 / 0.001, G = 14.86e3, Es = 200e3;
  const double Ec = 9.0 * K * G / (3.0 * K + G), nuc = (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
  const double rho = 2.0 * std::numbers::pi * 9.0 / (75.0 * 178.0);
  const double sigma_s = 300.0 / (1.0 + Es * (1.0 - nuc) * rho / Ec);
  const double sigma_c = -sigma_s * rho;

  int slab = -1, rebar = -1, rod = -1;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (scene.bodies[b].name == "slab") slab = static_cast<int>(b);
    if (scene.bodies[b].name == "rebar") rebar = static_cast<int>(b);
    if (scene.bodies[b].name == "projectile") rod = static_cast<int>(b);
  }
  ASSERT_TRUE(slab >= 0 && rebar >= 0 && rod >= 0);
  const ElementFields t = sim.trusses();
  const NodeFields n = sim.nodes();
  double bar_sum = 0.0, bar_min = 1e30, bar_max = -1e30;
  int bars = 0;
  for (std::size_t e = 0; e < t.size(); ++e) {
    const Vec3 mid = 0.5 * (n.position[static_cast<std::size_t>(t.connectivity[2 * e])] +
                            n.position[static_cast<std::size_t>(t.connectivity[2 * e + 1])]);
    if (mid.x > 200.0 || mid.y > 200.0) continue;
    const double s = t.stress[t.first_point[e]].xx;
    bar_sum += s, bar_min = std::min(bar_min, s), bar_max = std::max(bar_max, s), ++bars;
  }
  const ParticleFields p = sim.particles();
  double sxx = 0.0, syy = 0.0;
  int points = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != slab || p.position[i].x > 200.0 || p.position[i].y > 200.0) continue;
    sxx += p.stress[i].xx, syy += p.stress[i].yy, ++points;
  }
  ASSERT_GT(bars, 0);
  ASSERT_GT(points, 0);
  const double bar = bar_sum / bars;
  sxx /= points, syy /= points;
  const Energies e0 = sim.energies();
  const double weight = (e0.bodies.at(static_cast<std::size_t>(slab)).mass +
                         e0.bodies.at(static_cast<std::size_t>(rebar)).mass) *
                        core::norm(scene.run.gravity);
  std::printf(
      "relaxed in %ld steps: bars in the middle %.4g MPa (%.4g to %.4g; closed form %.4g, "
      "%+.2f %%), concrete sigma_xx %.4g, sigma_yy %.4g MPa (closed form %.4g: %+.2f, %+.2f %%)\n",
      relaxation_steps, bar, bar_min, bar_max, sigma_s, 100.0 * (bar / sigma_s - 1.0), sxx, syy,
      sigma_c, 100.0 * (sxx / sigma_c - 1.0), 100.0 * (syy / sigma_c - 1.0));
  EXPECT_NEAR(bar / sigma_s, 1.0, 0.05);
  EXPECT_NEAR(sxx / sigma_c, 1.0, 0.05);
  EXPECT_NEAR(syy / sigma_c, 1.0, 0.05);
  EXPECT_EQ(e0.bodies.at(static_cast<std::size_t>(slab)).kinetic, 0.0);

  const RunSummary s = sim.run();
  // A fixed rigid body's reaction holds its own weight too: the frame's share of the slab's
  // is what is left of it.
  double reaction = 0.0, frame_weight = 0.0;
  for (const ProbeSeries& probe : s.probes) {
    const int rfz = probe.column("rfz");
    ASSERT_GE(rfz, 0) << probe.name;
    for (std::size_t r = 0; r < probe.rows(); ++r)
      if (probe.time[r] == switch_time) reaction += probe.at(r, static_cast<std::size_t>(rfz));
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      if (scene.bodies[b].name == probe.name)
        frame_weight += e0.bodies.at(b).mass * core::norm(scene.run.gravity);
  }
  ASSERT_GT(frame_weight, 0.0);
  reaction -= frame_weight;
  std::printf(
      "frame reaction at the switch %.5g N (its own weight %.4g N taken off), weight %.5g N "
      "(%+.2f %%)\n",
      reaction, frame_weight, weight, 100.0 * (std::abs(reaction) / weight - 1.0));
  EXPECT_NEAR(std::abs(reaction) / weight, 1.0, 0.02);

  const BodySums& r = s.final.bodies.at(static_cast<std::size_t>(rod));
  const double vs = 1058.0, vr = -r.momentum.z / r.mass;
  std::printf(
      "preloaded: Vr %.0f m/s, energy error %+.2f %% (largest %.2f %%), %ld steps, %.0f s, "
      "%d threads\n",
      vr, 100.0 * s.energy_error, 100.0 * s.max_energy_error, s.steps, s.wall_seconds,
      core::thread_count());
  EXPECT_FALSE(s.terminated.empty()) << "the rod did not get through";
  EXPECT_LT(s.max_energy_error, 0.05);
  EXPECT_LT(vr, vs);
  const Row unloaded = run_row(vs);
  std::printf("Vr preloaded %.0f m/s, unloaded %.0f m/s (%+.2f %% of Vs)\n", vr, unloaded.residual,
              100.0 * (vr - unloaded.residual) / vs);
  EXPECT_NEAR((vr - unloaded.residual) / vs, 0.0, 0.05);
}

}  // namespace
}  // namespace afemp::coupling
