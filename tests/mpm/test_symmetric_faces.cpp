// A particle carried past a symmetric face is reflected back (mpm/symmetric_faces.cpp): the
// mirror image of its state. Reference: the mirror, exactly: x -> 2 x_face - x, the normal
// velocity and the shear stress components involving the normal reversed, the rest unchanged.
#include <gtest/gtest.h>

#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

TEST(SymmetricFaces, AParticlePastASymmetricFaceIsMirroredBack) {
  const core::Scene scene = core::parse_scene(R"([run]
end_time = 1.0
[grid]
cell = 1.0
min = [0, 0, 0]
max = [4, 4, 4]
boundary = { xmin = "symmetric" }
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
[[bodies]]
name = "block"
material = "steel"
shape = { box = { min = [0, 1, 1], max = [2, 3, 3] } }
)",
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
  std::size_t i = 0;
  while (q.id[i] != 0) ++i;
  EXPECT_NEAR(q.position[i].x, 0.05, 1e-6);
  EXPECT_NEAR(q.position[i].y, x0.y, 1e-6);
  EXPECT_GT(q.velocity[i].x, 29.0);  // reversed (the step's forces change it by far less)
  EXPECT_NEAR(q.velocity[i].y, 5.0, 1.0);
}

}  // namespace
}  // namespace afemp::mpm
