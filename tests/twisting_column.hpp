// The twisting column, VALIDATION V8's second case (Zhang et al. 2022, the mixed u-p
// total-Lagrangian MPM paper; the benchmark of Aguirre, Gil, Bonet & Carreno 2014,
// docs/references.md item 70): a 1 x 1 x 6 m column of gel (rho 1100, E 17 MPa, nu 0.499,
// neo-Hookean), its base z = 0 fixed, started with v0 = omega (-y, x, 0) sin(pi z / 12) about its
// axis and left to twist and untwist; the measure is the z-displacement history of point A, the
// top corner (0.5, 0.5, 6), to t = 0.3 s, and, at a small twist, the top's swing against
// Saint-Venant's torsion. Shared by the V8 validation (tests/validation/test_twisting_column.cpp)
// and the small twist in the default tests (tests/mpm/test_twisting_column_small.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "corner_fit.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "pressure_checkerboard.hpp"

namespace afemp::test::twisting_column {

using core::Vec3;

constexpr double kEndTime = 0.3, kSample = 0.0025;  // seconds: the run, and between samples

inline Vec3 initial_velocity(const Vec3& x, double omega) {
  const double s = omega * std::sin(M_PI * x.z / 12.0);
  return {-x.y * s, x.x * s, 0.0};
}

constexpr double kDensity = 1100.0, kYoung = 17e6, kLength = 6.0;

inline std::string material(double nu) {
  char text[160];
  std::snprintf(text, sizeof text,
                "[materials.gel]\ndensity = %.17g\nE = %.17g\nnu = %.17g\n"
                "strength = { model = \"neo-hookean\" }\n",
                kDensity, kYoung, nu);
  return text;
}

// The small twist's closed form. v0 is the first torsional mode of a fixed-free bar, sin(pi z /
// 2L), so at small amplitude the column swings in that mode alone: the top turns through
// theta(t) = omega / w1 sin(w1 t), w1 = pi c_t / 2L, with the torsional wave speed
// c_t = sqrt(G J / (rho I_p)) (Saint-Venant torsion: J = 0.1406 a^4 for a square of side a,
// Timoshenko & Goodier 1970, docs/references.md item 57; I_p = a^4 / 6). Its half period (the top
// back through zero) is 2L / c_t and its peak omega 2L / (pi c_t).
inline double torsional_wave_speed(double nu) {
  const double shear = kYoung / (2.0 * (1.0 + nu));
  return std::sqrt(shear * 0.1406 * 6.0 / kDensity);
}

struct History {
  std::vector<double> uz;     // point A's z-displacement, every kSample s from 0
  std::vector<double> twist;  // the top 0.5 m's mean rotation about z (rad)
  double energy = 0.0;        // largest |E - E0| / E0 over the run
  // Particles, at the end: the largest |p_c - mean of its 6 neighbours| over the range of the
  // cells' mean pressure (cells by the particles' reference positions), among cells whose six
  // neighbours hold particles, above the lowest metre (the fixed base's corners are singular).
  double checkerboard = 0.0;
  std::size_t points = 0;  // elements or particles
  long steps = 0;
};

// The rotation about z of the points whose reference lies in the top 0.5 m: atan2 of the
// summed cross and dot products of reference and current positions in the xy plane.
template <class Points>
double top_twist(const Points& x, const Points& x0) {
  double cross = 0.0, dot = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x0[i].z < 5.5) continue;
    cross += x0[i].x * x[i].y - x0[i].y * x[i].x;
    dot += x0[i].x * x[i].x + x0[i].y * x[i].y;
  }
  return std::atan2(cross, dot);
}

// Samples `uz` and `twist` while stepping `solver` (FeSolver or MpmSolver) to kEndTime.
template <class Solver, class Uz, class Twist>
History run_to_end(Solver& solver, Uz uz, Twist twist) {
  History h;
  const double e0 = solver.energies().total();
  double next = 0.0;
  while (true) {
    if (solver.time() >= next - 1e-12) {
      h.uz.push_back(uz());
      h.twist.push_back(twist());
      next += kSample;
    }
    if (solver.time() >= kEndTime - 1e-12) break;
    solver.step(std::min(solver.stable_time_step(), next - solver.time()));
    ++h.steps;
    h.energy = std::max(h.energy, std::abs(solver.energies().total() - e0) / e0);
  }
  return h;
}

// The column of B-bar hexahedra (`element = "full"`, F-bar for the neo-Hookean solid) `across`
// on a side and 6 `across` along the axis, its base's nodes fixed, at `factor` times LS-DYNA's
// step (0.5 for nu = 0.499; tests/fem/test_hyperelastic_hexahedra.cpp shows why).
inline core::Scene hexahedra_scene(int across, double nu = 0.499, double factor = 0.5) {
  char run[96];
  std::snprintf(run, sizeof run, "[run]\nend_time = 100.0\nelement_time_step_factor = %.17g\n",
                factor);
  const std::string text =
      std::string(run) + material(nu) +
      "[[bodies]]\nname = \"column\"\nmaterial = \"gel\"\ndiscretisation = \"hexahedra\"\n"
      "element = \"full\"\nshape = { box = { min = [-0.5, -0.5, 0], max = [0.5, 0.5, 6] } }\n"
      "mesh = { divisions = [" +
      std::to_string(across) + ", " + std::to_string(across) + ", " + std::to_string(6 * across) +
      "] }\n[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
      "fixed = [\"all\"]\n";
  return core::parse_scene(text, "twisting_column.toml");
}

// Starts the hexahedra's nodes above the base twisting at `omega`; returns point A's node.
inline std::size_t start_twisting(fem::FeNodes& nodes, double omega) {
  std::size_t corner = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.position[i].z > 0.0) nodes.velocity[i] = initial_velocity(nodes.position[i], omega);
    if (core::norm(nodes.position[i] - Vec3{0.5, 0.5, kLength}) < 1e-9) corner = i;
  }
  return corner;
}

// The reference: the hexahedra of hexahedra_scene.
inline History run_hexahedra(int across, double omega, double nu = 0.499) {
  const core::Scene scene = hexahedra_scene(across, nu);  // the solver keeps a reference
  fem::FeSolver solver(scene);
  const std::size_t corner = start_twisting(solver.mutable_nodes(), omega);
  History h = run_to_end(
      solver, [&] { return solver.nodes().position[corner].z - kLength; },
      [&] { return top_twist(solver.nodes().position, solver.nodes().initial_position); });
  h.points = static_cast<std::size_t>(6 * across * across * across);
  return h;
}

// The particles: `per_cell` per cell per direction on cells of `cell` m, in the
// total-Lagrangian MPM with `shape`; `pressure` "mixed" or "standard". The grid covers the
// column's reference configuration and no more (`margin` cells beyond its free faces, 0 by
// default): its faces are the column's, the base z = 0 a fixed face, the others free, where the
// B-splines are modified so that their face nodes carry the surface. With a free surface inside
// a cell instead, the FLIP transfer bends the quadratic B-spline's torsion and the affine one
// (`transfer` "apic") does not (docs/scene-format.md, `formulation`).
inline History run_particles(double cell, int per_cell, const std::string& shape,
                             const std::string& pressure, double omega, double nu = 0.499,
                             int margin = 0, const std::string& transfer = "flip") {
  char grid[240];
  const double m = margin * cell;
  std::snprintf(grid, sizeof grid,
                "cell = %.17g\nmin = [%.17g, %.17g, 0]\nmax = [%.17g, %.17g, %.17g]\n", cell,
                -0.5 - m, -0.5 - m, 0.5 + m, 0.5 + m, kLength + m);
  const std::string text =
      "[run]\nend_time = 100.0\n[grid]\n" + std::string(grid) +
      "boundary = { zmin = \"fixed\" }\n"
      "[mpm]\nformulation = \"total-lagrangian\"\nshape_function = \"" +
      shape + "\"\npressure = \"" + pressure + "\"\ntransfer = \"" + transfer + "\"\n" +
      material(nu) + "[[bodies]]\nname = \"column\"\nmaterial = \"gel\"\nparticles_per_cell = " +
      std::to_string(per_cell) +
      "\nshape = { box = { min = [-0.5, -0.5, 0], max = [0.5, 0.5, 6] } }\n";
  const core::Scene scene = core::parse_scene(text, "twisting_column.toml");
  mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
  mpm::Particles& p = solver.mutable_particles();
  for (std::size_t i = 0; i < p.size(); ++i) p.velocity[i] = initial_velocity(p.position[i], omega);
  History h = run_to_end(
      solver,
      [&] {
        return fitted_displacement<3>(solver.particles(), Vec3{0.5, 0.5, kLength}, 1.5 * cell, 2);
      },
      [&] {
        return top_twist(solver.particles().position, solver.particles().reference_position);
      });
  h.points = p.size();
  h.checkerboard = pressure_checkerboard<3>(
      solver.particles(), cell, {0, 1, 2}, Vec3{},
      [cell](const std::array<int, 3>& c) { return (c[2] + 1) * cell > 1.0; },
      [](const std::array<int, 3>&) { return true; });
  return h;
}

// The top's first return through zero twist (linear between samples): half the period.
inline double half_period(const History& h) {
  for (std::size_t k = 1; k < h.twist.size(); ++k)
    if (h.twist[k - 1] > 0.0 && h.twist[k] <= 0.0 && h.twist[k - 1] - h.twist[k] < 1.0)
      return kSample *
             (static_cast<double>(k - 1) + h.twist[k - 1] / (h.twist[k - 1] - h.twist[k]));
  return 0.0;
}

inline double peak_twist(const History& h) {
  return *std::max_element(h.twist.begin(), h.twist.end());
}

inline double lowest_twist(const History& h) {
  return *std::min_element(h.twist.begin(), h.twist.end());
}

// The difference of two u_z histories over their common samples, against b's: the largest
// |a - b| over b's largest |value| (`max`), and the root of the summed squares over b's (`rms`).
struct Difference {
  double max = 0.0, rms = 0.0;
};

inline Difference history_difference(const History& a, const History& b) {
  double diff = 0.0, peak = 0.0, squares = 0.0, reference = 0.0;
  for (std::size_t k = 0; k < std::min(a.uz.size(), b.uz.size()); ++k) {
    diff = std::max(diff, std::abs(a.uz[k] - b.uz[k]));
    peak = std::max(peak, std::abs(b.uz[k]));
    squares += (a.uz[k] - b.uz[k]) * (a.uz[k] - b.uz[k]);
    reference += b.uz[k] * b.uz[k];
  }
  return {diff / peak, std::sqrt(squares / reference)};
}

}  // namespace afemp::test::twisting_column
