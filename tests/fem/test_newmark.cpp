// Implicit dynamics (fem/static_solve.hpp, solve_newmark): an elastic bar released from its
// static deflection under an end force. The trapezoidal rule conserves its energy to round-off
// and gives its lowest mode the period that the rule's exact phase error predicts; HHT-alpha
// dissipates. A single truss oscillates as its consistent mass predicts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "static_test_support.hpp"

namespace afemp::fem {
namespace {

// A bar 10 x 1 x 1 of 20 elements along x, nu = 0 and every lateral component held (which then
// takes no force): the discrete system is exactly the 1-D bar of linear elements with the
// consistent mass. Its end x = 0 is held; `end_force` pulls on x = 10.
struct Bar {
  static constexpr double length = 10.0;
  static constexpr int elements = 20;
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {length, 1, 1}}, {elements, 1, 1});
  core::Material material = test::steel();
  StaticProblem problem(double end_force) const {
    StaticProblem p;
    p.mesh = &mesh;
    p.materials = {material};
    for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
      for (int i = 1; i < 3; ++i) p.prescribed.push_back({static_cast<std::int32_t>(n), i, 0.0});
    for (std::int32_t n : test::node_set(mesh, "xmin")) p.prescribed.push_back({n, 0, 0.0});
    if (end_force != 0.0) {
      p.nodal_forces.assign(mesh.nodes.size(), core::Vec3{});
      for (std::int32_t n : test::node_set(mesh, "xmax")) p.nodal_forces[n].x = end_force / 4.0;
    }
    return p;
  }
  Bar() { material.poisson_ratio = 0.0; }
};

double total(const NewmarkState& s) {
  return s.kinetic_energy + s.strain_energy;
}

// Released from the static deflection of an end force of 100, dt = T_1 / 100 for 600 steps.
// Energy (kinetic + strain) constant to 1e-10 of itself at every step (the trapezoidal rule
// conserves it exactly for a linear system). The lowest mode's coordinate q = phi_1 . M u,
// phi_1 = sin(k x), k = pi / 2L, evolves as its own oscillator (the discrete modes are
// M-orthogonal and the rule is linear), so q_{n+1} + q_{n-1} = 2 cos(Omega dt) q_n exactly:
// Omega by least squares over the steps. Reference: the mode's discrete frequency, linear
// elements with consistent mass, omega_h^2 = (6 c^2 / h^2) (1 - cos kh) / (2 + cos kh)
// (within 3e-4 of the bar's pi c / 2L), and the trapezoidal rule's phase,
// Omega dt = 2 atan(omega_h dt / 2) (Hughes 2000, sec. 9.1.3: period elongation about
// (omega dt)^2 / 12, here 3.3e-4): the measured period equal to that to 1e-9.
TEST(Newmark, TrapezoidalRuleConservesEnergyAndMatchesItsPeriodError) {
  const Bar bar;
  const StaticResult deflected = solve_static(bar.problem(100.0));
  const double c = std::sqrt(bar.material.youngs_modulus / bar.material.density);
  const double h = Bar::length / Bar::elements, k = 0.5 * std::numbers::pi / Bar::length;
  const double omega = k * c;
  const double omega_h =
      std::sqrt(6.0 * c * c / (h * h) * (1.0 - std::cos(k * h)) / (2.0 + std::cos(k * h)));
  const double dt = 2.0 * std::numbers::pi / omega_h / 100.0;

  // q = phi . M u with the 1-D consistent mass (rho A h / 6) [2 1; 1 2] per element: the nodes
  // of each cross-section carry a quarter of it.
  std::vector<double> q;
  NewmarkSettings settings;
  settings.time_step = dt;
  settings.steps = 600;
  settings.initial_displacement = deflected.displacement;
  settings.observe = [&](double, const std::vector<core::Vec3>& u) {
    std::vector<double> ux(Bar::elements + 1, 0.0);
    for (std::size_t n = 0; n < bar.mesh.nodes.size(); ++n)
      ux[static_cast<int>(std::lround(bar.mesh.nodes[n].x / h))] += 0.25 * u[n].x;
    double s = 0.0;
    for (int e = 0; e < Bar::elements; ++e) {
      const double pa = std::sin(k * e * h), pb = std::sin(k * (e + 1) * h);
      s += h / 6.0 * (pa * (2.0 * ux[e] + ux[e + 1]) + pb * (ux[e] + 2.0 * ux[e + 1]));
    }
    q.push_back(s);
  };
  const NewmarkResult r = solve_newmark(bar.problem(0.0), settings);

  const double e0 = total(r.states.front());
  double drift = 0.0;
  for (const NewmarkState& s : r.states) drift = std::max(drift, std::abs(total(s) / e0 - 1.0));
  double num = 0.0, den = 0.0;
  for (std::size_t n = 1; n + 1 < q.size(); ++n) {
    num += q[n] * (q[n + 1] + q[n - 1]);
    den += 2.0 * q[n] * q[n];
  }
  const double period = 2.0 * std::numbers::pi * dt / std::acos(num / den);
  const double expected = std::numbers::pi * dt / std::atan(0.5 * omega_h * dt);
  const double t_h = 2.0 * std::numbers::pi / omega_h;
  std::printf(
      "trapezoidal bar: energy drift %.2e over %d steps; omega_h / omega - 1 = %.2e; period "
      "%.9g, expected %.9g (elongation %.3e, (omega dt)^2/12 = %.3e): relative error %.2e\n",
      drift, settings.steps, omega_h / omega - 1.0, period, expected, period / t_h - 1.0,
      std::pow(omega_h * dt, 2) / 12.0, period / expected - 1.0);
  EXPECT_LT(drift, 1e-10);
  EXPECT_LT(omega_h / omega - 1.0, 3e-4);
  EXPECT_LT(std::abs(period / expected - 1.0), 1e-9);
}

// HHT with alpha = -0.1, the same release: the energy (kinetic + strain) is not a Lyapunov
// function of the HHT step, so it may rise within a period, but its largest value over each
// period T_1 (100 steps) falls from period to period, never above the initial energy (to
// 1e-12 of it), and 600 steps lose more than 1 % of it, the higher modes that the release
// excites being damped (Hilber, Hughes & Taylor 1977).
TEST(Newmark, HhtAlphaDissipates) {
  const Bar bar;
  const StaticResult deflected = solve_static(bar.problem(100.0));
  const double c = std::sqrt(bar.material.youngs_modulus / bar.material.density);
  NewmarkSettings settings;
  settings.time_step = 4.0 * Bar::length / c / 100.0;  // T_1 / 100
  settings.steps = 600;
  settings.alpha = -0.1;
  settings.initial_displacement = deflected.displacement;
  const NewmarkResult r = solve_newmark(bar.problem(0.0), settings);
  const double e0 = total(r.states.front());
  std::vector<double> peak(6, 0.0);  // the largest energy of each period
  for (std::size_t n = 1; n < r.states.size(); ++n)
    peak[(n - 1) / 100] = std::max(peak[(n - 1) / 100], total(r.states[n]) / e0);
  const double loss = 1.0 - total(r.states.back()) / e0;
  std::printf("HHT alpha -0.1: energy lost %.3f %% in %d steps; peaks per period / E0:",
              100.0 * loss, settings.steps);
  for (double p : peak) std::printf(" %.6f", p);
  std::printf("\n");
  EXPECT_LT(peak[0], 1.0 + 1e-12);
  for (std::size_t k = 1; k < peak.size(); ++k) EXPECT_LT(peak[k], peak[k - 1]) << "period " << k;
  EXPECT_GT(loss, 0.01);
}

// One truss (a line of length 2, area 0.1, no hexahedra), its node 0 held and node 1 free along
// the axis only: a single oscillator of stiffness E A / L and consistent mass rho A L / 3,
// omega^2 = 3 E / (rho L^2). Released from u = 1e-3 with dt = T / 50 for 200 steps: the
// trapezoidal rule keeps its energy, E A u^2 / 2L at the start, to 1e-10, and u_n =
// u_0 cos(n Omega dt), Omega dt = 2 atan(omega dt / 2), to 1e-9 of u_0.
TEST(Newmark, TrussOscillatesWithItsConsistentMass) {
  const double length = 2.0, area = 0.1, u0 = 1e-3;
  MeshData mesh;
  mesh.nodes = {{0, 0, 0}, {length, 0, 0}};
  mesh.lines = {{0, 1}};
  mesh.line_part = {0};
  mesh.line_area = {area};
  mesh.part_names = {"truss"};
  const core::Material m = test::steel();
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m};
  for (int i = 0; i < 3; ++i) problem.prescribed.push_back({0, i, 0.0});
  for (int i = 1; i < 3; ++i) problem.prescribed.push_back({1, i, 0.0});
  const double omega = std::sqrt(3.0 * m.youngs_modulus / (m.density * length * length));
  NewmarkSettings settings;
  settings.time_step = 2.0 * std::numbers::pi / omega / 50.0;
  settings.steps = 200;
  settings.initial_displacement = {{0, 0, 0}, {u0, 0, 0}};
  const double phase = 2.0 * std::atan(0.5 * omega * settings.time_step);
  double error = 0.0;
  int step = 0;
  settings.observe = [&](double, const std::vector<core::Vec3>& u) {
    error = std::max(error, std::abs(u[1].x - u0 * std::cos(step * phase)) / u0);
    ++step;
  };
  const NewmarkResult r = solve_newmark(problem, settings);
  const double e0 = 0.5 * m.youngs_modulus * area * u0 * u0 / length;
  double drift = 0.0;
  for (const NewmarkState& s : r.states) drift = std::max(drift, std::abs(total(s) / e0 - 1.0));
  std::printf("truss oscillator: energy drift %.2e, displacement error %.2e of u0\n", drift, error);
  EXPECT_EQ(step, settings.steps + 1);
  EXPECT_LT(drift, 1e-10);
  EXPECT_LT(error, 1e-9);
}

}  // namespace
}  // namespace afemp::fem
