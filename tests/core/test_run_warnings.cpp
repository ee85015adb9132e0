// The run summary's warnings (core/run_warnings.cpp) and what the models say sets their step
// (core::Model::time_step_setter): runs whose numbers need them, and runs that must stay quiet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "afemp/simulation.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "scratch_dir.hpp"

namespace afemp::core {
namespace {

// The warning that contains `what`, or "".
std::string warning_with(const std::vector<std::string>& warnings, const std::string& what) {
  for (const std::string& w : warnings)
    if (w.find(what) != std::string::npos) return w;
  return "";
}

// A steel block of particles at rest in a grid long along x; the energy guard is off, since
// the program below gives it energy no force supplies.
const std::string kBlock = R"(
[run]
end_time = 1
max_steps = 20
energy_error_limit = 0
[grid]
cell = 1
min = [0, 0, 0]
max = [14, 4, 4]
[materials.steel]
density = 7.85e-3
E = 2e5
nu = 0.3
[[bodies]]
name = "block"
material = "steel"
shape = { box = { min = [1, 1, 1], max = [3, 3, 3] } }
)";

// Reference: the grid's stable step is factor h / (c + |v|) (mpm_solver.hpp). A program that
// sets the block moving at 20 c after step 3 (a uniform velocity: no strain, c unchanged) makes
// it fall (c + 20 c) / c = 21-fold, and the particle with the largest c + |v| sets it; the
// kinetic energy it gave is no force's work, so the energy-balance error is K / K = +100 %.
// Both are warned of, after the run, in the summary and in warnings.txt, one a line.
TEST(RunWarnings, AStepThatFellTwentyOneFoldAndAnUnbookedEnergyAreWarnedOf) {
  const test::ScratchDir dir;
  SimulationOptions options;
  options.output_directory = dir.str();
  options.write_fields = false;
  Simulation sim(parse_scene(kBlock, "block.toml"), options);
  const double c = sim.scene().run.time_step_factor * 1.0 / sim.stable_time_step();
  sim.on_step([c](Simulation& s) {
    if (s.step_count() == 3)
      for (Vec3& v : s.particles().velocity) v = {20.0 * c, 0.0, 0.0};
  });
  const RunSummary summary = sim.run();
  for (const std::string& w : summary.warnings) std::printf("[ warning ] %s\n", w.c_str());
  ASSERT_EQ(summary.warnings.size(), 3u);
  const std::string fall = warning_with(summary.warnings, "fell 21-fold");
  EXPECT_NE(fall.find("; it was set by particle"), std::string::npos) << fall;
  EXPECT_NE(fall.find("of body 'block'"), std::string::npos) << fall;
  EXPECT_NE(fall.find("wave speed"), std::string::npos) << fall;
  const std::string energy =
      warning_with(summary.warnings, "energy-balance error reached +100.0 %");
  EXPECT_FALSE(energy.empty()) << summary.warnings[0] << "\n" << summary.warnings[1];
  // The particles' transfers are a mechanism no column books: the summary names it.
  EXPECT_FALSE(warning_with(summary.warnings, "the particle-grid transfers (FLIP blend 1").empty());

  std::ifstream file(dir.file("warnings.txt"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);) lines.push_back(line);
  EXPECT_EQ(lines, summary.warnings);
}

// One free elastic steel hexahedron, 1 mm, with nodal velocities along x of v_a = hourglass
// xi eta (mode 1 of the one-point element) + stretch xi, in m/s, at the natural coordinates of
// node a (the unit cube: xi = 2 x - 1); run for 10 us at 0.05 of its stable step (at 0.6
// the energy balance of this, the element's highest mode, measured with the half-step
// velocities of the central differences, swings by tens of percent).
RunSummary run_element(double hourglass, double stretch) {
  SimulationOptions options;
  options.defer_start = true;
  Simulation sim(parse_scene(R"(
[run]
end_time = 0.01
element_time_step_factor = 0.05
[materials.steel]
density = 7.85e-3
E = 2.1e5
nu = 0.3
[[bodies]]
name = "element"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }
mesh = { divisions = [1, 1, 1] }
)",
                             "element.toml"),
                 options);
  const NodeFields n = sim.nodes();
  for (std::size_t a = 0; a < n.size(); ++a) {
    const double xi = 2.0 * n.position[a].x - 1.0, eta = 2.0 * n.position[a].y - 1.0;
    n.velocity[a] = {hourglass * xi * eta + stretch * xi, 0.0, 0.0};
  }
  sim.start();
  return sim.run();
}

// Reference: the viscous hourglass force takes the kinetic energy of its mode (half the
// start's here) within some tens of steps (at the factor 0.6 it changes the mode's velocity by
// 0.96 of itself a step, tests/fem/test_hourglass_energy.cpp; here by a twelfth), while the
// internal energy of the stretch mode never exceeds the other half: the hourglass energy
// passes 100 % of the internal energy, far past 10 %, and the summary says when, and nothing
// else. The stretch alone books no hourglass energy (round-off, which the warning ignores) and
// the summary warns of nothing.
TEST(RunWarnings, HourglassEnergyPastTenPercentOfTheInternalIsWarnedOf) {
  const RunSummary both = run_element(1.0, 1.0);
  for (const std::string& w : both.warnings) std::printf("[ warning ] %s\n", w.c_str());
  ASSERT_EQ(both.warnings.size(), 1u);
  const std::string& w = both.warnings[0];
  double share = 0.0, time = -1.0;
  ASSERT_EQ(std::sscanf(w.c_str(),
                        "the hourglass energy reached %lf %% of the internal energy (%*f "
                        "of %*f) at t = %lf",
                        &share, &time),
            2)
      << w;
  EXPECT_GT(share, 100.0);
  EXPECT_GT(time, 0.0);
  EXPECT_LE(time, 0.01);
  const RunSummary stretch = run_element(0.0, 1.0);
  for (const std::string& x : stretch.warnings) std::printf("[ stretch ] %s\n", x.c_str());
  EXPECT_TRUE(stretch.warnings.empty());
}

// Reference: an element's critical step is its characteristic length over the wave speed; a
// bar of three 1 mm hexahedra whose middle one is crushed to 0.1 mm has its step set by that
// one, at a tenth of its volume.
TEST(RunWarnings, TheFeStepIsSetByTheCrushedElement) {
  const Scene scene = parse_scene(R"(
[run]
end_time = 1
[materials.steel]
density = 7.85e-3
E = 2.1e5
nu = 0.3
[[bodies]]
name = "bar"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [3, 1, 1] } }
mesh = { divisions = [3, 1, 1] }
)",
                                  "bar.toml");
  fem::FeSolver solver(scene);
  for (Vec3& x : solver.mutable_nodes().position)
    if (std::abs(x.x - 2.0) < 1e-12) x.x = 1.1;
  solver.step(1e-9);  // the critical steps of the crushed state
  int crushed = -1;
  const fem::HexElements& h = solver.hexahedra();
  for (std::size_t e = 0; e < h.size(); ++e) {
    double mean = 0.0;
    for (std::int32_t node : h.nodes[e])
      mean += solver.nodes().position[static_cast<std::size_t>(node)].x / 8.0;
    if (mean > 1.0 && mean < 1.1) crushed = static_cast<int>(e);
  }
  ASSERT_GE(crushed, 0);
  const std::string setter = solver.time_step_setter();
  std::printf("[ setter ] %s\n", setter.c_str());
  EXPECT_EQ(setter.rfind("hexahedron " + std::to_string(crushed) + " of body bar", 0), 0u)
      << setter;
  EXPECT_NE(setter.find("volume 0.1 of its initial"), std::string::npos) << setter;
}

// Reference: the grid's stable step is bounded by the particle with the largest c + |v|; one
// particle of a block at rest set moving at 3 c is it.
TEST(RunWarnings, TheGridStepIsSetByTheFastestParticle) {
  const Scene scene = parse_scene(kBlock, "block.toml");
  mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
  mpm::Particles& p = solver.mutable_particles();
  const double c = scene.run.time_step_factor * 1.0 / solver.stable_time_step();
  p.velocity[5] = {0.0, 3.0 * c, 0.0};
  const std::string setter = solver.time_step_setter();
  std::printf("[ setter ] %s\n", setter.c_str());
  EXPECT_EQ(setter.rfind("particle " + std::to_string(p.id[5]) + " of body 'block'", 0), 0u)
      << setter;
  char speeds[80];
  std::snprintf(speeds, sizeof speeds, "wave speed %.4g + speed %.4g over the cell 1", c, 3.0 * c);
  EXPECT_NE(setter.find(speeds), std::string::npos) << setter;
}

// Reference: the energy balance closes, or the summary names what it does not book. Two
// aluminium cubes of particles (4 mm, cell 1 mm) meet head-on at 2 x 50 m/s in grid contact
// and rebound: the contact's dissipation is only estimated (the contact column) and the
// transfers smooth some away, so the balance ends below -1 % and the summary names grid
// contact "left-right", with the estimate, and the transfers. A block of hexahedra on a rigid
// wall, every mechanism booked (the wall energy), closes within 1 % and warns of nothing.
TEST(RunWarnings, AnUnclosedBalanceNamesTheMechanismsNoColumnBooks) {
  const std::string cubes = R"(
[run]
end_time = 0.03
time_step_factor = 0.3
[grid]
cell = 1.0
min = [-8, -8, -8]
max = [20, 16, 12]
[materials.al]
density = 2.7e-3
E = 70e3
nu = 0.3
[[bodies]]
name = "left"
material = "al"
shape = { box = { min = [0, 0, 0], max = [4, 4, 4] } }
velocity = [50, 0, 0]
[[bodies]]
name = "right"
material = "al"
shape = { box = { min = [5, 0, 0], max = [9, 4, 4] } }
velocity = [-50, 0, 0]
[[contact]]
bodies = ["left", "right"]
)";
  SimulationOptions options;
  options.write_fields = false;
  Simulation sim(parse_scene(cubes, "cubes.toml"), options);
  const RunSummary summary = sim.run();
  for (const std::string& w : summary.warnings) std::printf("[ warning ] %s\n", w.c_str());
  const std::string unbooked = warning_with(summary.warnings, "no column of total books");
  EXPECT_LT(summary.energy_error, -0.01);
  EXPECT_NE(unbooked.find("grid contact left-right"), std::string::npos) << unbooked;
  EXPECT_NE(unbooked.find("the contact column's estimate"), std::string::npos) << unbooked;
  EXPECT_NE(unbooked.find("particle-grid transfers"), std::string::npos) << unbooked;

  const std::string block = R"(
[run]
end_time = 0.02
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.29
strength = { model = "johnson-cook", A = 792, B = 510, n = 0.26, C = 0.0 }
[[bodies]]
name = "block"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [-10, -10, 0.01], max = [10, 10, 20] } }
mesh = { size = 2.0 }
velocity = [0, 0, -300]
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
)";
  Simulation wall(parse_scene(block, "block.toml"), options);
  const RunSummary booked = wall.run();
  for (const std::string& w : booked.warnings) std::printf("[ warning ] %s\n", w.c_str());
  EXPECT_LT(std::abs(booked.energy_error), 0.01);
  EXPECT_TRUE(booked.warnings.empty());
}

}  // namespace
}  // namespace afemp::core
