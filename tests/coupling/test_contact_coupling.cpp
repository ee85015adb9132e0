// Contact coupling of FE and MPM bodies through the grid (CFEMP, coupling/coupled_model.hpp,
// Lian et al. 2013, §2.4 and §2.6). References: conservation of linear momentum (the contact
// impulses on the FE field and on the particles' field are equal and opposite, and the FE nodes
// receive exactly their field's impulse); the rule that contact creates no energy (kinetic +
// internal energy never above the start, in an elastic impact); the rebound of two equal cubes
// meeting head on, which by symmetry is that of one cube on a rigid frictionless wall (38.9 m/s
// from afemp's mesh-converged FE, tests/mpm/test_grid_contact.cpp); and a body at rest that stays
// at rest until the other's surface reaches it (gap / speed).
// Aluminium-like cubes, E = 70 GPa, nu = 0.3, rho = 2.7e-3 g/mm^3, 4 mm edge, 1 mm apart; the
// FE cube has 8 one-point hexahedra per edge (assumed-strain hourglass control, no bulk
// viscosity), the MPM cube 2 particles per 1 mm cell per direction; units mm, ms, g, N, MPa.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/scene.hpp"
#include "coupling/coupled_model.hpp"

namespace afemp::coupling {
namespace {

using core::Vec3;

std::string fe_and_mpm_cubes(const std::string& scheme, const std::string& fe_velocity,
                             const std::string& mpm_velocity, const std::string& mpm_box,
                             const std::string& contact, double cell = 1.0, int divisions = 8) {
  const std::string d = std::to_string(divisions);
  return "[run]\nend_time = 0.03\ntime_step_factor = 0.3\n"
         "[grid]\ncell = " +
         std::to_string(cell) +
         "\nmin = [-8, -8, -8]\nmax = [20, 16, 12]\n"
         "[mpm]\nscheme = \"" +
         scheme +
         "\"\n"
         "[materials.al]\ndensity = 2.7e-3\nE = 70e3\nnu = 0.3\n"
         "[[bodies]]\nname = \"fe\"\nmaterial = \"al\"\ndiscretisation = \"hexahedra\"\n"
         "shape = { box = { min = [0, 0, 0], max = [4, 4, 4] } }\n"
         "mesh = { divisions = [" +
         d + ", " + d + ", " + d +
         "] }\n"
         "hourglass = { form = \"assumed_strain\", coefficient = 1.0 }\n"
         "bulk_viscosity = { linear = 0, quadratic = 0 }\n"
         "velocity = " +
         fe_velocity +
         "\n"
         "[[bodies]]\nname = \"mpm\"\nmaterial = \"al\"\n"
         "shape = { box = " +
         mpm_box + " }\nvelocity = " + mpm_velocity + "\n" + contact;
}

const std::string contact = "[[contact]]\nbodies = [\"fe\", \"mpm\"]\n";
const std::string beside = "{ min = [5, 0, 0], max = [9, 4, 4] }";

struct CoupledRun {
  double max_momentum_error = 0.0;  // max |sum m v - P0| / sum m |v0|
  double max_energy_gain = 0.0;     // max (KE + IE) / E0 - 1
  double first_contact = -1.0;      // time of the first step with contact energy
  Vec3 fe_velocity, mpm_velocity;   // mean velocities at the end
  double final_energy = 0.0, initial_energy = 0.0, contact_energy = 0.0;
  // Per-body energies (the history's NAME.kinetic, NAME.internal): the largest relative gap
  // between their sums and the totals, and each body's kinetic energy at the start.
  double max_body_sum_gap = 0.0;
  double initial_body_kinetic[2] = {0.0, 0.0};
};

double body_sum_gap(const core::Energies& e) {
  double kinetic = 0.0, internal = 0.0;
  for (const core::BodySums& b : e.bodies) {
    kinetic += b.kinetic;
    internal += b.internal;
  }
  return (std::abs(kinetic - e.kinetic) + std::abs(internal - e.internal)) /
         (e.kinetic + e.internal);
}

CoupledRun run(const core::Scene& scene) {
  CoupledModel model(scene);
  const core::Energies e0 = model.energies();
  const Vec3 p0 = e0.bodies[0].momentum + e0.bodies[1].momentum;
  const double scale = core::norm(e0.bodies[0].momentum) + core::norm(e0.bodies[1].momentum);
  CoupledRun r;
  r.initial_energy = e0.kinetic + e0.internal;
  for (int b = 0; b < 2; ++b)
    r.initial_body_kinetic[b] = e0.bodies[static_cast<std::size_t>(b)].kinetic;
  while (model.time() < scene.run.end_time) {
    model.step(model.stable_time_step());
    const core::Energies e = model.energies();
    r.max_body_sum_gap = std::max(r.max_body_sum_gap, body_sum_gap(e));
    const Vec3 p = e.bodies[0].momentum + e.bodies[1].momentum;
    r.max_momentum_error = std::max(r.max_momentum_error, core::norm(p - p0) / scale);
    r.max_energy_gain =
        std::max(r.max_energy_gain, (e.kinetic + e.internal) / r.initial_energy - 1.0);
    if (e.contact > 0.0 && r.first_contact < 0.0) r.first_contact = model.time();
  }
  const core::Energies e = model.energies();
  r.fe_velocity = (1.0 / e.bodies[0].mass) * e.bodies[0].momentum;
  r.mpm_velocity = (1.0 / e.bodies[1].mass) * e.bodies[1].momentum;
  r.final_energy = e.kinetic + e.internal;
  r.contact_energy = e.contact;
  return r;
}

constexpr double wall_rebound = 38.9;  // m/s, tests/mpm/test_grid_contact.cpp

// Head on at +-50 m/s: momentum to round-off, no energy created at any step, contact no
// earlier than 0.25 mm before the surfaces meet (t = 0.01 ms), and the cubes separate at
// 0.7-1.0 times the wall rebound (the FE and MPM cubes are equal in mass).
TEST(ContactCoupling, FeAndMpmCubesHeadOnConserveMomentumCreateNoEnergyAndSeparate) {
  for (const char* scheme : {"MUSL", "USF"}) {
    const CoupledRun r = run(core::parse_scene(
        fe_and_mpm_cubes(scheme, "[50, 0, 0]", "[-50, 0, 0]", beside, contact), "head_on.toml"));
    std::printf(
        "%s: momentum %.2e  energy gain %+.2e  first contact %.4f ms  rebound fe %.2f "
        "mpm %.2f m/s  KE+IE %.1f of %.1f uJ  contact %.1f uJ\n",
        scheme, r.max_momentum_error, r.max_energy_gain, r.first_contact, -r.fe_velocity.x,
        r.mpm_velocity.x, r.final_energy, r.initial_energy, r.contact_energy);
    EXPECT_LT(r.max_momentum_error, 1e-12) << scheme;
    EXPECT_LT(r.max_energy_gain, 1e-12) << scheme;
    // Per body: 1/2 M v0^2 of each 4 mm aluminium cube at 50 m/s (2.7e-3 g/mm^3, so
    // 0.1728 g and 216 g mm^2/ms^2), and the bodies' energies sum to the totals.
    for (int b = 0; b < 2; ++b)
      EXPECT_NEAR(r.initial_body_kinetic[b], 0.5 * 0.1728 * 50.0 * 50.0, 1e-9 * 216.0)
          << scheme << " body " << b;
    EXPECT_LT(r.max_body_sum_gap, 1e-12) << scheme;
    EXPECT_GT(r.first_contact, 0.0075) << scheme;
    EXPECT_LT(r.first_contact, 0.0105) << scheme;
    EXPECT_NEAR(r.fe_velocity.x, -r.mpm_velocity.x, 1e-9) << scheme;
    EXPECT_LT(r.fe_velocity.x, -0.7 * wall_rebound) << scheme;
    EXPECT_GT(r.fe_velocity.x, -wall_rebound) << scheme;
  }
}

// The same impact from either side: an FE projectile at 100 m/s into an MPM cube at rest, and
// an MPM projectile onto an FE cube at rest. The struck cube stays at rest until the surfaces
// are within the contact distance (t ~ 0.01 ms), momentum is conserved and no energy created.
TEST(ContactCoupling, FeProjectileIntoMpmAndMpmProjectileOntoFe) {
  struct Case {
    const char* name;
    const char* fe_velocity;
    const char* mpm_velocity;
  };
  for (const Case& c : {Case{"FE into MPM", "[100, 0, 0]", "[0, 0, 0]"},
                        Case{"MPM onto FE", "[0, 0, 0]", "[-100, 0, 0]"}}) {
    const CoupledRun r = run(core::parse_scene(
        fe_and_mpm_cubes("MUSL", c.fe_velocity, c.mpm_velocity, beside, contact), "one.toml"));
    std::printf(
        "%s: momentum %.2e  energy gain %+.2e  first contact %.4f ms  fe %.2f  mpm "
        "%.2f m/s\n",
        c.name, r.max_momentum_error, r.max_energy_gain, r.first_contact, r.fe_velocity.x,
        r.mpm_velocity.x);
    EXPECT_LT(r.max_momentum_error, 1e-12) << c.name;
    EXPECT_LT(r.max_energy_gain, 1e-12) << c.name;
    EXPECT_GT(r.first_contact, 0.0075) << c.name;
    // Equal masses: the centre of mass keeps its velocity, and the cubes separate at 0.7-1.0
    // times the separation speed of the head-on case, 2 x the wall rebound.
    const bool fe_strikes = c.name[0] == 'F';
    EXPECT_NEAR(0.5 * (r.fe_velocity.x + r.mpm_velocity.x), fe_strikes ? 50.0 : -50.0, 1e-9)
        << c.name;
    const double separation = r.mpm_velocity.x - r.fe_velocity.x;  // the MPM cube is on the right
    EXPECT_GT(separation, 0.7 * 2 * wall_rebound) << c.name;
    EXPECT_LT(separation, 2 * wall_rebound) << c.name;
  }
}

}  // namespace
}  // namespace afemp::coupling
