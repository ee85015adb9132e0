// Two-node truss kernels (fem/truss.hpp) against rigid-body motion, force balance and power,
// the two-mass spring frequency sqrt(2k/m) / (2 pi), energy conservation of a central-
// difference run, and a 90-degree rigid rotation that must leave the axial stress untouched.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "core/materials/uniaxial_update.hpp"
#include "fem/truss.hpp"

namespace afemp::fem {
namespace {

using core::Vec3;

// Steel-like, units mm ms g N MPa.
core::Material steel(core::StrengthModel strength = core::Elastic{}) {
  core::Material m;
  m.name = "steel";
  m.density = 7.85e-3;
  m.youngs_modulus = 2.0e5;
  m.poisson_ratio = 0.3;
  m.strength = strength;
  return m;
}

Vec3 unit(const Vec3& a) {
  return (1.0 / core::norm(a)) * a;
}

// A single bar between nodes a (0) and b (1): its material point and section.
struct Bar {
  core::Material material;
  double area0 = 0.0, length0 = 0.0;
  core::PointState point;
  double mass() const { return material.density * area0 * length0; }
};

struct ElementStep {
  std::array<Vec3, 2> force;  // nodal forces at the new configuration
  double axial_force = 0.0;
  double work = 0.0;  // 1/2 (sigma_old + sigma_new) d_eps V_old: the internal energy increment
};

// Element part of a central-difference step from x (time n) to x_new (n+1) with the half-step
// velocities v: strain increment at the mid-step configuration, uniaxial stress update,
// forces along the new axis with the mass-conserving area.
ElementStep element_step(Bar& bar, const std::array<Vec3, 2>& x, const std::array<Vec3, 2>& x_new,
                         const std::array<Vec3, 2>& v, double dt) {
  const TrussKinematics mid =
      truss_kinematics(0.5 * (x[0] + x_new[0]), 0.5 * (x[1] + x_new[1]), v[0], v[1]);
  const double d_eps = mid.axial_strain_rate * dt;
  const double sigma_old = bar.point.stress.xx;
  const double volume_old = bar.mass() / bar.point.density;
  core::uniaxial_update(bar.material, bar.point, d_eps, dt);
  const TrussKinematics now = truss_kinematics(x_new[0], x_new[1], v[0], v[1]);
  const double area =
      current_area(bar.area0, bar.length0, bar.material.density, now.length, bar.point.density);
  ElementStep s;
  s.axial_force = bar.point.stress.xx * area;
  add_truss_forces(now, s.axial_force, s.force[0], s.force[1]);
  s.work = 0.5 * (sigma_old + bar.point.stress.xx) * d_eps * volume_old;
  return s;
}

TEST(TrussKinematics, RigidRotationGivesNoStrainRate) {
  // Reference: v = v0 + w x x is rigid, so (vb - va).e = (w x (xb - xa)).e = 0; the rate
  // must vanish to 1e-14 of |w| while |vb - va| / L = |w| sin(angle).
  const Vec3 xa{0.3, -1.2, 2.0}, xb{-2.1, 0.7, 4.5};
  const Vec3 w{3.0, -1.0, 2.0}, v0{10.0, 5.0, -7.0};
  const TrussKinematics k =
      truss_kinematics(xa, xb, v0 + core::cross(w, xa), v0 + core::cross(w, xb));
  EXPECT_NEAR(k.axial_strain_rate, 0.0, 1e-14 * core::norm(w));
  EXPECT_NEAR(k.length, core::norm(xb - xa), 1e-15 * k.length);
  EXPECT_NEAR(core::norm(k.direction), 1.0, 1e-15);
}

TEST(TrussKinematics, StretchAlongArbitraryAxisGivesItsLogarithmicRate) {
  // Reference: v = v0 + w x x + lambda ((x - xa).e) e stretches the bar at d(ln L)/dt = lambda
  // whatever the rigid part; 1e-14 relative, direction = (xb - xa) / L to 1e-15.
  const Vec3 e = unit({1.0, -2.0, 0.5});
  const double length = 3.0, lambda = 0.37;
  const Vec3 xa{1.0, 2.0, 3.0};
  const Vec3 xb = xa + length * e;
  const Vec3 w{-0.4, 2.0, 1.1}, v0{3.0, 0.0, -1.0};
  auto velocity = [&](const Vec3& x) {
    return v0 + core::cross(w, x) + (lambda * core::dot(x - xa, e)) * e;
  };
  const TrussKinematics k = truss_kinematics(xa, xb, velocity(xa), velocity(xb));
  EXPECT_NEAR(k.axial_strain_rate, lambda, 1e-14 * lambda);
  EXPECT_NEAR(k.length, length, 1e-15 * length);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(k.direction[i], e[i], 1e-15);
}

TEST(TrussForces, BalanceAndTheirPowerIsAxialForceTimesStretchRate) {
  // Reference: f_a + f_b = 0 (the bar carries no net force; 1e-15 |N|) and the power the bar
  // absorbs, -(f_a.v_a + f_b.v_b), equals N L rate (1e-14 rel). Forces are added to what the
  // node already holds.
  const Vec3 xa{0.0, 1.0, -1.0}, xb{2.0, -0.5, 1.5}, va{0.2, -3.0, 1.0}, vb{4.0, 1.0, -0.5};
  const TrussKinematics k = truss_kinematics(xa, xb, va, vb);
  const double n = 1.7e3;
  const Vec3 fa0{1.0, 2.0, 3.0}, fb0{-4.0, 0.5, 0.0};
  Vec3 fa = fa0, fb = fb0;
  add_truss_forces(k, n, fa, fb);
  const Vec3 da = fa - fa0, db = fb - fb0;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(da[i] + db[i], 0.0, 1e-15 * n);
  EXPECT_NEAR(core::dot(da, k.direction), n, 1e-14 * n);  // tension pulls a towards b
  const double power = -(core::dot(da, va) + core::dot(db, vb));
  const double expected = n * k.length * k.axial_strain_rate;
  EXPECT_NEAR(power, expected, 1e-14 * std::abs(expected));
}

TEST(TrussSection, PlasticStretchKeepsVolumeAndElasticStretchContractsWithPoisson) {
  // Reference: A = A0 L0 rho0 / (L rho) with rho from the uniaxial update. Elastic stretch to
  // eps = Y/E: A / A0 = exp(-2 nu eps) to O(eps^2) (tol 1e-6). Then perfectly plastic
  // stretch to 20 %: plastic flow is isochoric, so A L keeps the value it had at yield
  // (1e-12 rel) while L grows by 20 %.
  const double yield = 250.0;
  const core::Material m = steel(core::J2Plasticity{yield, 0.0});
  core::PointState point;
  point.density = m.density;
  const double area0 = 10.0, length0 = 100.0;
  const int n_elastic = 25;
  const double d_eps = yield / m.youngs_modulus / n_elastic;
  for (int i = 0; i < n_elastic; ++i) core::uniaxial_update(m, point, d_eps, 1e-4);
  double length = length0 * std::exp(n_elastic * d_eps);
  const double area_yield = current_area(area0, length0, m.density, length, point.density);
  EXPECT_NEAR(area_yield / area0, std::exp(-2.0 * m.poisson_ratio * n_elastic * d_eps), 1e-6);
  const double volume_yield = area_yield * length;
  for (int i = 0; i < 200; ++i) {
    core::uniaxial_update(m, point, 1e-3, 1e-4);
    length *= std::exp(1e-3);
  }
  const double area = current_area(area0, length0, m.density, length, point.density);
  EXPECT_NEAR(area * length, volume_yield, 1e-12 * volume_yield);
  EXPECT_GT(length, 1.2 * length0);
}

TEST(TrussTimeStep, IsTheCentralDifferenceLimitOfTheLumpedTruss) {
  // Reference: two lumped masses m = rho A L / 2 on a spring k = E A / L have
  // omega = sqrt(2k/m) = 2c/L, and central differences are stable for omega dt <= 2, so the
  // limit dt = L / sqrt(E / rho) must give omega dt = 2 (1e-14 rel).
  const double length = 40.0, e = 2.0e5, rho = 7.85e-3, area = 3.0;
  const double dt = truss_time_step(length, e, rho);
  const double k = e * area / length, m = 0.5 * rho * area * length;
  EXPECT_NEAR(std::sqrt(2.0 * k / m) * dt, 2.0, 2e-14);
}

TEST(TrussDynamics, TwoMassAxialVibrationMatchesSpringFrequencyAndConservesEnergy) {
  // Reference: a free elastic truss with its lumped masses m = rho A L / 2 at both ends
  // vibrates at f = sqrt(2k/m) / (2 pi), k = E A / L (within 0.5 %; central differences at
  // 200 steps a period shift it by (omega dt)^2 / 24 = 4e-5), and kinetic + internal energy
  // (sum of 1/2 (sigma_old + sigma_new) d_eps V) stays within 1e-3 of the initial kinetic
  // energy. The internal energy equals the material's m e (1e-8 rel): the area rule and the
  // material's density agree. Axis oblique, strain amplitude 1e-5.
  Bar bar{steel(), 10.0, 100.0, {}};
  bar.point.density = bar.material.density;
  const Vec3 e = unit({2.0, 1.0, -2.0});
  const double m = 0.5 * bar.mass();
  const double k = bar.material.youngs_modulus * bar.area0 / bar.length0;
  const double omega = std::sqrt(2.0 * k / m);
  const double dt = 2.0 * std::numbers::pi / omega / 200.0;
  const double c = std::sqrt(bar.material.youngs_modulus / bar.material.density);
  const double v0 = 1e-5 * c;  // relative speed 2 v0 = omega * amplitude -> strain 1e-5

  std::array<Vec3, 2> x{Vec3{1.0, 2.0, 3.0}, Vec3{1.0, 2.0, 3.0} + bar.length0 * e};
  std::array<Vec3, 2> v{-v0 * e, v0 * e};  // v^{1/2} = v^0: no force at rest length
  const double kinetic0 = m * v0 * v0;
  double internal = 0.0, worst_energy_error = 0.0;
  double previous_stretch = 0.0, first_crossing = -1.0, last_crossing = 0.0;
  int crossings = 0;
  for (int step = 1; step <= 1000; ++step) {
    const std::array<Vec3, 2> x_new{x[0] + dt * v[0], x[1] + dt * v[1]};
    const ElementStep s = element_step(bar, x, x_new, v, dt);
    internal += s.work;
    std::array<Vec3, 2> v_new;
    for (int a = 0; a < 2; ++a) v_new[a] = v[a] + (dt / m) * s.force[a];
    double kinetic = 0.0;  // at time n+1, from the mean of the half-step velocities
    for (int a = 0; a < 2; ++a) {
      const Vec3 vn = 0.5 * (v[a] + v_new[a]);
      kinetic += 0.5 * m * core::dot(vn, vn);
    }
    worst_energy_error = std::max(worst_energy_error, std::abs(kinetic + internal - kinetic0));
    const double stretch = core::norm(x_new[1] - x_new[0]) - bar.length0;
    if (previous_stretch < 0.0 && stretch >= 0.0) {  // upward crossing, interpolated
      const double t = (step - 1 + previous_stretch / (previous_stretch - stretch)) * dt;
      if (first_crossing < 0.0) first_crossing = t;
      last_crossing = t;
      ++crossings;
    }
    previous_stretch = stretch;
    x = x_new;
    v = v_new;
  }
  ASSERT_GE(crossings, 4);
  const double frequency = (crossings - 1) / (last_crossing - first_crossing);
  const double expected = omega / (2.0 * std::numbers::pi);
  EXPECT_NEAR(frequency, expected, 5e-3 * expected);
  EXPECT_LT(worst_energy_error, 1e-3 * kinetic0);
  EXPECT_NEAR(internal, bar.mass() * bar.point.energy, 1e-8 * kinetic0);
}

TEST(TrussDynamics, RigidRotationThroughNinetyDegreesKeepsAxialStress) {
  // Reference: a bar turned rigidly by 90 degrees about an oblique axis through its centre in
  // 2000 prescribed steps (nodes on the circle, v = (x_new - x) / dt) has no axial strain
  // rate, so an unstressed bar stays unstressed and a prestressed one keeps sigma0, both to
  // 1e-8 E, and the axial force turns with the bar: N = sigma0 A0 along e_end on node a,
  // orthogonal to the initial axis (1e-8 E A0).
  const Vec3 axis = unit({1.0, 1.0, 1.0});
  const Vec3 e0 = unit({1.0, -1.0, 0.0});  // perpendicular to the rotation axis
  const Vec3 centre{5.0, -3.0, 2.0};
  const double half = 50.0;
  for (const double sigma0 : {0.0, 120.0}) {
    Bar bar{steel(), 10.0, 2.0 * half, {}};
    bar.point.density = bar.material.density;
    bar.point.stress.xx = sigma0;
    auto positions = [&](double angle) {
      // Rodrigues: e0 is perpendicular to the axis, so e = cos e0 + sin (axis x e0).
      const Vec3 e = std::cos(angle) * e0 + std::sin(angle) * core::cross(axis, e0);
      return std::array<Vec3, 2>{centre - half * e, centre + half * e};
    };
    const int steps = 2000;
    const double dt = 1e-4, d_angle = 0.5 * std::numbers::pi / steps;
    std::array<Vec3, 2> x = positions(0.0);
    ElementStep s;
    for (int i = 1; i <= steps; ++i) {
      const std::array<Vec3, 2> x_new = positions(i * d_angle);
      const std::array<Vec3, 2> v{(1.0 / dt) * (x_new[0] - x[0]), (1.0 / dt) * (x_new[1] - x[1])};
      s = element_step(bar, x, x_new, v, dt);
      x = x_new;
      ASSERT_NEAR(bar.point.stress.xx, sigma0, 1e-8 * bar.material.youngs_modulus) << i;
    }
    const double force_tolerance = 1e-8 * bar.material.youngs_modulus * bar.area0;
    const Vec3 e_end = unit(x[1] - x[0]);
    EXPECT_NEAR(core::dot(e_end, e0), 0.0, 1e-12);
    EXPECT_NEAR(s.axial_force, sigma0 * bar.area0, force_tolerance);
    EXPECT_NEAR(core::dot(s.force[0], e0), 0.0, force_tolerance);
    EXPECT_NEAR(core::dot(s.force[0], e_end), s.axial_force, force_tolerance);
  }
}

}  // namespace
}  // namespace afemp::fem
