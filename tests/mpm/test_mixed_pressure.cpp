// The mixed displacement-pressure total-Lagrangian MPM ([mpm] pressure = "mixed"; Zhang et al.
// 2022, eqs 17-24; mpm/mixed_pressure.cpp). References:
// - under a uniform deformation every nodal average returns its input: the mixed pressure is
//   the point's own K (J - 1), so the stress is the standard scheme's to round-off;
// - a nearly incompressible cantilever (nu = 0.499) in plane strain vibrates in its first
//   bending mode at the period of the same beam of B-bar hexahedra (afemp's own, 8 across the
//   depth: V8's reference) within 3 % with the mixed pressure, under the linear hat (constant
//   pressure per cell) and the quadratic B-spline (linear pressure); the point-wise pressure on
//   the same cells locks (too fast: 0.45 of the period under the linear hat), and the mixed
//   pressure of quadratic B-splines shows no cell-to-cell checkerboard (V8: below 5 % of its
//   range);
// - bad input (the updated-Lagrangian form, a material without a volumetric energy) is refused
//   naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>

#include "afemp/errors.hpp"
#include "core/parallel.hpp"
#include "core/plausibility.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "scene_errors.hpp"

namespace afemp::mpm {
namespace {

using core::Vec3;

// A block stretched at a uniform rate, as in test_total_lagrangian.cpp, of a nearly
// incompressible neo-Hookean solid: the interior particles' stresses with the mixed and the
// point-wise pressure.
std::vector<core::SymTensor> stretched(const std::string& pressure, std::vector<bool>& interior) {
  const std::string text =
      "[run]\nend_time = 1.0\n"
      "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [8, 8, 24]\n"
      "[mpm]\nformulation = \"total-lagrangian\"\nshape_function = \"bspline2\"\npressure = \"" +
      pressure +
      "\"\n"
      "[materials.soft]\ndensity = 1e3\nE = 1e-6\nnu = 0.49\n"
      "strength = { model = \"neo-hookean\" }\n"
      "[[bodies]]\nname = \"block\"\nmaterial = \"soft\"\nparticles_per_cell = 2\n"
      "shape = { box = { min = [1, 1, 4], max = [7, 7, 20] } }\n";
  const core::Scene scene = core::parse_scene(text, "stretch.toml");
  Particles p = generate_particles(scene);
  const double rate = 0.5, dt = 0.01;
  for (std::size_t i = 0; i < p.size(); ++i)
    p.velocity[i] = {0, 0, rate * (p.position[i].z - 12.0)};
  MpmSolver solver(scene, std::move(p));
  for (int k = 0; k < 20; ++k) solver.step(dt);
  const Particles& q = solver.particles();
  std::vector<core::SymTensor> out(q.size());
  interior.assign(q.size(), false);
  for (std::size_t i = 0; i < q.size(); ++i) {
    const auto id = static_cast<std::size_t>(q.id[i]);
    out[id] = q.stress[i];
    const Vec3& x0 = q.reference_position[i];
    // F is uniform from 3 cells inside the stretched block's ends (the ends' nodes are partly
    // filled), and the two averages of the mixed pressure reach 2 cells further.
    interior[id] =
        std::abs(x0.x - 4.0) < 0.9 && std::abs(x0.y - 4.0) < 0.9 && std::abs(x0.z - 12.0) < 3.0;
  }
  return out;
}

TEST(MixedPressure, UnderAUniformStretchTheMixedPressureIsThePointsOwn) {
  std::vector<bool> interior;
  const std::vector<core::SymTensor> a = stretched("standard", interior);
  const std::vector<core::SymTensor> b = stretched("mixed", interior);
  double scale = 0.0, worst = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!interior[i]) continue;
    ++n;
    scale = std::max(scale, std::abs(a[i].trace()));
    const core::SymTensor d = a[i] - b[i];
    for (double c : {d.xx, d.yy, d.zz, d.yz, d.xz, d.xy}) worst = std::max(worst, std::abs(c));
  }
  std::printf(
      "[ uniform stretch ] %d interior particles, |sigma_mixed - sigma_point| %.2e of "
      "|tr sigma| %.3e\n",
      n, worst / scale, scale);
  EXPECT_GE(n, 100);
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(worst, 1e-10 * scale);
}

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

double mode_velocity(double z, double length) {
  const double b = 1.8751, s = 0.7341, x = b * z / length;
  return 0.05 * (std::cosh(x) - std::cos(x) - s * (std::sinh(x) - std::sin(x)));
}

constexpr double beam_length = 4.0;

std::string beam_scene(const std::string& pressure, const std::string& shape, double cell) {
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
Particles beam_particles(const core::Scene& scene) {
  Particles p = generate_particles(scene);
  for (std::size_t i = 0; i < p.size(); ++i)
    p.velocity[i] = {mode_velocity(p.position[i].z, beam_length), 0, 0};
  return p;
}

Beam bend(const std::string& pressure, const std::string& shape, double cell) {
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
      std::map<std::array<int, 2>, std::pair<double, int>> cells;
      for (std::size_t i = 0; i < q.size(); ++i) {
        const Vec3& x0 = q.reference_position[i];
        auto& [sum, count] = cells[{static_cast<int>(std::floor((x0.x + 1.0) / cell)),
                                    static_cast<int>(std::floor(x0.z / cell))}];
        sum -= q.stress[i].trace() / 3.0;
        ++count;
      }
      double lo = 1e300, hi = -1e300, jump = 0.0;
      for (const auto& [c, v] : cells) {
        lo = std::min(lo, v.first / v.second);
        hi = std::max(hi, v.first / v.second);
      }
      for (const auto& [c, v] : cells) {
        double sum = 0.0;
        int n = 0;
        for (const std::array<int, 2> d : {std::array<int, 2>{c[0] - 1, c[1]},
                                           {c[0] + 1, c[1]},
                                           {c[0], c[1] - 1},
                                           {c[0], c[1] + 1}}) {
          const auto it = cells.find(d);
          if (it == cells.end()) continue;
          sum += it->second.first / it->second.second;
          ++n;
        }
        // Cells two from the clamped face are left out: its corners are singular.
        if (n == 4 && c[1] >= 2) jump = std::max(jump, std::abs(v.first / v.second - sum / n));
      }
      b.checkerboard = jump / (hi - lo);
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

// The reference: the same beam of B-bar hexahedra (`element = "full"`), 8 across the depth,
// the material elastic (at these strains the neo-Hookean solid is linear elastic with the same
// E and nu), the clamped face's nodes fixed and every node held in y.
double bend_hexahedra() {
  const std::string text =
      "[run]\nend_time = 100.0\n"
      "[materials.gel]\ndensity = 1100\nE = 17e6\nnu = 0.499\n"
      "[[bodies]]\nname = \"beam\"\nmaterial = \"gel\"\ndiscretisation = \"hexahedra\"\n"
      "element = \"full\"\n"
      "shape = { box = { min = [-0.5, 0, 0], max = [0.5, 0.5, 4] } }\n"
      "mesh = { divisions = [8, 1, 32] }\n"
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

// V8's locking case on a small scale: the point-wise pressure locks the nearly incompressible
// beam (its J must stay near 1 at every particle, which bending cannot do with these bases), so
// it vibrates too fast; the mixed pressure bends it at the hexahedra's period.
TEST(MixedPressure, ANearlyIncompressibleBeamBendsAtTheBbarPeriodWhereThePointWiseSchemeLocks) {
  const double reference = bend_hexahedra();
  std::printf("[ beam ] B-bar hexahedra, 8 across: period %.4f s\n", reference);
  ASSERT_GT(reference, 0.0);
  std::map<std::string, Beam> runs;
  for (const char* shape : {"linear", "bspline2"})
    for (const char* pressure : {"mixed", "standard"}) {
      const Beam b = bend(pressure, shape, 0.25);
      runs[std::string(shape) + " " + pressure] = b;
      std::printf(
          "[ beam ] %-8s %-8s period %.4f s (%+.2f %% of B-bar), pressure checkerboard "
          "%.3f of its range, energy drift %.2e\n",
          shape, pressure, b.period, 100.0 * (b.period / reference - 1.0), b.checkerboard,
          b.energy);
    }
  for (const char* shape : {"linear", "bspline2"}) {
    const Beam& mixed = runs[std::string(shape) + " mixed"];
    const Beam& point = runs[std::string(shape) + " standard"];
    EXPECT_NEAR(mixed.period / reference, 1.0, 0.03) << shape;
    EXPECT_LT(mixed.energy, 0.01) << shape;  // the projected pressure's work is booked
    // Locking: stiffer, so faster, by more than the mixed scheme's own error.
    EXPECT_LT(point.period / reference, 0.96) << shape;
  }
  EXPECT_LT(runs["linear standard"].period / reference, 0.7);
  // V8's mark for the paper's pairing (quadratic displacement, linear pressure). The linear
  // hat's pressure is one constant per cell, whose steps are its own (measured 0.059).
  EXPECT_LT(runs["bspline2 mixed"].checkerboard, 0.05);
}

// The projection's sums sweep colour layers in a fixed order: the same bits at 1 and 2 threads
// (tolerance 0), here on 8192 particles (every loop threaded).
TEST(MixedPressure, SameParticleBitsAtOneAndTwoThreads) {
  auto run = [](int threads) {
#ifdef _OPENMP
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    const core::Scene scene =
        core::parse_scene(beam_scene("mixed", "bspline2", 0.125), "beam.toml");
    MpmSolver solver(scene, beam_particles(scene));
    EXPECT_TRUE(core::worth_threads(solver.particles().size()));
    for (int k = 0; k < 100; ++k) solver.step(solver.stable_time_step());
#ifdef _OPENMP
    omp_set_num_threads(before);
#endif
    return solver.particles();
  };
  const Particles one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.stress.data(), two.stress.data(), one.size() * sizeof(core::SymTensor)),
            0);
  EXPECT_EQ(std::memcmp(one.position.data(), two.position.data(), one.size() * sizeof(Vec3)), 0);
  EXPECT_EQ(std::memcmp(one.energy.data(), two.energy.data(), one.size() * sizeof(double)), 0);
}

// Bad input: the mixed pressure with the updated-Lagrangian form (file, line and key), and
// with a material whose strength has no volumetric energy of its own (the material's key).
TEST(MixedPressure, WhatTheMixedPressureCannotReplaceIsRefused) {
  const std::string head =
      "[run]\nend_time = 1.0\n"
      "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [4, 4, 4]\n";
  const std::string body =
      "[[bodies]]\nname = \"block\"\nmaterial = \"m\"\n"
      "shape = { box = { min = [1, 1, 1], max = [3, 3, 3] } }\n";
  const std::string nh =
      "[materials.m]\ndensity = 1\nE = 1\nnu = 0.49\nstrength = { model = \"neo-hookean\" }\n";
  const std::string ul =
      head + "[mpm]\nshape_function = \"bspline2\"\npressure = \"mixed\"\n" + nh + body;
  std::string e = test::error_of(ul, "mixed.toml");
  for (const std::string& part :
       {"mixed.toml:" + std::to_string(test::line_of(ul, "pressure =")), std::string("pressure"),
        std::string("total-lagrangian"), std::string("\"standard\"")})
    EXPECT_NE(e.find(part), std::string::npos) << part << " in: " << e;
  const std::string tl =
      "[mpm]\nformulation = \"total-lagrangian\"\nshape_function = \"bspline2\"\n"
      "pressure = \"mixed\"\n";
  const std::string elastic = head + tl + "[materials.m]\ndensity = 1\nE = 1\nnu = 0.49\n" + body;
  e = test::checked_error_of(elastic, "mixed.toml");
  for (const std::string& part :
       {std::string("materials.m.strength"), std::string("no volumetric energy"),
        std::string("\"neo-hookean\" or \"mooney-rivlin\"")})
    EXPECT_NE(e.find(part), std::string::npos) << part << " in: " << e;
  EXPECT_NO_THROW(core::check_scene(core::parse_scene(head + tl + nh + body, "mixed.toml")));
  // A compressible solid is allowed, with a warning that the averaging softens it (the same
  // beam at nu = 0.3: +7.1 % of the B-bar period, one run).
  auto warnings = [&](const std::string& nu) {
    std::string text = head + tl + nh + body;
    text.replace(text.find("nu = 0.49"), 9, "nu = " + nu);
    std::string all;
    for (const core::SceneWarning& w :
         core::plausibility_warnings(core::parse_scene(text, "m.toml")))
      all += w.text() + "\n";
    return all;
  };
  const std::string soft = warnings("0.3");
  EXPECT_NE(soft.find("mpm.pressure"), std::string::npos) << soft;
  EXPECT_NE(soft.find("nu = 0.3"), std::string::npos) << soft;
  EXPECT_EQ(warnings("0.499").find("mpm.pressure"), std::string::npos);
}

}  // namespace
}  // namespace afemp::mpm
