// Particles carried past a face that keeps them (mpm/face_crossings.cpp). References: a
// symmetric face gives the mirror image exactly (x -> 2 x_face - x, the normal velocity and the
// shear stress components involving the normal reversed, the rest unchanged); a far-field face
// puts the particle back on its plane with its mass, momentum and state.
#include <gtest/gtest.h>

#include <string>

#include "core/scene.hpp"
#include "explosive_scenes.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

// A 4 mm cube of 1 mm cells with the given grid keys (faces), materials and bodies.
std::string cube(const std::string& grid_keys, const std::string& rest) {
  return R"([run]
end_time = 1.0
[grid]
cell = 1.0
min = [0, 0, 0]
max = [4, 4, 4]
)" + grid_keys +
         rest;
}

// The particle that started first (id 0) wherever binning has put it.
std::size_t first_particle(const Particles& q) {
  std::size_t i = 0;
  while (q.id[i] != 0) ++i;
  return i;
}

TEST(FaceCrossings, AParticlePastASymmetricFaceIsMirroredBack) {
  const core::Scene scene = core::parse_scene(cube("boundary = { xmin = \"symmetric\" }", R"(
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
[[bodies]]
name = "block"
material = "steel"
shape = { box = { min = [0, 1, 1], max = [2, 3, 3] } }
)"),
                                              "mirror.toml");
  Particles p = generate_particles(scene);
  // The first particle as if the last step had carried it 0.05 past x = 0.
  const Vec3 x0 = p.position[0];
  p.position[0].x = -0.05;
  p.velocity[0] = {-30.0, 5.0, 7.0};
  p.stress[0] = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  MpmSolver solver(scene, std::move(p));
  solver.step(1e-9);  // binning mirrors it first; the tiny step barely moves it
  const Particles& q = solver.particles();
  const std::size_t i = first_particle(q);
  EXPECT_NEAR(q.position[i].x, 0.05, 1e-6);
  EXPECT_NEAR(q.position[i].y, x0.y, 1e-6);
  EXPECT_GT(q.velocity[i].x, 29.0);  // reversed (the step's forces change it by far less)
  EXPECT_NEAR(q.velocity[i].y, 5.0, 1.0);
  // The stress mirrored about x: xz and xy reversed, the rest kept. The 1 ns step changes it by
  // E v dt / h ~ 6e-3 MPa at most.
  EXPECT_NEAR(q.stress[i].yz, 4.0, 0.05);
  EXPECT_NEAR(q.stress[i].xz, -5.0, 0.05);
  EXPECT_NEAR(q.stress[i].xy, -6.0, 0.05);
}

TEST(FaceCrossings, AParticlePastAFarFieldFaceIsPutBackOnItsPlane) {
  const core::Scene scene = core::parse_scene(cube(R"(boundary = { xmax = "absorbing" }
far_field = { centre = [0, 0, 0], pressure = 10.0 }
)",
                                                   test::water_material() + R"(
[[bodies]]
name = "water"
material = "water"
shape = { box = { min = [0, 0, 0], max = [4, 4, 4] } }
pressure = 10.0
)"),
                                              "hold.toml");
  Particles p = generate_particles(scene);
  // The first particle carried 0.3 past x = 4 by an outgoing flow.
  p.position[0].x = 4.3;
  p.velocity[0] = {3.0, 0.0, 0.0};
  const double m = p.mass[0];
  MpmSolver solver(scene, std::move(p));
  solver.step(1e-9);
  const Particles& q = solver.particles();
  const std::size_t i = first_particle(q);
  EXPECT_NEAR(q.position[i].x, 4.0, 1e-6);
  EXPECT_LE(q.position[i].x, 4.0);
  EXPECT_EQ(q.mass[i], m);
  EXPECT_NEAR(q.velocity[i].x, 3.0, 0.1);  // kept: the flow carries it on into the far field
  EXPECT_NEAR(core::pressure(q.stress[i]), 10.0, 0.01);
}

}  // namespace
}  // namespace afemp::mpm
