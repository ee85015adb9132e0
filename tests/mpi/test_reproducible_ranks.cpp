// The reproducible mode ([run] reproducible = true; mpm/reproducible_sums.cpp,
// fem/reproducible_energies.cpp) on 1 to 4 ranks: the grid's nodal sums in fixed point and the
// energies and forces summed exactly, so that a run of particles, of meshes or of both coupled
// divided among any number of ranks gives one process's figures to the bit, at one thread and at
// two. Reference: the
// same scene in one process (every rank runs it whole); and, to show the mode computes the same
// physics, the run without the mode, within the round-off of its other order of summation (1e-10 of
// the initial kinetic energy, as the divided runs' tests of test_mpm_ranks.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

#include "copper_bar_on_wall.hpp"
#include "core/mpi/mpi_rank_link.hpp"
#include "core/mpi/ranks.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "coupled_run.hpp"
#include "coupling/coupled_model.hpp"
#include "explosive_scenes.hpp"
#include "fem/fe_solver.hpp"
#include "mixed_beam.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "shared_scratch.hpp"
#include "stretched_column.hpp"
#include "striker_on_plate.hpp"

namespace afemp::test {

// The runs a test of the mode compares: one process at one thread (the reference), at two
// threads (on one rank; under more ranks the 2 cores are taken, and it is the first again), the
// run divided among the ranks, and one process without the mode. `run(scene, link, steps,
// threads)` makes each.
template <class R>
struct FourRuns {
  R whole, threads, divided, plain;
};

template <class R, class F>
FourRuns<R> four_runs(const std::string& text, int steps, F run) {
  const core::Scene scene = core::parse_scene(text, "scene.toml");
  EXPECT_TRUE(scene.run.reproducible);
  FourRuns<R> r;
  r.whole = run(scene, nullptr, steps, 1);
  r.threads = core::rank_count() == 1 ? run(scene, nullptr, steps, 2) : r.whole;
  core::MpiRankLink link;
  r.divided = run(scene, &link, steps, 1);
  core::Scene plain = scene;
  plain.run.reproducible = false;
  r.plain = run(plain, nullptr, steps, 1);
  return r;
}

}  // namespace afemp::test

namespace afemp::mpm {
namespace {

struct ParticleRun {
  std::vector<Energies> energies;         // after each step
  std::vector<std::vector<Vec3>> forces;  // after each step: walls' forces, then grid contacts'
  Particles particles;                    // this rank's at the end
};

ParticleRun run_from(const core::Scene& scene, Particles start, core::RankLink* link, int steps,
                     int threads) {
  core::set_thread_count(threads);
  MpmSolver solver(scene, std::move(start));
  if (link) solver.divide_among_ranks(*link, {});
  ParticleRun r;
  for (int k = 0; k < steps; ++k) {
    solver.step(solver.stable_time_step());
    r.energies.push_back(solver.energies());
    std::vector<Vec3> f = solver.wall_forces();
    for (const MpmSolver::InterfaceForce& c : solver.grid_contact_forces())
      f.insert(f.end(), {c.normal, c.tangential});
    r.forces.push_back(f);
  }
  r.particles = solver.particles();
  core::set_thread_count(1);
  return r;
}

ParticleRun run(const core::Scene& scene, core::RankLink* link, int steps, int threads) {
  return run_from(scene, generate_particles(scene), link, steps, threads);
}

// The splitting tests' column, stretched (tests/stretched_column.hpp).
ParticleRun run_stretched(const core::Scene& scene, core::RankLink* link, int steps, int threads) {
  Particles start = generate_particles(scene);
  test::stretch_column(start);
  return run_from(scene, std::move(start), link, steps, threads);
}

// How many of the particles' positions, velocities, stresses and plastic strains differ from
// those of the particle of the same id in `whole` (every particle of `p` is in `whole`).
long differences(const Particles& p, const Particles& whole) {
  std::unordered_map<std::int32_t, std::size_t> at;
  for (std::size_t i = 0; i < whole.size(); ++i) at[whole.id[i]] = i;
  long differ = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t j = at.at(p.id[i]);
    for (int c = 0; c < 3; ++c)
      differ +=
          (p.position[i][c] != whole.position[j][c]) + (p.velocity[i][c] != whole.velocity[j][c]);
    const core::SymTensor &a = p.stress[i], &b = whole.stress[j];
    differ += !(a.xx == b.xx && a.yy == b.yy && a.zz == b.zz && a.xy == b.xy && a.yz == b.yz &&
                a.xz == b.xz);
    differ += p.plastic_strain[i] != whole.plastic_strain[j];
  }
  return differ;
}

// Every figure energies() gives, bit for bit.
void expect_same_bits(const Energies& a, const Energies& b, int step) {
  EXPECT_EQ(b.kinetic, a.kinetic) << "step " << step;
  EXPECT_EQ(b.internal, a.internal) << "step " << step;
  EXPECT_EQ(b.plastic, a.plastic) << "step " << step;
  EXPECT_EQ(b.viscous, a.viscous) << "step " << step;
  EXPECT_EQ(b.external_work, a.external_work) << "step " << step;
  EXPECT_EQ(b.contact, a.contact) << "step " << step;
  EXPECT_EQ(b.friction, a.friction) << "step " << step;
  EXPECT_EQ(b.outflow, a.outflow) << "step " << step;
  EXPECT_EQ(b.outflow_mass, a.outflow_mass) << "step " << step;
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(b.outflow_momentum[c], a.outflow_momentum[c]) << "step " << step;
  ASSERT_EQ(b.bodies.size(), a.bodies.size());
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    EXPECT_EQ(b.bodies[k].mass, a.bodies[k].mass) << "step " << step;
    EXPECT_EQ(b.bodies[k].kinetic, a.bodies[k].kinetic) << "step " << step;
    EXPECT_EQ(b.bodies[k].internal, a.bodies[k].internal) << "step " << step;
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(b.bodies[k].momentum[c], a.bodies[k].momentum[c]) << "step " << step;
  }
}

// The mode on ranks (and on one rank at two threads) against one process at one thread, bit
// for bit: every
// energy and force after every step, and every particle's position, velocity, stress and
// plastic strain at the end (each rank's particles against the one-process particle of its
// id; every particle on one rank). And the mode against the run without it: energies within
// 1e-10 of the initial kinetic plus internal energy at every step. `yields`: the bar strikes
// something and yields (its plastic work past 1 % of that energy).
// The nearly incompressible beam of the mixed u-p tests, started in its first bending mode.
ParticleRun run_beam(const core::Scene& scene, core::RankLink* link, int steps, int threads) {
  return run_from(scene, test::mixed_beam::beam_particles(scene), link, steps, threads);
}

using Runner = ParticleRun (*)(const core::Scene&, core::RankLink*, int, int);

void expect_bit_identical(const std::string& text, int steps, bool yields = true,
                          Runner runner = run) {
  const auto [whole, threads, divided, plain] = test::four_runs<ParticleRun>(text, steps, runner);

  // The scale: the initial kinetic plus internal energy (a body struck, or a gas bubble at rest).
  const double e0 = whole.energies.front().kinetic + whole.energies.front().internal;
  ASSERT_GT(e0, 0.0);
  for (int k = 0; k < steps; ++k) {
    const auto s = static_cast<std::size_t>(k);
    expect_same_bits(whole.energies[s], threads.energies[s], k);
    expect_same_bits(whole.energies[s], divided.energies[s], k);
    ASSERT_EQ(divided.forces[s].size(), whole.forces[s].size());
    for (std::size_t f = 0; f < whole.forces[s].size(); ++f)
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(threads.forces[s][f][c], whole.forces[s][f][c]) << "step " << k;
        EXPECT_EQ(divided.forces[s][f][c], whole.forces[s][f][c]) << "step " << k;
      }
    const Energies& a = plain.energies[s];
    const Energies& b = whole.energies[s];
    EXPECT_NEAR(b.kinetic, a.kinetic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.external_work, a.external_work, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.contact, a.contact, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.outflow, a.outflow, 1e-10 * e0) << "step " << k;
  }
  if (yields) {
    EXPECT_GT(whole.energies.back().plastic, 0.01 * e0);  // the material did yield
  }

  for (const ParticleRun* r : {&threads, &divided})
    EXPECT_EQ(differences(r->particles, whole.particles), 0)
        << "values that differ from one process's";
  EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(divided.particles.size())),
            static_cast<std::int64_t>(whole.particles.size()));
}

std::string bar(const std::string& mpm, const std::string& run = "") {
  return test::copper_bar_on_wall("end_time = 0.01\nreproducible = true\n" + run, mpm);
}

TEST(MpiReproducible, MuslLinearHatIsBitIdenticalOnAnyRankCount) {
  expect_bit_identical(bar("scheme = \"MUSL\"\n"), 100);
}

TEST(MpiReproducible, UsfGimpApicIsBitIdenticalOnAnyRankCount) {
  expect_bit_identical(bar("scheme = \"USF\"\nshape_function = \"gimp\"\ntransfer = \"apic\"\n"),
                       100);
}

// Gravity's work is booked at the nodes, each by its block's owner, and summed exactly.
TEST(MpiReproducible, UslQuadraticSplineWithGravityIsBitIdenticalOnAnyRankCount) {
  expect_bit_identical(
      bar("scheme = \"USL\"\nshape_function = \"bspline2\"\n", "gravity = [0, 0, -5e3]\n"), 100);
}

// The bar pushed at its top by 2 kN rising from zero over 0.01 ms (a load on particles): its
// nodal shares go into the fixed-point force sums on whichever rank holds the loaded particles,
// its work into an exact sum.
TEST(MpiReproducible, LoadOnParticlesIsBitIdenticalOnAnyRankCount) {
  expect_bit_identical(bar("scheme = \"MUSL\"\n") + R"(
[[loads]]
body = "bar"
particles = { box = { min = [0, 0, 24.5], max = [10, 10, 26] } }
force = [0, 0, -2000]
curve = [[0, 0], [0.01, 1]]
)",
                       100);
}

// The bar through an outflow face instead of onto a wall: each rank takes out its own particles
// and books their mass, momentum and energy exactly. Reference: besides the bits, the mass left
// on the grid plus the mass booked out is the initial mass (to the rounding of the two sums).
std::string outflow_bar() {
  std::string text = bar("scheme = \"MUSL\"\n");
  text.replace(text.find("zmin = \"wall\""), 13, "zmin = \"outflow\"");
  return text;
}

TEST(MpiReproducible, OutflowFaceIsBitIdenticalOnAnyRankCount) {
  const std::string text = outflow_bar();
  expect_bit_identical(text, 100, false);
  const core::Scene scene = core::parse_scene(text, "scene.toml");
  MpmSolver solver(scene, generate_particles(scene));
  const double m0 = solver.energies().bodies.at(0).mass;
  for (int k = 0; k < 100; ++k) solver.step(solver.stable_time_step());
  const Energies e = solver.energies();
  EXPECT_GT(e.outflow_mass, 0.01 * m0) << "particles left through the face";
  EXPECT_NEAR(e.bodies.at(0).mass + e.outflow_mass, m0, 1e-15 * m0);
  EXPECT_GT(e.outflow, 0.0);
}

// The divided run's checkpoint after `first` steps (in a scratch file every rank reads),
// continued for `rest` steps on this run's ranks and in one process; and the uninterrupted run in
// one process.
struct Continued {
  ParticleRun whole, on_ranks, in_one;
};

Continued continue_from_checkpoint(const core::Scene& scene, int first, int rest,
                                   const std::string& file) {
  Continued c;
  c.whole = run(scene, nullptr, first + rest, 1);
  core::MpiRankLink link;
  const std::string path = test::shared_scratch_file(link, file);
  EXPECT_FALSE(path.empty()) << "rank 0 could not make a scratch directory";
  if (path.empty()) return c;
  {
    MpmSolver divided(scene, generate_particles(scene));
    divided.divide_among_ranks(link);
    for (int k = 0; k < first; ++k) divided.step(divided.stable_time_step());
    test::save_checkpoint(link, divided, path);
  }
  auto continued = [&](MpmSolver& solver) {
    test::load_checkpoint(solver, path);
    ParticleRun r;
    for (int k = 0; k < rest; ++k) {
      solver.step(solver.stable_time_step());
      r.energies.push_back(solver.energies());
    }
    r.particles = solver.particles();
    return r;
  };
  MpmSolver again(scene, generate_particles(scene));
  again.divide_among_ranks(link);
  c.on_ranks = continued(again);
  MpmSolver alone(scene, generate_particles(scene));
  c.in_one = continued(alone);
  test::remove_shared_scratch(link, path);
  return c;
}

// The outflow bar's checkpoint of step 50 on ranks (particles have left by then), continued to
// step 100 on the ranks and in one process: the two the same bits, every energy and outflow book
// after every step; the books the uninterrupted run's to 1e-14 (the checkpoint holds each exact
// sum rounded once).
TEST(MpiReproducible, OutflowBooksContinueFromACheckpointOnRanksAndInOneProcess) {
  const core::Scene scene = core::parse_scene(outflow_bar(), "bar.toml");
  constexpr int first = 50, rest = 50;
  const auto [whole, on_ranks, in_one] =
      continue_from_checkpoint(scene, first, rest, "outflow_50.h5");
  ASSERT_GT(whole.energies[first - 1].outflow_mass, 0.0) << "none left before the checkpoint";
  ASSERT_EQ(in_one.energies.size(), static_cast<std::size_t>(rest));
  for (int k = 0; k < rest; ++k) {
    const auto s = static_cast<std::size_t>(k);
    expect_same_bits(in_one.energies[s], on_ranks.energies[s], first + k);
    const Energies& a = whole.energies[static_cast<std::size_t>(first + k)];
    const Energies& b = in_one.energies[s];
    EXPECT_NEAR(b.outflow_mass, a.outflow_mass, 1e-14 * a.outflow_mass) << "step " << first + k;
    EXPECT_NEAR(b.outflow, a.outflow, 1e-14 * a.outflow) << "step " << first + k;
    EXPECT_NEAR(b.outflow_momentum.z, a.outflow_momentum.z, 1e-14 * std::abs(a.outflow_momentum.z))
        << "step " << first + k;
  }
}

// The bar up to the grid's top, an absorbing face there (its dashpots take energy out once the
// impact's wave arrives): each node's damping work booked exactly by the rank that books it.
TEST(MpiReproducible, AbsorbingFaceIsBitIdenticalOnAnyRankCount) {
  std::string text = bar("scheme = \"MUSL\"\n");
  text.replace(text.find("length = 25.4"), 13, "length = 28");
  text.replace(text.find("zmin = \"wall\""), 13, "zmin = \"wall\", zmax = \"absorbing\"");
  expect_bit_identical(text, 100);
}

// A gas bubble at 10.5 MPa in water at 10 MPa behind far-field faces (Geers's doubly asymptotic
// approximation: each face node's lag from step to step, on the nodes that are the same bits on
// every rank): 100 steps carry its wave onto the faces, whose work is summed exactly.
TEST(MpiReproducible, FarFieldFacesAreBitIdenticalOnAnyRankCount) {
  std::string text = test::sphere_in_water("gas", "internal_energy = 2.5e6\npressure = 10.5");
  text.replace(text.find("[run]\n"), 6, "[run]\nreproducible = true\n");
  expect_bit_identical(text, 100, false);
}

// An aluminium column stretched by its own inertia (the splitting tests' jet): its particles
// split from about step 130, each rank its own, the pieces with their one-process ids; the
// pieces' masses and states follow their parents', whose bits are one process's.
TEST(MpiReproducible, ParticleSplittingIsBitIdenticalOnAnyRankCount) {
  std::string text = test::column("splitting = { alpha = 0.9 }");
  text.replace(text.find("[run]\n"), 6, "[run]\nreproducible = true\n");
  expect_bit_identical(text, 250, false, run_stretched);
  const core::Scene scene = core::parse_scene(text, "column.toml");
  const std::size_t start = generate_particles(scene).size();
  EXPECT_GT(run_stretched(scene, nullptr, 250, 1).particles.size(), start + 50) << "pieces";
}

// The nearly incompressible beam of the mixed u-p total-Lagrangian MPM (neo-Hookean gel at
// nu = 0.499), bending: the projection's three nodal sums (N V0, N V0 J, N K V0 (Jbar - 1)) in
// fixed point, under the quadratic B-spline (the pressure on the linear hat) and under the
// linear hat (the pressure constant per cell).
TEST(MpiReproducible, MixedPressureIsBitIdenticalOnAnyRankCount) {
  for (const char* shape : {"bspline2", "linear"}) {
    SCOPED_TRACE(shape);
    std::string text = test::mixed_beam::beam_scene("mixed", shape, 0.25);
    text.replace(text.find("[run]\n"), 6, "[run]\nreproducible = true\n");
    expect_bit_identical(text, 100, false, run_beam);
  }
}

// A rigid wall at the particles moving up at 5 m/s with friction 0.3: its contacts are swept
// in the particles' id order on every rank (mpm/contact_nodes.hpp), on nodes that are now the
// same bits.
TEST(MpiReproducible, ParticleWallWithFrictionIsBitIdenticalOnAnyRankCount) {
  expect_bit_identical(bar("scheme = \"MUSL\"\n") + R"(
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
velocity = [0, 0, 5]
friction = 0.3
bodies = ["bar"]
)",
                       100);
}

// The checkpoint of the divided run after 70 steps (the bar with the quadratic B-spline and
// gravity onto the moving wall with friction), continued for 80 steps on this run's ranks and in
// one process. Reference: each other, bit for bit (a restart from N ranks on M gives one
// result): every energy after every step and every particle at the end; and the uninterrupted
// run: its particles' bits (the checkpoint holds their state whole), its energies within 1e-10
// of the initial kinetic energy (the running works pass through the checkpoint as doubles).
TEST(MpiReproducible, CheckpointContinuesBitForBitOnRanksAndInOneProcess) {
  const core::Scene scene = core::parse_scene(
      bar("scheme = \"USL\"\nshape_function = \"bspline2\"\n", "gravity = [0, 0, -5e3]\n") +
          R"(
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
velocity = [0, 0, 5]
friction = 0.3
bodies = ["bar"]
)",
      "bar.toml");
  constexpr int first = 70, rest = 80;
  const auto [whole, on_ranks, in_one] = continue_from_checkpoint(scene, first, rest, "step_70.h5");
  ASSERT_EQ(in_one.energies.size(), static_cast<std::size_t>(rest));
  const double e0 = whole.energies.front().kinetic;
  for (int k = 0; k < rest; ++k) {
    const auto s = static_cast<std::size_t>(k);
    expect_same_bits(in_one.energies[s], on_ranks.energies[s], first + k);
    const Energies& a = whole.energies[static_cast<std::size_t>(first + k)];
    EXPECT_NEAR(in_one.energies[s].kinetic, a.kinetic, 1e-10 * e0) << "step " << first + k;
    EXPECT_NEAR(in_one.energies[s].plastic, a.plastic, 1e-10 * e0) << "step " << first + k;
    EXPECT_NEAR(in_one.energies[s].external_work, a.external_work, 1e-10 * e0)
        << "step " << first + k;
    EXPECT_NEAR(in_one.energies[s].friction, a.friction, 1e-10 * e0) << "step " << first + k;
  }
  EXPECT_EQ(differences(on_ranks.particles, in_one.particles), 0);
  EXPECT_EQ(differences(in_one.particles, whole.particles), 0);
}

// The striker of particles in grid contact with friction 0.2 with the plate: the mass
// gradients in fixed point, the contact's dissipation and force summed exactly.
TEST(MpiReproducible, GridContactWithFrictionIsBitIdenticalOnAnyRankCount) {
  expect_bit_identical(test::striker_on_plate(false, "end_time = 1.0\nreproducible = true\n"), 100);
}

}  // namespace
}  // namespace afemp::mpm

namespace afemp::fem {
namespace {

struct FeRun {
  std::vector<core::Energies> energies;       // after each step
  std::vector<std::vector<core::Vec3>> wall;  // the walls' forces after each step
  std::vector<core::Vec3> position;           // the nodes at the end
};

FeRun run(const core::Scene& scene, core::RankLink* link, int steps, int threads) {
  core::set_thread_count(threads);
  FeSolver solver(scene);
  if (link) solver.divide_among_ranks(*link);
  FeRun r;
  for (int k = 0; k < steps; ++k) {
    solver.step(solver.stable_time_step());
    r.energies.push_back(solver.energies());
    r.wall.push_back(solver.wall_forces());
  }
  r.position = solver.nodes().position;
  core::set_thread_count(1);
  return r;
}

// As expect_bit_identical above, for meshes divided by their elements: every energy (the
// element energies and works, gravity's and the wall's work, the eroded energy) and the walls'
// forces after every step the bits of one process at one thread, on ranks and (on one rank)
// at two threads; the nodes at the end too; and within 1e-10 of the initial kinetic energy of
// the run without the mode.
void expect_mesh_bit_identical(const std::string& text, int steps) {
  const auto [whole, threads, divided, plain] = test::four_runs<FeRun>(text, steps, run);
  const double e0 = whole.energies.front().kinetic;
  ASSERT_GT(e0, 0.0);
  for (int k = 0; k < steps; ++k) {
    const auto s = static_cast<std::size_t>(k);
    for (const FeRun* r : {&threads, &divided}) {
      const core::Energies& a = whole.energies[s];
      const core::Energies& b = r->energies[s];
      mpm::expect_same_bits(a, b, k);
      EXPECT_EQ(b.hourglass, a.hourglass) << "step " << k;
      EXPECT_EQ(b.stabilisation, a.stabilisation) << "step " << k;
      EXPECT_EQ(b.eroded, a.eroded) << "step " << k;
      EXPECT_EQ(b.wall, a.wall) << "step " << k;
      ASSERT_EQ(r->wall[s].size(), whole.wall[s].size());
      for (std::size_t w = 0; w < whole.wall[s].size(); ++w)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(r->wall[s][w][c], whole.wall[s][w][c]) << k;
    }
    const core::Energies& a = plain.energies[s];
    const core::Energies& b = whole.energies[s];
    EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.eroded, a.eroded, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.external_work, a.external_work, 1e-10 * e0) << "step " << k;
    EXPECT_EQ(b.kinetic, a.kinetic) << "the nodes are the mode's and the plain run's alike";
  }
  EXPECT_GT(whole.energies.back().plastic, 0.01 * e0);  // the material yielded
  EXPECT_GT(whole.energies.back().eroded, 0.0);         // and eroded
  for (const FeRun* r : {&threads, &divided})
    for (std::size_t i = 0; i < whole.position.size(); ++i)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(r->position[i][c], whole.position[i][c]) << i;
}

// One-point hexahedra with gravity, symmetry constraints, a rigid wall and erosion.
TEST(MpiReproducible, ErodingOnePointHexahedraAreBitIdenticalOnAnyRankCount) {
  std::string text = test::eroding_copper_bar_of_hexahedra();
  text.replace(0, 6, "[run]\nreproducible = true\n");
  expect_mesh_bit_identical(text, 100);
}

// Fully integrated hexahedra that erode beside a rod of trusses, onto a rigid wall.
TEST(MpiReproducible, FullHexahedraAndTrussesAreBitIdenticalOnAnyRankCount) {
  expect_mesh_bit_identical(test::block_and_rod_on_wall("reproducible = true\n"), 120);
}

}  // namespace
}  // namespace afemp::fem

namespace afemp::coupling {
namespace {

using test::CoupledRun;

CoupledRun run(const core::Scene& scene, core::RankLink* link, int steps, int threads) {
  core::set_thread_count(threads);
  CoupledModel model(scene);
  if (link) model.divide_among_ranks(*link);
  CoupledRun r;
  test::advance(model, r, steps);
  core::set_thread_count(1);
  return r;
}

// The couplings in the mode: the mesh nodes' terms join the grid's fixed-point sums (mesh
// points, mpm/grid_points.hpp). As the particles' and the meshes' tests above: every energy (the
// hourglass, converted and sliding energies too) and every force column of the history after
// every step, and every mesh node after every step, the bits of one process at one thread, on
// ranks and (on one rank) at two threads; every particle at the end likewise (a converted one
// against the one-process particle of its id); and within 1e-10 of the initial kinetic energy of
// the run without the mode. `caught`: the contact's dissipation is booked as contact energy
// (grid contact), else as sliding energy (surface contact's friction).
CoupledRun expect_coupled_bit_identical(const std::string& text, int steps, bool caught = true) {
  const auto [whole, threads, divided, plain] = test::four_runs<CoupledRun>(text, steps, run);
  const double e0 = whole.energies.front().kinetic;
  EXPECT_GT(e0, 0.0);
  for (int k = 0; k < steps; ++k) {
    const auto s = static_cast<std::size_t>(k);
    for (const CoupledRun* r : {&threads, &divided}) {
      const core::Energies& a = whole.energies[s];
      const core::Energies& b = r->energies[s];
      mpm::expect_same_bits(a, b, k);
      EXPECT_EQ(b.hourglass, a.hourglass) << "step " << k;
      EXPECT_EQ(b.converted, a.converted) << "step " << k;
      EXPECT_EQ(b.sliding, a.sliding) << "step " << k;
      EXPECT_EQ(r->forces[s], whole.forces[s]) << "step " << k;
      EXPECT_EQ(r->nodes[s].size(), whole.nodes[s].size());
      if (r->nodes[s].size() == whole.nodes[s].size()) {
        EXPECT_EQ(std::memcmp(r->nodes[s].data(), whole.nodes[s].data(),
                              whole.nodes[s].size() * sizeof(core::Vec3)),
                  0)
            << "the mesh nodes after step " << k;
      }
    }
    const core::Energies& a = plain.energies[s];
    const core::Energies& b = whole.energies[s];
    EXPECT_NEAR(b.kinetic, a.kinetic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.internal, a.internal, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.plastic, a.plastic, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.contact, a.contact, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.sliding, a.sliding, 1e-10 * e0) << "step " << k;
    EXPECT_NEAR(b.converted, a.converted, 1e-10 * e0) << "step " << k;
  }
  // The run met what it is for: the contact took energy out, the plate yielded.
  EXPECT_GT(caught ? whole.energies.back().contact : whole.energies.back().sliding, 1e-3 * e0);
  EXPECT_GT(whole.energies.back().plastic, 1e-2 * e0);
  for (const CoupledRun* r : {&threads, &divided})
    EXPECT_EQ(mpm::differences(r->particles, whole.particles), 0)
        << "values that differ from one process's";
  EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(divided.particles.size())),
            static_cast<std::int64_t>(whole.particles.size()));
  return whole;
}

const std::string coupled_scene =
    test::striker_on_plate(true, "end_time = 1.0\nreproducible = true\n");

// The striker's hexahedra in grid contact with the plate's particles (CFEMP) beside a rod of
// trusses bonded into the plate (HFEMP).
TEST(MpiReproducible, ContactAndBondedMeshNodesAreBitIdenticalOnAnyRankCount) {
  expect_coupled_bit_identical(coupled_scene, 100);
}

// The striker's hexahedra converting into particles as they yield (AFEMP): the nodes they
// shared with live elements bond to the new particles, whose field the contact nodes share.
TEST(MpiReproducible, ConvertingHexahedraAreBitIdenticalOnAnyRankCount) {
  std::string text = coupled_scene;
  const std::string mesh = "mesh = { size = 1.0, sectors = 1 }";
  text.replace(text.find(mesh), mesh.size(),
               mesh + "\nconversion = { plastic_strain = 0.05, points = 2 }");
  const CoupledRun whole = expect_coupled_bit_identical(text, 100);
  ASSERT_GT(whole.particles.size(), 4608u + 8u) << "elements converted (8 particles each)";
  EXPECT_GT(whole.energies.back().converted, 0.0);
}

// The striker's hexahedra meeting the plate's particles at its faces (surface contact with
// friction 0.2).
TEST(MpiReproducible, SurfaceContactIsBitIdenticalOnAnyRankCount) {
  std::string text = coupled_scene;
  const std::string pair = "bodies = [\"striker\", \"plate\"]";
  text.replace(text.find(pair), pair.size(), pair + "\nmethod = \"surface\"\nfriction = 0.2");
  expect_coupled_bit_identical(text, 100, false);
}

}  // namespace
}  // namespace afemp::coupling
