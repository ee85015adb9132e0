// Particles at the faces of a mesh (coupling/particle_surface_contact.cpp, [[contact]] method
// "surface"). Units mm, ms, g, N, MPa.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "coupling/coupled_model.hpp"
#include "scene_errors.hpp"

namespace afemp::coupling {
namespace {

// Elastic steel: rho 7.85e-3, E 2.1e5, nu 0.3; c_L = 6001 m/s in uniaxial strain.
constexpr const char* kSteel = "[materials.steel]\ndensity = 7.85e-3\nE = 2.1e5\nnu = 0.3\n";

double wave_speed() {
  return std::sqrt(2.1e5 * 0.7 / (1.3 * 0.4 * 7.85e-3));
}

// A column of particles, 1 x 1 x 10 mm held across by the grid's symmetric side faces
// (uniaxial strain), moving at 5 m/s onto the top face of `target` (a mesh body's TOML) at z = 0.
std::string scene(const std::string& target) {
  std::string s =
      "[run]\nend_time = 0.01\n[grid]\ncell = 0.25\nmin = [0, 0, -11]\n"
      "max = [1, 1, 11]\nboundary = { xmin = \"symmetric\", xmax = \"symmetric\", "
      "ymin = \"symmetric\", ymax = \"symmetric\" }\n";
  s += kSteel;
  s += "[[bodies]]\nname = \"column\"\nmaterial = \"steel\"\n"
       "shape = { box = { min = [0, 0, 0], max = [1, 1, 10] } }\nvelocity = [0, 0, -5]\n";
  s += target;
  s += "[[contact]]\nbodies = [\"column\", \"target\"]\nmethod = \"surface\"\n";
  return s;
}

// A rigid steel block of 3 x 3 x 2 hexahedra under the column, from z = bottom to 0; `rigid`
// is the value of its key (true, or { fixed = [...] }).
std::string rigid_block(double bottom, const std::string& rigid) {
  return "[[bodies]]\nname = \"target\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
         "shape = { box = { min = [-1, -1, " +
         std::to_string(bottom) +
         "], max = [2, 2, 0] } }\nmesh = { divisions = [3, 3, 2] }\nrigid = " + rigid + "\n";
}

struct Outcome {
  double duration = 0.0, plateau = 0.0;
  core::Energies start, end;
};

// Steps to t_end; the contact lasts from the first to the last step its force on the column
// (the history's column "column-target.fz") is positive, and the plateau is that force's mean
// over the middle half of the contact. Checks each step that the particles and the target
// hold the momentum they started with (to 1e-9 of m v) when `conserved`.
Outcome run(const std::string& text, double t_end, bool conserved) {
  const core::Scene s = core::parse_scene(text, "surface.toml");
  CoupledModel model(s);
  const std::vector<std::string> columns = model.force_columns();
  const auto fz = static_cast<std::size_t>(
      std::find(columns.begin(), columns.end(), "column-target.fz") - columns.begin());
  EXPECT_LT(fz, columns.size());
  Outcome r;
  r.start = model.energies();
  const double scale = r.start.bodies[0].mass * 5.0;
  const Vec3 p0 = r.start.bodies[0].momentum + r.start.bodies[1].momentum;
  std::vector<std::array<double, 3>> steps;
  std::vector<double> forces;
  double first = -1.0, last = -1.0;
  while (model.time() < t_end) {
    const double dt = model.stable_time_step();
    const double t0 = model.time();
    model.step(dt);
    model.force_values(forces);
    const double f = forces[fz];
    if (f > 1e-6) {
      if (first < 0.0) first = t0;
      last = model.time();
    }
    steps.push_back({t0, model.time(), f});
    if (conserved) {
      const core::Energies e = model.energies();
      const Vec3 p = e.bodies[0].momentum + e.bodies[1].momentum;
      EXPECT_NEAR(p.z, p0.z, 1e-9 * scale) << "step " << steps.size();
    }
  }
  r.end = model.energies();
  r.duration = last - first;
  const double quarter = 0.25 * r.duration;
  double impulse = 0.0, span = 0.0;
  for (const auto& [a, b, f] : steps)
    if (a >= first + quarter && b <= last - quarter) {
      impulse += f * (b - a);
      span += b - a;
    }
  r.plateau = impulse / span;
  return r;
}

// Reference (1-D elastic impact on a rigid face): contact for 2 L / c_L = 3.333 us, a force
// plateau rho c_L v A = 235.5 N, rebound at +5 m/s. The target is a fixed rigid block of
// hexahedra. Pass: contact time and plateau within 5 %, rebound within 5 % (the column leaves
// ringing: 4.77 m/s, as on a [[walls]] plane, tests/mpm/test_particle_walls.cpp).
TEST(ParticleSurfaceContact, ColumnOnAFixedRigidBlockRestsTwoWaveTransits) {
  const Outcome r = run(scene(rigid_block(-2.0, "{ fixed = [\"all\"] }")), 0.01, false);
  const double c = wave_speed(), duration = 20.0 / c, force = 7.85e-3 * c * 5.0;
  const double rebound = r.end.bodies[0].momentum.z / r.end.bodies[0].mass;
  std::printf(
      "column on a fixed rigid block: contact %.4g us (2L/c %.4g, %+.2f %%), plateau "
      "%.4g N (rho c v A %.4g, %+.2f %%), rebound %.4g m/s\n",
      1e3 * r.duration, 1e3 * duration, 100.0 * (r.duration / duration - 1.0), r.plateau, force,
      100.0 * (r.plateau / force - 1.0), rebound);
  EXPECT_NEAR(r.duration, duration, 0.05 * duration);
  EXPECT_NEAR(r.plateau, force, 0.05 * force);
  EXPECT_NEAR(rebound, 5.0, 0.05 * 5.0);
}

// Reference: a free rigid block takes exactly the impulse the particles give up: the momentum of
// column + block stays that of the start (to 1e-9 of m v, every step), and the block leaves with
// the momentum the column lost.
TEST(ParticleSurfaceContact, AFreeRigidBlockTakesTheImpulseTheParticlesGiveUp) {
  const Outcome r = run(scene(rigid_block(-4.0, "true")), 0.006, true);
  const double block = r.end.bodies[1].momentum.z;
  // What the column gave up (its momentum points down: the change is negative too).
  const double given = r.start.bodies[0].momentum.z - r.end.bodies[0].momentum.z;
  std::printf("free rigid block: it took %.6g g m/s, the column gave up %.6g\n", block, given);
  EXPECT_LT(block, 0.0);  // pushed down
  EXPECT_NEAR(block, given, 1e-9 * std::abs(given));
}

// Reference (1-D): a column of particles striking an identical elastic column of hexahedra at
// rest (held across: uniaxial strain) stays in contact for 2 L / c_L and hands it its whole
// momentum: the particles stop and the mesh leaves at -5 m/s. Momentum is conserved to 1e-9 of
// m v every step. Pass: contact time within 5 %, the velocities within 5 % of v.
TEST(ParticleSurfaceContact, ParticlesHandAnIdenticalMeshColumnTheirMomentum) {
  std::string target =
      "[[bodies]]\nname = \"target\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [0, 0, -10], max = [1, 1, 0] } }\nmesh = { divisions = [4, 4, 40] "
      "}\n";
  for (const char* plane : {"[0, 0, 0], normal = [1, 0, 0] } }\nfixed = [\"x\"]",
                            "[1, 0, 0], normal = [1, 0, 0] } }\nfixed = [\"x\"]",
                            "[0, 0, 0], normal = [0, 1, 0] } }\nfixed = [\"y\"]",
                            "[0, 1, 0], normal = [0, 1, 0] } }\nfixed = [\"y\"]"})
    target += std::string("[[constraints]]\nnodes = { plane = { point = ") + plane + "\n";
  const Outcome r = run(scene(target), 0.006, true);
  const double c = wave_speed(), duration = 20.0 / c;
  const double v_particles = r.end.bodies[0].momentum.z / r.end.bodies[0].mass;
  const double v_mesh = r.end.bodies[1].momentum.z / r.end.bodies[1].mass;
  std::printf(
      "particles on a mesh column: contact %.4g us (2L/c %.4g, %+.2f %%), particles "
      "%.4g m/s, mesh %.4g m/s, energy kept %.2f %%\n",
      1e3 * r.duration, 1e3 * duration, 100.0 * (r.duration / duration - 1.0), v_particles, v_mesh,
      100.0 * (r.end.kinetic + r.end.internal) / (r.start.kinetic + r.start.internal));
  EXPECT_NEAR(r.duration, duration, 0.05 * duration);
  EXPECT_NEAR(v_particles, 0.0, 0.05 * 5.0);
  EXPECT_NEAR(v_mesh, -5.0, 0.05 * 5.0);
}

// Bad input: a surface contact between two particle bodies names the file, line and key.
TEST(ParticleSurfaceContact, SurfaceContactBetweenParticleBodiesIsAnError) {
  std::string s = scene(
      "[[bodies]]\nname = \"target\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [0, 0, -10], max = [1, 1, 0] } }\n");
  const std::string e = afemp::test::error_of(s, "surface.toml");
  const std::string where =
      "surface.toml:" + std::to_string(afemp::test::line_of(s, "method = \"surface\"")) +
      ": key 'contact[0].method'";
  EXPECT_NE(e.find(where), std::string::npos) << e;
  EXPECT_NE(e.find("a body of particles and a body of hexahedra"), std::string::npos) << e;
}

// Reference: `afemp check` says how the target meets the column: through surface contact at
// its faces, not as a body "in no contact" that "does not meet the particles" (issue 46).
TEST(ParticleSurfaceContact, AfempCheckSaysTheMeshMeetsTheParticlesAtItsFaces) {
  const core::Scene s = core::parse_scene(scene(rigid_block(-1.0, "true")), "surface.toml");
  const std::string text = CoupledModel(s).describe();
  EXPECT_EQ(text.find("does not meet"), std::string::npos) << text;
  EXPECT_NE(text.find("body target: meets column at its faces (surface contact"), std::string::npos)
      << text;
}

}  // namespace
}  // namespace afemp::coupling
