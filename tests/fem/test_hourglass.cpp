// Flanagan-Belytschko hourglass control: the shape vectors ignore every linear field, the
// viscous form opposes and dissipates hourglass motion, and the stiffness form stores it as an
// elastic oscillation of a single lumped-mass cube (central differences, closed-form period).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fem/hourglass.hpp"
#include "hexahedron_test_support.hpp"

namespace afemp::fem {
namespace {

using test::cube;
using test::distorted_hex;
using test::linear_field;

constexpr int kSeeds = 20;

// Steel-like constants; the tests only need them to be realistic, not exact.
constexpr double kDensity = 7850.0;
constexpr double kWaveSpeed = 5900.0;
constexpr double kModulus = kDensity * kWaveSpeed * kWaveSpeed;  // lambda + 2 mu = rho c^2

HourglassModes modes_of(const HexVectors& x) {
  return hourglass_modes(one_point_hex(x), x);
}

// v_a = amplitude h_k,a e_i: hourglass mode k in direction i.
HexVectors mode_velocity(int k, int i, double amplitude) {
  HexVectors v{};
  for (int a = 0; a < 8; ++a) v[a][i] = amplitude * kHourglassBase[k][a];
  return v;
}

double nodal_power(const HexVectors& f, const HexVectors& v) {
  double p = 0.0;
  for (int a = 0; a < 8; ++a) p += core::dot(f[a], v[a]);
  return p;
}

double max_norm(const HexVectors& f) {
  double m = 0.0;
  for (const core::Vec3& fa : f) m = std::max(m, core::norm(fa));
  return m;
}

TEST(Hourglass, GammaVectorsAreOrthogonalToLinearFields) {
  // Reference: sum_a gamma_k,a = 0 and sum_a gamma_k,a x_a,i = 0 (FB's construction, using
  // linear completeness of the B vectors), to 1e-12 on 20 distorted elements; on a cube, a
  // parallelepiped, gamma_k = h_k exactly (1e-15).
  for (int seed = 0; seed < kSeeds; ++seed) {
    const HexVectors x = distorted_hex(seed);
    const HourglassModes m = modes_of(x);
    for (int k = 0; k < 4; ++k) {
      double sum = 0.0;
      core::Vec3 moment;
      for (int a = 0; a < 8; ++a) {
        sum += m.gamma[k][a];
        moment += m.gamma[k][a] * x[a];
      }
      EXPECT_NEAR(sum, 0.0, 1e-12) << "seed " << seed << " mode " << k;
      EXPECT_LT(core::norm(moment), 1e-12) << "seed " << seed << " mode " << k;
    }
  }
  const HourglassModes cube_modes = modes_of(cube(0.3));
  for (int k = 0; k < 4; ++k)
    for (int a = 0; a < 8; ++a) EXPECT_NEAR(cube_modes.gamma[k][a], kHourglassBase[k][a], 1e-15);
}

TEST(Hourglass, LinearVelocityFieldsIncludingRigidMotionGiveNoForce) {
  // Reference: a linear field (here a general one and a rigid rotation plus translation) has no
  // hourglass velocity, so neither form produces a force: below 1e-12 of the force a unit
  // hourglass velocity produces, on 20 distorted elements.
  std::mt19937 rng(31);
  for (int seed = 0; seed < kSeeds; ++seed) {
    const HexVectors x = distorted_hex(seed);
    const OnePointHex e = one_point_hex(x);
    const HourglassModes m = hourglass_modes(e, x);
    HexVectors reference{};
    add_hourglass_viscous(m, mode_velocity(0, 0, 1.0), kDefaultViscousHourglass, kDensity,
                          kWaveSpeed, e.volume, reference);
    const double scale = max_norm(reference);
    // The spin of the rotation about (0.3, -0.8, 0.5).
    const core::Mat3 w{{{0.0, -0.5, -0.8}, {0.5, 0.0, -0.3}, {0.8, 0.3, 0.0}}};
    for (const HexVectors& v : {linear_field(x, test::random_mat(rng), test::random_vec(rng)),
                                linear_field(x, w, test::random_vec(rng))}) {
      HexVectors f{};
      std::array<core::Vec3, 4> q{};
      add_hourglass_viscous(m, v, kDefaultViscousHourglass, kDensity, kWaveSpeed, e.volume, f);
      EXPECT_LT(max_norm(f), 1e-12 * scale) << "seed " << seed;
      // One Courant step of the unit element: k_h dt is then of the order of a_h.
      const double dt = 1.0 / kWaveSpeed;
      add_hourglass_stiffness(m, v, kDefaultStiffnessHourglass, kModulus, e.volume, dt, q, f);
      EXPECT_LT(max_norm(f), 1e-12 * scale) << "seed " << seed;
    }
  }
}

TEST(Hourglass, ViscousForceOnACubeMatchesTheClosedForm) {
  // Reference: on a cube of edge h, gamma_1 = h_1 and h_1 . h_1 = 8, so v_a = u h_1,a e_x gives
  // q_1x = 8 u and f_a = -a_h 8 u h_1,a e_x with a_h = Q_hg rho c h^2 / 4 (LS-DYNA), absorbing
  // the power a_h (8 u)^2; relative tolerance 1e-13.
  const double h = 0.02, u = 3.0;
  const HexVectors x = cube(h);
  const OnePointHex e = one_point_hex(x);
  const HexVectors v = mode_velocity(0, 0, u);
  HexVectors f{};
  const double power = add_hourglass_viscous(hourglass_modes(e, x), v, kDefaultViscousHourglass,
                                             kDensity, kWaveSpeed, e.volume, f);
  const double a_h = kDefaultViscousHourglass * kDensity * kWaveSpeed * h * h / 4.0;
  for (int a = 0; a < 8; ++a) {
    const double expected = -a_h * 8.0 * u * kHourglassBase[0][a];
    EXPECT_NEAR(f[a].x, expected, 1e-13 * std::abs(expected));
    EXPECT_NEAR(f[a].y, 0.0, 1e-13 * std::abs(expected));
    EXPECT_NEAR(f[a].z, 0.0, 1e-13 * std::abs(expected));
  }
  EXPECT_NEAR(power, a_h * 64.0 * u * u, 1e-13 * a_h * 64.0 * u * u);
}

TEST(Hourglass, ViscousForceOpposesEveryHourglassModeOnADistortedElement) {
  // Reference: the viscous forces' power is -a_h sum q^2 < 0 for any hourglass velocity; for each
  // of the 4 modes in each of the 3 directions on 20 distorted elements the nodal power is
  // negative and equals minus the returned absorbed power (relative 1e-12).
  for (int seed = 0; seed < kSeeds; ++seed) {
    const HexVectors x = distorted_hex(seed);
    const OnePointHex e = one_point_hex(x);
    const HourglassModes m = hourglass_modes(e, x);
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) {
        const HexVectors v = mode_velocity(k, i, 1.0);
        HexVectors f{};
        const double absorbed = add_hourglass_viscous(m, v, kDefaultViscousHourglass, kDensity,
                                                      kWaveSpeed, e.volume, f);
        EXPECT_LT(nodal_power(f, v), 0.0) << "seed " << seed << " mode " << k;
        EXPECT_NEAR(nodal_power(f, v), -absorbed, 1e-12 * absorbed);
      }
  }
}

TEST(Hourglass, StiffnessForceGrowsLinearlyWithHourglassDisplacement) {
  // Reference: at constant hourglass velocity u h_2 e_y on a cube of edge h, after n steps
  // Q_2y = k_h 8 u n dt with k_h = Q_hg (lambda + 2 mu) (sum b.b) / (3V) = Q_hg M h / 2
  // (sum b.b = 3 h^4 / 2), so f_a = -Q_2y h_2,a e_y: n times the first step's force, 1e-13.
  const double h = 0.01, u = 0.5, dt = 1e-7;
  const HexVectors x = cube(h);
  const OnePointHex e = one_point_hex(x);
  const HourglassModes m = hourglass_modes(e, x);
  const HexVectors v = mode_velocity(1, 1, u);
  const double k_h = kDefaultStiffnessHourglass * kModulus * h / 2.0;
  std::array<core::Vec3, 4> q{};
  for (int n = 1; n <= 10; ++n) {
    HexVectors f{};
    add_hourglass_stiffness(m, v, kDefaultStiffnessHourglass, kModulus, e.volume, dt, q, f);
    const double generalised = k_h * 8.0 * u * n * dt;
    EXPECT_NEAR(q[1].y, generalised, 1e-13 * generalised);
    for (int a = 0; a < 8; ++a) {
      EXPECT_NEAR(f[a].y, -generalised * kHourglassBase[1][a], 1e-13 * generalised);
      EXPECT_EQ(f[a].x, 0.0);
    }
  }
}

// One cube with lumped masses rho h^3 / 8, started in hourglass mode 1 (x direction) with
// velocity amplitude w and no displacement, integrated by central differences with the
// geometry held fixed (small amplitude). Records the displacement pattern amplitude s_n and the
// staggered energy 1/2 sum m v^(n-1/2) . v^(n+1/2) + sum |Q_n|^2 / (2 k_h).
struct Oscillation {
  std::vector<double> amplitude, energy;
};

Oscillation oscillate(double h, double w, double dt, int steps) {
  const HexVectors x = cube(h);
  const OnePointHex e = one_point_hex(x);
  const HourglassModes m = hourglass_modes(e, x);
  const double mass = kDensity * h * h * h / 8.0;
  const double k_h = kDefaultStiffnessHourglass * kModulus * m.b_squared / (3.0 * e.volume);
  HexVectors u{}, v = mode_velocity(0, 0, w);
  std::array<core::Vec3, 4> q{};
  Oscillation out;
  for (int n = 1; n <= steps; ++n) {
    for (int a = 0; a < 8; ++a) u[a] += dt * v[a];
    HexVectors f{};
    add_hourglass_stiffness(m, v, kDefaultStiffnessHourglass, kModulus, e.volume, dt, q, f);
    double kinetic = 0.0;
    for (int a = 0; a < 8; ++a) {
      const core::Vec3 next = v[a] + (dt / mass) * f[a];
      kinetic += 0.5 * mass * core::dot(v[a], next);
      v[a] = next;
    }
    double stored = 0.0;
    for (const core::Vec3& qk : q) stored += core::dot(qk, qk) / (2.0 * k_h);
    out.amplitude.push_back(u[0].x / kHourglassBase[0][0]);
    out.energy.push_back(kinetic + stored);
  }
  return out;
}

TEST(Hourglass, StiffnessFormOscillatesElasticallyWithTheClosedFormFrequency) {
  // Reference: the mode obeys m s'' = -8 k_h s, omega^2 = 8 k_h / m = 32 Q_hg c^2 / h^2. Central
  // differences then give exactly s_n = A sin(omega_d n dt) with sin(omega_d dt / 2) =
  // omega dt / 2 and A = w dt / sin(omega_d dt), and conserve the staggered energy exactly.
  // Over 400 steps (about 13 periods at omega dt = 0.2): s_n within 1e-9 A of the closed form
  // and the energy constant to 1e-12 relative (the form stores hourglass energy, it does not
  // dissipate it).
  const double h = 0.01, w = 0.1;
  const double omega = std::sqrt(32.0 * kDefaultStiffnessHourglass) * kWaveSpeed / h;
  const double dt = 0.2 / omega;
  const Oscillation run = oscillate(h, w, dt, 400);
  const double omega_d = 2.0 * std::asin(0.5 * omega * dt) / dt;
  const double amplitude = w * dt / std::sin(omega_d * dt);
  for (std::size_t n = 0; n < run.amplitude.size(); ++n) {
    const double t = static_cast<double>(n + 1) * dt;
    EXPECT_NEAR(run.amplitude[n], amplitude * std::sin(omega_d * t), 1e-9 * amplitude)
        << "step " << n + 1;
    EXPECT_NEAR(run.energy[n], run.energy.front(), 1e-12 * run.energy.front()) << "step " << n + 1;
  }
}

TEST(Hourglass, ViscousFormDissipatesHourglassMotion) {
  // Reference: with the viscous form alone the mode obeys m s'' = -8 a_h s', and the explicit
  // update v^(n+1/2) = v^(n-1/2) (1 - 8 a_h dt / m) decays geometrically: after each of 50 steps
  // the kinetic energy is that of the closed form (relative 1e-12) and smaller than before.
  const double h = 0.01, w = 0.1;
  const HexVectors x = cube(h);
  const OnePointHex e = one_point_hex(x);
  const HourglassModes m = hourglass_modes(e, x);
  const double mass = kDensity * h * h * h / 8.0;
  const double a_h = kDefaultViscousHourglass * kDensity * kWaveSpeed * h * h / 4.0;
  const double dt = 0.05 * mass / (8.0 * a_h);
  const double factor = 1.0 - 8.0 * a_h * dt / mass;
  HexVectors v = mode_velocity(0, 0, w);
  double previous = 0.5 * 8.0 * mass * w * w;
  for (int n = 1; n <= 50; ++n) {
    HexVectors f{};
    add_hourglass_viscous(m, v, kDefaultViscousHourglass, kDensity, kWaveSpeed, e.volume, f);
    double kinetic = 0.0;
    for (int a = 0; a < 8; ++a) {
      v[a] += (dt / mass) * f[a];
      kinetic += 0.5 * mass * core::dot(v[a], v[a]);
    }
    const double expected = 0.5 * 8.0 * mass * w * w * std::pow(factor, 2 * n);
    EXPECT_NEAR(kinetic, expected, 1e-12 * expected) << "step " << n;
    EXPECT_LT(kinetic, previous);
    previous = kinetic;
  }
}

}  // namespace
}  // namespace afemp::fem
