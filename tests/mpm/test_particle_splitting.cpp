// Adaptive multi-axis particle splitting (mpm/particle_splitting.cpp; eqs 14-17 of the 2020
// MPM paper on explosion and impact in the Journal of Harbin Engineering University,
// docs/references.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "core/output/field_writer.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_model.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "scratch_dir.hpp"
#include "stretched_column.hpp"

namespace afemp::mpm {
namespace {

using test::column;

struct Stretch {
  std::size_t particles = 0;
  long splits = 0;
  double length = 0.0;          // extent of the particles along z at the end
  int empty_cells = 0;          // layers of cells between the ends holding no particle
  double mass_error = 0.0;      // |M - M0| / M0
  double momentum_error = 0.0;  // |P - P0| / (M0 * 1000 m/s)
  double seconds = 0.0;
};

Stretch stretch(const std::string& splitting, const std::string& more_bodies = "") {
  const core::Scene scene = core::parse_scene(column(splitting, more_bodies), "column.toml");
  MpmSolver solver(scene, generate_particles(scene));
  Particles& p = solver.mutable_particles();
  test::stretch_column(p);  // the column (a second body stays at rest)
  const core::Energies e0 = solver.energies();
  const auto start = std::chrono::steady_clock::now();
  // Until the particles span 4x their initial 9.75 mm (or 30 us).
  auto extent = [&] {
    double lo = 1e300, hi = -1e300;
    for (const Vec3& x : solver.particles().position)
      lo = std::min(lo, x.z), hi = std::max(hi, x.z);
    return hi - lo;
  };
  while (extent() < 39.0 && solver.time() < 30e-3) solver.step(solver.stable_time_step());
  Stretch r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const core::Energies e = solver.energies();
  const Particles& q = solver.particles();
  r.particles = q.size();
  r.splits = solver.split_count();
  r.mass_error = std::abs(e.bodies[0].mass - e0.bodies[0].mass) / e0.bodies[0].mass;
  r.momentum_error =
      core::norm(e.bodies[0].momentum - e0.bodies[0].momentum) / (e0.bodies[0].mass * 1000.0);
  // Continuity: every layer of cells (normal to z) between the two ends holds a particle.
  double lo = 1e300, hi = -1e300;
  std::set<int> layers;
  for (std::size_t i = 0; i < q.size(); ++i) {
    lo = std::min(lo, q.position[i].z);
    hi = std::max(hi, q.position[i].z);
    layers.insert(solver.grid().cell_of(q.position[i])[2]);
  }
  r.length = hi - lo;
  const int first = solver.grid().cell_of({0.5, 0.5, lo})[2];
  const int last = solver.grid().cell_of({0.5, 0.5, hi})[2];
  for (int k = first; k <= last; ++k)
    if (!layers.count(k)) ++r.empty_cells;
  std::printf(
      "splitting %s: %zu particles, %ld splits, length %.3f mm, %d empty cells, mass "
      "%.2e, momentum %.2e, %.3f s\n",
      splitting.empty() ? "off" : "on", r.particles, r.splits, r.length, r.empty_cells,
      r.mass_error, r.momentum_error, r.seconds);
  return r;
}

// Reference: the paper's claim (eqs 14-17) made testable. Stretched 4x, the bar without
// splitting opens empty layers of cells (its particle layers drift 2 cells apart); with
// splitting (alpha 0.9) it stays continuous, and mass and momentum are conserved to 1e-12 (the
// shares are exact powers of two).
TEST(ParticleSplitting, ColumnStretchedFourTimesStaysContinuousWithMassAndMomentumKept) {
  const Stretch off = stretch("");
  const Stretch on = stretch("splitting = { alpha = 0.9 }");
  EXPECT_GE(off.length, 39.0);
  EXPECT_GE(on.length, 39.0);
  EXPECT_GT(off.empty_cells, 0);
  EXPECT_EQ(on.empty_cells, 0);
  EXPECT_GT(on.splits, 0);
  EXPECT_GT(on.particles, 3 * off.particles);
  EXPECT_LT(on.mass_error, 1e-12);
  EXPECT_LT(on.momentum_error, 1e-12);
}

// The field output writes each particle's mass (`mass`), so a reader can weigh what it
// selects (a jet's slices, a fragment): after splits, the frame's masses are the pieces' own,
// and they sum to the column's mass (conservation; the shares are exact powers of two).
TEST(ParticleSplitting, TheFieldOutputWritesEachPiecesMass) {
  const core::Scene scene = core::parse_scene(column("splitting = { alpha = 0.9 }"), "column.toml");
  MpmModel model(scene);
  MpmSolver& solver = model.solver();
  const double mass = solver.energies().bodies[0].mass;
  const std::size_t n0 = solver.particles().size();
  test::stretch_column(solver.mutable_particles());
  while (solver.split_count() == 0 && solver.time() < 30e-3) solver.step(solver.stable_time_step());
  ASSERT_GT(solver.split_count(), 0);
  const test::ScratchDir dir;
  {
    core::FieldWriter writer(dir.str());
    model.write_fields(writer);
  }
  std::vector<std::size_t> dims;
  const std::vector<double> written =
      core::read_dataset(dir.file("fields.h5"), "/frame_000000/particles/node/mass", &dims);
  const Particles& p = solver.particles();
  ASSERT_EQ(written.size(), p.size());
  EXPECT_GT(p.size(), n0);
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(written[i], p.mass[i]) << i;
    if (p.body[i] == 0) sum += written[i];
  }
  EXPECT_NEAR(sum, mass, 1e-12 * mass);
}

// [mpm] splitting.bodies: only the bodies named split. A column not named keeps its particles
// (and opens gaps as without splitting); named, it splits as with all bodies splitting. A
// name that is not a body of particles is an error naming the key.
TEST(ParticleSplitting, OnlyTheBodiesNamedSplit) {
  const std::string block =
      "[[bodies]]\nname = \"block\"\nmaterial = \"aluminium\"\n"
      "shape = { box = { min = [1.5, 0, 4.75], max = [2, 0.5, 5.25] } }\n";
  // The column named: its particles split once it has doubled (about 5 us at this rate).
  const core::Scene scene = core::parse_scene(
      column("splitting = { alpha = 0.9, bodies = [\"column\"] }", block), "named.toml");
  MpmSolver solver(scene, generate_particles(scene));
  Particles& p = solver.mutable_particles();
  test::stretch_column(p);
  const std::size_t start = p.size();
  while (solver.time() < 10e-3 && solver.particles().size() == start)
    solver.step(solver.stable_time_step());
  EXPECT_GT(solver.particles().size(), start);
  // Only the block named: the column stretches to 4x without a split and opens gaps.
  const Stretch other = stretch("splitting = { alpha = 0.9, bodies = [\"block\"] }", block);
  EXPECT_EQ(other.splits, 0);
  EXPECT_GT(other.empty_cells, 0);
  try {
    core::parse_scene(column("splitting = { bodies = [\"nothing\"] }"), "names.toml");
    FAIL() << "an unknown body was taken";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.key(), "mpm.splitting.bodies") << e.what();
  }
}

// [mpm] splitting.axes: a particle splits only along the axes named. The column stretches
// along z: split along z only, it stays continuous with the same splits as with all three axes
// (its x and y lengths shrink, so they never split); split along x and y only, it never
// splits and opens gaps as without splitting. An unknown axis, or none, is an error naming
// the key.
TEST(ParticleSplitting, OnlyTheAxesNamedSplit) {
  const Stretch all = stretch("splitting = { alpha = 0.9 }");
  const Stretch along = stretch("splitting = { alpha = 0.9, axes = [\"z\"] }");
  EXPECT_GT(along.splits, 0);
  EXPECT_EQ(along.splits, all.splits);
  EXPECT_EQ(along.particles, all.particles);
  EXPECT_EQ(along.empty_cells, 0);
  EXPECT_LT(along.mass_error, 1e-12);
  EXPECT_LT(along.momentum_error, 1e-12);
  const Stretch across = stretch("splitting = { alpha = 0.9, axes = [\"x\", \"y\"] }");
  EXPECT_EQ(across.splits, 0);
  EXPECT_GT(across.empty_cells, 0);
  for (const char* axes : {"[\"w\"]", "[]"}) {
    try {
      core::parse_scene(column(std::string("splitting = { axes = ") + axes + " }"), "axes.toml");
      FAIL() << "axes = " << axes << " was taken";
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.key(), "mpm.splitting.axes") << e.what();
      EXPECT_NE(std::string(e.what()).find("\"x\", \"y\", \"z\""), std::string::npos) << e.what();
    }
  }
}

TEST(ParticleSplitting, ACapOnTheParticleCountStopsTheRunWithAClearMessage) {
  const core::Scene scene =
      core::parse_scene(column("splitting = { alpha = 0.9, max_particles = 1000 }"), "cap.toml");
  MpmSolver solver(scene, generate_particles(scene));
  test::stretch_column(solver.mutable_particles());
  try {
    while (solver.time() < 30e-3) solver.step(solver.stable_time_step());
    FAIL() << "the particle count passed max_particles";
  } catch (const core::SimulationError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("max_particles = 1000"), std::string::npos) << what;
    EXPECT_LE(solver.particles().size(), 1000u);
  }
}

}  // namespace
}  // namespace afemp::mpm
