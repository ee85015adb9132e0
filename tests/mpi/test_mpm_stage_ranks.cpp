// The MPM stages that divided among ranks last (MpmSolver::divide_among_ranks over
// MpiRankLink): loads on particles, outflow faces, absorbing and far-field faces, the mixed
// pressure and particle splitting, each on 1 to 4 ranks against the same scene run whole in one
// process on every rank. The divided run must give the one-process run's figures to round-off,
// step by step, and end with the same particles, by id.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "copper_bar_on_wall.hpp"
#include "core/mpi/mpi_rank_link.hpp"
#include "core/mpi/ranks.hpp"
#include "core/scene.hpp"
#include "explosive_scenes.hpp"
#include "mixed_beam.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "shared_scratch.hpp"
#include "stretched_column.hpp"

namespace afemp::mpm {
namespace {

struct StageRun {
  std::vector<Energies> energies;  // after each step
  Particles particles;             // this rank's at the end
  std::size_t whole = 0;           // the whole run's particles at the end
  long outflow = 0, splits = 0;    // particles out through outflow faces, splits (this rank's)
};

StageRun run(const core::Scene& scene, const Particles& start, core::RankLink* link, int steps,
             const core::RankBalance& balance = {}) {
  MpmSolver solver(scene, start);
  if (link) solver.divide_among_ranks(*link, balance);
  StageRun r;
  for (int k = 0; k < steps; ++k) {
    solver.step(solver.stable_time_step());
    r.energies.push_back(solver.energies());
  }
  r.particles = solver.particles();
  r.whole = link ? solver.whole_particle_count() : solver.particles().size();
  r.outflow = solver.outflow_count();
  r.splits = solver.split_count();
  return r;
}

// Reference: the one-process run of `steps` steps. Tolerances: every energy, work and outflow
// book within 1e-10 of the run's largest kinetic plus internal energy at every step, each
// body's mass within 1e-12 relative and momentum within 1e-10 of the largest M v_rms (a body's
// mass times its root-mean-square speed, sqrt(2 M E_k): a stretched column's momentum sums to
// nearly nothing); at the end the
// same particles by id on the ranks together, each within 1e-10 cell and its velocity within
// 1e-10 of the run's largest speed of its one-process self (the shared nodes add in another
// order: round-off). Returns the one-process run for the scene's own checks.
StageRun expect_same_as_one_process(const core::Scene& scene, const Particles& start, int steps,
                                    const core::RankBalance& balance = {}) {
  const StageRun whole = run(scene, start, nullptr, steps);
  core::MpiRankLink link;
  const StageRun divided = run(scene, start, &link, steps, balance);

  double scale = 0.0, momentum = 0.0;
  for (const Energies& e : whole.energies) {
    scale = std::max(scale, std::abs(e.kinetic) + std::abs(e.internal));
    for (const BodySums& b : e.bodies)  // M v_rms: a body's momentum may sum to nothing
      momentum = std::max(momentum, std::sqrt(2.0 * b.mass * std::abs(b.kinetic)));
  }
  EXPECT_GT(scale, 0.0);
  for (int k = 0; k < steps; ++k) {
    const Energies& a = whole.energies[static_cast<std::size_t>(k)];
    const Energies& b = divided.energies[static_cast<std::size_t>(k)];
    EXPECT_NEAR(b.kinetic, a.kinetic, 1e-10 * scale) << "step " << k;
    EXPECT_NEAR(b.internal, a.internal, 1e-10 * scale) << "step " << k;
    EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * scale) << "step " << k;
    EXPECT_NEAR(b.external_work, a.external_work, 1e-10 * scale) << "step " << k;
    EXPECT_NEAR(b.outflow, a.outflow, 1e-10 * scale) << "step " << k;
    EXPECT_NEAR(b.outflow_mass, a.outflow_mass, 1e-12 * a.bodies[0].mass) << "step " << k;
    EXPECT_LE(norm(b.outflow_momentum - a.outflow_momentum), 1e-10 * momentum) << "step " << k;
    for (std::size_t body = 0; body < a.bodies.size(); ++body) {
      EXPECT_NEAR(b.bodies[body].mass, a.bodies[body].mass, 1e-12 * a.bodies[body].mass)
          << "step " << k << ", body " << body;
      EXPECT_LE(norm(b.bodies[body].momentum - a.bodies[body].momentum), 1e-10 * momentum)
          << "step " << k << ", body " << body;
    }
  }

  EXPECT_EQ(divided.whole, whole.particles.size());
  EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(divided.particles.size())),
            static_cast<std::int64_t>(whole.particles.size()));
  EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(divided.outflow)), whole.outflow);
  EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(divided.splits)), whole.splits);
  double speed = 0.0;
  for (const Vec3& v : whole.particles.velocity) speed = std::max(speed, norm(v));
  std::unordered_map<std::int32_t, std::size_t> at;
  for (std::size_t i = 0; i < whole.particles.size(); ++i) at[whole.particles.id[i]] = i;
  const Particles& p = divided.particles;
  std::int64_t ids = 0, all_ids = 0, unknown = 0;
  double worst_x = 0.0, worst_v = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ids += p.id[i];
    const auto j = at.find(p.id[i]);
    if (j == at.end()) {
      ++unknown;
      continue;
    }
    worst_x = std::max(worst_x, norm(p.position[i] - whole.particles.position[j->second]));
    worst_v = std::max(worst_v, norm(p.velocity[i] - whole.particles.velocity[j->second]));
  }
  for (std::int32_t id : whole.particles.id) all_ids += id;
  EXPECT_EQ(unknown, 0) << "particles whose id the one-process run does not have";
  EXPECT_EQ(core::sum_over_ranks(ids), all_ids);
  EXPECT_LE(worst_x, 1e-10 * scene.mpm.grid.cell);
  EXPECT_LE(worst_v, 1e-10 * speed);
  return whole;
}

core::Scene parsed(const std::string& text) {
  return core::parse_scene(text, "scene.toml");
}

// `text` with its first `from` replaced by `to`.
std::string with(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

std::string bar(const std::string& extra = "") {
  return test::copper_bar_on_wall("end_time = 0.01\n", "scheme = \"MUSL\"\n") + extra;
}

// The bar pushed at its top by 2 kN rising from zero over 0.01 ms: the load's work at the
// nodes (its own booking) and the loaded particles on whichever rank holds them.
TEST(MpiMpmStageRanks, LoadsOnParticlesGiveOneProcessFigures) {
  const core::Scene scene = parsed(bar(R"(
[[loads]]
body = "bar"
particles = { box = { min = [0, 0, 24.5], max = [10, 10, 26] } }
force = [0, 0, -2000]
curve = [[0, 0], [0.01, 1]]
)"));
  const StageRun whole = expect_same_as_one_process(scene, generate_particles(scene), 100);
  EXPECT_GT(whole.energies.back().external_work, 1e-4 * whole.energies.front().kinetic);
}

// The bar through an outflow face instead of onto a wall: its foot leaves the grid, each rank
// taking out and booking its own particles. Then a checkpoint on ranks at step 50, continued in
// one process to step 100, ends with the uninterrupted run's books and particle count.
TEST(MpiMpmStageRanks, OutflowFaceGivesOneProcessFiguresAndCheckpoints) {
  const core::Scene scene = parsed(with(bar(), "zmin = \"wall\"", "zmin = \"outflow\""));
  const StageRun whole = expect_same_as_one_process(scene, generate_particles(scene), 100);
  EXPECT_GT(whole.outflow, 50) << "particles left through the face";
  EXPECT_GT(whole.energies.back().outflow_mass, 0.0);

  core::MpiRankLink link;
  const std::string path = test::shared_scratch_file(link, "outflow_50.h5");
  ASSERT_FALSE(path.empty()) << "rank 0 could not make a scratch directory";
  {
    MpmSolver divided(scene, generate_particles(scene));
    divided.divide_among_ranks(link);
    for (int k = 0; k < 50; ++k) divided.step(divided.stable_time_step());
    test::save_checkpoint(link, divided, path);
  }
  MpmSolver alone(scene, generate_particles(scene));
  test::load_checkpoint(alone, path);
  for (int k = 50; k < 100; ++k) alone.step(alone.stable_time_step());
  const Energies a = whole.energies.back(), b = alone.energies();
  const double e0 = whole.energies.front().kinetic;
  EXPECT_NEAR(b.outflow, a.outflow, 1e-10 * e0);
  EXPECT_NEAR(b.outflow_mass, a.outflow_mass, 1e-12 * a.bodies[0].mass);
  EXPECT_NEAR(b.kinetic, a.kinetic, 1e-10 * e0);
  EXPECT_EQ(alone.outflow_count(), whole.outflow);
  EXPECT_EQ(alone.particles().size(), whole.particles.size());
  test::remove_shared_scratch(link, path);
}

// The bar up to the grid's top, an absorbing face there: the impact's wave reaches it within
// 100 steps and the face's dashpots take energy out (negative external work), booked once for
// each node by the rank that books the node.
TEST(MpiMpmStageRanks, AbsorbingFaceGivesOneProcessFigures) {
  std::string text = with(bar(), "length = 25.4", "length = 28");
  text = with(text, "zmin = \"wall\"", "zmin = \"wall\", zmax = \"absorbing\"");
  const core::Scene scene = parsed(text);
  const StageRun whole = expect_same_as_one_process(scene, generate_particles(scene), 100);
  EXPECT_LT(whole.energies.back().external_work, -1e-6 * whole.energies.front().kinetic);
}

// A gas bubble at 10.5 MPa in water at 10 MPa behind far-field faces (Geers's doubly
// asymptotic approximation, whose lag is each face node's state from step to step): 100 steps
// carry its wave onto the faces. The ranks are rebalanced by measured time every 10 steps
// (whenever a rank's time is above the mean), so that face nodes pass from rank to rank and
// carry their lags with them.
TEST(MpiMpmStageRanks, FarFieldFacesGiveOneProcessFigures) {
  const core::Scene scene =
      parsed(test::sphere_in_water("gas", "internal_energy = 2.5e6\npressure = 10.5"));
  const core::RankBalance by_time{core::RankBalance::Cost::time, 1.0, 10};
  const StageRun whole = expect_same_as_one_process(scene, generate_particles(scene), 100, by_time);
  EXPECT_NE(whole.energies.back().external_work, 0.0) << "the far field did work";
}

// The nearly incompressible cantilever of the mixed u-p total-Lagrangian MPM, started in its
// first bending mode: the pressure's nodal averages made whole over the ranks before each
// division.
TEST(MpiMpmStageRanks, MixedPressureGivesOneProcessFigures) {
  const core::Scene scene = parsed(test::mixed_beam::beam_scene("mixed", "bspline2", 0.25));
  expect_same_as_one_process(scene, test::mixed_beam::beam_particles(scene), 100);
}

// An aluminium column stretched by its own inertia (v_z = 200 (z - 5) m/s, the splitting tests'
// jet): its particles split from about step 130, each rank its own, the pieces taking ids in
// the order of their parents' ids over every rank, so that every piece has its one-process id.
TEST(MpiMpmStageRanks, ParticleSplittingGivesOneProcessFiguresAndIds) {
  const core::Scene scene = parsed(test::column("splitting = { alpha = 0.9 }"));
  Particles start = generate_particles(scene);
  test::stretch_column(start);
  const StageRun whole = expect_same_as_one_process(scene, start, 250);
  EXPECT_GT(whole.splits, 50);
  EXPECT_GT(whole.particles.size(), start.size() + 50);
}

}  // namespace
}  // namespace afemp::mpm
