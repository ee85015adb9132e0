// The [[phases]] of a scene on MPI ranks (core::TimeLoop over afemp::Simulation with an
// MpiRankLink), on 1 to 4 ranks against the same scene run whole in one process on every rank.
// A static or implicit phase is solved on rank 0 in an undivided model, whose state every rank
// then takes (TimeLoop::solve_phase_on_rank_0); a relaxation phase runs as the explicit steps do,
// each rank damping its own points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "afemp/simulation.hpp"
#include "core/mpi/mpi_rank_link.hpp"
#include "core/mpi/ranks.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "fem/phase_test_support.hpp"

namespace afemp {
namespace {

struct PhaseRun {
  std::vector<double> times;                   // after each step (a phase is one step)
  std::vector<Energies> energies;              // the whole run's, after each step
  std::vector<core::Vec3> position, velocity;  // the mesh's nodes at the end
  std::string log;                             // the phase log (the switch's stress lines)
};

PhaseRun run(const std::string& text, core::RankLink* link) {
  SimulationOptions options;
  std::ostringstream log;
  options.phase_log = &log;
  options.ranks = link;
  Simulation sim(core::parse_scene(text, "phases.toml"), options);
  PhaseRun r;
  sim.on_step([&](Simulation& s) {
    r.times.push_back(s.time());
    r.energies.push_back(s.energies());
  });
  sim.run();
  const NodeFields n = sim.nodes();
  r.position.assign(n.position.begin(), n.position.end());
  r.velocity.assign(n.velocity.begin(), n.velocity.end());
  r.log = log.str();
  return r;
}

// The lines of the phase log that give each body's stresses at a switch.
std::vector<std::string> stress_lines(const std::string& log) {
  std::vector<std::string> out;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);)
    if (line.find("von Mises up to") != std::string::npos) out.push_back(line);
  return out;
}

// Reference: the one-process run. Every step at the same time, its energies within `tolerance`
// of the run's largest kinetic plus internal energy; with `nodes_exact` the mesh's nodes at the
// end equal to the bit (a phase's solve is the one-process solve, and a divided mesh moves its
// nodes as one process does); the switch's stress lines (every rank's points) as one process
// prints them.
void expect_same_as_one_process(const std::string& text, double tolerance, bool nodes_exact) {
  const PhaseRun whole = run(text, nullptr);
  core::MpiRankLink link;
  const PhaseRun divided = run(text, &link);
  ASSERT_EQ(divided.times.size(), whole.times.size());
  double scale = 0.0;
  for (const Energies& e : whole.energies)
    scale = std::max(scale, std::abs(e.kinetic) + std::abs(e.internal));
  EXPECT_GT(scale, 0.0);
  for (std::size_t k = 0; k < whole.times.size(); ++k) {
    EXPECT_EQ(divided.times[k], whole.times[k]) << "step " << k;
    const Energies& a = whole.energies[k];
    const Energies& b = divided.energies[k];
    EXPECT_NEAR(b.kinetic, a.kinetic, tolerance * scale) << "step " << k;
    EXPECT_NEAR(b.internal, a.internal, tolerance * scale) << "step " << k;
    EXPECT_NEAR(b.external_work, a.external_work, tolerance * scale) << "step " << k;
    EXPECT_NEAR(b.damped, a.damped, tolerance * scale) << "step " << k;
  }
  if (nodes_exact) {
    ASSERT_EQ(divided.position.size(), whole.position.size());
    EXPECT_FALSE(whole.position.empty());
    for (std::size_t i = 0; i < whole.position.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(divided.position[i][c], whole.position[i][c]) << "node " << i;
        ASSERT_EQ(divided.velocity[i][c], whole.velocity[i][c]) << "node " << i;
      }
    }
  }
  const std::vector<std::string> lines = stress_lines(whole.log);
  EXPECT_FALSE(lines.empty()) << whole.log;
  EXPECT_EQ(stress_lines(divided.log), lines);
}

// The reproducible mode ([run] reproducible = true) through the phases: on ranks, and in one
// process at two threads (on one rank; under more the 2 cores are taken), against one process at
// one thread. Reference: the same bits (the mode's promise, docs/parallel.md), every step at the
// same time, every energy and each body's momentum after every step, the mesh's nodes at the end.
void expect_reproducible(const std::string& scene) {
  std::string text = scene;
  text.replace(text.find("[run]\n"), 6, "[run]\nreproducible = true\n");
  const int threads = core::thread_count();
  core::set_thread_count(1);
  const PhaseRun whole = run(text, nullptr);
  core::MpiRankLink link;
  const PhaseRun divided = run(text, &link);
  PhaseRun two = divided;
  if (core::rank_count() == 1) {
    core::set_thread_count(2);
    two = run(text, nullptr);
  }
  core::set_thread_count(threads);
  for (const PhaseRun* r : std::vector<const PhaseRun*>{&divided, &two}) {
    const char* which = r == &divided ? "on ranks" : "at two threads";
    ASSERT_EQ(r->times.size(), whole.times.size()) << which;
    for (std::size_t k = 0; k < whole.times.size(); ++k) {
      const Energies& a = whole.energies[k];
      const Energies& b = r->energies[k];
      ASSERT_EQ(r->times[k], whole.times[k]) << which << ", step " << k;
      ASSERT_EQ(b.kinetic, a.kinetic) << which << ", step " << k;
      ASSERT_EQ(b.internal, a.internal) << which << ", step " << k;
      ASSERT_EQ(b.external_work, a.external_work) << which << ", step " << k;
      ASSERT_EQ(b.damped, a.damped) << which << ", step " << k;
      ASSERT_EQ(b.bodies.size(), a.bodies.size());
      for (std::size_t i = 0; i < a.bodies.size(); ++i)
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(b.bodies[i].momentum[c], a.bodies[i].momentum[c])
              << which << ", step " << k << ", body " << i;
    }
    ASSERT_EQ(r->position.size(), whole.position.size());
    EXPECT_FALSE(whole.position.empty());
    for (std::size_t i = 0; i < whole.position.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(r->position[i][c], whole.position[i][c]) << which << ", node " << i;
        ASSERT_EQ(r->velocity[i][c], whole.velocity[i][c]) << which << ", node " << i;
      }
  }
}

// The steel column under its weight (fem/phase_test_support.hpp): solved static, run explicit,
// then implicit (HHT-alpha, from the explicit phase's motion) and explicit again. Bit for bit:
// the solves are rank 0's one-process solves, and a divided mesh's steps are one process's
// (MpiFeRanks); the energies add the ranks' elements in rank order (tolerance 1e-12).
std::string column_in_phases() {
  return test::column_scene(
      "element = \"full\"",
      "[[phases]]\nkind = \"static\"\nend_time = 1.0\nload_steps = 2\n"
      "[[phases]]\nkind = \"explicit\"\nend_time = 1.01\n"
      "[[phases]]\nkind = \"implicit\"\nend_time = 1.05\ntime_step = 0.01\nalpha = -0.1\n"
      "[[phases]]\nkind = \"explicit\"\n",
      1.06);
}

TEST(MpiPhases, StaticImplicitAndExplicitPhasesOfAColumnAreOneProcesssToTheBit) {
  expect_same_as_one_process(column_in_phases(), 1e-12, true);
}

// A block of particles on the grid's floor relaxes under its weight (each rank damps its own
// particles; the kinetic energy that decides convergence is every rank's: 2,750 steps), then a
// steel cube of hexahedra, held at rest through the relaxation, meets it in grid contact and
// bounces (the coupled model; 1,382 explicit steps). Tolerance 1e-10: the shared grid nodes add
// in another order on ranks.
std::string particles_relaxed_then_struck() {
  return R"([run]
end_time = 12.0
gravity = [0, 0, -9.81e-3]
[grid]
cell = 10
min = [0, 0, 0]
max = [80, 80, 160]
boundary = { zmin = "fixed" }
[materials.soil]
density = 2e-3
E = 100
nu = 0.3
[materials.steel]
density = 7.85e-3
E = 2e5
nu = 0.3
[[bodies]]
name = "soil"
material = "soil"
shape = { box = { min = [20, 20, 0], max = [60, 60, 60] } }
[[bodies]]
name = "cube"
material = "steel"
discretisation = "hexahedra"
element = "full"
mesh = { divisions = [2, 2, 2] }
velocity = [0, 0, -2]
shape = { box = { min = [30, 30, 61], max = [50, 50, 81] } }
[[phases]]
kind = "relaxation"
end_time = 10.0
damping_factor = 0.95
[[phases]]
kind = "explicit"
[[contact]]
bodies = ["cube", "soil"]
)";
}

TEST(MpiPhases, RelaxationThenExplicitOfParticlesAndAMeshGiveOneProcessFigures) {
  expect_same_as_one_process(particles_relaxed_then_struck(), 1e-10, false);
}

// Both scenes above in the reproducible mode: the column's static and implicit solves (the BLAS
// on one thread) and the particles' relaxation and impact give the bits of one process at one
// thread on any rank count and at two threads.
TEST(MpiPhases, ReproducibleModeGivesOneProcesssBitsThroughEveryPhase) {
  expect_reproducible(column_in_phases());
  expect_reproducible(particles_relaxed_then_struck());
}

}  // namespace
}  // namespace afemp
