// Static and implicit phases between explicit ones (core/phases.hpp: each starts from the state
// the phase before leaves). References: the steel column of test_static_phase.cpp under its
// weight, whose static top displacement is rho g H^2 / 2E (the static phase run first gives it
// on this mesh); the same column run explicitly throughout (the implicit phase between two
// explicit ones must follow it); the energy balance across the phases (what a static phase takes
// out of the motion is booked as damped); and a restart across a phase's start and end.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "afemp/run_directory.hpp"
#include "afemp/simulation.hpp"
#include "core/scene.hpp"
#include "phase_test_support.hpp"
#include "scratch_dir.hpp"

namespace afemp {
namespace {

constexpr double kRho = test::kColumnDensity, kE = test::kColumnModulus, kG = test::kColumnGravity,
                 kH = test::kColumnHeight;
// The half period of the column's modes, 2H/c.
const double kHalfPeriod = 2.0 * kH / std::sqrt(kE / kRho);
using test::max_speed;
using test::top_displacement;

// The column (phase_test_support.hpp) of fully integrated hexahedra, under gravity from t = 0.
std::string column(const std::string& phases, double end_time, const std::string& run = "") {
  return test::column_scene("element = \"full\"", phases, end_time, run);
}

std::string phase(const char* kind, double end, const std::string& extra = "") {
  char text[160];
  if (end > 0.0)
    std::snprintf(text, sizeof text, "[[phases]]\nkind = \"%s\"\nend_time = %.17g\n", kind, end);
  else
    std::snprintf(text, sizeof text, "[[phases]]\nkind = \"%s\"\n", kind);
  return text + extra;
}

// The column swings under gravity applied at once (explicit, to 0.7 of its half period, moving
// fast), then a static phase finds its equilibrium from there: the top displacement of the
// static phase run first (within 1e-4 of it: the increment is a small-strain step on the
// current geometry), at rest; the motion's kinetic energy is booked as damped and the balance
// closes; the explicit phase after it leaves the column at rest.
TEST(PhaseSequence, StaticPhaseAfterAnExplicitOneFindsTheEquilibriumAtRest) {
  const double t1 = 0.7 * kHalfPeriod, t2 = t1 + 0.01, end = t2 + 0.2 * kHalfPeriod;
  Simulation first(core::parse_scene(
      column(phase("static", 0.01) + phase("explicit", 0.0), 0.01 + 0.2 * kHalfPeriod), "c.toml"));
  first.run_to(0.01);
  const double u_static = top_displacement(first);
  const double u_exact = -kRho * kG * kH * kH / (2.0 * kE);

  std::ostringstream log;
  SimulationOptions options;
  options.phase_log = &log;
  Simulation sim(
      core::parse_scene(
          column(phase("explicit", t1) + phase("static", t2) + phase("explicit", 0.0), end),
          "c.toml"),
      options);
  EXPECT_NE(sim.describe().find("2. static, t "), std::string::npos) << sim.describe();
  EXPECT_NE(sim.describe().find("a small-strain step on the current geometry"), std::string::npos);
  sim.run_to(t1);
  const double moving = max_speed(sim);
  const double kinetic = sim.energies().kinetic;
  EXPECT_GT(kinetic, 0.1 * sim.energies().external_work);
  const long steps = sim.step_count();
  const Energies e_t1 = sim.energies();
  std::vector<double> z_t1;
  for (std::size_t i = 0; i < sim.nodes().size(); ++i) z_t1.push_back(sim.nodes().position[i].z);
  sim.run_to(t2);
  EXPECT_EQ(sim.step_count(), steps);  // the static phase is no explicit step
  EXPECT_NEAR(sim.time(), t2, 1e-12);
  EXPECT_NE(log.str().find("the static phase ends at t = "), std::string::npos) << log.str();
  const double u = top_displacement(sim);
  // Not closer: the step is taken on the geometry the swing left (strains of 4e-4).
  EXPECT_NEAR(u / u_static, 1.0, 1e-3) << u << " " << u_static;
  EXPECT_NEAR(u / u_exact, 1.0, 0.01);
  EXPECT_EQ(max_speed(sim), 0.0);
  // Gravity's work f . du over the phase, and the damped energy the motion plus what the
  // stresses do not hold of that work: the balance closes at the switch as it stood before.
  const Energies before_phase = e_t1;
  const Energies e = sim.energies();
  EXPECT_GT(e.damped, kinetic);
  const double gravity_work = [&] {
    const NodeFields n = sim.nodes();
    double w = 0.0;
    for (std::size_t i = 0; i < n.size(); ++i) w -= n.mass[i] * kG * (n.position[i].z - z_t1[i]);
    return w;
  }();
  EXPECT_NEAR(e.external_work - before_phase.external_work, gravity_work,
              1e-9 * std::abs(e.external_work));
  EXPECT_NEAR(e.total() - e.external_work, before_phase.total() - before_phase.external_work,
              1e-9 * e.external_work);
  double fastest = 0.0;
  sim.on_step([&](Simulation& s) { fastest = std::max(fastest, max_speed(s)); });
  const RunSummary summary = sim.run();
  EXPECT_LT(fastest, 0.01 * moving) << fastest << " of " << moving;
  EXPECT_NEAR(top_displacement(sim) / u_static, 1.0, 1e-3);
  // The explicit phase's own measurement (on half-step velocities) at the switch stays in the
  // balance: 0.4 % here, where the all-explicit run reaches 4.7 % in mid-swing.
  EXPECT_LT(std::abs(summary.energy_error), 0.01);
  std::printf(
      "static phase after explicit: u_top %.6g (static first %.6g, closed form %.6g); kinetic "
      "%.4g taken out (damped %.4g); explicit after: fastest node %.3g of %.3g before, balance "
      "at the end %.2g\n",
      u, u_static, u_exact, kinetic, e.damped, fastest, moving, summary.energy_error);
}

// Explicit, implicit (trapezoidal, 50 steps) and explicit again follow the column run explicitly
// throughout: the state and the velocities are handed on both ways (the top within 2 % of the
// static displacement of the all-explicit run at the switches and after).
TEST(PhaseSequence, ImplicitPhaseBetweenExplicitOnesFollowsTheExplicitRun) {
  const double t1 = 0.5 * kHalfPeriod, t2 = 1.3 * kHalfPeriod, end = 2.0 * kHalfPeriod;
  char step[64];
  std::snprintf(step, sizeof step, "time_step = %.17g\n", (t2 - t1) / 50.0);
  Simulation sim(core::parse_scene(
      column(phase("explicit", t1) + phase("implicit", t2, step) + phase("explicit", 0.0), end),
      "c.toml"));
  Simulation reference(core::parse_scene(column("", end), "c.toml"));
  const double u_static = -kRho * kG * kH * kH / (2.0 * kE);
  double worst = 0.0, work = 0.0;
  for (double t : {t1, t2, 1.5 * kHalfPeriod, 1.75 * kHalfPeriod, end}) {
    sim.run_to(t);
    reference.run_to(t);
    work = std::max(work, sim.energies().external_work);
    const double d = std::abs(top_displacement(sim) - top_displacement(reference));
    EXPECT_LT(d / std::abs(u_static), 0.02) << "t " << t;
    worst = std::max(worst, d);
  }
  const Energies e = sim.energies();
  // The implicit phase's share: the mass matrices' difference, at its start and its end (the
  // largest work of gravity on the swing, at the switches, is the scale).
  EXPECT_LT(std::abs(e.damped), 1e-3 * work) << e.damped << " of " << work;
  std::printf(
      "explicit, implicit, explicit: worst |u_top - all-explicit| %.3g of u_static, "
      "damped %.3g of the work %.4g\n",
      worst / std::abs(u_static), e.damped, work);
}

// Restarts across the static phase between explicit ones: from a checkpoint written before it
// (the phase runs after the restart) and from the one at its end, the run ends as the run that
// went through (the history, bit for bit at the same thread count).
TEST(PhaseSequence, RestartsBeforeAndAfterAPhaseBetweenExplicitOnesEndAsTheWholeRun) {
  const test::ScratchDir scratch;
  const double t1 = 0.7 * kHalfPeriod, t2 = t1 + 0.01, end = t2 + 0.2 * kHalfPeriod;
  char every[64];
  std::snprintf(every, sizeof every, "checkpoint_every = %.17g\ncheckpoint_keep = 10\n", 0.5 * t1);
  const core::Scene scene = core::parse_scene(
      column(phase("explicit", t1) + phase("static", t2) + phase("explicit", 0.0), end, every),
      "c.toml");
  const std::filesystem::path whole = scratch.path() / "whole";
  SimulationOptions a;
  a.output_directory = whole.string();
  Simulation first(scene, a);
  first.run();
  auto read = [](const std::filesystem::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  std::vector<std::filesystem::path> checkpoints;
  for (const auto& entry : std::filesystem::directory_iterator(whole / "checkpoints"))
    checkpoints.push_back(entry.path());
  std::sort(checkpoints.begin(), checkpoints.end());
  ASSERT_GE(checkpoints.size(), 2u);
  int restarts = 0;
  for (const std::filesystem::path& checkpoint : checkpoints) {
    const std::filesystem::path again = scratch.path() / ("again" + std::to_string(restarts));
    std::filesystem::copy(whole, again,
                          std::filesystem::copy_options::recursive |
                              std::filesystem::copy_options::overwrite_existing);
    SimulationOptions b;
    b.output_directory = again.string();
    b.restart_from = (again / "checkpoints" / checkpoint.filename()).string();
    Simulation second(scene, b);
    second.run();
    EXPECT_EQ(read(whole / "history.csv"), read(again / "history.csv")) << checkpoint;
    ++restarts;
  }
  std::printf("%d restarts end as the whole run\n", restarts);
}

// A static phase after an explicit one that fails (max_iterations = 1 cannot take the plastic
// steps that three times the gravity asks of a column yielding at 200 MPa) stops the run and
// leaves a checkpoint of the state it started from; the same scene with max_iterations = 25
// restarts from it (a phase's solver settings may change until it starts) and ends as the run
// that went through with 25 from the start.
TEST(PhaseSequence, FailedStaticPhaseRunsAgainFromItsStartWithOtherSettings) {
  const test::ScratchDir scratch;
  const double t1 = 0.5 * kHalfPeriod, t2 = t1 + 0.01, end = t2 + 0.1 * kHalfPeriod;
  auto scene_with = [&](int iterations) {
    std::string text = column(
        phase("explicit", t1) +
            phase("static", t2,
                  "gravity = [0, 0, -300]\nmax_iterations = " + std::to_string(iterations) + "\n") +
            phase("explicit", 0.0),
        end);
    text.replace(text.find("nu = 0.3\n"), 9,
                 "nu = 0.3\nstrength = { model = \"j2\", yield = 200, tangent_modulus = 2000 }\n");
    return core::parse_scene(text, "c.toml");
  };
  const core::Scene failing = scene_with(1), passing = scene_with(25);
  const std::filesystem::path run = scratch.path() / "run", whole = scratch.path() / "whole";
  std::ostringstream log;
  SimulationOptions a;
  a.output_directory = run.string();
  a.phase_log = &log;
  try {
    Simulation first(failing, a);
    first.run();
    FAIL() << "no error";
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("did not converge in 1 iterations"), std::string::npos)
        << e.what();
  }
  EXPECT_NE(log.str().find("holds the state the phase started from"), std::string::npos)
      << log.str();
  const std::string checkpoint = restart_checkpoint(run.string(), passing);
  EXPECT_NEAR(read_checkpoint_info(checkpoint).time, t1, 1e-12);
  // Another change than a phase's solver settings is still refused.
  core::Scene moved = scene_with(25);
  moved.source.replace(moved.source.find("yield = 200"), 11, "yield = 250");
  EXPECT_THROW(restart_checkpoint(run.string(), moved), CheckpointError);

  SimulationOptions b;
  b.output_directory = run.string();
  b.restart_from = checkpoint;
  Simulation second(passing, b);
  second.run();
  SimulationOptions c;
  c.output_directory = whole.string();
  Simulation through(passing, c);
  through.run();
  auto read = [](const std::filesystem::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  EXPECT_EQ(read(run / "history.csv"), read(whole / "history.csv"));
  double plastic = 0.0;
  for (double p : second.hexahedra().plastic_strain) plastic = std::max(plastic, p);
  EXPECT_GT(plastic, 0.0);
}

}  // namespace
}  // namespace afemp
