// The implicit phase of a scene (kind = "implicit": fem/static_phase.hpp, run_implicit_phase):
// Newmark's trapezoidal rule or HHT-alpha on the mesh bodies, its state and velocities handed to
// the explicit phase. References: the steel column of test_static_phase.cpp under gravity
// applied at t = 0 from its unloaded shape, whose top reaches twice its static displacement at
// t = 2H/c (every mode of the fixed-free bar, omega_n = (2n - 1) pi c / 2H, is at its far turn
// there); the same scene run explicitly throughout; the balance of energy across the phases
// (what the trapezoidal rule dissipates is round-off and the consistent mass's kinetic energy
// against the lumped one's, what HHT's alpha dissipates is more); a bar pulled slowly at its
// top by a constraint's velocity, whose stress is E v t / L; and the scene file's errors.
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
#include "scene_errors.hpp"
#include "scratch_dir.hpp"

namespace afemp {
namespace {

constexpr double kRho = test::kColumnDensity, kE = test::kColumnModulus, kG = test::kColumnGravity,
                 kH = test::kColumnHeight;
using test::top_displacement;

// The column (phase_test_support.hpp) of fully integrated hexahedra, under gravity from t = 0.
std::string column(const std::string& phases, double end_time) {
  return test::column_scene("element = \"full\"", phases, end_time);
}

// The half period of the column's modes, 2H/c, and its static top displacement.
const double kHalfPeriod = 2.0 * kH / std::sqrt(kE / kRho);
const double kStatic = -kRho * kG * kH * kH / (2.0 * kE);

// An implicit phase over the half period in `steps` steps, then the explicit phase.
std::string implicit_then_explicit(double alpha, int steps = 100) {
  char text[240];
  std::snprintf(text, sizeof text,
                "[[phases]]\nkind = \"implicit\"\nend_time = %.17g\ntime_step = %.17g\n"
                "alpha = %g\n[[phases]]\nkind = \"explicit\"\n",
                kHalfPeriod, kHalfPeriod / steps, alpha);
  return text;
}

// Trapezoidal rule over the first half period (100 steps), then explicit: the top reaches
// 2 u_static at the switch (within 3 %, the 20 elements' dispersion), the explicit phase goes
// on from the handed velocities as the all-explicit run does (the top within 2 % of u_static
// of it over the next half period), and the energy balances across the phases.
TEST(ImplicitPhase, ColumnUnderSuddenGravityReachesTwiceItsStaticShapeAndGoesOnExplicitly) {
  const double end = 2.0 * kHalfPeriod;
  std::ostringstream log;
  SimulationOptions options;
  options.phase_log = &log;
  Simulation sim(core::parse_scene(column(implicit_then_explicit(0.0), end), "column.toml"),
                 options);
  EXPECT_NE(sim.describe().find("1. implicit, t 0 -> "), std::string::npos) << sim.describe();
  EXPECT_NE(sim.describe().find("Newmark's trapezoidal rule, no numerical damping, 100 steps"),
            std::string::npos)
      << sim.describe();
  sim.run_to(kHalfPeriod);
  EXPECT_EQ(sim.step_count(), 0);
  EXPECT_NEAR(sim.time() / kHalfPeriod, 1.0, 1e-12);
  EXPECT_NE(log.str().find("newmark step 100/100 iteration 1"), std::string::npos);
  EXPECT_NE(log.str().find("the implicit phase ends at t = "), std::string::npos) << log.str();
  const double u_switch = top_displacement(sim);
  EXPECT_NEAR(u_switch / (2.0 * kStatic), 1.0, 0.03) << u_switch;
  const Energies e = sim.energies();
  // The trapezoidal rule conserves the consistent-mass energy; what is booked as damped is the
  // lumped kinetic energy's difference from it, small beside the work.
  EXPECT_GT(e.external_work, 0.0);
  EXPECT_LT(std::abs(e.damped), 0.01 * e.external_work) << e.damped;
  EXPECT_NEAR((e.internal + e.kinetic + e.damped) / e.external_work, 1.0, 1e-9);

  Simulation reference(core::parse_scene(column("", end), "column.toml"));
  reference.run_to(kHalfPeriod);
  const double u_reference = top_displacement(reference);
  EXPECT_NEAR((u_switch - u_reference) / kStatic, 0.0, 0.02) << u_switch << " " << u_reference;
  double worst = 0.0;
  for (int k = 1; k <= 4; ++k) {
    const double t = kHalfPeriod * (1.0 + 0.25 * k);
    sim.run_to(t);
    reference.run_to(t);
    worst = std::max(worst, std::abs(top_displacement(sim) - top_displacement(reference)));
  }
  EXPECT_LT(worst / std::abs(kStatic), 0.02) << worst;
  // The balance across the phases: no worse than the all-explicit run's, whose kinetic energy
  // is measured on half-step velocities (a few per cent in mid-swing on this column).
  const RunSummary summary = sim.run();
  const RunSummary reference_summary = reference.run();
  EXPECT_LE(summary.max_energy_error, reference_summary.max_energy_error);
  EXPECT_LT(summary.max_energy_error, 0.05);
  EXPECT_LT(std::abs(summary.energy_error), 1e-3);
  std::printf(
      "trapezoidal: u_top at 2H/c %.6g (2 u_static %.6g, all-explicit %.6g); work %.6g, damped "
      "%.3g; explicit phase: worst |u_top - all-explicit| %.3g of u_static, balance largest %.2g "
      "(all-explicit %.2g), at the end %.2g\n",
      u_switch, 2.0 * kStatic, u_reference, e.external_work, e.damped, worst / std::abs(kStatic),
      summary.max_energy_error, reference_summary.max_energy_error, summary.energy_error);
}

// HHT-alpha damps what its steps do not resolve: in 10 steps over the half period (omega dt
// 0.31 for the first mode, above 1 from the fourth), alpha = -0.3 books a share of the work as
// damped energy where the trapezoidal rule books none but the lumped mass's difference, and the
// balance still holds.
TEST(ImplicitPhase, HhtAlphaBooksItsNumericalDampingAsDampedEnergy) {
  double damped[2] = {0.0, 0.0};
  const double alphas[2] = {0.0, -0.3};
  for (int k = 0; k < 2; ++k) {
    Simulation sim(core::parse_scene(
        column(implicit_then_explicit(alphas[k], 10), 1.2 * kHalfPeriod), "c.toml"));
    sim.run_to(kHalfPeriod);
    const Energies e = sim.energies();
    damped[k] = e.damped / e.external_work;
    EXPECT_NEAR((e.internal + e.kinetic + e.damped) / e.external_work, 1.0, 1e-9) << alphas[k];
    // Still the same motion to within the damping of the first mode (of order alpha (omega dt)^2).
    EXPECT_NEAR(top_displacement(sim) / (2.0 * kStatic), 1.0, 0.05) << alphas[k];
  }
  EXPECT_GT(damped[1], damped[0] + 1e-3) << damped[0] << " " << damped[1];
  std::printf("damped share of the work: trapezoidal %.3g, HHT alpha -0.3 %.3g\n", damped[0],
              damped[1]);
}

// A bar on symmetry planes (uniaxial stress) whose top a constraint pulls at v = 0.001 mm/ms
// for 1 ms, over 63 periods of its first mode, in 20 implicit steps with HHT's alpha = -0.3
// (whose damping takes out the start's transient: the top moving at once, the rest at rest; the
// trapezoidal rule would carry it through undamped): quasi-static, its stress E v t / L (within
// 0.5 %), its top moving at v at the switch and its middle at v / 2; the explicit phase takes
// the velocities on.
TEST(ImplicitPhase, ConstraintVelocityPullsTheBarSlowly) {
  const double v = 0.001, length = 20.0, t_end = 1.0;
  const std::string text =
      "[run]\nend_time = 1.0005\n"
      "[materials.steel]\ndensity = 7.85e-3\nE = 2.0e5\nnu = 0.3\n"
      "[[bodies]]\nname = \"bar\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "element = \"full\"\nshape = { box = { min = [0, 0, 0], max = [4, 4, 20] } }\n"
      "mesh = { divisions = [2, 2, 4] }\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
      "fixed = [\"z\"]\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }\n"
      "fixed = [\"x\"]\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 1, 0] } }\n"
      "fixed = [\"y\"]\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 20], normal = [0, 0, 1] } }\n"
      "velocity = [0, 0, 0.001]\ncomponents = [\"z\"]\n"
      "[[phases]]\nkind = \"implicit\"\nend_time = 1.0\ntime_step = 0.05\nalpha = -0.3\n"
      "[[phases]]\nkind = \"explicit\"\n";
  Simulation sim(core::parse_scene(text, "bar.toml"));
  sim.run_to(t_end);
  const double stress = kE * v * t_end / length;
  ElementFields h = sim.hexahedra();
  for (std::size_t p = 0; p < h.stress.size(); ++p) {
    ASSERT_NEAR(h.stress[p].zz / stress, 1.0, 5e-3) << p;
    ASSERT_NEAR(h.stress[p].xx / stress, 0.0, 5e-3) << p;
  }
  const NodeFields n = sim.nodes();
  double middle = 0.0;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (n.position[i].z > length - 1.0) {
      ASSERT_NEAR(n.position[i].z - length, v * t_end, 1e-12 * length);
      ASSERT_NEAR(n.velocity[i].z, v, 1e-12);
    }
    if (std::abs(n.position[i].z - 0.5 * length) < 1.0) {
      ASSERT_NEAR(n.velocity[i].z / (0.5 * v), 1.0, 0.02) << i;
      middle = std::max(middle, std::abs(n.velocity[i].z / (0.5 * v) - 1.0));
    }
  }
  const Energies e = sim.energies();
  // The constraint's work E A v^2 t^2 / 2L is the stored energy.
  const double work = kE * 16.0 * v * v * t_end * t_end / (2.0 * length);
  EXPECT_NEAR(e.external_work / work, 1.0, 5e-3);
  EXPECT_NEAR(e.internal / work, 1.0, 5e-3);
  double worst = 0.0;
  for (std::size_t p = 0; p < h.stress.size(); ++p)
    worst = std::max(worst, std::abs(h.stress[p].zz / stress - 1.0));
  const RunSummary summary = sim.run();
  h = sim.hexahedra();
  for (std::size_t p = 0; p < h.stress.size(); ++p)
    ASSERT_NEAR(h.stress[p].zz / (kE * v * 1.0005 / length), 1.0, 5e-3) << p;
  EXPECT_LT(summary.max_energy_error, 1e-3);
  std::printf(
      "bar pulled in 20 HHT steps: stress worst %.2g from E v t / L, middle's speed %.2g from "
      "v / 2, work %.6g (E A v^2 t^2 / 2L %.6g), internal %.6g, damped %.3g; explicit phase "
      "balance %.2g\n",
      worst, middle, e.external_work, work, e.internal, e.damped, summary.max_energy_error);
}

// The phase's Newton iterations and energies are in its output directory, and a run restarted
// from the checkpoint at the switch ends as the run that went through.
TEST(ImplicitPhase, WritesItsIterationsAndEnergiesAndRestartsFromTheSwitch) {
  const test::ScratchDir dir;
  const double end = 1.2 * kHalfPeriod;
  const core::Scene scene = core::parse_scene(column(implicit_then_explicit(0.0), end), "c.toml");
  SimulationOptions options;
  options.output_directory = (dir.path() / "whole").string();
  Simulation whole(scene, options);
  whole.run();
  std::ifstream energies(dir.path() / "whole" / "implicit_energies.csv");
  std::string header, row;
  std::getline(energies, header);
  EXPECT_EQ(header, "time,kinetic,strain,external_work,plastic_and_dissipated");
  int rows = 0;
  double worst = 0.0, work = 0.0;
  while (std::getline(energies, row)) {
    double t, kinetic, strain, w, other;
    ASSERT_EQ(std::sscanf(row.c_str(), "%lf,%lf,%lf,%lf,%lf", &t, &kinetic, &strain, &w, &other),
              5);
    worst = std::max(worst, std::abs(other));
    work = std::max(work, w);
    ++rows;
  }
  EXPECT_EQ(rows, 101);
  // Newmark's trapezoidal rule conserves the energy of a linear body to round-off (1e-14
  // measured).
  EXPECT_LT(worst, 1e-10 * work) << worst << " of " << work;
  std::printf("trapezoidal phase: work less the energy held, at most %.3g of the work %.6g\n",
              worst / work, work);
  std::ifstream iterations(dir.path() / "whole" / "implicit_phase.csv");
  std::getline(iterations, header);
  EXPECT_EQ(header, "phase,time_step,iteration,residual,force_scale,energy,step_length");

  const std::string checkpoint = newest_checkpoint((dir.path() / "whole").string());
  ASSERT_FALSE(checkpoint.empty());
  std::filesystem::copy(
      dir.path() / "whole", dir.path() / "again",
      std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
  SimulationOptions again;
  again.output_directory = (dir.path() / "again").string();
  again.restart_from = newest_checkpoint(again.output_directory);
  Simulation restarted(scene, again);
  restarted.run();
  auto read = [](const std::filesystem::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  const std::string history = read(dir.path() / "whole" / "history.csv");
  EXPECT_NE(history.find("damped"), std::string::npos);
  EXPECT_EQ(history, read(dir.path() / "again" / "history.csv"));
}

// A tendon prestressed to 800 MPa, held at its base and free to shorten at its top, released in
// an implicit phase: HHT's alpha = -0.3 with steps 1.3 times its period takes out the motion
// over the phase (3 ms, 38 periods), leaving it unstressed and shortened by
// sigma_p L / E = 0.4 mm;
// the elastic energy it held, sigma_p^2 A L / 2E = 3200 N mm, is what the scheme dissipated.
TEST(ImplicitPhase, PrestressedTendonReleasedAtOneEndShortensBySigmaLOverE) {
  const std::string text =
      "[run]\nend_time = 3.001\n[materials.steel]\ndensity = 7.85e-3\nE = 2.0e5\nnu = 0.3\n"
      "[[bodies]]\nname = \"tendon\"\ndiscretisation = \"trusses\"\nmaterial = \"steel\"\n"
      "shape = { line = { from = [0, 0, 0], to = [0, 0, 100] } }\narea = 20\n"
      "mesh = { segments = 10 }\nprestress = 800\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
      "fixed = [\"all\"]\n"
      "[[constraints]]\nnodes = { box = { min = [-1, -1, 1], max = [1, 1, 101] } }\n"
      "fixed = [\"x\", \"y\"]\n"
      "[[phases]]\nkind = \"implicit\"\nend_time = 3.0\ntime_step = 0.1\nalpha = -0.3\n"
      "[[phases]]\nkind = \"explicit\"\n";
  Simulation sim(core::parse_scene(text, "t.toml"));
  const double energy = 800.0 * 800.0 * 20.0 * 100.0 / (2.0 * 2.0e5);
  EXPECT_NEAR(sim.energies().internal / energy, 1.0, 1e-12);
  sim.run_to(3.0);
  for (const SymTensor& st : sim.trusses().stress) EXPECT_NEAR(st.xx / 800.0, 0.0, 1e-3);
  const NodeFields n = sim.nodes();
  double top = 0.0;
  for (std::size_t i = 0; i < n.size(); ++i)
    if (n.position[i].z > 90.0) top = n.position[i].z - 100.0;
  EXPECT_NEAR(top / (-800.0 * 100.0 / 2.0e5), 1.0, 1e-3) << top;
  const Energies e = sim.energies();
  EXPECT_NEAR(e.damped / energy, 1.0, 1e-3) << e.damped;
  EXPECT_NEAR(e.internal / energy, 0.0, 1e-3);
  const RunSummary summary = sim.run();
  EXPECT_LT(summary.max_energy_error, 1e-6);
  std::printf("released tendon: top %.6g (-sigma L / E -0.4), damped %.6g of %.6g held\n", top,
              e.damped, energy);
}

// A time step that does not converge (max_iterations = 1 cannot take the first plastic step:
// the column, yield 100 MPa, yields at its base as its swing passes 1.27 times the static stress)
// stops the run with the step, the iteration, the residual and the element that yields most;
// the state after the last converged step is the model's, at its time, and the run's frame.
TEST(ImplicitPhase, StepThatDoesNotConvergeStopsWithItAndKeepsTheLastConvergedState) {
  const test::ScratchDir dir;
  std::string text = column(
      "[[phases]]\nkind = \"implicit\"\nend_time = 0.05\ntime_step = 0.0005\n"
      "max_iterations = 1\n[[phases]]\nkind = \"explicit\"\n",
      0.06);
  text.replace(text.find("nu = 0.3\n"), 9,
               "nu = 0.3\nstrength = { model = \"j2\", yield = 100 }\n");
  SimulationOptions options;
  options.output_directory = dir.str();
  Simulation sim(core::parse_scene(text, "c.toml"), options);
  try {
    sim.run();
    FAIL() << "no error";
  } catch (const SimulationError& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    for (const char* part : {"the implicit phase", "newmark solve: time step", "iteration 1",
                             "did not converge", "tolerance", "the element that yields most",
                             "of part 'column'", "is kept", "the run's last frame"})
      EXPECT_NE(what.find(part), std::string::npos) << part;
    // The failing step is named; the model holds the step before, at rest from none of it.
    const std::size_t at = what.find("time step ") + 10;
    const int failed = std::stoi(what.substr(at));
    EXPECT_GT(failed, 1);
    EXPECT_NEAR(sim.time(), 0.0005 * (failed - 1), 1e-12);
    EXPECT_LT(top_displacement(sim), 0.0);
    for (double p : sim.hexahedra().plastic_strain) EXPECT_EQ(p, 0.0);
    // The phase's iterations, the failing step's included, are in its file.
    std::ifstream in(dir / "implicit_phase.csv");
    const std::string rows(std::istreambuf_iterator<char>(in), {});
    EXPECT_NE(rows.find("\n1," + std::to_string(failed) + ",0,"), std::string::npos) << rows.size();
    EXPECT_NE(rows.find("\n1," + std::to_string(failed - 1) + ",1,"), std::string::npos);
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "fields.xmf"));
}

TEST(ImplicitPhase, SceneErrorsNameTheKeyAndWhatIsAllowed) {
  using test::error_of;
  EXPECT_NE(error_of(column("[[phases]]\nkind = \"implicit\"\nend_time = 0.05\n"
                            "[[phases]]\nkind = \"explicit\"\n",
                            0.1))
                .find("time_step"),
            std::string::npos);
  const std::string alpha = error_of(
      column("[[phases]]\nkind = \"implicit\"\nend_time = 0.05\ntime_step = 0.001\nalpha = 0.1\n"
             "[[phases]]\nkind = \"explicit\"\n",
             0.1));
  EXPECT_NE(alpha.find(".alpha"), std::string::npos) << alpha;
  EXPECT_NE(alpha.find("<= value <= 0"), std::string::npos) << alpha;
  EXPECT_NE(error_of(column("[[phases]]\nkind = \"implicit\"\nend_time = 0.05\ntime_step = "
                            "0.001\nload_steps = 3\n[[phases]]\nkind = \"explicit\"\n",
                            0.1))
                .find("load_steps"),
            std::string::npos);
  EXPECT_NE(error_of(column("[[phases]]\nkind = \"implicit\"\nend_time = 0.05\ntime_step = 0.01\n"
                            "[[phases]]\nkind = \"relaxation\"\nend_time = 0.08\n"
                            "[[phases]]\nkind = \"explicit\"\n",
                            0.1))
                .find("a relaxation phase comes first"),
            std::string::npos);
}

}  // namespace
}  // namespace afemp
