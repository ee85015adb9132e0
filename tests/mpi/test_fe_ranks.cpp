// The explicit FE step divided among 1 to 4 ranks by its elements (FeSolver::divide_among_ranks
// over MpiRankLink), every rank moving every node: each scene is run on every rank once by
// itself (the reference: one process, the whole run) and once divided. The nodes must be the
// one-process run's to the bit at every step (every rank gathers the same element forces in the
// same order), the energies its to round-off (the element parts are added over the ranks in
// rank order), and the erosion records, gathered on rank 0, its own in its order.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "copper_bar_on_wall.hpp"
#include "core/mpi/mpi_rank_link.hpp"
#include "core/mpi/ranks.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "shared_scratch.hpp"

namespace afemp::fem {
namespace {

// The eroding copper bar of hexahedra (copper_bar_on_wall.hpp): its foot erodes within 100 steps.
const std::string eroding_bar = test::eroding_copper_bar_of_hexahedra();

// Two bodies onto a wall (copper_bar_on_wall.hpp).
const std::string block_and_rod = test::block_and_rod_on_wall();

struct FeRun {
  std::vector<core::Energies> energies;           // after each step
  std::vector<std::vector<core::Vec3>> position;  // the nodes after each step
  std::vector<core::Vec3> velocity;               // the nodes at the end
  std::vector<ErosionEvent> events;               // on rank 0 (divided), or all (one process)
  std::vector<std::uint8_t> alive;                // hexahedra, at the end
  std::string setter;
};

void advance(FeSolver& solver, FeRun& r, int steps) {
  for (int k = 0; k < steps; ++k) {
    solver.step(solver.stable_time_step());
    r.energies.push_back(solver.energies());
    r.position.push_back(solver.nodes().position);
    for (ErosionEvent& e : solver.take_erosion_events()) r.events.push_back(std::move(e));
  }
  r.velocity = solver.nodes().velocity;
  r.alive = solver.hexahedra().alive;
  r.setter = solver.time_step_setter();
}

FeRun run(const core::Scene& scene, core::RankLink* link, int steps) {
  FeSolver solver(scene);
  if (link) solver.divide_among_ranks(*link);
  FeRun r;
  advance(solver, r, steps);
  return r;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// Tolerances: node positions and velocities and the alive flags equal to the bit, at every
// step; kinetic energy and momentum (the nodes' sums, the same on every rank) to the bit;
// internal, plastic, hourglass and eroded energy within 1e-10 of the initial kinetic energy
// (each rank's elements summed, then the ranks in rank order); the erosion records on rank 0
// the one-process run's, in its order, their energies within 1e-10 relative. Repeated, the
// divided run gives the same bits.
void expect_divided_run(const std::string& text, int steps) {
  const core::Scene scene = core::parse_scene(text, "fe.toml");
  const FeRun whole = run(scene, nullptr, steps);
  core::MpiRankLink link;
  const FeRun divided = run(scene, &link, steps);
  const FeRun again = run(scene, &link, steps);
  const double e0 = whole.energies.front().kinetic;
  ASSERT_GT(e0, 0.0);
  for (int k = 0; k < steps; ++k) {
    const auto s = static_cast<std::size_t>(k);
    ASSERT_TRUE(same_bits(divided.position[s], whole.position[s])) << "nodes at step " << k;
    const core::Energies& a = whole.energies[s];
    const core::Energies& b = divided.energies[s];
    EXPECT_EQ(b.kinetic, a.kinetic) << "step " << k;
    EXPECT_EQ(b.bodies[0].momentum.z, a.bodies[0].momentum.z) << "step " << k;
    EXPECT_EQ(b.bodies[0].mass, a.bodies[0].mass) << "step " << k;
    EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.hourglass, a.hourglass, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.eroded, a.eroded, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.external_work, a.external_work, 1e-10 * e0) << "step " << k;
    EXPECT_EQ(again.energies[s].internal, b.internal) << "step " << k;
  }
  EXPECT_TRUE(same_bits(divided.velocity, whole.velocity));
  EXPECT_TRUE(same_bits(divided.alive, whole.alive));
  EXPECT_TRUE(same_bits(again.position.back(), divided.position.back()));
  EXPECT_EQ(divided.setter, whole.setter);
  EXPECT_GT(whole.energies.back().plastic, 0.01 * e0);  // the foot yielded
  ASSERT_FALSE(whole.events.empty());                   // and eroded
  if (core::rank_index() != 0) {
    EXPECT_TRUE(divided.events.empty()) << "rank 0 holds the records";
    return;
  }
  ASSERT_EQ(divided.events.size(), whole.events.size());
  for (std::size_t k = 0; k < whole.events.size(); ++k) {
    const ErosionEvent& a = whole.events[k];
    const ErosionEvent& b = divided.events[k];
    EXPECT_EQ(std::string(b.kind), a.kind) << "record " << k;
    EXPECT_EQ(b.id, a.id) << "record " << k;
    EXPECT_EQ(b.body, a.body) << "record " << k;
    EXPECT_EQ(b.time, a.time) << "record " << k;
    EXPECT_EQ(b.reason, a.reason) << "record " << k;
    EXPECT_NEAR(b.energy, a.energy, 1e-10 * std::abs(a.energy)) << "record " << k;
    EXPECT_EQ(b.mass, a.mass) << "record " << k;
  }
}

TEST(MpiFeRanks, OnePointHexahedraThatErodeGiveOneProcessNodesBitForBit) {
  expect_divided_run(eroding_bar, 100);
}

TEST(MpiFeRanks, FullHexahedraAndTrussesGiveOneProcessNodesBitForBit) {
  expect_divided_run(block_and_rod, 120);
}

// Reference: the uninterrupted one-process run (120 steps). The divided run's checkpoint after
// 60 steps is written by rank 0 alone (FeSolver::prepare_checkpoint gathers every element's
// points and adds every rank's running sums). A solver divided among this run's ranks and one
// in a single process each read it and take the remaining 60 steps: their nodes are the
// uninterrupted run's to the bit at every step, their energies within 1e-10 of its initial
// kinetic energy.
TEST(MpiFeRanks, CheckpointOfTheDividedRunRestartsOnRanksAndInOneProcess) {
  const core::Scene scene = core::parse_scene(eroding_bar, "fe.toml");
  constexpr int first = 60, rest = 60;
  const FeRun whole = run(scene, nullptr, first + rest);
  core::MpiRankLink link;
  const std::string path = test::shared_scratch_file(link, "step_60.h5");
  ASSERT_FALSE(path.empty()) << "rank 0 could not make a scratch directory";
  {
    FeSolver divided(scene);
    divided.divide_among_ranks(link);
    FeRun r;
    advance(divided, r, first);
    test::save_checkpoint(link, divided, path);
  }
  const double e0 = whole.energies.front().kinetic;
  const auto expect_rest = [&](FeSolver& solver, const char* what) {
    FeRun r;
    advance(solver, r, rest);
    for (int k = 0; k < rest; ++k) {
      const auto s = static_cast<std::size_t>(k), w = static_cast<std::size_t>(first + k);
      ASSERT_TRUE(same_bits(r.position[s], whole.position[w])) << what << ", step " << first + k;
      const core::Energies& a = whole.energies[w];
      const core::Energies& b = r.energies[s];
      EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << what << ", step " << first + k;
      EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << what << ", step " << first + k;
      EXPECT_NEAR(b.eroded, a.eroded, 1e-10 * e0) << what << ", step " << first + k;
      EXPECT_NEAR(b.hourglass, a.hourglass, 1e-10 * e0) << what << ", step " << first + k;
    }
    EXPECT_EQ(solver.step_count(), first + rest) << what;
  };
  FeSolver again(scene);
  again.divide_among_ranks(link);
  test::load_checkpoint(again, path);
  expect_rest(again, "on ranks");
  FeSolver alone(scene);
  test::load_checkpoint(alone, path);
  expect_rest(alone, "in one process");
  test::remove_shared_scratch(link, path);
}

}  // namespace
}  // namespace afemp::fem
