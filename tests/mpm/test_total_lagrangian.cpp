// Total-Lagrangian MPM ([mpm] formulation = "total-lagrangian"; de Vaucorbeil, Nguyen &
// Hutchinson 2020). References:
// - the first axial mode of a bar clamped at one end: u(z, t) = (v0 / w) sin(pi z / 2L) sin(w t),
//   w = pi c / 2L, c = sqrt(E / rho) (a slender bar); period and tip amplitude to 1 %, energy
//   kept to 0.5 % (measured at half the stable step: period -0.3 %, amplitude -0.1 %, energy
//   0.24 %);
// - the deformation gradient is the integral of the velocity gradient: F_zz of a bar stretched
//   at a uniform rate follows 1 + rate t to round-off, and det F <= 0 stops the run naming the
//   particle;
// - what has no meaning in the reference configuration is refused, naming the key;
// - a run stopped and restarted ends bit-identical.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "afemp/errors.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "scene_errors.hpp"

namespace afemp::mpm {
namespace {

using core::Vec3;

// A copper bar 2 x 2 x 40 mm on a clamped face (zmin fixed), 2 particles per cell and axis;
// `strength` is the copper's strength table, if any.
std::string bar(const std::string& mpm, const std::string& strength = "") {
  return "[run]\nend_time = 1.0\n"
         "[grid]\ncell = 1.0\nmin = [-2, -2, 0]\nmax = [4, 4, 44]\n"
         "boundary = { zmin = \"fixed\" }\n"
         "[mpm]\nscheme = \"MUSL\"\n" +
         mpm + "[materials.copper]\ndensity = 8.93e-3\nE = 1.24e5\nnu = 0.34\n" + strength +
         "[[bodies]]\nname = \"bar\"\nmaterial = \"copper\"\nparticles_per_cell = 2\n"
         "shape = { box = { min = [0, 0, 0], max = [2, 2, 40] } }\n";
}

struct Mode {
  double period = 0.0, amplitude = 0.0, energy_drift = 0.0;
};

// The bar started in its first mode's velocity, v_z = v0 sin(pi z / 2L), over two periods: the
// period from the tip's zero crossings, its largest displacement, and the largest change of
// kinetic + internal energy over the start's.
Mode first_mode(const std::string& shape, const std::string& strength = "",
                const std::string& formulation = "total-lagrangian") {
  const std::string mpm =
      "formulation = \"" + formulation + "\"\nshape_function = \"" + shape + "\"\n";
  const core::Scene scene = core::parse_scene(bar(mpm, strength), "bar.toml");
  Particles p = generate_particles(scene);
  const double pi = std::acos(-1.0), length = 40.0, v0 = 1.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    p.velocity[i] = {0.0, 0.0, v0 * std::sin(pi * p.position[i].z / (2.0 * length))};
  const std::vector<Vec3> start = p.position;
  MpmSolver solver(scene, std::move(p));
  const double e0 = solver.energies().total();
  const double c = std::sqrt(1.24e5 / 8.93e-3), period = 4.0 * length / c;
  Mode m;
  double last = 0.0, first_crossing = -1.0;
  int crossings = 0;
  while (solver.time() < 2.2 * period) {
    solver.step(0.5 * solver.stable_time_step());
    const Particles& q = solver.particles();
    double u = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      const Vec3& x0 = start[static_cast<std::size_t>(q.id[i])];
      if (x0.z < 39.0) continue;
      u += q.position[i].z - x0.z;
      ++n;
    }
    u /= n;
    m.amplitude = std::max(m.amplitude, std::abs(u));
    // Down-crossings of the tip displacement: one per period, the first at T / 2.
    if (last > 0.0 && u <= 0.0) {
      const double t = solver.time();
      if (crossings == 0) first_crossing = t;
      m.period = t - first_crossing;
      ++crossings;
    }
    last = u;
    const core::Energies e = solver.energies();
    m.energy_drift = std::max(m.energy_drift, std::abs(e.total() - e.external_work - e0) / e0);
  }
  EXPECT_EQ(crossings, 2) << shape;
  const double w = 2.0 * pi / period;
  std::printf(
      "[ first mode %s %s %s] period %.5f ms (closed form %.5f), tip amplitude %.5f mm (%.5f), "
      "energy drift %.2e\n",
      shape.c_str(), formulation.c_str(), strength.empty() ? "" : "neo-hookean ", m.period, period,
      m.amplitude, v0 / w, m.energy_drift);
  m.period /= period;
  m.amplitude /= v0 / w;
  return m;
}

// The neo-Hookean solid at this strain (1.7e-4) is linear elastic with the same E and nu: the
// same marks, in both formulations (the updated one tracks F for it).
TEST(TotalLagrangian, ANeoHookeanBarVibratesInItsFirstModeInEitherFormulation) {
  const std::string nh = "strength = { model = \"neo-hookean\" }\n";
  for (const char* formulation : {"total-lagrangian", "updated-lagrangian"}) {
    const Mode m = first_mode("bspline2", nh, formulation);
    EXPECT_NEAR(m.period, 1.0, 0.01) << formulation;
    EXPECT_NEAR(m.amplitude, 1.0, 0.01) << formulation;
    EXPECT_LT(m.energy_drift, 0.005) << formulation;
  }
}

TEST(TotalLagrangian, ABarClampedAtOneEndVibratesInItsFirstMode) {
  for (const char* shape : {"linear", "bspline2"}) {
    const Mode m = first_mode(shape);
    EXPECT_NEAR(m.period, 1.0, 0.01) << shape;
    EXPECT_NEAR(m.amplitude, 1.0, 0.01) << shape;
    EXPECT_LT(m.energy_drift, 0.005) << shape;
  }
}

// A block stretched at a uniform rate (a soft material, particles given v_z = rate (z - z_c),
// which nothing changes): the grid takes the affine field exactly at the interior nodes of the
// reference lattice, so dF/dt = sum v_I (x) grad_X S_I = rate e_z (x) e_z and the interior
// particles' F_zz is 1 + rate t, their positions z_c + F_zz (Z - z_c), to round-off. Then a
// compression faster than 1 / dt turns F inside out and the run stops naming the particle and
// det F.
TEST(TotalLagrangian, TheDeformationGradientIntegratesTheVelocityGradientAndAnInvertedOneStops) {
  const std::string text =
      "[run]\nend_time = 1.0\n"
      "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [8, 8, 24]\n"
      "[mpm]\nformulation = \"total-lagrangian\"\n"
      "[materials.soft]\ndensity = 1e3\nE = 1e-8\nnu = 0.3\n"
      "[[bodies]]\nname = \"block\"\nmaterial = \"soft\"\nparticles_per_cell = 2\n"
      "shape = { box = { min = [2, 2, 4], max = [6, 6, 20] } }\n";
  const core::Scene scene = core::parse_scene(text, "stretch.toml");
  Particles p = generate_particles(scene);
  const double rate = 0.5, dt = 0.01;
  for (std::size_t i = 0; i < p.size(); ++i)
    p.velocity[i] = {0, 0, rate * (p.position[i].z - 12.0)};
  MpmSolver solver(scene, std::move(p));
  for (int k = 0; k < 20; ++k) solver.step(dt);
  const double expected = 1.0 + rate * dt * 20;
  const Particles& q = solver.particles();
  double worst = 0.0;
  int checked = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const Vec3& x0 = q.reference_position[i];
    if (std::abs(x0.x - 4.0) > 1.0 || std::abs(x0.y - 4.0) > 1.0 || std::abs(x0.z - 12.0) > 4.0)
      continue;
    ++checked;
    worst = std::max(worst, std::abs(q.deformation_gradient[i].m[2][2] - expected));
    // Position: x = x_c + F (X - X_c) along z.
    worst = std::max(worst, std::abs(q.position[i].z - (12.0 + expected * (x0.z - 12.0))) / 8.0);
  }
  std::printf("[ stretch ] F_zz after 20 steps: reference %.12f, largest error %.2e\n", expected,
              worst);
  EXPECT_GE(checked, 50);
  EXPECT_LT(worst, 1e-12);
  // Compress at 2 / dt: F_zz = 1 - 2 = -1 after one step.
  Particles& m = solver.mutable_particles();
  for (std::size_t i = 0; i < m.size(); ++i)
    m.velocity[i] = {0, 0, -2.0 / dt * (m.position[i].z - 12.0)};
  std::string message;
  try {
    for (int k = 0; k < 3; ++k) solver.step(dt);
  } catch (const core::SimulationError& e) {
    message = e.what();
  }
  std::printf("[ inverted ] %s\n", message.c_str());
  for (const std::string& part :
       {std::string("of body 'block'"), std::string("deformation gradient"),
        std::string("det F = "), std::string("updated-lagrangian")})
    EXPECT_NE(message.find(part), std::string::npos) << part;
}

// Bad input: what acts on a place in space, or deforms the domains the reference weights stand
// for, is refused with the file, line and key ([mpm] keys) or the key (across tables).
TEST(TotalLagrangian, WhatHasNoMeaningInTheReferenceConfigurationIsRefused) {
  const std::string tl = "formulation = \"total-lagrangian\"\n";
  struct Case {
    std::string mpm, file_text, key, says;
  };
  const std::string base = bar(tl);
  const Case cases[] = {
      {tl + "shape_function = \"cpdi1\"\n", "", "shape_function", "CPDI deforms the domains"},
  };
  for (const Case& c : cases) {
    const std::string text = bar(c.mpm);
    const std::string e = test::error_of(text, "tl.toml");
    for (const std::string& part :
         {"tl.toml:" + std::to_string(test::line_of(text, c.key + " =")), c.key, c.says})
      EXPECT_NE(e.find(part), std::string::npos) << part << " in: " << e;
  }
  // A wall face: a place in space.
  std::string wall = base;
  wall.replace(wall.find("zmin = \"fixed\""), 14, "zmin = \"wall\"");
  std::string e = test::error_of(wall, "tl.toml");
  EXPECT_NE(e.find("formulation"), std::string::npos) << e;
  EXPECT_NE(e.find("zmin is \"wall\""), std::string::npos) << e;
  // Grid contact between two bodies of particles, across tables: check_scene names the key.
  const std::string two = base +
                          "[[bodies]]\nname = \"other\"\nmaterial = \"copper\"\n"
                          "shape = { box = { min = [0, 0, 41], max = [2, 2, 43] } }\n"
                          "[[contact]]\nbodies = [\"bar\", \"other\"]\n";
  e = test::checked_error_of(two, "tl.toml");
  EXPECT_NE(e.find("contact"), std::string::npos) << e;
  EXPECT_NE(e.find("where they started"), std::string::npos) << e;
  EXPECT_NO_THROW(core::check_scene(core::parse_scene(base, "tl.toml")));
}

}  // namespace
}  // namespace afemp::mpm
