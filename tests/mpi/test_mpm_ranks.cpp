// The MPM step divided among 1 to 4 ranks (MpmSolver::divide_among_ranks over MpiRankLink): a
// copper bar striking a wall, run on every rank once by itself (the reference: one process, the
// whole run) and once divided among the ranks. The divided run must give the one-process run's
// figures to round-off, step by step, and repeat itself bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "copper_bar_on_wall.hpp"
#include "core/mpi/mpi_rank_link.hpp"
#include "core/mpi/ranks.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "shared_scratch.hpp"

namespace afemp::mpm {
namespace {

// The bar with the given [mpm] lines (and [run] lines beside its end time).
std::string bar_scene(const std::string& mpm, const std::string& run = "") {
  return test::copper_bar_on_wall("end_time = 0.01\n" + run, mpm);
}

// A rigid wall at the particles under the bar's foot, moving up at 5 m/s, with friction 0.3: it
// holds the foot's particles before the grid's wall face does, and resists their spreading.
const std::string moving_wall = R"(
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
velocity = [0, 0, 5]
friction = 0.3
bodies = ["bar"]
)";

struct Run {
  std::vector<Energies> energies;  // after each step
  Particles particles;             // this rank's at the end
  long sent = 0;                   // particles sent between ranks, over all ranks
  std::string setter;              // what sets the stable step at the end
};

Run run(const core::Scene& scene, core::RankLink* link, int steps,
        const core::RankBalance& balance = {}) {
  MpmSolver solver(scene, generate_particles(scene));
  if (link) solver.divide_among_ranks(*link, balance);
  Run r;
  for (int k = 0; k < steps; ++k) {
    solver.step(solver.stable_time_step());
    r.energies.push_back(solver.energies());
  }
  r.particles = solver.particles();
  r.sent = static_cast<long>(core::sum_over_ranks(solver.particles_sent()));
  r.setter = solver.time_step_setter();
  return r;
}

// Reference: the same scene in one process (every rank runs it whole). 150 steps take the bar
// 4 mm into the wall, across a block (4 cells), with plastic flow at its foot. Tolerances:
// kinetic, internal, plastic and external work within 1e-10 of the initial kinetic energy at
// every step; mass within 1e-14 relative (the same particles, added in another order); each
// particle's position within 1e-10 cell and velocity within 1e-10 of the impact speed of its
// own one-process value (the partial sums at shared nodes add in another order: round-off,
// which the plastic flow amplifies little over 150 steps). The divided run repeated gives the
// same bits; with more than one rank, particles do cross to other ranks.
void expect_same_as_one_process(const std::string& text) {
  const core::Scene scene = core::parse_scene(text, "bar.toml");
  constexpr int steps = 150;
  const Run whole = run(scene, nullptr, steps);
  core::MpiRankLink link;
  const Run divided = run(scene, &link, steps);
  const Run again = run(scene, &link, steps);

  const double e0 = whole.energies.front().kinetic;
  ASSERT_GT(e0, 0.0);
  for (int k = 0; k < steps; ++k) {
    const Energies& a = whole.energies[static_cast<std::size_t>(k)];
    const Energies& b = divided.energies[static_cast<std::size_t>(k)];
    const Energies& c = again.energies[static_cast<std::size_t>(k)];
    EXPECT_NEAR(b.kinetic, a.kinetic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.external_work, a.external_work, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.bodies[0].mass, a.bodies[0].mass, 1e-12 * a.bodies[0].mass);
    const double p0 = std::abs(whole.energies.front().bodies[0].momentum.z);
    EXPECT_NEAR(b.bodies[0].momentum.z, a.bodies[0].momentum.z, 1e-10 * p0) << "step " << k;
    EXPECT_EQ(c.kinetic, b.kinetic) << "step " << k;
    EXPECT_EQ(c.internal, b.internal) << "step " << k;
    EXPECT_EQ(c.bodies[0].momentum.z, b.bodies[0].momentum.z) << "step " << k;
  }
  EXPECT_GT(whole.energies.back().plastic, 0.01 * e0);  // the foot did yield
  // The particle that sets the stable step is the whole run's, whichever rank holds it (its
  // speeds printed to 4 digits, which round-off does not reach).
  EXPECT_FALSE(whole.setter.empty());
  EXPECT_EQ(divided.setter, whole.setter);

  // Every particle on exactly one rank, each where the one-process run has it.
  std::unordered_map<std::int32_t, std::size_t> at;
  for (std::size_t i = 0; i < whole.particles.size(); ++i) at[whole.particles.id[i]] = i;
  const Particles& p = divided.particles;
  std::int64_t ids = 0;
  double worst_x = 0.0, worst_v = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ids += p.id[i];
    const std::size_t j = at.at(p.id[i]);
    worst_x = std::max(worst_x, norm(p.position[i] - whole.particles.position[j]));
    worst_v = std::max(worst_v, norm(p.velocity[i] - whole.particles.velocity[j]));
  }
  std::int64_t all_ids = 0;
  for (std::int32_t id : whole.particles.id) all_ids += id;
  EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(p.size())),
            static_cast<std::int64_t>(whole.particles.size()));
  EXPECT_EQ(core::sum_over_ranks(ids), all_ids);
  EXPECT_LE(worst_x, 1e-10 * scene.mpm.grid.cell);
  EXPECT_LE(worst_v, 1e-10 * 200.0);
  if (core::rank_count() > 1) {
    EXPECT_GT(divided.sent, 0);
  }
}

TEST(MpiMpmRanks, MuslLinearHatGivesOneProcessFigures) {
  expect_same_as_one_process(bar_scene("scheme = \"MUSL\"\n"));
}

TEST(MpiMpmRanks, UsfGimpApicGivesOneProcessFigures) {
  expect_same_as_one_process(
      bar_scene("scheme = \"USF\"\nshape_function = \"gimp\"\ntransfer = \"apic\"\n"));
}

// Gravity books its work at the nodes: a shared node must count once.
TEST(MpiMpmRanks, UslQuadraticSplineWithGravityGivesOneProcessFigures) {
  expect_same_as_one_process(
      bar_scene("scheme = \"USL\"\nshape_function = \"bspline2\"\n", "gravity = [0, 0, -5e3]\n"));
}

// Reference: the uninterrupted one-process run (150 steps; USL with the quadratic B-spline and
// gravity, whose nodal work each rank books for its own blocks, onto a rigid wall at the
// particles that moves up at 5 m/s with friction 0.3, whose work rank 0 books and whose
// dissipation every rank holds whole). The divided run's checkpoint
// after 70 steps is written by rank 0 alone (MpmSolver::prepare_checkpoint gathers every
// particle and sums every rank's work). A solver divided among this run's ranks and one in a
// single process each read it and take the remaining 80 steps: both hold every particle once,
// and their energies stay within 1e-10 of the initial kinetic energy of the uninterrupted run's
// at every step (round-off: the partition is made anew from the particles' present blocks).
TEST(MpiMpmRanks, CheckpointOfTheDividedRunRestartsOnRanksAndInOneProcess) {
  const core::Scene scene = core::parse_scene(
      bar_scene("scheme = \"USL\"\nshape_function = \"bspline2\"\n", "gravity = [0, 0, -5e3]\n") +
          moving_wall,
      "bar.toml");
  constexpr int first = 70, rest = 80;
  const auto whole = run(scene, nullptr, first + rest);
  core::MpiRankLink link;
  const std::string path = test::shared_scratch_file(link, "step_70.h5");
  ASSERT_FALSE(path.empty()) << "rank 0 could not make a scratch directory";
  {
    MpmSolver divided(scene, generate_particles(scene));
    divided.divide_among_ranks(link);
    for (int k = 0; k < first; ++k) divided.step(divided.stable_time_step());
    test::save_checkpoint(link, divided, path);
  }
  const double e0 = whole.energies.front().kinetic;
  const auto expect_rest = [&](MpmSolver& solver, const char* what) {
    for (int k = first; k < first + rest; ++k) {
      solver.step(solver.stable_time_step());
      const Energies& a = whole.energies[static_cast<std::size_t>(k)];
      const Energies b = solver.energies();
      EXPECT_NEAR(b.kinetic, a.kinetic, 1e-10 * e0) << what << ", step " << k;
      EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << what << ", step " << k;
      EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << what << ", step " << k;
      EXPECT_NEAR(b.external_work, a.external_work, 1e-10 * e0) << what << ", step " << k;
      EXPECT_NEAR(b.friction, a.friction, 1e-10 * e0) << what << ", step " << k;
    }
    EXPECT_EQ(solver.step_count(), first + rest) << what;
  };
  MpmSolver again(scene, generate_particles(scene));
  again.divide_among_ranks(link);
  test::load_checkpoint(again, path);
  EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(again.particles().size())),
            static_cast<std::int64_t>(whole.particles.size()));
  EXPECT_EQ(again.whole_particle_count(), whole.particles.size());
  expect_rest(again, "on ranks");
  MpmSolver alone(scene, generate_particles(scene));
  test::load_checkpoint(alone, path);
  EXPECT_EQ(alone.particles().size(), whole.particles.size());
  expect_rest(alone, "in one process");
  EXPECT_GT(whole.energies.back().external_work, 0.0);   // gravity did work
  EXPECT_GT(whole.energies.back().friction, 1e-6 * e0);  // the wall's friction dissipated
  test::remove_shared_scratch(link, path);
}

// Reference: the one-process run (150 steps). Rebalanced every 10 steps whatever the imbalance
// (imbalance 1: any rank above the mean), by particle count and by measured time, the divided
// runs give the one-process energies within 1e-10 of the initial kinetic energy at every step
// and hold every particle once; by count, after the last rebalance (step 150) each rank holds
// the mean count within two of the fullest block's particles (recursive bisection: each of its
// at most two levels for 4 ranks cuts within one block's weight of the even split), and the
// run repeats itself bit for bit.
TEST(MpiMpmRanks, RebalancingByCountAndByTimeKeepsTheOneProcessFigures) {
  const core::Scene scene = core::parse_scene(bar_scene("scheme = \"MUSL\"\n"), "bar.toml");
  constexpr int steps = 150;
  const auto whole = run(scene, nullptr, steps);
  const double e0 = whole.energies.front().kinetic;
  core::MpiRankLink link;
  for (const auto cost : {core::RankBalance::Cost::particles, core::RankBalance::Cost::time}) {
    const core::RankBalance balance{cost, 1.0, 10};
    const char* what = cost == core::RankBalance::Cost::time ? "by time" : "by count";
    MpmSolver solver(scene, generate_particles(scene));
    solver.divide_among_ranks(link, balance);
    for (int k = 0; k < steps; ++k) {
      solver.step(solver.stable_time_step());
      const Energies b = solver.energies();
      const Energies& a = whole.energies[static_cast<std::size_t>(k)];
      EXPECT_NEAR(b.kinetic, a.kinetic, 1e-10 * e0) << what << ", step " << k;
      EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << what << ", step " << k;
      EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << what << ", step " << k;
    }
    const Particles& p = solver.particles();
    EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(p.size())),
              static_cast<std::int64_t>(whole.particles.size()))
        << what;
    if (core::rank_count() == 1) continue;
    EXPECT_GE(solver.rebalances(), 1) << what;
    if (cost == core::RankBalance::Cost::time) continue;
    std::map<core::BlockCoord, double> in_block;
    const core::BackgroundGrid& grid = solver.grid();
    for (std::size_t i = 0; i < p.size(); ++i)
      in_block[grid.block_of_cell(grid.cell_of(p.position[i]))] += 1.0;
    double fullest = 0.0;
    for (const auto& [b, n] : in_block) fullest = std::max(fullest, n);
    fullest = link.max_over_ranks(fullest);
    const double mean =
        static_cast<double>(whole.particles.size()) / static_cast<double>(core::rank_count());
    EXPECT_LE(std::abs(static_cast<double>(p.size()) - mean), 2.0 * fullest)
        << "rank " << core::rank_index() << " holds " << p.size() << ", the mean is " << mean;
    const auto again = run(scene, &link, steps, balance);
    EXPECT_EQ(again.energies.back().kinetic, solver.energies().kinetic) << "repeated";
  }
}

// Reference: the one-process run. The bar's particles meet the moving wall with friction
// ([[walls]] at particles, above): every rank sweeps
// every rank's contacts in the order of their ids. Beside the figures above (the wall's work is
// external work), the wall's force within 1e-9 of its largest and friction's dissipation within
// 1e-10 of the initial kinetic energy at every step; the wall pushed and friction dissipated.
TEST(MpiMpmRanks, ParticleWallWithFrictionGivesOneProcessFigures) {
  const std::string text = bar_scene("scheme = \"MUSL\"\n") + moving_wall;
  expect_same_as_one_process(text);
  const core::Scene scene = core::parse_scene(text, "wall.toml");
  struct Wall {
    std::vector<Vec3> force;
    std::vector<double> friction;
  };
  const auto run_wall = [&](core::RankLink* link) {
    MpmSolver solver(scene, generate_particles(scene));
    if (link) solver.divide_among_ranks(*link);
    Wall w;
    for (int k = 0; k < 150; ++k) {
      solver.step(solver.stable_time_step());
      w.force.push_back(solver.wall_forces().at(0));
      w.friction.push_back(solver.energies().friction);
    }
    return w;
  };
  const Wall whole = run_wall(nullptr);
  core::MpiRankLink link;
  const Wall divided = run_wall(&link);
  double largest = 0.0;
  for (const Vec3& f : whole.force) largest = std::max(largest, norm(f));
  ASSERT_GT(largest, 0.0);
  MpmSolver start(scene, generate_particles(scene));
  const double kinetic0 = start.energies().kinetic;
  for (std::size_t k = 0; k < whole.force.size(); ++k) {
    EXPECT_LE(norm(divided.force[k] - whole.force[k]), 1e-9 * largest) << "step " << k;
    EXPECT_NEAR(divided.friction[k], whole.friction[k], 1e-10 * kinetic0) << "step " << k;
  }
  EXPECT_GT(whole.friction.back(), 1e-6 * kinetic0) << "friction dissipated";
}

// Reference: more ranks than blocks that hold particles are refused on every rank, naming the
// blocks, before any particle moves.
TEST(MpiMpmRanks, RefusesMoreRanksThanBlocks) {
  core::MpiRankLink link;
  std::string small = bar_scene("scheme = \"MUSL\"\n");
  small.replace(small.find("radius = 3.8, length = 25.4"), 27, "radius = 1.0, length = 2.0");
  const core::Scene one_block = core::parse_scene(small, "small.toml");
  MpmSolver tiny(one_block, generate_particles(one_block));
  if (core::rank_count() == 1) {
    EXPECT_NO_THROW(tiny.divide_among_ranks(link));
    return;
  }
  try {
    tiny.divide_among_ranks(link);
    ADD_FAILURE() << "a one-block body was divided among " << core::rank_count() << " ranks";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ranks for 1 grid blocks"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace afemp::mpm
