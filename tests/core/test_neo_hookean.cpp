// The compressible neo-Hookean solid (afemp/neo_hookean.hpp). References, to round-off unless
// stated:
// - uniaxial stretch F = diag(l, 1, 1): sigma_xx = 2/3 mu l^(-5/3) (l^2 - 1) + K (l - 1),
//   sigma_yy = sigma_zz = -1/3 mu l^(-5/3) (l^2 - 1) + K (l - 1);
// - a rigid rotation F = R is stress-free, and F = R U gives R sigma(U) R^T (objectivity);
// - small strain F = I + e: sigma = 2 mu dev(e) + K tr(e) I to O(|e|^2) (linear elasticity with
//   the material's E and nu);
// - the scene: "neo-hookean" takes no eos, and a body of elements given it is refused naming
//   the body and the material.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "afemp/errors.hpp"
#include "core/materials/material.hpp"
#include "core/scene.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

Material rubber() {
  Material m;
  m.name = "rubber";
  m.density = 1.1e-3;
  m.youngs_modulus = 17.0;
  m.poisson_ratio = 0.45;
  m.strength = NeoHookean{};
  m.validate();
  return m;
}

SymTensor stress_at(const Material& m, const Mat3& f) {
  PointState p;
  p.density = m.density;
  p.deformation_gradient = &f;
  constitutive_update(m, std::get<NeoHookean>(m.strength), NoEos{}, false, p, SymTensor{}, 1.0);
  return p.stress;
}

Mat3 product(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r.m[i][j] += a.m[i][k] * b.m[k][j];
  return r;
}

Mat3 rotation(double angle) {  // about the axis (1, 2, 2) / 3
  const double n[3] = {1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0};
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 r;
  const double e[3][3][3] = {{{0, 0, 0}, {0, 0, 1}, {0, -1, 0}},
                             {{0, 0, -1}, {0, 0, 0}, {1, 0, 0}},
                             {{0, 1, 0}, {-1, 0, 0}, {0, 0, 0}}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double cross = 0.0;
      for (int k = 0; k < 3; ++k) cross -= e[i][j][k] * n[k];
      r.m[i][j] = (i == j ? c : 0.0) + (1.0 - c) * n[i] * n[j] + s * cross;
    }
  return r;
}

// sigma as a full matrix, and R sigma R^T.
Mat3 full(const SymTensor& s) {
  Mat3 m;
  m.m[0][0] = s.xx, m.m[1][1] = s.yy, m.m[2][2] = s.zz;
  m.m[1][2] = m.m[2][1] = s.yz, m.m[0][2] = m.m[2][0] = s.xz, m.m[0][1] = m.m[1][0] = s.xy;
  return m;
}

TEST(NeoHookean, UniaxialStretchMatchesTheClosedForm) {
  const Material m = rubber();
  const double mu = m.shear_modulus(), k = m.bulk_modulus();
  for (double l : {0.5, 0.9, 1.0, 1.3, 2.5}) {
    Mat3 f;
    f.m[0][0] = l, f.m[1][1] = 1.0, f.m[2][2] = 1.0;
    const SymTensor s = stress_at(m, f);
    const double d = mu * std::pow(l, -5.0 / 3.0) * (l * l - 1.0), p = k * (l - 1.0);
    EXPECT_NEAR(s.xx, 2.0 / 3.0 * d + p, 1e-13 * (mu + k)) << l;
    EXPECT_NEAR(s.yy, -1.0 / 3.0 * d + p, 1e-13 * (mu + k)) << l;
    EXPECT_NEAR(s.zz, s.yy, 1e-13 * (mu + k)) << l;
    EXPECT_NEAR(s.xy, 0.0, 1e-13 * mu);
  }
}

TEST(NeoHookean, RotationsAreExactAndSmallStrainIsLinearElastic) {
  const Material m = rubber();
  const double mu = m.shear_modulus(), k = m.bulk_modulus();
  const Mat3 r = rotation(1.1);
  EXPECT_LT(std::sqrt(double_dot(stress_at(m, r), stress_at(m, r))), 1e-13 * mu);
  // F = R U with U a stretch and shear.
  Mat3 u;
  const double a[3][3] = {{1.2, 0.1, -0.05}, {0.1, 0.85, 0.2}, {-0.05, 0.2, 1.05}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) u.m[i][j] = a[i][j];
  const Mat3 rotated = full(stress_at(m, product(r, u)));
  Mat3 rt;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rt.m[i][j] = r.m[j][i];
  const Mat3 expected = product(product(r, full(stress_at(m, u))), rt);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(rotated.m[i][j], expected.m[i][j], 1e-12 * (mu + k));
  // Small strain: e of size 1e-6, the error O(|e|^2) = 1e-12 of the stress scale mu + K
  // (measured 7e-13).
  const double e[3][3] = {{1e-6, 3e-7, 0}, {3e-7, -5e-7, 2e-7}, {0, 2e-7, 4e-7}};
  Mat3 f;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.m[i][j] = (i == j ? 1.0 : 0.0) + e[i][j];
  const SymTensor s = stress_at(m, f);
  const SymTensor eps{e[0][0], e[1][1], e[2][2], e[1][2], e[0][2], e[0][1]};
  const SymTensor linear = (2.0 * mu) * eps.deviator() + (k * eps.trace()) * SymTensor::identity();
  EXPECT_LT(std::sqrt(double_dot(s - linear, s - linear)), 1e-11 * (mu + k));
  // ... and the linear part is what is left: 2.5e-5 of mu + K here.
  EXPECT_GT(std::sqrt(double_dot(linear, linear)), 1e-6 * (mu + k));
}

TEST(NeoHookean, ItTakesNoEos) {
  const std::string with_eos =
      "[run]\nend_time = 1.0\n[materials.rubber]\ndensity = 1.1e-3\nE = 17\nnu = 0.45\n"
      "strength = { model = \"neo-hookean\" }\n"
      "eos = { model = \"linear\", bulk_modulus = 50 }\n"
      "[[bodies]]\nname = \"b\"\nmaterial = \"rubber\"\n"
      "shape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }\n";
  const std::string e = test::error_of(with_eos, "rubber.toml");
  EXPECT_NE(e.find("takes no eos"), std::string::npos) << e;
}

// The log form (MPM3D-F90's neoh): sigma = (1 / J) dW/dF F^T with
// W = mu / 2 (I1 - 3) - mu ln J + lambda / 2 (ln J)^2, dW/dF by central differences (step 1e-6),
// to 1e-7 of mu + K; small strain is the same linear elasticity as the split form's.
TEST(NeoHookean, TheLogFormsStressIsTheDerivativeOfItsEnergy) {
  Material m = rubber();
  NeoHookean log_form;
  log_form.form = NeoHookean::Form::log;
  m.strength = log_form;
  const double mu = m.shear_modulus(), k = m.bulk_modulus(), lambda = k - 2.0 * mu / 3.0;
  auto energy = [&](const Mat3& f) {
    double i1 = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) i1 += f.m[i][j] * f.m[i][j];
    const double lj = std::log(determinant(f));
    return 0.5 * mu * (i1 - 3.0) - mu * lj + 0.5 * lambda * lj * lj;
  };
  const double a[3][3] = {{1.3, 0.2, -0.1}, {-0.15, 0.8, 0.25}, {0.05, 0.3, 1.1}};
  Mat3 f;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.m[i][j] = a[i][j];
  const Mat3 s = full(stress_at(m, f));
  double worst = 0.0;
  const double jac = determinant(f), h = 1e-6;
  Mat3 p;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Mat3 u = f, d = f;
      u.m[i][j] += h, d.m[i][j] -= h;
      p.m[i][j] = (energy(u) - energy(d)) / (2.0 * h);
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double expected = 0.0;
      for (int c = 0; c < 3; ++c) expected += p.m[i][c] * f.m[j][c];
      worst = std::max(worst, std::abs(s.m[i][j] - expected / jac));
    }
  std::printf("[ neo-hookean log ] |sigma - (1/J) dW/dF F^T| %.2e of mu + K\n", worst / (mu + k));
  EXPECT_LT(worst, 1e-7 * (mu + k));
  // Small strain: both forms are linear elasticity with E and nu, to O(|e|^2).
  const double e[3][3] = {{1e-6, 3e-7, 0}, {3e-7, -5e-7, 2e-7}, {0, 2e-7, 4e-7}};
  Mat3 g;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g.m[i][j] = (i == j ? 1.0 : 0.0) + e[i][j];
  const SymTensor eps{e[0][0], e[1][1], e[2][2], e[1][2], e[0][2], e[0][1]};
  const SymTensor linear = (2.0 * mu) * eps.deviator() + (k * eps.trace()) * SymTensor::identity();
  const SymTensor small = stress_at(m, g);
  EXPECT_LT(std::sqrt(double_dot(small - linear, small - linear)), 1e-11 * (mu + k));
}

}  // namespace
}  // namespace afemp::core
