// Deterministic by design: the particle-to-grid sweep sums every node in an order fixed by
// the colour layers and the particle order, never by the threads, so a run gives the same
// particle state bit for bit with one thread, with two, and when repeated.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "core/material_fixtures.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

const std::string scene_text = std::string("[run]\n") + core::fixtures::kDeterminismCopperToml + R"(
[grid]
cell = 1.0
min = [0, 0, 0]
max = [12, 12, 24]
boundary = { zmin = "wall", xmin = "symmetric", ymin = "symmetric" }
[mpm]
scheme = "MUSL"
[[bodies]]
name = "bar"
material = "copper"
shape = { cylinder = { base = [0, 0, 0.5], radius = 4, length = 20 } }
particles_per_cell = 3
velocity = [0, 0, -200]
)";

// `method`: extra [mpm] lines (shape function, transfer).
Particles run(int threads, const std::string& method = "") {
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  std::string text = scene_text;
  const std::string key = "scheme = \"MUSL\"\n";
  text.insert(text.find(key) + key.size(), method);
  const core::Scene scene = core::parse_scene(text, "determinism.toml");
  MpmSolver solver(scene, generate_particles(scene));
  // 150 steps: the bar hits the wall, yields and spreads; the particles get reordered once.
  // ~6800 particles: enough for every particle loop to run threaded (core::worth_threads).
  EXPECT_TRUE(core::worth_threads(solver.particles().size()));
  for (int k = 0; k < 150; ++k) solver.step(solver.stable_time_step());
#ifdef _OPENMP
  omp_set_num_threads(before);
#endif
  return solver.particles();
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expect_same_bits(const std::string& method) {
  const Particles one = run(1, method), two = run(2, method), two_again = run(2, method);
  for (const Particles* other : {&two, &two_again}) {
    EXPECT_TRUE(same_bits(one.position, other->position));
    EXPECT_TRUE(same_bits(one.velocity, other->velocity));
    EXPECT_TRUE(same_bits(one.stress, other->stress));
    EXPECT_TRUE(same_bits(one.volume, other->volume));
    EXPECT_TRUE(same_bits(one.plastic_strain, other->plastic_strain));
    EXPECT_TRUE(same_bits(one.energy, other->energy));
    EXPECT_TRUE(same_bits(one.id, other->id));
    EXPECT_TRUE(same_bits(one.affine, other->affine));
  }
  // The run did something: the bar yielded.
  double max_eps = 0.0;
  for (double e : one.plastic_strain) max_eps = std::max(max_eps, e);
  EXPECT_GT(max_eps, 0.01);
}

TEST(Determinism, SameParticleBitsForOneTwoAndRepeatedThreads) {
  // Reference: bitwise equality of every particle array (tolerance 0).
  expect_same_bits("");
}

// uGIMP sweeps four colour layers, not two, and APIC adds the affine velocity: the same
// reference (tolerance 0).
TEST(Determinism, SameParticleBitsWithGimpAndAffineTransfer) {
  expect_same_bits("shape_function = \"gimp\"\ntransfer = \"apic\"\n");
}

// The cubic B-spline's 64-node stencil, with the affine transfer: the same reference.
TEST(Determinism, SameParticleBitsWithCubicBsplineAndAffineTransfer) {
  expect_same_bits("shape_function = \"bspline3\"\ntransfer = \"apic\"\n");
}

// CPDI2's tracked corners move per particle and sum into 64-node boxes (CPDI1 shares the boxes
// and moves its edge vectors the same way): the same reference.
TEST(Determinism, SameParticleBitsWithCpdi) {
  expect_same_bits("shape_function = \"cpdi2\"\n");
}

}  // namespace
}  // namespace afemp::mpm
