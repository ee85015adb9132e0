// A nearly incompressible beam for the mixed displacement-pressure MPM (mpm/mixed_pressure.cpp)
// and its reference of B-bar hexahedra: shared by tests/mpm/test_mixed_pressure.cpp (one cell
// size) and tests/validation/test_mixed_pressure_beam.cpp (convergence).
#pragma once

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "pressure_checkerboard.hpp"

namespace afemp::test::mixed_beam {

using core::Vec3;
using mpm::MpmSolver;
using mpm::Particles;

// A nearly incompressible cantilever (gel of the paper's soft beam and column: rho 1100, E 17 MPa,
// nu 0.499) 4 m long and 1 m deep, in plane strain (symmetric faces on both sides of its 0.5 m
// width), clamped at z = 0 on a fixed face, started in its first bending mode (Euler-Bernoulli
// shape, tip 0.1 m/s: strains below 1e-3). Its period comes from the tip's deflection, twice the
// time of its first return through zero.
struct Beam {
  double period = 0.0;
  // Largest |p_c - mean of its 4 in-plane neighbours| / range of p over the interior cells
  // (zero for any linear field), away from the clamped face.
  double checkerboard = 0.0;
  double energy = 0.0;  // largest |E - E0| / E0 over the run
};

inline double mode_velocity(double z, double length) {
  const double b = 1.8751, s = 0.7341, x = b * z / length;
  return 0.05 * (std::cosh(x) - std::cos(x) - s * (std::sinh(x) - std::sin(x)));
}

constexpr double beam_length = 4.0;

inline std::string beam_scene(const std::string& pressure, const std::string& shape, double cell) {
  char grid[160];
  std::snprintf(grid, sizeof grid, "cell = %g\nmin = [-1, 0, 0]\nmax = [1, 0.5, %g]\n", cell,
                beam_length + 1.0);
  return "[run]\nend_time = 100.0\n[grid]\n" + std::string(grid) +
         "boundary = { zmin = \"fixed\", ymin = \"symmetric\", ymax = \"symmetric\" }\n"
         "[mpm]\nformulation = \"total-lagrangian\"\nshape_function = \"" +
         shape + "\"\npressure = \"" + pressure +
         "\"\n"
         "[materials.gel]\ndensity = 1100\nE = 17e6\nnu = 0.499\n"
         "strength = { model = \"neo-hookean\" }\n"
         "[[bodies]]\nname = \"beam\"\nmaterial = \"gel\"\nparticles_per_cell = 2\n"
         "shape = { box = { min = [-0.5, 0, 0], max = [0.5, 0.5, 4] } }\n";
}

// The beam's particles, started in the mode.
inline Particles beam_particles(const core::Scene& scene) {
  Particles p = mpm::generate_particles(scene);
  for (std::size_t i = 0; i < p.size(); ++i)
    p.velocity[i] = {mode_velocity(p.position[i].z, beam_length), 0, 0};
  return p;
}

inline Beam bend(const std::string& pressure, const std::string& shape, double cell) {
  const core::Scene scene = core::parse_scene(beam_scene(pressure, shape, cell), "beam.toml");
  MpmSolver solver(scene, beam_particles(scene));
  Beam b;
  double last = 0.0, largest = 0.0;
  const double e0 = solver.energies().total();
  while (solver.time() < 2.0) {
    solver.step(solver.stable_time_step());
    const core::Energies e = solver.energies();
    b.energy = std::max(b.energy, std::abs(e.total() - e.external_work - e0) / e0);
    const Particles& q = solver.particles();
    double u = 0.0, m = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (q.reference_position[i].z < beam_length - cell) continue;
      u += q.mass[i] * (q.position[i].x - q.reference_position[i].x);
      m += q.mass[i];
    }
    u /= m;
    // The pressure at the largest deflection (a quarter period), cell by cell (x, z).
    if (u < largest && b.checkerboard == 0.0) {
      // Cells two from the clamped face are left out: its corners are singular.
      b.checkerboard = pressure_checkerboard<2>(
          q, cell, {0, 2}, Vec3{-1.0, 0.0, 0.0},
          [](const std::array<int, 2>& c) { return c[1] >= 2; },
          [](const std::array<int, 2>&) { return true; });
    }
    largest = std::max(largest, u);
    if (last > 0.0 && u <= 0.0) {
      b.period = 2.0 * solver.time();
      break;
    }
    last = u;
  }
  return b;
}

// The reference: the same beam of B-bar hexahedra (`element = "full"`), `across` the depth,
// the material elastic (at these strains the neo-Hookean solid is linear elastic with the same
// E and nu) unless `strength` gives the material's strength line, the clamped face's nodes fixed
// and every node held in y.
inline double bend_hexahedra(int across = 8, const std::string& strength = "") {
  const std::string text =
      "[run]\nend_time = 100.0\n"
      "[materials.gel]\ndensity = 1100\nE = 17e6\nnu = 0.499\n" +
      strength +
      "[[bodies]]\nname = \"beam\"\nmaterial = \"gel\"\ndiscretisation = \"hexahedra\"\n"
      "element = \"full\"\n"
      "shape = { box = { min = [-0.5, 0, 0], max = [0.5, 0.5, 4] } }\n"
      "mesh = { divisions = [" +
      std::to_string(across) + ", 1, " + std::to_string(4 * across) +
      "] }\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
      "fixed = [\"all\"]\n"
      "[[constraints]]\nnodes = { box = { min = [-1, -1, -1], max = [1, 1, 10] } }\n"
      "fixed = [\"y\"]\n";
  const core::Scene scene = core::parse_scene(text, "beam_hexahedra.toml");
  fem::FeSolver solver(scene);
  fem::FeNodes& nodes = solver.mutable_nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.position[i].z > 0.0)
      nodes.velocity[i] = {mode_velocity(nodes.position[i].z, beam_length), 0, 0};
  double last = 0.0;
  while (solver.time() < 2.0) {
    solver.step(solver.stable_time_step());
    const fem::FeNodes& q = solver.nodes();
    double u = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (q.initial_position[i].z < beam_length - 1e-9) continue;
      u += q.position[i].x - q.initial_position[i].x;
      ++n;
    }
    u /= n;
    if (last > 0.0 && u <= 0.0) return 2.0 * solver.time();
    last = u;
  }
  return 0.0;
}

}  // namespace afemp::test::mixed_beam
