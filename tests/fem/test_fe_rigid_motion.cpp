// W5 (VALIDATION.md): rigid motion of a hexahedron mesh must strain nothing. A free box in
// translation, and a box driven through the exact rotation positions x = R(omega t) X, for
// which the mid-step velocity gradient of central differences is skew (a Cayley transform),
// so D = 0 and the stress, hourglass energy and internal energy must stay at round-off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/scene.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {
namespace {

using core::Vec3;

constexpr double young = 200e3;  // steel, units mm, ms, g, N, MPa
constexpr int steps = 1000;

// A 10 mm steel cube centred on the origin in 4 x 4 x 4 elements of the given type.
std::string cube_scene(const std::string& element, const Vec3& velocity) {
  char v[128];
  std::snprintf(v, sizeof v, "[%.17g, %.17g, %.17g]", velocity.x, velocity.y, velocity.z);
  return R"(
[run]
end_time = 1.0
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
[[bodies]]
name = "cube"
material = "steel"
discretisation = "hexahedra"
element = ")" +
         element + R"("
shape = { box = { min = [-5, -5, -5], max = [5, 5, 5] } }
mesh = { divisions = [4, 4, 4] }
velocity = )" +
         v + "\n";
}

double largest_stress(const HexElements& h) {
  double s = 0.0;
  for (const core::SymTensor& t : h.stress)
    s = std::max({s, std::abs(t.xx), std::abs(t.yy), std::abs(t.zz), std::abs(t.yz), std::abs(t.xz),
                  std::abs(t.xy)});
  return s;
}

// Rodrigues: the rotation by angle about the unit axis n.
Vec3 rotate(const Vec3& x, const Vec3& n, double angle) {
  const Vec3 nx{n.y * x.z - n.z * x.y, n.z * x.x - n.x * x.z, n.x * x.y - n.y * x.x};
  return std::cos(angle) * x + std::sin(angle) * nx +
         ((1.0 - std::cos(angle)) * core::dot(n, x)) * n;
}

class FeRigidMotion : public ::testing::TestWithParam<const char*> {};

TEST_P(FeRigidMotion, TranslationLeavesStressAndEnergiesUnchanged) {
  const Vec3 v0{6.0, -3.0, 2.0};  // 7 m/s
  const core::Scene scene = core::parse_scene(cube_scene(GetParam(), v0), "w5.toml");
  FeSolver solver(scene);
  const double ke0 = solver.energies().kinetic;
  double ke_drift = 0.0, stress = 0.0;
  for (int n = 0; n < steps; ++n) {
    solver.step(solver.stable_time_step());
    stress = std::max(stress, largest_stress(solver.hexahedra()));
    ke_drift = std::max(ke_drift, std::abs(solver.energies().kinetic - ke0) / ke0);
  }
  const core::Energies e = solver.energies();
  double position_error = 0.0;
  const FeNodes& nodes = solver.nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    position_error =
        std::max(position_error,
                 core::norm(nodes.position[i] - nodes.initial_position[i] - solver.time() * v0));
  std::printf(
      "[W5 translation, %s] %d steps, t = %.4g ms: max |stress| %.3g MPa (limit 1e-8 E = "
      "%.3g), kinetic drift %.3g, internal %.3g, hourglass %.3g (of kinetic %.6g), "
      "position error %.3g mm\n",
      GetParam(), steps, solver.time(), stress, 1e-8 * young, ke_drift, e.internal, e.hourglass,
      ke0, position_error);
  EXPECT_LT(stress, 1e-8 * young);
  EXPECT_LT(ke_drift, 1e-12);
  EXPECT_LT(std::abs(e.internal), 1e-12 * ke0);
  EXPECT_LT(std::abs(e.hourglass), 1e-12 * ke0);
  EXPECT_LT(position_error, 1e-10);
}

TEST_P(FeRigidMotion, DrivenRotationLeavesStressAndEnergiesUnchanged) {
  const core::Scene scene = core::parse_scene(cube_scene(GetParam(), Vec3{}), "w5.toml");
  FeSolver solver(scene);
  const Vec3 axis = (1.0 / std::sqrt(14.0)) * Vec3{1.0, 2.0, 3.0};  // through the centre
  const double omega = 2.0;                                         // rad/ms
  // Every velocity component imposed: the nodal update then sets v^{n+1/2} to the value that
  // carries each node from x^n to R(omega t^{n+1}) X exactly.
  FeNodes& nodes = solver.mutable_nodes();
  std::fill(nodes.imposed.begin(), nodes.imposed.end(), std::uint8_t{7});
  const double dt = solver.stable_time_step();
  double stress = 0.0, ke_min = 1e300, ke_max = 0.0;
  for (int n = 0; n < steps; ++n) {
    const double angle = omega * (solver.time() + dt);
    for (std::size_t i = 0; i < nodes.size(); ++i)
      nodes.imposed_velocity[i] =
          (1.0 / dt) * (rotate(nodes.initial_position[i], axis, angle) - nodes.position[i]);
    solver.step(dt);
    stress = std::max(stress, largest_stress(solver.hexahedra()));
    const double ke = solver.energies().kinetic;
    ke_min = std::min(ke_min, ke);
    ke_max = std::max(ke_max, ke);
  }
  const core::Energies e = solver.energies();
  double position_error = 0.0;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    position_error = std::max(
        position_error, core::norm(nodes.position[i] -
                                   rotate(nodes.initial_position[i], axis, omega * solver.time())));
  const double ke_drift = (ke_max - ke_min) / ke_max;
  std::printf(
      "[W5 rotation, %s] %d steps of %.4g ms, %.3f rad about (1,2,3): max |stress| %.3g "
      "MPa (limit 1e-8 E = %.3g), kinetic spread %.3g, internal %.3g, hourglass %.3g "
      "(of kinetic %.6g), position error %.3g mm\n",
      GetParam(), steps, dt, omega * solver.time(), stress, 1e-8 * young, ke_drift, e.internal,
      e.hourglass, ke_max, position_error);
  EXPECT_GT(omega * solver.time(), 0.5);  // a real rotation, not a few degrees
  EXPECT_LT(stress, 1e-8 * young);
  EXPECT_LT(ke_drift, 1e-10);
  EXPECT_LT(std::abs(e.internal), 1e-12 * ke_max);
  EXPECT_LT(std::abs(e.hourglass), 1e-12 * ke_max);
  EXPECT_LT(position_error, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(BothHexahedra, FeRigidMotion, ::testing::Values("one-point", "full"),
                         [](const auto& test) {
                           return std::string(test.param) == "full" ? "FullBbar" : "OnePoint";
                         });

}  // namespace
}  // namespace afemp::fem
