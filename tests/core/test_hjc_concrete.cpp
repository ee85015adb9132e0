// Holmquist-Johnson-Cook concrete (hjc_compaction.cpp, holmquist_johnson_cook.cpp) against
// closed forms with the 48 MPa concrete of Holmquist, Johnson & Cook (1993), SI units: the
// compaction law in each regime, unloading and tension, the yield surface with the rate term
// and SFMAX, damage growth and its EFMIN floor, the energy of a crush-release cycle, the wave
// speed and the scene keys.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "afemp/errors.hpp"
#include "core/materials/holmquist_johnson_cook.hpp"
#include "core/materials/material.hpp"
#include "core/scene.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

constexpr double kFc = 48e6, kT = 4e6, kG = 14.86e9;

HolmquistJohnsonCook concrete_strength() {
  HolmquistJohnsonCook s;
  s.A = 0.79;
  s.B = 1.60;
  s.N = 0.61;
  s.C = 0.007;
  s.compressive_strength = kFc;
  s.tensile_strength = kT;
  s.reference_strain_rate = 1.0;
  s.min_fracture_strain = 0.01;
  s.max_strength = 7.0;
  s.D1 = 0.04;
  s.D2 = 1.0;
  return s;
}

HjcCompaction concrete_compaction() {
  return {16e6, 0.001, 800e6, 0.10, 85e9, -171e9, 208e9};
}

Material concrete() {
  Material m;
  m.name = "concrete";
  m.density = 2440.0;
  m.strength = concrete_strength();
  m.eos = concrete_compaction();
  m.set_shear_and_bulk_modulus(kG, 16e9);
  m.validate();
  return m;
}

PointState at_rest(const Material& m) {
  PointState p;
  p.density = m.density;
  return p;
}

// One update to volumetric strain mu (rho = rho0 (1 + mu)) with the deviatoric increment
// de_dev: the volume change d_vol = rho_old / rho_new - 1 is what the solvers pass.
PointUpdate step_to(const Material& m, PointState& p, double mu, const SymTensor& de_dev = {},
                    double dt = 1.0) {
  const double rho_new = m.density * (1.0 + mu);
  const double d_vol = p.density / rho_new - 1.0;
  p.density = rho_new;
  return constitutive_update(m, std::get<HolmquistJohnsonCook>(m.strength),
                             std::get<HjcCompaction>(m.eos), false, p,
                             de_dev + (d_vol / 3.0) * SymTensor::identity(), dt);
}

double p_of(const PointState& p) {
  return pressure(p.stress);
}
double mu_of(const Material& m, const PointState& p) {
  return p.density / m.density - 1.0;
}

// ------------------------------------------------------------------------------------------
// Compaction law

TEST(HjcCompaction, LoadingPressureMatchesEachRegime) {
  const HjcCompaction eos = concrete_compaction();
  // Elastic: K_e = PC / muc = 16 GPa, P(0.0005) = 8 MPa; 1e-12 relative.
  EXPECT_NEAR(eos.elastic_modulus(), 16e9, 1e-3);
  EXPECT_NEAR(eos.loading_pressure(0.0005), 8e6, 1e-12 * 8e6);
  // mu_plock: K1 x + K2 x^2 + K3 x^3 = PL at x = 0.00959480691858857 (bisection by hand to
  // double precision), mu_plock = mul + (1 + mul) x = 0.110554287610447; 1e-12 relative.
  EXPECT_NEAR(eos.plock_strain(), 0.110554287610447, 1e-12 * 0.11);
  // Crushing: halfway between (muc, PC) and (mu_plock, PL), P = (PC + PL) / 2 = 408 MPa.
  const double mid = 0.5 * (0.001 + eos.plock_strain());
  EXPECT_NEAR(eos.loading_pressure(mid), 408e6, 1e-12 * 408e6);
  // Fully dense: mubar = (0.15 - 0.1) / 1.1, P = K1 mubar + K2 mubar^2 + K3 mubar^3
  // = 3529864763.3358 Pa by hand; 1e-12 relative.
  const double mubar = 0.05 / 1.1;
  const double dense = 85e9 * mubar - 171e9 * mubar * mubar + 208e9 * mubar * mubar * mubar;
  EXPECT_NEAR(eos.loading_pressure(0.15), dense, 1e-12 * dense);
  EXPECT_NEAR(eos.loading_pressure(0.15), 3529864763.3358, 1e-12 * dense);
  // Continuous at both regime boundaries (1e-9 relative of the pressures there).
  EXPECT_NEAR(eos.loading_pressure(0.001 * (1 + 1e-12)), 16e6, 1e-9 * 16e6);
  EXPECT_NEAR(eos.loading_pressure(eos.plock_strain() * (1 + 1e-12)), 800e6, 1e-9 * 800e6);
}

TEST(HjcCompaction, UnloadingFromCrushKeepsPermanentCompaction) {
  // Reference: from mu_max = (muc + mu_plock) / 2 (F = 1/2) the unloading modulus is
  // K_u = (K_e + K1) / 2 = 50.5 GPa; P = 408 MPa - K_u (mu_max - mu) reaches 0 at
  // mu_p = mu_max - 408e6 / 50.5e9 = 0.0476979358844316 > 0. Driven through the point update
  // (hydrostatic, 200 steps each way); 1e-9 relative.
  const Material m = concrete();
  const HjcCompaction& eos = std::get<HjcCompaction>(m.eos);
  const double mu_max = 0.5 * (0.001 + eos.plock_strain());
  EXPECT_NEAR(eos.unloading_modulus(mu_max), 50.5e9, 1e-12 * 50.5e9);
  PointState p = at_rest(m);
  for (int i = 1; i <= 200; ++i) step_to(m, p, mu_max * i / 200.0);
  EXPECT_NEAR(p_of(p), 408e6, 1e-9 * 408e6);
  EXPECT_DOUBLE_EQ(p.history[core::kMaxCompaction], mu_max);
  const double mu_p = mu_max - 408e6 / 50.5e9;
  EXPECT_NEAR(mu_p, 0.0476979358844316, 1e-12);
  EXPECT_NEAR(eos.plastic_compaction(mu_max), mu_p, 1e-15);
  for (int i = 1; i <= 200; ++i) {
    const double mu = mu_max + (mu_p - mu_max) * i / 200.0;
    step_to(m, p, mu);
    EXPECT_NEAR(p_of(p), 408e6 - 50.5e9 * (mu_max - mu), 1e-9 * 408e6);
  }
  EXPECT_NEAR(p_of(p), 0.0, 1e-9 * 408e6);  // P = 0 with mu = mu_p > 0 left
  EXPECT_GT(mu_of(m, p), 0.047);
  EXPECT_DOUBLE_EQ(p.history[core::kMaxCompaction], mu_max);
  // Reloading retraces the unloading line back to (mu_max, 408 MPa).
  step_to(m, p, mu_max);
  EXPECT_NEAR(p_of(p), 408e6, 1e-9 * 408e6);
}

TEST(HjcCompaction, TensionIsCutOffAtDamagedTensileStrength) {
  const Material m = concrete();
  // Elastic tension above the cutoff: P = K_e mu = -1.6 MPa at mu = -1e-4 (1e-9 relative).
  PointState p = at_rest(m);
  step_to(m, p, -1e-4);
  EXPECT_NEAR(p_of(p), -1.6e6, 1e-9 * 1.6e6);
  // K_e mu = -16 MPa at mu = -1e-3 is cut off at -T = -4 MPa, and at -T (1 - D) = -3 MPa
  // with D = 0.25 (exact up to rounding).
  step_to(m, p, -1e-3);
  EXPECT_NEAR(p_of(p), -kT, 1e-9 * kT);
  PointState damaged = at_rest(m);
  damaged.damage = 0.25;
  step_to(m, damaged, -1e-3);
  EXPECT_NEAR(p_of(damaged), -0.75 * kT, 1e-9 * kT);
  EXPECT_DOUBLE_EQ(damaged.damage, 0.25);  // no plastic strain, no crushing: D unchanged
  // Fully dense: unloading from mu_max = 0.15 follows the K1 line in mubar,
  // P = P(0.15) - K1 / 1.1 (0.15 - mu): 1.21168...e9 at mu = 0.12; below the mu where that line
  // crosses zero the pressure is cut off at -T (1 - D), D from the crushing on the way.
  PointState dense = at_rest(m);
  for (int i = 1; i <= 300; ++i) step_to(m, dense, 0.15 * i / 300.0);
  const double p_max = std::get<HjcCompaction>(m.eos).loading_pressure(0.15);
  EXPECT_NEAR(p_of(dense), p_max, 1e-9 * p_max);
  step_to(m, dense, 0.12);
  EXPECT_NEAR(p_of(dense), p_max - 85e9 / 1.1 * 0.03, 1e-9 * p_max);
  const double d = dense.damage;
  EXPECT_GT(d, 0.0);
  EXPECT_LT(d, 1.0);
  step_to(m, dense, 0.15 - p_max / (85e9 / 1.1) - 1e-3);
  EXPECT_NEAR(p_of(dense), -kT * (1.0 - d), 1e-9 * kT);
}

// ------------------------------------------------------------------------------------------
// Strength

TEST(HolmquistJohnsonCook, UniaxialStrainReturnsToYieldSurfaceAtCurrentPressureAndRate) {
  // Uniaxial strain de = -1e-5 per step to 1 % at equivalent deviatoric rate
  // (2/3) |de| / dt = 100 / s. Reference at the last (plastic) step:
  // q = fc [A (1 - D) + B P*^N](1 + C ln 100), D the damage before the step, P the compaction
  // law's loading pressure at the point's mu; 1e-10 relative (radial return at fixed P is exact).
  const Material m = concrete();
  const HolmquistJohnsonCook& s = std::get<HolmquistJohnsonCook>(m.strength);
  const HjcCompaction& eos = std::get<HjcCompaction>(m.eos);
  const double de = -1e-5, dt = (2.0 / 3.0) * 1e-5 / 100.0;
  PointState p = at_rest(m);
  double d_before = 0.0, eps_p_before = 0.0;
  for (int i = 0; i < 1000; ++i) {
    d_before = p.damage;
    eps_p_before = p.plastic_strain;
    const double rho_new = p.density / (1.0 + de);
    p.density = rho_new;
    constitutive_update(m, s, eos, false, p, SymTensor{de, 0, 0, 0, 0, 0}, dt);
  }
  ASSERT_GT(p.plastic_strain, eps_p_before);  // the last step flowed
  const double mu = mu_of(m, p);
  EXPECT_GT(mu, 0.001);  // crushing
  EXPECT_DOUBLE_EQ(p.history[core::kMaxCompaction], mu);
  const double p_ref = eos.loading_pressure(mu);
  EXPECT_NEAR(p_of(p), p_ref, 1e-12 * p_ref);
  const double q_ref = kFc * (s.A * (1.0 - d_before) + s.B * std::pow(p_ref / kFc, s.N)) *
                       (1.0 + s.C * std::log(100.0));
  EXPECT_NEAR(von_mises(p.stress), q_ref, 1e-10 * q_ref);
  std::printf("HJC uniaxial strain 1 %%: P = %.4f MPa, q = %.4f MPa (closed form %.4f), D = %.4f\n",
              p_of(p) / 1e6, von_mises(p.stress) / 1e6, q_ref / 1e6, p.damage);
}

TEST(HolmquistJohnsonCook, StrengthIsCappedAtSfmax) {
  // Hydrostatic crush to mu = 0.08 (P* ~ 12, B P*^N ~ 7.3 > SFMAX = 7), then tensor shear
  // 1e-4 per step at constant volume and rate below epsdot_0: q = SFMAX fc = 336 MPa once the
  // cap is reached; 1e-10 relative.
  const Material m = concrete();
  const HolmquistJohnsonCook& s = std::get<HolmquistJohnsonCook>(m.strength);
  PointState p = at_rest(m);
  for (int i = 1; i <= 800; ++i) step_to(m, p, 0.08 * i / 800.0);
  const double p_star = p_of(p) / kFc;
  EXPECT_GT(s.B * std::pow(p_star, s.N), 7.0);
  for (int i = 0; i < 150; ++i) step_to(m, p, 0.08, SymTensor{0, 0, 0, 0, 0, 1e-4});
  EXPECT_NEAR(von_mises(p.stress), 7.0 * kFc, 1e-10 * 7.0 * kFc);
  EXPECT_NEAR(p_of(p) / kFc, p_star, 1e-12 * p_star);  // shear at constant volume keeps P
}

// ------------------------------------------------------------------------------------------
// Damage

// Pure shear at fixed mu (so fixed P): each plastic step must add d eps_p / eps_f to D, with
// the radial return landing on fc [A (1 - D_old) + B P*^N]; returns the damage after `steps`.
void shear_and_check_damage(const Material& m, PointState& p, double mu, double eps_f, int steps) {
  const HolmquistJohnsonCook& s = std::get<HolmquistJohnsonCook>(m.strength);
  const double p_star = p_of(p) / kFc;
  for (int i = 0; i < steps && p.damage < 1.0; ++i) {
    const double d_old = p.damage, eps_old = p.plastic_strain;
    step_to(m, p, mu, SymTensor{0, 0, 0, 0, 0, 1e-4});
    const double d_eps_p = p.plastic_strain - eps_old;
    if (p.damage < 1.0)
      EXPECT_NEAR(p.damage - d_old, d_eps_p / eps_f, 1e-12);
    else
      EXPECT_GE(d_old + d_eps_p / eps_f, 1.0 - 1e-12);
    if (d_eps_p > 0.0) {
      const double q_ref = kFc * (s.A * (1.0 - d_old) + s.B * std::pow(p_star, s.N));
      EXPECT_NEAR(von_mises(p.stress), q_ref, 1e-10 * q_ref);
    }
  }
}

TEST(HolmquistJohnsonCook, ShearDamageGrowsByPlasticStrainOverFractureStrainToFailure) {
  // P = K_e 9e-4 = 14.4 MPa, P* = 0.3, T* = 1/12: eps_f = D1 (P* + T*)^D2 = 0.04 * 0.383333
  // = 0.0153333 > EFMIN. D reaches 1 after eps_p = eps_f, then q = fc B P*^N
  // = 48e6 * 1.6 * 0.3^0.61 = 36.847 MPa (1e-10 relative).
  const Material m = concrete();
  const HolmquistJohnsonCook& s = std::get<HolmquistJohnsonCook>(m.strength);
  PointState p = at_rest(m);
  step_to(m, p, 9e-4);
  EXPECT_NEAR(p_of(p), 14.4e6, 1e-9 * 14.4e6);
  const double eps_f = 0.04 * (0.3 + 1.0 / 12.0);
  EXPECT_NEAR(s.fracture_strain(0.3), eps_f, 1e-15);
  shear_and_check_damage(m, p, 9e-4, eps_f, 1000);
  ASSERT_EQ(p.damage, 1.0);
  EXPECT_NEAR(p.plastic_strain, eps_f, 2e-4);  // within one step's plastic increment
  step_to(m, p, 9e-4, SymTensor{0, 0, 0, 0, 0, 1e-4});
  const double q_failed = kFc * s.B * std::pow(0.3, s.N);
  EXPECT_NEAR(q_failed, 36.847e6, 1e-4 * 36.847e6);
  EXPECT_NEAR(von_mises(p.stress), q_failed, 1e-10 * q_failed);
}

TEST(HolmquistJohnsonCook, FractureStrainIsFlooredAtEfminAtLowPressure) {
  // P = K_e 2e-4 = 3.2 MPa, P* + T* = 1/15 + 1/12 = 0.15: D1 * 0.15 = 0.006 < EFMIN = 0.01,
  // so dD = d eps_p / 0.01; in tension beyond the cutoff (P* + T* < 0) it is EFMIN too.
  const Material m = concrete();
  const HolmquistJohnsonCook& s = std::get<HolmquistJohnsonCook>(m.strength);
  EXPECT_DOUBLE_EQ(s.fracture_strain(1.0 / 15.0), 0.01);
  EXPECT_DOUBLE_EQ(s.fracture_strain(-0.2), 0.01);
  PointState p = at_rest(m);
  step_to(m, p, 2e-4);
  shear_and_check_damage(m, p, 2e-4, 0.01, 60);
  EXPECT_GT(p.damage, 0.1);  // the steps above flowed plastically
}

// ------------------------------------------------------------------------------------------
// Energy and wave speed

TEST(HolmquistJohnsonCook, CrushReleaseCycleEnergyIsTheClosedFormPressureWork) {
  // Hydrostatic (no deviatoric work): load 0 -> muc -> mu_max (crushing), unload to P = 0 at
  // mu_p. e = int P dmu / (rho0 (1 + mu)^2); on a segment P = a + b mu, with u = 1 + mu,
  // int = (a - b)(1/u1 - 1/u2) + b ln(u2 / u1). Midpoint rule in specific volume, 1000 steps a
  // segment: 1e-6 relative.
  const Material m = concrete();
  const HjcCompaction& eos = std::get<HjcCompaction>(m.eos);
  const double muc = 0.001, mu_max = 0.5 * (muc + eos.plock_strain());
  const double k_e = 16e9, slope = (800e6 - 16e6) / (eos.plock_strain() - muc), k_u = 50.5e9;
  const double mu_p = mu_max - 408e6 / k_u;
  auto segment = [&](double a, double b, double mu1, double mu2) {
    const double u1 = 1.0 + mu1, u2 = 1.0 + mu2;
    return ((a - b) * (1.0 / u1 - 1.0 / u2) + b * std::log(u2 / u1)) / m.density;
  };
  const double reference = segment(0.0, k_e, 0.0, muc) +
                           segment(16e6 - slope * muc, slope, muc, mu_max) +
                           segment(408e6 - k_u * mu_max, k_u, mu_max, mu_p);
  PointState p = at_rest(m);
  const int n = 1000;
  for (int i = 1; i <= n; ++i) step_to(m, p, muc * i / n);
  for (int i = 1; i <= n; ++i) step_to(m, p, muc + (mu_max - muc) * i / n);
  for (int i = 1; i <= n; ++i) step_to(m, p, mu_max + (mu_p - mu_max) * i / n);
  EXPECT_GT(reference, 0.0);  // the crushing dissipates energy
  EXPECT_NEAR(p.energy, reference, 1e-6 * reference);
  std::printf("HJC crush-release cycle: e = %.6f J/kg, closed form %.6f J/kg\n", p.energy,
              reference);
}

TEST(HolmquistJohnsonCook, WaveSpeedUsesTheStifferOfLoadingAndUnloadingModuli) {
  // At rest: c = sqrt((K_e + 4G/3) / rho0) = 3831.1 m/s. Crushed to mu_max and unloaded a
  // little: K_t = (1 + mu) K_u(mu_max), K_u = 50.5 GPa at F = 1/2. 1e-12 relative.
  const Material m = concrete();
  const HjcCompaction& eos = std::get<HjcCompaction>(m.eos);
  PointState p = at_rest(m);
  const double c0 = std::sqrt((16e9 + 4.0 / 3.0 * kG) / 2440.0);
  EXPECT_NEAR(wave_speed(m, p), c0, 1e-12 * c0);
  EXPECT_NEAR(c0, 3831.1, 0.1);
  const double mu_max = 0.5 * (0.001 + eos.plock_strain());
  for (int i = 1; i <= 100; ++i) step_to(m, p, mu_max * i / 100.0);
  step_to(m, p, mu_max - 1e-3);
  const double k_t = (1.0 + mu_max - 1e-3) * 50.5e9;
  const double c = std::sqrt((k_t + 4.0 / 3.0 * kG) / p.density);
  EXPECT_NEAR(wave_speed(m, p), c, 1e-12 * c);
}

TEST(HolmquistJohnsonCook, FullyDamagedConcreteInTensionCarriesNoStressAndNoSignal) {
  // D = 1 and rho < rho0: the pressure is cut off at -T (1 - D) = 0 and the strength
  // A (1 - D)(1 + P*/T*) is 0, so any increment, expanding, shearing or compressing while the
  // point stays below rho0, leaves the stress at 0 (exactly), and the wave speed is 0. The
  // same point compacted again (mu > 0) carries pressure and strength B P*^N again and has
  // c = sqrt((K_t + 4G/3) / rho) once more (1e-12 relative).
  const Material m = concrete();
  PointState p = at_rest(m);
  p.damage = 1.0;
  const SymTensor shear{0.0, 0.0, 0.0, 0.0, 0.0, 1e-3};
  for (double mu : {-1e-3, -0.5, -0.9, -0.95, -0.5}) {
    step_to(m, p, mu, shear, 1e-6);
    EXPECT_EQ(p.stress.xx, 0.0) << mu;
    EXPECT_EQ(p.stress.xy, 0.0) << mu;
    EXPECT_EQ(wave_speed(m, p), 0.0) << mu;
  }
  PointState q = at_rest(m);
  q.damage = 1.0;
  step_to(m, q, 1e-4, shear, 1e-6);
  EXPECT_GT(p_of(q), 0.0);
  EXPECT_GT(std::abs(q.stress.xy), 0.0);
  const double c = std::sqrt((16e9 * (1.0 + 1e-4) + 4.0 / 3.0 * kG) / q.density);
  EXPECT_NEAR(wave_speed(m, q), c, 1e-12 * c);
}

// ------------------------------------------------------------------------------------------
// Scene keys

const std::string kHead = R"([run]
end_time = 1e-5

[grid]
cell = 1e-3
min = [0, 0, 0]
max = [0.01, 0.01, 0.01]

[materials.concrete]
density = 2440
)";
const std::string kModuli = "G = 14.86e9\n";
const std::string kStrength =
    "strength = { model = \"holmquist-johnson-cook\", A = 0.79, B = 1.60, N = 0.61, C = 0.007, "
    "fc = 48e6, T = 4e6, reference_strain_rate = 1.0, EFMIN = 0.01, SFMAX = 7.0, D1 = 0.04, "
    "D2 = 1.0 }\n";
const std::string kEos =
    "eos = { model = \"hjc-compaction\", PC = 16e6, muc = 0.001, PL = 800e6, mul = 0.10, "
    "K1 = 85e9, K2 = -171e9, K3 = 208e9 }\n";
const std::string kTail = R"(
[[bodies]]
name = "block"
material = "concrete"
shape = { box = { min = [0.002, 0.002, 0.002], max = [0.004, 0.004, 0.004] } }
)";

using test::error_of;
using test::line_of;

// The error names file, line and dotted key first.
void expect_error_at(const std::string& text, const std::string& needle, const std::string& key,
                     const std::string& message) {
  const std::string what = error_of(text);
  const std::string prefix =
      "scene.toml:" + std::to_string(line_of(text, needle)) + ": key '" + key + "': ";
  EXPECT_EQ(what.rfind(prefix, 0), 0u) << what;
  EXPECT_NE(what.find(message), std::string::npos) << what;
}

TEST(HjcSceneKeys, The48MPaConcreteParsesToItsValues) {
  // Reference: the keys as written; E and nu from G and K_e = PC / muc = 16 GPa
  // (shear_modulus() and bulk_modulus() give them back to 1e-12 relative).
  const Scene scene = parse_scene(kHead + kModuli + kStrength + kEos + kTail, "scene.toml");
  const Material& m = scene.materials.at(0);
  EXPECT_NEAR(m.shear_modulus(), kG, 1e-12 * kG);
  EXPECT_NEAR(m.bulk_modulus(), 16e9, 1e-12 * 16e9);
  const auto& s = std::get<HolmquistJohnsonCook>(m.strength);
  EXPECT_EQ(s.A, 0.79);
  EXPECT_EQ(s.B, 1.60);
  EXPECT_EQ(s.N, 0.61);
  EXPECT_EQ(s.C, 0.007);
  EXPECT_EQ(s.compressive_strength, 48e6);
  EXPECT_EQ(s.tensile_strength, 4e6);
  EXPECT_EQ(s.reference_strain_rate, 1.0);
  EXPECT_EQ(s.min_fracture_strain, 0.01);
  EXPECT_EQ(s.max_strength, 7.0);
  EXPECT_EQ(s.D1, 0.04);
  EXPECT_EQ(s.D2, 1.0);
  const auto& e = std::get<HjcCompaction>(m.eos);
  EXPECT_EQ(e.crush_pressure(), 16e6);
  EXPECT_EQ(e.crush_strain(), 0.001);
  EXPECT_EQ(e.lock_pressure(), 800e6);
  EXPECT_EQ(e.lock_strain(), 0.10);
  EXPECT_EQ(e.k1(), 85e9);
  EXPECT_EQ(e.k2(), -171e9);
  EXPECT_EQ(e.k3(), 208e9);
  EXPECT_NEAR(e.plock_strain(), 0.110554287610447, 1e-12);
}

TEST(HjcSceneKeys, MissingOrOutOfRangeKeysNameFileLineAndKey) {
  std::string strength = kStrength;
  strength.replace(strength.find(", D1 = 0.04"), 11, "");
  std::string text = kHead + kModuli + strength + kEos + kTail;
  expect_error_at(text, "strength =", "materials.concrete.strength.D1", "required key is missing");

  std::string eos = kEos;
  eos.replace(eos.find("PL = 800e6"), 10, "PL = 10e6");
  text = kHead + kModuli + kStrength + eos + kTail;
  expect_error_at(text, "eos =", "materials.concrete.eos.PL", "allowed: value > 16000000");

  strength = kStrength;
  strength.replace(strength.find("N = 0.61"), 8, "N = 0");
  text = kHead + kModuli + strength + kEos + kTail;
  expect_error_at(text, "strength =", "materials.concrete.strength.N", "allowed: value > 0");
}

TEST(HjcSceneKeys, HjcStrengthAndCompactionGoTogetherAndTakeGOnly) {
  std::string text = kHead + kModuli + kStrength +
                     "eos = { model = \"mie-gruneisen\", c0 = 3000, s = 1.5, gamma0 = 1.0 }\n" +
                     kTail;
  expect_error_at(text, "eos =", "materials.concrete.eos",
                  "needs eos = { model = \"hjc-compaction\"");
  text = kHead + kModuli + kStrength + kTail;
  expect_error_at(text, "strength =", "materials.concrete.strength",
                  "needs eos = { model = \"hjc-compaction\"");
  text = kHead + "E = 30e9\nnu = 0.2\nstrength = { model = \"j2\", yield = 40e6 }\n" + kEos + kTail;
  expect_error_at(text, "eos =", "materials.concrete.eos", "goes with it only");
  text = kHead + "E = 30e9\nnu = 0.2\n" + kStrength + kEos + kTail;
  expect_error_at(text, "eos =", "materials.concrete.eos", "give the material's shear modulus G");
  text = kHead + "G = 30e9\n" + kStrength + kEos + kTail;
  expect_error_at(text, "G = 30e9", "materials.concrete.G", ">= 2 G / 3");
}

TEST(HjcSceneKeys, ValidateRejectsAnUnpairedModelByName) {
  Material m = concrete();
  m.eos = LinearEos{16e9};
  try {
    m.validate();
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("needs eos hjc-compaction"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace afemp::core
