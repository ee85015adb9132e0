// Plate impact of boron carbide with JH-2 (label `validation`, under a second):
// examples/b4c_plate_impact/scene.toml, a 15 mm column of one-point hexahedra (0.025 mm) in
// uniaxial strain at 1000 m/s on a rigid wall, B4C on B4C at 2000 m/s by symmetry. Gauge
// elements 5 and 7.5 mm from the wall record the axial stress -(p + 2/3 q) and the velocity.
// Source: the JH-2 constants of B4C as the Altair Radioss Reference Guide (2021), /MAT/LAW79
// (JOHN_HOLM), "Input Example" table, tabulates them from Johnson & Holmquist's boron carbide
// paper (its reference [2], not read here): rho 2510 kg/m^3, G 197 GPa, A 0.927, B 0.70,
// C 0.005, M 0.85, N 0.67, SFMAX 0.2, T 0.26 GPa, HEL 19.0 GPa, PHEL 8.71 GPa, D1 0.001,
// D2 0.5, K1 233, K2 -593, K3 2800 GPa; beta is not in the table (1, afemp's default).
// The wave at the gauge: the elastic precursor rises to the HEL, the B4C fractures there at
// once (D1 = 0.001: D = 1 within a step) and its stress collapses to about 10 GPa, rising to
// about 13 GPa before the plastic wave brings the material to rest at about 27.5 GPa.
// Checks, with why the tolerances are what they are:
//  * the precursor's peak against the published HEL, 19.0 GPa, 5 %: the constants are
//    consistent with their own HEL only to about 2 % (the elastic path reaches
//    sigma_HEL = 3/2 (HEL - PHEL) at 8.54 GPa, not PHEL 8.71), and C = 0.005 moves the yield
//    by about 1.5 % per decade of the front's strain rate, which the mesh and the bulk
//    viscosity set (printed beside it: the constants' own yield in uniaxial strain at
//    1e6 1/s, one point driven through the library's update);
//  * the state behind the plastic wave against momentum across it, sigma2 = sigma_a +
//    rho0 U (u2 - u_a), from the state just ahead of it and its Lagrangian speed U between the
//    gauges, 2 % (the front spreads over a few elements; its times are read at one level);
//  * the particle velocity jump, 1 % (the wall stops the column), and the strength behind the
//    wave, the published cap SFMAX sigma_HEL once D = 1, 2 %.
// No measured B4C Hugoniot points were reachable here, so the shocked state is checked against
// the jump conditions and the published strength cap, not against an experiment
// (docs/validation.md, V11).
// Measured (600 hexahedra, 1041 steps, 2 threads, 0.29 s on the 2-core machine, 8-12 s while other
// builds ran): precursor peak 19.41 GPa (+2.1 %; the constants' own yield at 1e6 1/s 18.65 GPa),
// ahead of the plastic wave 12.85 GPa at 381 m/s, behind it 27.48 GPa at 999.5 m/s against 27.40
// GPa from momentum with its speed 9378 m/s (+0.3 %), strength behind 3066 MPa against 3087 MPa.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "analysis/reference_checks.hpp"
#include "core/materials/material.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "example_text.hpp"
#include "fem/fe_model.hpp"

namespace afemp::fem {
namespace {

constexpr double kPublishedHel = 19.0e3;  // MPa
constexpr double kJump = 1000.0;          // m/s: the column's speed onto the wall

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::numeric_limits<double>::quiet_NaN() : v[v.size() / 2];
}

// The constants' own HEL: the axial stress (compression positive) at which one point,
// compressed in uniaxial strain along z at the steady rate `rate` (1/ms) through the library's
// update, first yields.
double uniaxial_yield(const core::Material& m, double rate, double d_strain) {
  const auto& strength = std::get<core::JohnsonHolmquist2>(m.strength);
  const auto& eos = std::get<core::Jh2Pressure>(m.eos);
  core::PointState p;
  p.density = m.density;
  for (double e = d_strain; e < 0.2; e += d_strain) {
    const double rho_new = m.density / (1.0 - e);
    const double d_vol = p.density / rho_new - 1.0;  // the volume change the solvers pass
    p.density = rho_new;
    core::constitutive_update(m, strength, eos, false, p, {0.0, 0.0, d_vol, 0.0, 0.0, 0.0},
                              d_strain / rate);
    if (p.plastic_strain > 0.0) return -p.stress.zz;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// The axial stress (compression positive) and velocity at a gauge, and the time its stress
// first reaches `level`, interpolated between samples.
struct Gauge {
  std::vector<double> time, stress, vz;
  double first_at(double level) const {
    for (std::size_t i = 1; i < time.size(); ++i)
      if (stress[i] >= level)
        return time[i - 1] +
               (time[i] - time[i - 1]) * (level - stress[i - 1]) / (stress[i] - stress[i - 1]);
    return std::numeric_limits<double>::quiet_NaN();
  }
  // The medians of the stress and the velocity over the times in (from, to).
  std::pair<double, double> state(double from, double to) const {
    std::vector<double> s, v;
    for (std::size_t i = 0; i < time.size(); ++i)
      if (time[i] > from && time[i] < to) {
        s.push_back(stress[i]);
        v.push_back(vz[i]);
      }
    return {median(s), median(v)};
  }
};

Gauge gauge(const core::ProbeSeries& g) {
  const int p = g.column("pressure"), q = g.column("von_mises"), vz = g.column("vz");
  Gauge r;
  for (std::size_t i = 0; i < g.rows(); ++i) {
    r.time.push_back(g.time[i]);
    r.stress.push_back(g.at(i, p) + 2.0 / 3.0 * g.at(i, q));
    r.vz.push_back(g.at(i, vz));
  }
  return r;
}

TEST(B4cPlateImpact, PrecursorPeaksAtThePublishedHelAndTheShockedStateKeepsMomentum) {
  const std::string path = "b4c_plate_impact/scene.toml";
  const core::Scene scene = core::parse_scene(test::example_text(path), path);
  FeModel model(scene);
  const core::RunSummary s = analysis::run(model, scene, {});
  ASSERT_EQ(s.probes.size(), 2u);
  const Gauge near = gauge(s.probes[0]), far = gauge(s.probes[1]);
  const double x_near = 5.0125, x_far = 7.5125;  // mm, the gauges' Lagrangian depths

  // The plastic wave: where the stress passes 1.15 HEL (it rises from about 13 to 27.5 GPa).
  const double level = 1.15 * kPublishedHel;
  const double t_near = near.first_at(level), t_far = far.first_at(level);
  const double t_elastic = far.first_at(0.5 * kPublishedHel);
  ASSERT_TRUE(t_elastic < t_far && t_near < t_far) << t_elastic << " " << t_near << " " << t_far;
  const double settle = 1.5e-4;  // ms: the plastic front has passed the far gauge
  ASSERT_LT(t_far + settle, s.time);

  double hel = 0.0;  // the precursor's peak, before the plastic wave
  for (std::size_t i = 0; i < far.time.size() && far.time[i] < t_far - 1e-4; ++i)
    hel = std::max(hel, far.stress[i]);
  const auto [sigma_a, v_a] = far.state(t_far - 6e-5, t_far - 3e-5);  // just ahead of it
  const auto [sigma2, v2] = far.state(t_far + settle, s.time);        // behind it
  std::vector<double> behind_q;
  const int q = s.probes[1].column("von_mises");
  for (std::size_t i = 0; i < far.time.size(); ++i)
    if (far.time[i] > t_far + settle) behind_q.push_back(s.probes[1].at(i, q));
  const double q2 = median(behind_q);

  const core::Material& b4c = scene.materials.at(0);
  const auto& jh2 = std::get<core::JohnsonHolmquist2>(b4c.strength);
  const double own_hel = uniaxial_yield(b4c, 1e3, 2e-6);  // 1e6 1/s in 1/ms
  const double cap = jh2.max_fractured_strength * jh2.hel_strength();
  // Velocities in the column's frame (it came at -1000 m/s): u = vz + 1000.
  const double u_a = v_a + kJump, u2 = v2 + kJump;
  const double speed = (x_far - x_near) / (t_far - t_near);  // mm/ms = m/s
  const double momentum = sigma_a + b4c.density * speed * (u2 - u_a);

  std::printf(
      "B4C plate impact (JH-2, 2000 m/s symmetric), %zu hexahedra, %ld steps, %.2f s, %d "
      "threads:\n"
      "  precursor peak %.0f MPa against the published HEL %.0f MPa (%+.2f %%); the "
      "constants' own yield at 1e6 1/s %.0f MPa\n"
      "  ahead of the plastic wave %.0f MPa at %.1f m/s; behind it %.0f MPa at %.1f m/s, "
      "against momentum with its speed %.0f m/s: %.0f MPa (%+.2f %%)\n"
      "  particle velocity jump %.1f m/s (%.0f); strength behind %.1f MPa against SFMAX "
      "sigma_HEL %.1f MPa (%+.2f %%)\n",
      s.elements, s.steps, s.wall_seconds, core::thread_count(), hel, kPublishedHel,
      100.0 * (hel / kPublishedHel - 1.0), own_hel, sigma_a, u_a, sigma2, u2, speed, momentum,
      100.0 * (sigma2 / momentum - 1.0), u2, kJump, q2, cap, 100.0 * (q2 / cap - 1.0));
  EXPECT_NEAR(hel, kPublishedHel, 0.05 * kPublishedHel);
  EXPECT_NEAR(sigma2, momentum, 0.02 * momentum);
  EXPECT_NEAR(u2, kJump, 0.01 * kJump);
  EXPECT_NEAR(q2, cap, 0.02 * cap);
}

}  // namespace
}  // namespace afemp::fem
