// Plastic trusses in the implicit solves (core::small_strain_bar_update, the 1-D return map of
// Simo & Hughes 1998, sec. 1.4): its tangent against finite differences of the update, a bar
// pulled past yield against the bilinear (J2) and Johnson-Cook curves with Newton quadratic on
// the plastic steps, and a bar struck hard enough to yield in the Newmark solve against the
// energy balance of its closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "core/materials/small_strain_tangent.hpp"
#include "static_test_support.hpp"

namespace afemp::fem {
namespace {

constexpr double kLength = 2.0, kArea = 0.1;

// d sigma / d eps of the bar update by central differences (step 1e-9 of a strain of about
// 5e-3) against its tangent, loading from a virgin bar and from one hardened by an earlier
// plastic increment, in tension and compression: equal to 1e-6 of E (the differences'
// round-off is about 1e-16 E eps / 1e-9).
TEST(StaticTruss, BarTangentMatchesFiniteDifferences) {
  for (const core::Material& m : {test::j2_steel(2000.0), test::jc_steel()}) {
    const double e = m.youngs_modulus;
    for (double sign : {1.0, -1.0}) {
      for (double pre : {0.0, 3e-3}) {
        const core::SmallStrainBarResult r = core::small_strain_bar_update(m, {}, sign * pre);
        const core::SmallStrainBarPoint from{sign * pre, r.stress, r.plastic_strain};
        const double strain = sign * (pre + 5e-3), step = 1e-9;
        const core::SmallStrainBarResult at = core::small_strain_bar_update(m, from, strain);
        ASSERT_GT(at.plastic_strain, from.plastic_strain);
        const double fd = (core::small_strain_bar_update(m, from, strain + step).stress -
                           core::small_strain_bar_update(m, from, strain - step).stress) /
                          (2.0 * step);
        std::printf("bar tangent of '%s' (sign %+g, pre-strain %g): %.6g, differences %.6g\n",
                    m.name.c_str(), sign, pre, at.tangent, fd);
        EXPECT_LT(std::abs(fd - at.tangent), 1e-6 * e);
      }
    }
  }
}

// One truss along x of length 2 and area 0.1: node 0 held, node 1 free along the axis only,
// pulled (or pushed) by `force` in `steps` load steps.
struct Truss {
  MeshData mesh;
  StaticProblem problem;
  Truss(const core::Material& m, double force) {
    mesh.nodes = {{0, 0, 0}, {kLength, 0, 0}};
    mesh.lines = {{0, 1}};
    mesh.line_part = {0};
    mesh.line_area = {kArea};
    mesh.part_names = {"truss"};
    problem.mesh = &mesh;
    problem.materials = {m};
    for (int i = 0; i < 3; ++i) problem.prescribed.push_back({0, i, 0.0});
    for (int i = 1; i < 3; ++i) problem.prescribed.push_back({1, i, 0.0});
    problem.nodal_forces = {{}, {force, 0.0, 0.0}};
  }
  Truss(const Truss&) = delete;  // problem points at mesh
};

StaticResult pull_truss(const core::Material& m, double force, int steps, std::ostream* log) {
  const Truss truss(m, force);
  NewtonSettings settings;
  settings.load_steps = steps;
  settings.log = log;
  return solve_static(truss.problem, settings);
}

// The largest rho_{k+1} / rho_k^2 of the relative residuals rho of each step, over the
// iterations with rho_k < 1e-2 and rho_{k+1} above round-off (1e-14).
double quadratic_ratio(const std::vector<NewtonIteration>& iterations) {
  double worst = 0.0;
  for (std::size_t k = 0; k + 1 < iterations.size(); ++k) {
    const NewtonIteration &a = iterations[k], &b = iterations[k + 1];
    const double rho = a.residual / a.reference, next = b.residual / b.reference;
    if (a.load_step == b.load_step && rho < 1e-2 && next > 1e-14)
      worst = std::max(worst, next / (rho * rho));
  }
  return worst;
}

// J2 with linear hardening (sigma_y 250, H = 2000), force control at 0.5, 1.5 and 3 times the
// yield force and at -2 times it: the extension u = L sigma / E while elastic, and
// u = L (sigma / E + (|sigma| - sigma_y) / H) sign(sigma) past yield (the bilinear curve, whose
// slope after yield is E_t = E H / (E + H)), to 1e-10 of it, and the plastic strain
// (|sigma| - sigma_y) / H likewise. The curve is piecewise linear, so each plastic step is
// solved by two corrections, the elastic guess and then one with the exact tangent E_t, and a
// third at round-off meets the energy criterion.
TEST(StaticTruss, PulledPastYieldFollowsTheBilinearCurve) {
  const double hardening = 2000.0, yield = 250.0;
  const core::Material m = test::j2_steel(hardening);
  const double e = m.youngs_modulus;
  for (double k : {0.5, 1.5, 3.0, -2.0}) {
    const StaticResult r = pull_truss(m, k * yield * kArea, 3, nullptr);
    const double sigma = k * yield;
    const double plastic = std::max(std::abs(sigma) - yield, 0.0) / hardening;
    const double expected = kLength * (sigma / e + std::copysign(plastic, sigma));
    const double error = std::abs(r.displacement[1].x / expected - 1.0);
    int solves = 0;
    for (const NewtonIteration& it : r.iterations) solves = std::max(solves, it.iteration);
    std::printf(
        "J2 truss at %+.1f F_y: u = %.9g (closed form %.9g, error %.2e), eps_p %.6g, "
        "at most %d Newton solves a step\n",
        k, r.displacement[1].x, expected, error, r.line_plastic_strain[0], solves);
    EXPECT_LT(error, 1e-10);
    EXPECT_NEAR(r.line_stress[0], sigma, 1e-10 * yield);
    EXPECT_NEAR(r.line_plastic_strain[0], plastic, 1e-10 * std::max(plastic, 1e-3));
    EXPECT_LE(solves, 3);
  }
}

// Johnson-Cook steel (static_test_support.hpp: A 300, B 500, n 0.3 at 600 K, thermal factor
// theta = 0.806) pulled in one load step to 1.5 and 2.5 times the yield force A theta area:
// sigma = (A + B eps_p^n) theta gives eps_p = ((sigma / theta - A) / B)^(1/n), and
// u = L (sigma / E + eps_p), to 1e-9 (the residual tolerance 1e-10 over a tangent that falls
// to about E / 30). Newton from the elastic state: once the relative residual is below 1e-2,
// rho_{k+1} <= 10 rho_k^2 (the consistent tangent E H / (E + H)).
TEST(StaticTruss, JohnsonCookBarConvergesQuadraticallyOnItsCurve) {
  const core::Material m = test::jc_steel();
  const core::JohnsonCook& jc = std::get<core::JohnsonCook>(m.strength);
  const double theta = 1.0 - std::pow((600.0 - 293.0) / (1800.0 - 293.0), jc.m);
  for (double k : {1.5, 2.5}) {
    const double sigma = k * jc.A * theta;
    const double plastic = std::pow((sigma / theta - jc.A) / jc.B, 1.0 / jc.n);
    const double expected = kLength * (sigma / m.youngs_modulus + plastic);
    std::ostringstream log;
    const StaticResult r = pull_truss(m, sigma * kArea, 1, &log);
    std::printf("%s", log.str().c_str());
    const double error = std::abs(r.displacement[1].x / expected - 1.0);
    const double ratio = quadratic_ratio(r.iterations);
    std::printf(
        "JC truss at %.1f F_y: u = %.9g (closed form %.9g, error %.2e), eps_p %.6g "
        "(closed form %.6g), %zu rows, largest rho_k+1 / rho_k^2 %.3g\n",
        k, r.displacement[1].x, expected, error, r.line_plastic_strain[0], plastic,
        r.iterations.size(), ratio);
    EXPECT_LT(error, 1e-9);
    EXPECT_NEAR(r.line_plastic_strain[0] / plastic, 1.0, 1e-9);
    EXPECT_LT(ratio, 10.0);
    EXPECT_LE(r.iterations.size(), 12u);
  }
}

// The truss of J2 steel (sigma_y 250, H = 2000) under a force f A = 0.75 sigma_y A applied
// suddenly at rest: elastic, it would swing to 2 f = 1.5 sigma_y, so it yields once, to
// sigma_max = sigma_y + H eps_p, and then oscillates elastically about its new equilibrium
// without yielding again (between 2 f - sigma_max and sigma_max). At the peak (v = 0) the
// load's work equals the stored and the dissipated energy per unit volume:
// f (sigma_max / E + eps_p) = sigma_max^2 / 2E + (sigma_y + sigma_max) eps_p / 2, solved for
// eps_p by bisection. The trapezoidal rule at dt = T / 100 (T = 2 pi / omega, omega^2 =
// 3 E / (rho L^2), the consistent mass's) over 3 periods: eps_p within 0.5 % of it (measured
// 0.09 %: the steps that cross the yield point are integrated as trapezoids), and once past
// 1.5 periods (after the peak) KE + stored energy - f A u, which the rule conserves exactly on
// the linear branch, constant to 1e-10 of the load's work at the peak.
TEST(NewmarkTruss, SuddenlyLoadedBarYieldsOnceAsTheEnergyBalancePredicts) {
  const double hardening = 2000.0, yield = 250.0, f = 0.75 * yield;
  const core::Material m = test::j2_steel(hardening);
  const double e = m.youngs_modulus;
  auto surplus = [&](double eps_p) {  // work - stored - dissipated, falls with eps_p
    const double top = yield + hardening * eps_p;
    return f * (top / e + eps_p) - top * top / (2.0 * e) - 0.5 * (yield + top) * eps_p;
  };
  double lo = 0.0, hi = 2.0 * f / hardening;
  for (int i = 0; i < 200; ++i) (surplus(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double plastic = 0.5 * (lo + hi);

  const Truss truss(m, f * kArea);
  const double omega = std::sqrt(3.0 * e / (m.density * kLength * kLength));
  NewmarkSettings settings;
  settings.time_step = 2.0 * std::numbers::pi / omega / 100.0;
  settings.steps = 300;
  std::vector<double> u;
  settings.observe = [&](double, const std::vector<core::Vec3>& x) { u.push_back(x[1].x); };
  const NewmarkResult r = solve_newmark(truss.problem, settings);
  const double peak_work = f * kArea * kLength * ((yield + hardening * plastic) / e + plastic);
  double lo_energy = 1e300, hi_energy = -1e300;
  for (std::size_t n = 150; n < r.states.size(); ++n) {
    const double energy = r.states[n].kinetic_energy + r.states[n].strain_energy - f * kArea * u[n];
    lo_energy = std::min(lo_energy, energy);
    hi_energy = std::max(hi_energy, energy);
  }
  const double error = std::abs(r.line_plastic_strain[0] / plastic - 1.0);
  std::printf(
      "suddenly loaded truss: eps_p %.6g (energy balance %.6g, error %.2e), energy "
      "after the peak constant to %.2e of the peak work\n",
      r.line_plastic_strain[0], plastic, error, (hi_energy - lo_energy) / peak_work);
  EXPECT_LT(error, 0.005);
  EXPECT_LT(hi_energy - lo_energy, 1e-10 * peak_work);
}

}  // namespace
}  // namespace afemp::fem
