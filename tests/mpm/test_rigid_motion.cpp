// Rigid-body motion (validation plan W5). References: a rigid motion has zero rate of
// deformation, so an objective stress update must leave an unstressed body unstressed, and
// kinetic energy is conserved. Steel box of 4 x 4 x 4 cells at 2 particles per cell per
// direction (512 particles), h = 1 mm, in a 28^3-cell grid with free faces, no gravity;
// units mm, ms, g, MPa; time_step_factor 0.3, 1000 steps, schemes USF, USL, MUSL, USAVG, with the
// linear hat and FLIP (the default) and with uGIMP weights and FLIP or APIC.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

using core::Vec3;

constexpr double youngs = 200e3;  // MPa
const char* const schemes[] = {"USF", "USL", "MUSL", "USAVG"};

// Shape function and velocity transfer, as the scene spells them.
struct Method {
  const char* shape = "linear";
  const char* transfer = "flip";
};
constexpr Method linear_flip{}, gimp_flip{"gimp", "flip"}, gimp_apic{"gimp", "apic"};
constexpr Method quadratic_flip{"bspline2", "flip"}, quadratic_apic{"bspline2", "apic"},
    cubic_flip{"bspline3", "flip"}, cubic_apic{"bspline3", "apic"};

core::Scene box_scene(const std::string& scheme, Method method) {
  return core::parse_scene(
      "[run]\nend_time = 1.0\ntime_step_factor = 0.3\n"
      "[grid]\ncell = 1.0\nmin = [-12, -12, -12]\nmax = [16, 16, 16]\n"
      "[mpm]\nscheme = \"" +
          scheme + "\"\njaumann = true\nshape_function = \"" + method.shape + "\"\ntransfer = \"" +
          method.transfer +
          "\"\n"
          "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
          "[[bodies]]\nname = \"box\"\nmaterial = \"steel\"\nparticles_per_cell = 2\n"
          "shape = { box = { min = [0, 0, 0], max = [4, 4, 4] } }\n",
      "rigid.toml");
}

struct RigidResult {
  double max_stress_over_e = 0.0;  // max over particles and steps of |sigma| (Frobenius) / E
  double interior_stress_over_e_step1 = 0.0;  // after step 1, particles of the 2^3 core cells
  double max_kinetic_drift = 0.0;             // max over steps of |KE / KE0 - 1|
  double max_energy_drift = 0.0;              // max over steps of |(KE + internal) / E0 - 1|
  double energy_drift = 0.0;                  // (KE + internal) / E0 - 1 at the end
  Vec3 momentum;
  double momentum_scale = 0.0;  // sum m |v| at the start
  long steps = 0;
  std::string error;  // a SimulationError that stopped the run, if any
};

double stress_norm(const core::SymTensor& s) {
  return std::sqrt(core::double_dot(s, s));
}

// Runs 1000 steps from the velocity field v(x) and records stress and energies. With the
// affine transfer every particle also starts with the affine velocity `gradient`.
template <class Velocity>
RigidResult run_rigid(const std::string& scheme, Velocity velocity, Method method = linear_flip,
                      const core::Mat3& gradient = {}) {
  const core::Scene scene = box_scene(scheme, method);
  Particles p = generate_particles(scene);
  EXPECT_EQ(p.size(), 512u);
  RigidResult r;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.velocity[i] = velocity(p.position[i]);
    r.momentum_scale += p.mass[i] * core::norm(p.velocity[i]);
  }
  if (std::string(method.transfer) == "apic") p.affine.assign(p.size(), gradient);
  MpmSolver solver(scene, std::move(p));
  const Energies e0 = solver.energies();
  try {
    for (int k = 0; k < 1000; ++k) {
      // The core cells [1, 3]^3 at the start of the step: all 8 nodes of their particles
      // have full support inside the body.
      std::vector<char> core_particle(solver.particles().size());
      for (std::size_t i = 0; i < core_particle.size(); ++i) {
        const Vec3& x = solver.particles().position[i];
        core_particle[i] = x.x > 1 && x.x < 3 && x.y > 1 && x.y < 3 && x.z > 1 && x.z < 3;
      }
      solver.step(solver.stable_time_step());
      ++r.steps;
      const Particles& q = solver.particles();
      double smax = 0.0;
      for (std::size_t i = 0; i < q.size(); ++i) {
        const double s = stress_norm(q.stress[i]);
        smax = std::max(smax, s);
        if (k == 0 && core_particle[i])
          r.interior_stress_over_e_step1 = std::max(r.interior_stress_over_e_step1, s / youngs);
      }
      r.max_stress_over_e = std::max(r.max_stress_over_e, smax / youngs);
      const Energies e = solver.energies();
      r.max_kinetic_drift = std::max(r.max_kinetic_drift, std::abs(e.kinetic / e0.kinetic - 1.0));
      r.energy_drift = e.total() / e0.total() - 1.0;
      r.max_energy_drift = std::max(r.max_energy_drift, std::abs(r.energy_drift));
    }
  } catch (const core::SimulationError& e) {
    r.error = e.what();
  }
  for (std::size_t i = 0; i < solver.particles().size(); ++i)
    r.momentum += solver.particles().mass[i] * solver.particles().velocity[i];
  return r;
}

// (a) Rigid translation v = (100, -50, 30) m/s. The grid velocity is the same at every node
// (p_I / m_I = v up to round-off), so L = v (x) sum_I grad N_I = 0 to round-off: the stress
// must stay zero and no node may get a force. W5 pass mark: max |sigma| < 1e-8 E over the
// 1000 steps; kinetic energy unchanged to 1e-10 relative; momentum to 1e-12 relative.
// Measured: USF and MUSL keep |sigma| ~ 1e-16 E and the kinetic energy to ~1e-15.
// With the linear hat USL is left out: it stops at step ~176 with NaN stress, the small-mass
// weakness of textbook USL (Lian et al. 2013, §2.1.2 calls it unstable; use MUSL, USF or uGIMP).
// Its strain sweep reads v^{k+1}_I = v_I + dt f_I / m_I; when the moving body's edge particles
// give a node a tiny mass (m_I / m_p ~ 1e-4..1e-3 as they cross cell faces), the round-off
// stress (1e-13 MPa) becomes a velocity jump ~ dt f_I / m_I that the particle multiplies by
// grad N_I = O(1 / h) rather than by its tiny weight: the stress grows ~10x per step while
// the small mass lasts (1e-12 -> 1e-4 MPa at steps 100-115, then 1e-3 -> 4e3 MPa at 167-173).
void expect_translation_is_rigid(const char* scheme, Method method = linear_flip) {
  const Vec3 v{100.0, -50.0, 30.0};
  const RigidResult r = run_rigid(
      scheme, [&](const Vec3&) { return v; }, method);
  std::printf("[ translation %s %s %s ] %ld steps, max |sigma| / E = %.3g, kinetic drift = %.3g\n",
              scheme, method.shape, method.transfer, r.steps, r.max_stress_over_e,
              r.max_kinetic_drift);
  EXPECT_TRUE(r.error.empty()) << "rigid translation blew up: " << r.error;
  EXPECT_EQ(r.steps, 1000);
  EXPECT_LT(r.max_stress_over_e, 1e-8);
  EXPECT_LT(r.max_kinetic_drift, 1e-10);
  const double mass = 512 * 7.85e-3 * 0.125;  // 512 particles of (h / 2)^3
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(r.momentum[a], mass * v[a], 1e-12 * r.momentum_scale);
}

TEST(Rigid, TranslationStaysStressFreeAndKeepsKineticEnergyUSF) {
  expect_translation_is_rigid("USF");
}
TEST(Rigid, TranslationStaysStressFreeAndKeepsKineticEnergyMUSL) {
  expect_translation_is_rigid("MUSL");
}
TEST(Rigid, TranslationStaysStressFreeAndKeepsKineticEnergyUSAVG) {
  expect_translation_is_rigid("USAVG");
}

// With uGIMP weights every scheme translates rigidly, USL included: a node the body barely
// reaches gets a weight that fades as the square of the overlap and a gradient that fades
// linearly, so the round-off force over its mass stays bounded.
TEST(Rigid, TranslationWithGimpStaysStressFreeInEveryScheme) {
  for (const char* scheme : schemes)
    for (Method method : {gimp_flip, gimp_apic}) {
      SCOPED_TRACE(std::string(scheme) + " " + method.transfer);
      expect_translation_is_rigid(scheme, method);
    }
}

// The B-splines' weights fade with their gradients as uGIMP's do (quadratically and
// cubically at the edge of the support): the same reference in every scheme.
TEST(Rigid, TranslationWithBsplinesStaysStressFreeInEveryScheme) {
  for (const char* scheme : schemes)
    for (Method method : {quadratic_flip, cubic_apic}) {
      SCOPED_TRACE(std::string(scheme) + " " + method.shape + " " + method.transfer);
      expect_translation_is_rigid(scheme, method);
    }
}

// (b) Rigid rotation about the box centre c, omega = 2 rad/ms about z, v = omega x (x - c)
// (|v| <= 5.7 m/s), Jaumann rate on, 1000 steps (0.1 rad).
// What is guaranteed, and asserted:
//  * after the first step the particles of the core cells [1, 3]^3 are stress-free to
//    round-off (1e-12 E; measured 4e-20 E; USAVG: below): all their nodes have full support, the
//    lumped nodal velocity is exactly the linear field omega x (x_I - c), L = W is skew and d = 0;
//  * linear momentum stays zero (1e-12 sum m |v|; free faces, internal forces only).
// What W5 asks and the linear hat with FLIP does NOT meet (see (c) for the method that does):
// max |sigma| < 1e-8 E. Measured max over
// the 1000 steps: 2.0e-4 E (USF, MUSL), 1.0e-4 E (USL); after the very first step already
// 2.1e-5 E. The figure is linear in omega (1.6e-5 E at 0.2 rad/ms, 1.6e-6 E at 0.02) and the
// same with jaumann = false, so it is neither the centrifugal stress a spinning free body
// needs (rho omega^2 R^2 / E = 1.3e-6, quadratic in omega) nor a Jaumann error: it is the
// spurious rate of deformation at the body's surface nodes, whose support is only partly
// filled, so that p_I / m_I is the rigid field at the mass centroid of the support, not at
// x_I (an O(h / 4) offset: |d| ~ 0.2 omega). That is a property of linear-hat MPM with a
// lumped mass matrix (uGIMP alone does not change it: 4.2e-6 E at 0.05 rad/ms; the affine
// transfer of (c) removes it), not a coding error.
// The bound below is the measured figure with 50% margin; the kinetic energy drops by
// 1.0-2.4% (into that spurious strain energy for USF/MUSL, whose total energy is kept to
// 0.2%; USL dissipates it: total energy -2.4%).
TEST(Rigid, RotationStaysStressFreeInTheCoreAndBoundedAtTheSurface) {
  const Vec3 centre{2.0, 2.0, 2.0}, omega{0.0, 0.0, 2.0};
  for (const char* scheme : schemes) {
    SCOPED_TRACE(scheme);
    const RigidResult r =
        run_rigid(scheme, [&](const Vec3& x) { return core::cross(omega, x - centre); });
    std::printf(
        "[ rotation %s ] max |sigma| / E = %.3g (core after step 1: %.3g), kinetic "
        "drift %.3g, total energy drift %.3g (max %.3g)\n",
        scheme, r.max_stress_over_e, r.interior_stress_over_e_step1, r.max_kinetic_drift,
        r.energy_drift, r.max_energy_drift);
    ASSERT_TRUE(r.error.empty()) << r.error;
    // USAVG takes its forces from the mid-step stress: the surface particles' spurious stress
    // of the first half step (about 2e-5 E) already pushes the nodes the core shares with them,
    // so the core is not stress-free after step 1 (measured 2.8e-8 E); the others take the
    // initial, zero, stress.
    EXPECT_LT(r.interior_stress_over_e_step1, std::string(scheme) == "USAVG" ? 1e-7 : 1e-12);
    EXPECT_LT(r.max_stress_over_e, 3e-4);
    EXPECT_LT(r.max_kinetic_drift, 0.03);
    if (std::string(scheme) == "USL") {
      EXPECT_LE(r.energy_drift, 1e-3);  // dissipative, never a gain
      EXPECT_GT(r.energy_drift, -0.03);
    } else {
      EXPECT_LT(r.max_energy_drift, 5e-3);
    }
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(r.momentum[a], 0.0, 1e-12 * r.momentum_scale);
  }
}

// (c) W5 rotation with uGIMP weights and the affine (APIC) transfer, each particle starting
// with C_p = W, the skew gradient of the rotation. The P2G of m S (v_p + C_p (x_I - x_p))
// gives every node, surface nodes included, the rigid velocity W (x_I - c), and
// L = sum v_I (x) grad S = W because sum_I x_I (x) grad S_I = I: the O(omega) surface error
// of (b) is gone. What is left is O(omega^2): a particle's velocity was rigid at its old
// position, the discrete form of the centripetal stress a free spinning body must carry,
// rho omega^2 R^2 / E = 1.3e-6 at omega = 2 rad/ms (measured there: 9e-7 E, FLIP 1e-3 E).
// Reference (W5): at omega = 0.05 rad/ms, where the centripetal stress is 8e-10 E, the stress
// stays below 1e-8 E over the 1000 steps in every scheme (measured 5.6e-10 E; uGIMP with FLIP
// gives 4.2e-6 E). The tangent position update x += dt v lets the kinetic energy drift by
// (omega dt)^2 per step, 6.7e-9 over the run (measured 3e-9 USF, 6e-9 MUSL; USL, whose strain
// rate reads v^{k+1}, 5e-8): at most 1e-7. Linear momentum stays zero (1e-12).
// The B-splines with the affine transfer (Jiang et al. 2015 introduced it with them): the same
// reference.
TEST(Rigid, RotationWithGimpAndAffineTransferStaysStressFree) {
  const Vec3 centre{2.0, 2.0, 2.0}, omega{0.0, 0.0, 0.05};
  core::Mat3 spin;  // W_ij = -e_ijk omega_k: v = W (x - c) = omega x (x - c)
  spin.m[0][1] = -omega.z;
  spin.m[1][0] = omega.z;
  for (Method method : {gimp_apic, quadratic_apic, cubic_apic})
    for (const char* scheme : schemes) {
      SCOPED_TRACE(std::string(scheme) + " " + method.shape);
      const RigidResult r = run_rigid(
          scheme, [&](const Vec3& x) { return core::cross(omega, x - centre); }, method, spin);
      std::printf(
          "[ rotation %s apic %s ] max |sigma| / E = %.3g (limit 1e-8), kinetic drift "
          "%.3g (limit 1e-7)\n",
          method.shape, scheme, r.max_stress_over_e, r.max_kinetic_drift);
      ASSERT_TRUE(r.error.empty()) << r.error;
      EXPECT_EQ(r.steps, 1000);
      EXPECT_LT(r.max_stress_over_e, 1e-8);
      EXPECT_LT(r.max_kinetic_drift, 1e-7);
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(r.momentum[a], 0.0, 1e-12 * r.momentum_scale);
    }
}

}  // namespace
}  // namespace afemp::mpm
