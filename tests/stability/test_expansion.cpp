// Stability suite (ctest label `stability`), extreme case: a pressurised slab released into
// vacuum at both faces (a column 1 x 1 mm between symmetry planes, so the flow is 1D in z).
// A gas charge expands and separates into a thinning cloud; a hot copper slab goes into
// tension where the two release waves cross. Each runs with no NaN/Inf, total energy and
// z-momentum conserved, against closed forms of the centred rarefaction.
// Units mm, ms, g, N, MPa (velocity m/s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/reference_checks.hpp"
#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "coupling/make_model.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::coupling {
namespace {

std::string slab_scene(double end_time, double half_room, const std::string& material,
                       double internal_energy) {
  return "[run]\nend_time = " + std::to_string(end_time) + R"(
[grid]
cell = 0.25
min = [0, 0, -)" +
         std::to_string(half_room) + R"(]
max = [1, 1, )" +
         std::to_string(half_room) + R"(]
boundary = { xmin = "symmetric", xmax = "symmetric", ymin = "symmetric", ymax = "symmetric" }
)" + material +
         R"(
[[bodies]]
name = "slab"
material = "m"
shape = { box = { min = [0, 0, -2], max = [1, 1, 2] } }
internal_energy = )" +
         std::to_string(internal_energy) + "\n";
}

// An ideal gas (gamma = 1.4: linear-polynomial EOS with C4 = C5 = 0.4, p = 0.4 rho e), rho0 =
// 1e-3, e0 = 2.5e5 J/kg: p0 = 100 MPa, c0 = sqrt(gamma p0 / rho0) = 374.2 m/s. Its shear
// modulus is negligible (E = 1e-3 MPa).
constexpr const char* gas = R"(
[materials.m]
density = 1.0e-3
E = 1.0e-3
nu = 0.3
eos = { model = "linear-polynomial", C4 = 0.4, C5 = 0.4 }
)";
constexpr double p0 = 100.0, e0 = 2.5e5, c0 = 374.17;

// z-momentum of the particles that started at z > 0 (the slab's upper half).
double upper_half_momentum(const core::Model& model, double* max_speed = nullptr) {
  const mpm::Particles& p = dynamic_cast<const mpm::MpmModel&>(model).solver().particles();
  double pz = 0.0, vmax = 0.0;
  for (std::size_t q = 0; q < p.size(); ++q) {
    vmax = std::max(vmax, std::abs(p.velocity[q].z));
    if (p.position[q].z > 0.0) pz += p.mass[q] * p.velocity[q].z;
  }
  if (max_speed) *max_speed = vmax;
  return pz;
}

// Before the two rarefaction heads meet (t < 2 mm / c0 = 5.3 us) the mid-plane stays at p0,
// so the upper half has taken the impulse p0 A t (A = 1 mm^2), exactly: 0.4 g mm/ms at 4 us.
// References: that impulse within 8 % (measured -5.0 %: the stress is zero over the first step
// and the head is spread over two cells); the energy balance within 2 %; the total z-momentum zero
// (1e-12 of the upper half's).
TEST(Stability, GasSlabReleasedIntoVacuumTakesTheImpulseOfItsMidPlanePressure) {
  const double t = 0.004;
  const core::Scene scene = core::parse_scene(slab_scene(t, 12, gas, e0), "gas.toml");
  const auto model = make_model(scene);
  const core::RunSummary s = analysis::run(*model, scene, core::RunOptions{});
  double vmax = 0.0;
  const double pz = upper_half_momentum(*model, &vmax);
  const double total = s.final.bodies[0].momentum.z;
  std::printf(
      "gas release, 4 us: %ld steps, upper-half momentum %.4f (closed form %.4f), total "
      "%.1e, fastest particle %.0f m/s (escape speed 2 c0 / (gamma - 1) = %.0f), "
      "energy %+.2f %% (largest %.2f %%)\n",
      s.steps, pz, p0 * t, total, vmax, 2.0 * c0 / 0.4, 100.0 * s.energy_error,
      100.0 * s.max_energy_error);
  EXPECT_NEAR(pz, p0 * t, 0.08 * p0 * t);
  EXPECT_LT(std::abs(total), 1e-12 * pz);
  EXPECT_LT(s.max_energy_error, 0.02);
  EXPECT_LT(vmax, 2.0 * c0 / 0.4);  // nothing outruns the escape speed
}

// Long after the release the gas has spread to many times its thickness and the particles
// separate (cells between them empty). References: the energy balance within 5 % (measured
// -3.2 %: the thinning cloud's few particles per cell lose some) while the internal energy turns
// into kinetic energy (more than 40 % of it by 30 us, measured 46 %); the cloud at least four
// times the slab's thickness (measured 54 mm from 4); total z-momentum zero.
TEST(Stability, GasSlabExpandsAndSeparates) {
  const core::Scene scene = core::parse_scene(slab_scene(0.03, 40, gas, e0), "gas.toml");
  const auto model = make_model(scene);
  core::RunSummary s;
  try {
    s = analysis::run(*model, scene, core::RunOptions{});
  } catch (const std::exception& e) {
    FAIL() << e.what();
  }
  const mpm::Particles& p = dynamic_cast<const mpm::MpmModel&>(*model).solver().particles();
  double zmin = 0.0, zmax = 0.0;
  for (const core::Vec3& x : p.position) zmin = std::min(zmin, x.z), zmax = std::max(zmax, x.z);
  const double e_total = s.initial.total();
  std::printf(
      "gas release, 30 us: %ld steps, cloud %.1f mm wide (slab 4 mm), kinetic %.3f of "
      "the initial energy, energy %+.2f %% (largest %.2f %%)\n",
      s.steps, zmax - zmin, s.final.kinetic / e_total, 100.0 * s.energy_error,
      100.0 * s.max_energy_error);
  EXPECT_GT(zmax - zmin, 16.0);
  EXPECT_GT(s.final.kinetic, 0.4 * e_total);
  EXPECT_LT(s.max_energy_error, 0.05);
  EXPECT_LT(std::abs(s.final.bodies[0].momentum.z), 1e-12 * s.final.kinetic);
}

// A hot copper slab: Mie-Grueneisen copper (Gamma0 rho0 = 0.0175) with e0 = 57,130 J/kg has a
// thermal pressure p0 = Gamma0 rho0 e0 = 1.0 GPa at its reference density (sigma = -p0 I, no
// strength model: elastic). Acoustic closed form in uniaxial strain: the release from each face
// changes sigma_zz by +p0; where the two cross (the mid-plane, after 2 mm / c_L = 0.42 us)
// sigma_zz = +p0, tension (the lateral stresses change by nu / (1 - nu) of that, so the
// pressure only falls to -0.385 p0). References at 0.55 us (the waves have crossed, the
// reflections from the faces are not back): mean sigma_zz of the central 0.5 mm equal to +p0
// within 20 %; energy within 2 %; total z-momentum zero.
TEST(Stability, HotCopperSlabReleasedGoesIntoTensionAtItsMidPlane) {
  const std::string copper = R"(
[materials.m]
density = 8.93e-3
E = 124e3
nu = 0.35
eos = { model = "mie-gruneisen", c0 = 3940, s = 1.49, gamma0 = 1.96 }
)";
  const double p_hot = 1.96 * 8.93e-3 * 57130.0;
  const core::Scene scene = core::parse_scene(slab_scene(0.00055, 4, copper, 57130.0), "hot.toml");
  const auto model = make_model(scene);
  const core::RunSummary s = analysis::run(*model, scene, core::RunOptions{});
  const mpm::Particles& p = dynamic_cast<const mpm::MpmModel&>(*model).solver().particles();
  double sum = 0.0, szz = 0.0;
  int n = 0;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (std::abs(p.position[q].z) < 0.25)
      sum += -(p.stress[q].xx + p.stress[q].yy + p.stress[q].zz) / 3.0, szz += p.stress[q].zz, ++n;
  const double p_mid = sum / n, szz_mid = szz / n;
  std::printf(
      "hot copper release, 0.55 us: %ld steps, p0 %.0f MPa, mid-plane sigma_zz %+.0f MPa, "
      "pressure %+.0f MPa, energy %+.2f %% (largest %.2f %%)\n",
      s.steps, p_hot, szz_mid, p_mid, 100.0 * s.energy_error, 100.0 * s.max_energy_error);
  EXPECT_NEAR(szz_mid, p_hot, 0.2 * p_hot);
  EXPECT_LT(s.max_energy_error, 0.02);
  EXPECT_LT(std::abs(s.final.bodies[0].momentum.z), 1e-10 * s.final.kinetic + 1e-14);
}

}  // namespace
}  // namespace afemp::coupling
