// Grid contact and the FE-MPM couplings divided among 1 to 4 ranks: the particles by the grid's
// blocks (MpmSolver::divide_among_ranks), the elements in runs dealt round the ranks with every
// node on every rank (FeSolver::divide_among_ranks), the mesh nodes on the grid scattered by the
// rank of their block and their results sent to every rank (coupling/node_points.hpp). Each
// scene runs on every rank once by itself (the reference: one process, the whole run) and once
// divided; the divided run must give the one-process figures to round-off step by step, repeat
// itself bit for bit, and keep every rank's copy of the mesh nodes the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/mpi/mpi_rank_link.hpp"
#include "core/mpi/ranks.hpp"
#include "core/scene.hpp"
#include "coupled_run.hpp"
#include "coupling/coupled_model.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "shared_scratch.hpp"
#include "striker_on_plate.hpp"

namespace afemp::coupling {
namespace {

// The striker on the plate (striker_on_plate.hpp) as particles in grid contact with friction, and
// as hexahedra in grid contact (CFEMP) beside a rod of trusses bonded into the plate (HFEMP).
const std::string particles_in_contact = test::striker_on_plate(false);
const std::string meshes_on_the_grid = test::striker_on_plate(true);

using test::advance;
using test::CoupledRun;

CoupledRun run(const core::Scene& scene, core::RankLink* link, int steps) {
  CoupledModel model(scene);
  if (link) model.divide_among_ranks(*link);
  CoupledRun r;
  advance(model, r, steps);
  return r;
}

struct MpmRun {
  std::vector<core::Energies> energies;
  std::vector<std::vector<double>> forces;  // each grid contact's: the force's x, y, z on body 1
  mpm::Particles particles;
};

MpmRun run_particles(const core::Scene& scene, core::RankLink* link, int steps) {
  mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
  if (link) solver.divide_among_ranks(*link, {});
  MpmRun r;
  for (int k = 0; k < steps; ++k) {
    solver.step(solver.stable_time_step());
    r.energies.push_back(solver.energies());
    r.forces.emplace_back();
    for (const mpm::MpmSolver::InterfaceForce& f : solver.grid_contact_forces()) {
      const core::Vec3 total = f.normal + f.tangential;
      r.forces.back().insert(r.forces.back().end(), {total.x, total.y, total.z});
    }
  }
  r.particles = solver.particles();
  return r;
}

// Every particle on one rank, each within `tolerance` of where the one-process run has it.
void expect_same_particles(const mpm::Particles& whole, const mpm::Particles& divided,
                           double tolerance) {
  std::unordered_map<std::int32_t, std::size_t> at;
  for (std::size_t i = 0; i < whole.size(); ++i) at[whole.id[i]] = i;
  double worst = 0.0;
  std::int64_t ids = 0;
  for (std::size_t i = 0; i < divided.size(); ++i) {
    ids += divided.id[i];
    worst = std::max(worst, core::norm(divided.position[i] - whole.position[at.at(divided.id[i])]));
  }
  std::int64_t all_ids = 0;
  for (std::int32_t id : whole.id) all_ids += id;
  EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(divided.size())),
            static_cast<std::int64_t>(whole.size()));
  EXPECT_EQ(core::sum_over_ranks(ids), all_ids);
  EXPECT_LE(worst, tolerance);
}

// Reference: one process. Tolerances: kinetic, internal, plastic and contact energy within 1e-10
// of the initial kinetic energy at every step; each body's momentum within 1e-10 of the
// striker's initial momentum; each contact force component within 1e-9 of its largest magnitude
// over the run (the nodes' impulses are added in another order, and a force is the difference
// of momenta 1e6 times larger per step); particles within 1e-10 cell. The divided run repeated
// gives the same bits.
// `caught`: the contact books its dissipation as contact energy (grid contact); surface contact
// books friction's as sliding energy (its normal catch shows in the balance).
void expect_energies(const std::vector<core::Energies>& whole,
                     const std::vector<core::Energies>& divided,
                     const std::vector<core::Energies>& again, bool caught = true) {
  ASSERT_EQ(divided.size(), whole.size());
  const double e0 = whole.front().kinetic;
  const double p0 = std::abs(whole.front().bodies[1].momentum.z);
  ASSERT_GT(e0, 0.0);
  for (std::size_t k = 0; k < whole.size(); ++k) {
    const core::Energies& a = whole[k];
    const core::Energies& b = divided[k];
    EXPECT_NEAR(b.kinetic, a.kinetic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.contact, a.contact, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.hourglass, a.hourglass, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.sliding, a.sliding, 1e-10 * e0) << "step " << k;
    for (std::size_t body = 0; body < a.bodies.size(); ++body) {
      EXPECT_NEAR(b.bodies[body].momentum.z, a.bodies[body].momentum.z, 1e-10 * p0)
          << "step " << k << ", body " << body;
      EXPECT_NEAR(b.bodies[body].mass, a.bodies[body].mass, 1e-12 * a.bodies[body].mass);
    }
    EXPECT_EQ(again[k].kinetic, b.kinetic) << "step " << k;
    EXPECT_EQ(again[k].contact, b.contact) << "step " << k;
  }
  // The run met what it is for: the contact took energy out, the plate yielded.
  EXPECT_GT(caught ? whole.back().contact : whole.back().sliding, 1e-3 * e0);
  EXPECT_GT(whole.back().plastic, 1e-2 * e0);
}

void expect_forces(const std::vector<std::vector<double>>& whole,
                   const std::vector<std::vector<double>>& divided) {
  ASSERT_EQ(divided.size(), whole.size());
  ASSERT_FALSE(whole.empty());
  std::vector<double> largest(whole.front().size(), 0.0);
  for (const std::vector<double>& row : whole)
    for (std::size_t c = 0; c < row.size(); ++c)
      largest[c] = std::max(largest[c], std::abs(row[c]));
  for (std::size_t k = 0; k < whole.size(); ++k) {
    ASSERT_EQ(divided[k].size(), whole[k].size());
    for (std::size_t c = 0; c < whole[k].size(); ++c)
      EXPECT_NEAR(divided[k][c], whole[k][c], 1e-9 * largest[c]) << "step " << k << " column " << c;
  }
}

// The mesh nodes within `tolerance` of the one-process run's at every step, and every rank's
// copy of them at the end every other rank's, to the bit.
void expect_same_nodes(const CoupledRun& whole, const CoupledRun& divided, double tolerance,
                       core::RankLink& link) {
  ASSERT_EQ(divided.nodes.size(), whole.nodes.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < whole.nodes.size(); ++k)
    for (std::size_t i = 0; i < whole.nodes[k].size(); ++i)
      worst = std::max(worst, core::norm(divided.nodes[k][i] - whole.nodes[k][i]));
  EXPECT_LE(worst, tolerance);
  const std::vector<core::Vec3>& mine = divided.nodes.back();
  for (const std::vector<std::byte>& theirs :
       link.gather(core::bytes_of(std::span<const core::Vec3>(mine)))) {
    ASSERT_EQ(theirs.size(), mine.size() * sizeof(core::Vec3));
    EXPECT_EQ(std::memcmp(theirs.data(), mine.data(), theirs.size()), 0);
  }
}

TEST(MpiCoupledRanks, GridContactBetweenParticleBodiesGivesOneProcessFigures) {
  const core::Scene scene = core::parse_scene(particles_in_contact, "contact.toml");
  constexpr int steps = 100;
  const MpmRun whole = run_particles(scene, nullptr, steps);
  core::MpiRankLink link;
  const MpmRun divided = run_particles(scene, &link, steps);
  const MpmRun again = run_particles(scene, &link, steps);
  expect_energies(whole.energies, divided.energies, again.energies);
  expect_forces(whole.forces, divided.forces);
  ASSERT_EQ(whole.forces.back().size(), 3u);
  EXPECT_GT(whole.forces.back()[2], 0.0);  // the plate pushes the striker back (+z)
  expect_same_particles(whole.particles, divided.particles, 1e-10 * scene.mpm.grid.cell);
}

// The mesh nodes are the same on every rank (each rank moves every node from the same forces and
// the same grid results) and within 1e-10 cell of the one-process run's at every step.
TEST(MpiCoupledRanks, ContactAndBondedMeshNodesGiveOneProcessFigures) {
  const core::Scene scene = core::parse_scene(meshes_on_the_grid, "coupled.toml");
  constexpr int steps = 100;
  const CoupledRun whole = run(scene, nullptr, steps);
  core::MpiRankLink link;
  const CoupledRun divided = run(scene, &link, steps);
  const CoupledRun again = run(scene, &link, steps);
  expect_energies(whole.energies, divided.energies, again.energies);
  expect_forces(whole.forces, divided.forces);
  const double h = scene.mpm.grid.cell;
  expect_same_nodes(whole, divided, 1e-10 * h, link);
  expect_same_particles(whole.particles, divided.particles, 1e-10 * h);
  // The striker was stopped by the contact, and the bonded rod moved with the plate.
  const core::Energies& end = whole.energies.back();
  EXPECT_GT(end.bodies[1].momentum.z, 0.98 * whole.energies.front().bodies[1].momentum.z)
      << "the striker slows";
  EXPECT_LT(end.bodies[2].momentum.z, 0.0) << "the rod moves down with the plate";
}

// Reference: the uninterrupted one-process run (100 steps). The divided run's checkpoint after 50
// steps is written by rank 0 alone, as one process's (every particle, every element's points,
// the nodes on the grid, the sums of every rank). A model divided among this run's ranks and one
// in a single process each read it and take the remaining 50 steps: energies within 1e-10 of
// the initial kinetic energy and the mesh nodes within 1e-10 cell of the uninterrupted run's
// at every step.
TEST(MpiCoupledRanks, CheckpointOfTheDividedRunRestartsOnRanksAndInOneProcess) {
  const core::Scene scene = core::parse_scene(meshes_on_the_grid, "coupled.toml");
  constexpr int first = 50, rest = 50;
  const CoupledRun whole = run(scene, nullptr, first + rest);
  core::MpiRankLink link;
  const std::string path = test::shared_scratch_file(link, "step_50.h5");
  ASSERT_FALSE(path.empty()) << "rank 0 could not make a scratch directory";
  {
    CoupledModel divided(scene);
    divided.divide_among_ranks(link);
    CoupledRun r;
    advance(divided, r, first);
    test::save_checkpoint(link, divided, path);
  }
  const double e0 = whole.energies.front().kinetic;
  const double h = scene.mpm.grid.cell;
  const auto expect_rest = [&](CoupledModel& model, const char* what) {
    CoupledRun r;
    advance(model, r, rest);
    for (int k = 0; k < rest; ++k) {
      const auto s = static_cast<std::size_t>(k), w = static_cast<std::size_t>(first + k);
      const core::Energies& a = whole.energies[w];
      const core::Energies& b = r.energies[s];
      EXPECT_NEAR(b.kinetic, a.kinetic, 1e-10 * e0) << what << ", step " << first + k;
      EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << what << ", step " << first + k;
      EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << what << ", step " << first + k;
      EXPECT_NEAR(b.contact, a.contact, 1e-10 * e0) << what << ", step " << first + k;
      double worst = 0.0;
      for (std::size_t i = 0; i < r.nodes[s].size(); ++i)
        worst = std::max(worst, core::norm(r.nodes[s][i] - whole.nodes[w][i]));
      EXPECT_LE(worst, 1e-10 * h) << what << ", step " << first + k;
    }
    EXPECT_EQ(model.step_count(), first + rest) << what;
  };
  CoupledModel again(scene);
  again.divide_among_ranks(link);
  test::load_checkpoint(again, path);
  expect_rest(again, "on ranks");
  CoupledModel alone(scene);
  test::load_checkpoint(alone, path);
  expect_rest(alone, "in one process");
  test::remove_shared_scratch(link, path);
}

// The striker's hexahedra convert into particles (AFEMP) as they yield: every rank receives the
// retired elements with their points' state and makes the same particles, keeping those of its
// blocks. Reference: one process, 100 steps. Tolerances as above; the converted particles carry
// the one-process run's ids (each particle compared with the one of its id), and the energy
// conversion lost agrees within 1e-10 of the initial kinetic energy.
TEST(MpiCoupledRanks, ConvertingHexahedraGiveOneProcessParticlesAndFigures) {
  std::string text = meshes_on_the_grid;
  const std::string mesh = "mesh = { size = 1.0, sectors = 1 }";
  text.replace(text.find(mesh), mesh.size(),
               mesh + "\nconversion = { plastic_strain = 0.05, points = 2 }");
  const core::Scene scene = core::parse_scene(text, "afemp.toml");
  constexpr int steps = 100;
  const CoupledRun whole = run(scene, nullptr, steps);
  core::MpiRankLink link;
  const CoupledRun divided = run(scene, &link, steps);
  const CoupledRun again = run(scene, &link, steps);
  expect_energies(whole.energies, divided.energies, again.energies);
  const double e0 = whole.energies.front().kinetic;
  for (std::size_t k = 0; k < whole.energies.size(); ++k)
    EXPECT_NEAR(divided.energies[k].converted, whole.energies[k].converted, 1e-10 * e0)
        << "step " << k;
  const double h = scene.mpm.grid.cell;
  expect_same_nodes(whole, divided, 1e-10 * h, link);
  // Elements did convert, into 8 particles each beside the plate's 4,608; the divided run made
  // as many (expect_same_particles: the count over the ranks, and every id).
  ASSERT_GT(whole.particles.size(), 4608u + 8u);
  EXPECT_EQ((whole.particles.size() - 4608u) % 8u, 0u);
  expect_same_particles(whole.particles, divided.particles, 1e-10 * h);
}

// The striker's hexahedra meet the plate's particles at its faces (surface contact, friction
// 0.2): each rank finds the hits of its own particles and every rank sweeps every rank's in the
// order of the particles' ids (mpm/contact_nodes.hpp). Reference: one process, 100 steps;
// tolerances as above (friction's dissipation, booked as sliding energy, within 1e-10 of the
// initial kinetic energy), the contact's normal and friction force within 1e-9 of their
// largest.
TEST(MpiCoupledRanks, SurfaceContactGivesOneProcessFigures) {
  std::string text = meshes_on_the_grid;
  const std::string pair = "bodies = [\"striker\", \"plate\"]";
  text.replace(text.find(pair), pair.size(), pair + "\nmethod = \"surface\"\nfriction = 0.2");
  const core::Scene scene = core::parse_scene(text, "surface.toml");
  constexpr int steps = 100;
  const CoupledRun whole = run(scene, nullptr, steps);
  core::MpiRankLink link;
  const CoupledRun divided = run(scene, &link, steps);
  const CoupledRun again = run(scene, &link, steps);
  expect_energies(whole.energies, divided.energies, again.energies, false);
  expect_forces(whole.forces, divided.forces);
  const double h = scene.mpm.grid.cell;
  expect_same_nodes(whole, divided, 1e-10 * h, link);
  expect_same_particles(whole.particles, divided.particles, 1e-10 * h);
}

}  // namespace
}  // namespace afemp::coupling
