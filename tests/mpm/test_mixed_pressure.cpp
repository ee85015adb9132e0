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
#include "mixed_beam.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "scene_errors.hpp"

namespace afemp::mpm {
namespace {

using core::Vec3;
using test::mixed_beam::Beam;
using test::mixed_beam::beam_particles;
using test::mixed_beam::beam_scene;
using test::mixed_beam::bend;
using test::mixed_beam::bend_hexahedra;

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
        std::string("\"neo-hookean\" with form = \"split\" or \"mooney-rivlin\"")})
    EXPECT_NE(e.find(part), std::string::npos) << part << " in: " << e;
  // The neo-Hookean log form's volumetric energy is not K / 2 (J - 1)^2.
  std::string log_form = head + tl + nh + body;
  log_form.replace(log_form.find("model = \"neo-hookean\""), 22,
                   "model = \"neo-hookean\", form = \"log\"");
  e = test::checked_error_of(log_form, "mixed.toml");
  for (const std::string& part : {std::string("materials.m.strength"), std::string("log form"),
                                  std::string("form = \"split\"")})
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
