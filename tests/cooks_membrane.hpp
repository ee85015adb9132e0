// Cook's membrane, VALIDATION V8's first case (Zhang et al. 2022, the mixed u-p total-Lagrangian
// MPM paper, §3.1; the geometry of Cook 1974): a tapered panel with corners (0, 0), (48, 44),
// (48, 60) and (0, 44) m, clamped along x = 0, loaded by a uniform vertical shear traction of
// 0.25 Pa (0.25 N per metre of edge and metre of thickness) on x = 48, nearly incompressible
// (E 1000 Pa, nu 0.499, rho 1, neo-Hookean), in plane strain; the measure is the top-right
// corner's vertical displacement at t = 3 s, the load applied at t = 0. Shared by the V8
// validation (tests/validation/test_cooks_membrane.cpp) and its coarse run in the default tests
// (tests/mpm/test_cooks_membrane_coarse.cpp). Plane strain: the panel is a slab along z between
// two symmetric grid faces (particles) or held in z (hexahedra), its thickness two cells or one
// element.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/scene.hpp"
#include "corner_fit.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "pressure_checkerboard.hpp"

namespace afemp::test::cooks_membrane {

using core::Vec3;

constexpr double kTraction = 0.25, kEndTime = 3.0;

// The panel's point at natural coordinates (s, r) in [0, 1]^2: x = 48 s, y from the lower edge
// 44 s to the upper edge 44 + 16 s.
inline Vec3 panel(double s, double r) {
  const double x = 48.0 * s, lo = 44.0 * s, hi = 44.0 + 16.0 * s;
  return {x, lo + r * (hi - lo), 0.0};
}

// The panel's area element dA = |dx/ds x dx/dr| ds dr: 48 (44 - 28 s) ds dr (bilinear in s only).
inline double panel_jacobian(double s) {
  return 48.0 * (44.0 - 28.0 * s);
}

inline const char* kMaterial =
    "[materials.gel]\ndensity = 1.0\nE = 1000.0\nnu = 0.499\n"
    "strength = { model = \"neo-hookean\" }\n";

struct Result {
  double deflection = 0.0;  // the top-right corner's vertical displacement at t = 3 s
  double nearest = 0.0;     // particles: that of the particle nearest the corner
  // Particles, at t = 3 s: the largest |p_c - mean of its 4 neighbours| over the range of the
  // cells' mean pressure, among cells wholly inside the panel whose neighbours are too, away
  // from the clamped edge (as tests/mixed_beam.hpp measures the beam's).
  double checkerboard = 0.0;
  double energy = 0.0;     // |E - E0 - W_ext| / W_ext at the end
  std::size_t points = 0;  // particles or elements
  long steps = 0;
};

// The reference: B-bar hexahedra (`element = "full"`, F-bar for the neo-Hookean solid) on an
// n x n mapped mesh one element thick, every node held in z, the nodes of x = 0 fixed, the load
// a [[loads]] traction on the faces of x = 48, at half LS-DYNA's step (nu = 0.499).
inline Result run_hexahedra(int n, const std::filesystem::path& dir) {
  const std::filesystem::path mesh = dir / ("cook_" + std::to_string(n) + ".inp");
  {
    std::ofstream f(mesh);
    f << "*NODE\n";
    const double thickness = 48.0 / n;
    auto id = [n](int i, int j, int k) { return 1 + i + (n + 1) * (j + (n + 1) * k); };
    for (int k = 0; k <= 1; ++k)
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          const Vec3 x = panel(static_cast<double>(i) / n, static_cast<double>(j) / n);
          char line[160];
          std::snprintf(line, sizeof line, "%d, %.17g, %.17g, %.17g\n", id(i, j, k), x.x, x.y,
                        k * thickness);
          f << line;
        }
    f << "*ELEMENT, TYPE=C3D8, ELSET=panel\n";
    int e = 1;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        f << e++ << ", " << id(i, j, 0) << ", " << id(i + 1, j, 0) << ", " << id(i + 1, j + 1, 0)
          << ", " << id(i, j + 1, 0) << ", " << id(i, j, 1) << ", " << id(i + 1, j, 1) << ", "
          << id(i + 1, j + 1, 1) << ", " << id(i, j + 1, 1) << "\n";
  }
  char traction[64];
  std::snprintf(traction, sizeof traction, "traction = [0, %.17g, 0]\n", kTraction);
  const std::string text =
      "[run]\nend_time = 3.0\nelement_time_step_factor = 0.5\n" + std::string(kMaterial) +
      "[[bodies]]\nname = \"panel\"\nmaterial = \"gel\"\ndiscretisation = \"hexahedra\"\n"
      "element = \"full\"\nshape = { mesh = { file = \"" +
      mesh.string() +
      "\" } }\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }\n"
      "fixed = [\"all\"]\n"
      "[[constraints]]\nnodes = { box = { min = [-1, -1, -1], max = [49, 61, 10] } }\n"
      "fixed = [\"z\"]\n"
      "[[loads]]\nbody = \"panel\"\nnodes = { plane = { point = [48, 0, 0], normal = [1, 0, 0] } "
      "}\n" +
      traction;
  const core::Scene scene = core::parse_scene(text, "cook_hexahedra.toml");
  fem::FeSolver solver(scene);
  std::size_t corner = 0;
  const fem::FeNodes& nodes = solver.nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (core::norm(nodes.initial_position[i] - Vec3{48, 60, 0}) <
        core::norm(nodes.initial_position[corner] - Vec3{48, 60, 0}))
      corner = i;
  const double e0 = solver.energies().total();
  Result r;
  while (solver.time() < kEndTime) {
    solver.step(std::min(solver.stable_time_step(), kEndTime - solver.time()));
    ++r.steps;
  }
  const core::Energies e = solver.energies();
  r.energy = std::abs(e.total() - e0 - e.external_work) / e.external_work;
  r.deflection = nodes.position[corner].y - nodes.initial_position[corner].y;
  r.points = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  return r;
}

// The particles: the panel mapped from 2 per cell per direction along x (s) and as many along y
// (r), each particle at the centre of its piece of the map with that piece's volume (so the
// edges lie where the panel's do and the last column of particles is one layer of equal
// particles along x = 48), two cells through the thickness with 2 particles per cell, in the
// total-Lagrangian MPM with quadratic B-splines; `pressure` "mixed" or "standard". The grid:
// cells of `cell` m from x = 0 (a fixed face: the clamped edge), two cells thick between
// symmetric faces.
inline Result run_particles(const std::string& pressure, double cell,
                            const std::filesystem::path& dir,
                            const std::string& shape = "bspline2") {
  const int n = static_cast<int>(std::lround(2.0 * 48.0 / cell));
  const double thickness = 2.0 * cell;
  const std::filesystem::path points = dir / ("cook_" + std::to_string(n) + ".txt");
  {
    std::ofstream f(points);
    char line[160];
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double s = (i + 0.5) / n, r = (j + 0.5) / n;
          // The exact volume of the piece [i/n, (i+1)/n] x [j/n, (j+1)/n]: the Jacobian is
          // linear in s, so its value at the centre is the mean.
          const double volume = panel_jacobian(s) / (static_cast<double>(n) * n) * thickness / 4.0;
          const Vec3 x = panel(s, r);
          std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g\n", x.x, x.y,
                        (k + 0.5) * thickness / 4.0, volume);
          f << line;
        }
  }
  char grid[200], load[200];
  std::snprintf(grid, sizeof grid,
                "cell = %.17g\nmin = [0, %.17g, 0]\nmax = [%.17g, %.17g, %.17g]\n", cell,
                -2.0 * cell, 48.0 + 2.0 * cell, 60.0 + 2.0 * cell, thickness);
  // The last column of particles, at x = 48 - cell / 4, shares the edge's force, 0.25 Pa over
  // 16 m by the thickness.
  std::snprintf(load, sizeof load,
                "[[loads]]\nbody = \"panel\"\nparticles = { box = { min = [%.17g, 40, -1], max = "
                "[49, 61, %.17g] } }\nforce = [0, %.17g, 0]\n",
                48.0 - 0.5 * cell, thickness + 1.0, kTraction * 16.0 * thickness);
  const std::string text =
      "[run]\nend_time = 3.0\n[grid]\n" + std::string(grid) +
      "boundary = { xmin = \"fixed\", zmin = \"symmetric\", zmax = \"symmetric\" }\n"
      "[mpm]\nformulation = \"total-lagrangian\"\nshape_function = \"" +
      shape + "\"\npressure = \"" + pressure + "\"\n" + kMaterial +
      "[[bodies]]\nname = \"panel\"\nmaterial = \"gel\"\nshape = { points = { file = \"" +
      points.string() + "\" } }\n" + load;
  const core::Scene scene = core::parse_scene(text, "cook_particles.toml");
  mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
  const mpm::Particles& p = solver.particles();
  // The corner's particle: of the last column, the one nearest the top (48, 60), whichever
  // layer through the thickness (plane strain: they move alike).
  std::size_t corner = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (core::norm(p.reference_position[i] - Vec3{48, 60, p.reference_position[i].z}) <
        core::norm(p.reference_position[corner] - Vec3{48, 60, p.reference_position[corner].z}))
      corner = i;
  const std::int32_t corner_id = p.id[corner];
  const double e0 = solver.energies().total();
  Result r;
  while (solver.time() < kEndTime) {
    solver.step(std::min(solver.stable_time_step(), kEndTime - solver.time()));
    ++r.steps;
  }
  const core::Energies e = solver.energies();
  r.energy = std::abs(e.total() - e0 - e.external_work) / e.external_work;
  const mpm::Particles& q = solver.particles();
  for (std::size_t i = 0; i < q.size(); ++i)
    if (q.id[i] == corner_id) r.nearest = q.position[i].y - q.reference_position[i].y;
  // The corner's own: u_y fitted linearly to the particles within 1.5 cells of the corner
  // (reference positions, in the panel's plane), its value at the corner.
  r.deflection = fitted_displacement<2>(q, Vec3{48.0, 60.0, 0.0}, 1.5 * cell, 1);
  r.points = q.size();
  // The pressure, cell by cell in the panel's plane (x, y) at the particles' reference
  // positions, among the cells wholly inside the panel (a cell's mean is not that of a sliver at
  // an edge), away from the clamped edge, whose corners are singular.
  auto whole = [cell](const std::array<int, 2>& c) {
    const double x0 = c[0] * cell, y0 = c[1] * cell;
    return x0 >= 0.0 && x0 + cell <= 48.0 && y0 >= 44.0 / 48.0 * (x0 + cell) &&
           y0 + cell <= 44.0 + 16.0 / 48.0 * x0;
  };
  r.checkerboard = pressure_checkerboard<2>(
      q, cell, {0, 1}, Vec3{}, [&](const std::array<int, 2>& c) { return c[0] >= 2 && whole(c); },
      whole);
  return r;
}

}  // namespace afemp::test::cooks_membrane
