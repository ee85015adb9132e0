// Gurney's symmetric sandwich (validation label: 18 s on 2 threads). A 10 mm TNT slab between
// two 2.076 mm steel plates (M/C = 2, M both plates' mass) is lit at its mid-plane; particles of
// 0.25 mm cells with splitting (the products expand twentyfold), held laterally, outflow faces
// beyond. Reference: V / sqrt(2E) = (M/C + 1/3)^(-1/2) with TNT's sqrt(2E) = 2.44 km/s
// (P. W. Cooper, Explosives Engineering, 1996): 1597 m/s; each plate within 10 % at 60 us
// (measured: 1550.5 m/s, -2.9 %).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/scene.hpp"
#include "explosive_scenes.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

TEST(Gurney, SymmetricSandwichDrivesBothPlatesAtTheGurneyVelocity) {
  const core::Scene scene = core::parse_scene(
      test::sandwich_column(0.06, -120, 120, true) + test::tnt_material() +
          test::steel_plate_material() + R"(
[[bodies]]
name = "charge"
material = "tnt"
shape = { box = { min = [0, 0, 0], max = [0.5, 0.5, 10] } }
[[bodies]]
name = "front"
material = "steel"
shape = { box = { min = [0, 0, 10], max = [0.5, 0.5, 12.0764] } }
[[bodies]]
name = "back"
material = "steel"
shape = { box = { min = [0, 0, -2.0764], max = [0.5, 0.5, 0] } }
)" + test::plane_detonation(5.0),
      "sandwich.toml");
  MpmSolver solver(scene, generate_particles(scene));
  const double e0 = solver.energies().total();
  while (solver.time() < 0.06) solver.step(std::min(solver.stable_time_step(), 0.06 - solver.time()));
  const core::Energies e = solver.energies();
  const double front = e.bodies[1].momentum.z / e.bodies[1].mass;
  const double back = e.bodies[2].momentum.z / e.bodies[2].mass;
  const double mc = 2.0 * 7.85 * 2.0764 / (1.63 * 10.0);
  const double gurney = 2440.0 / std::sqrt(mc + 1.0 / 3.0);
  std::printf("symmetric sandwich, M/C = %.3f: plates at %.1f and %.1f m/s, Gurney %.1f m/s "
              "(%+.1f %%); energy balance %+.2f %%\n",
              mc, front, back, gurney, 100.0 * (front / gurney - 1.0),
              100.0 * (e.total() / e0 - 1.0));
  EXPECT_NEAR(front, gurney, 0.10 * gurney);
  EXPECT_NEAR(-back, gurney, 0.10 * gurney);
}

}  // namespace
}  // namespace afemp::mpm
