// The compressible Mooney-Rivlin solid (afemp/mooney_rivlin.hpp). References:
// - the stress is the derivative of the strain energy: sigma = (1 / J) dW/dF F^T with
//   W = C10 (I1bar - 3) + C01 (I2bar - 3) + K / 2 (J - 1)^2, dW/dF taken by central differences
//   of W (step 1e-6; truncation 1e-12 and round-off 1e-10 of the stress scale), at general F:
//   to 1e-7 of mu + K;
// - C01 = 0 is the neo-Hookean solid (to round-off);
// - small strain is linear elastic with shear modulus 2 (C10 + C01) and the material's K;
// - a material whose E and nu give another shear modulus is refused, the message giving the E
//   that agrees.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "afemp/errors.hpp"
#include "core/materials/material.hpp"
#include "core/scene.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

// mu = 2 (C10 + C01) = 6 and nu = 0.45: E = 2 (1 + nu) mu = 17.4.
Material rubber(double c10, double c01) {
  Material m;
  m.name = "rubber";
  m.density = 1.1e-3;
  m.poisson_ratio = 0.45;
  m.youngs_modulus = 2.0 * 1.45 * 2.0 * (c10 + c01);
  m.strength = MooneyRivlin{c10, c01};
  m.validate();
  return m;
}

template <class Model>
SymTensor stress_at(const Material& m, const Mat3& f) {
  PointState p;
  p.density = m.density;
  p.deformation_gradient = &f;
  constitutive_update(m, std::get<Model>(m.strength), NoEos{}, false, p, SymTensor{}, 1.0);
  return p.stress;
}

double energy(double c10, double c01, double k, const Mat3& f) {
  Mat3 c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a) c.m[i][j] += f.m[a][i] * f.m[a][j];
  double tr = 0.0, tr2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    tr += c.m[i][i];
    for (int j = 0; j < 3; ++j) tr2 += c.m[i][j] * c.m[j][i];
  }
  const double j = determinant(f);
  const double i1 = std::pow(j, -2.0 / 3.0) * tr,
               i2 = std::pow(j, -4.0 / 3.0) * 0.5 * (tr * tr - tr2);
  return c10 * (i1 - 3.0) + c01 * (i2 - 3.0) + 0.5 * k * (j - 1.0) * (j - 1.0);
}

Mat3 general_f() {
  Mat3 f;
  const double a[3][3] = {{1.3, 0.2, -0.1}, {-0.15, 0.8, 0.25}, {0.05, 0.3, 1.1}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.m[i][j] = a[i][j];
  return f;
}

TEST(MooneyRivlin, TheStressIsTheDerivativeOfTheStrainEnergy) {
  const double c10 = 2.0, c01 = 1.0;
  const Material m = rubber(c10, c01);
  const double k = m.bulk_modulus(), scale = m.shear_modulus() + k;
  for (double stretch : {0.7, 1.0, 1.6}) {
    Mat3 f = general_f();
    for (int i = 0; i < 3; ++i) f.m[i][0] *= stretch;
    const SymTensor s = stress_at<MooneyRivlin>(m, f);
    // P = dW/dF by central differences, sigma = P F^T / J.
    Mat3 p;
    const double h = 1e-6;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Mat3 a = f, b = f;
        a.m[i][j] += h, b.m[i][j] -= h;
        p.m[i][j] = (energy(c10, c01, k, a) - energy(c10, c01, k, b)) / (2.0 * h);
      }
    const double jac = determinant(f);
    double worst = 0.0;
    const double got[3][3] = {{s.xx, s.xy, s.xz}, {s.xy, s.yy, s.yz}, {s.xz, s.yz, s.zz}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double expected = 0.0;
        for (int a = 0; a < 3; ++a) expected += p.m[i][a] * f.m[j][a];
        worst = std::max(worst, std::abs(got[i][j] - expected / jac));
      }
    std::printf("[ mooney-rivlin ] stretch %.1f: |sigma - (1/J) dW/dF F^T| %.2e of mu + K\n",
                stretch, worst / scale);
    EXPECT_LT(worst, 1e-7 * scale) << stretch;
  }
}

TEST(MooneyRivlin, WithoutC01ItIsTheNeoHookeanSolidAndSmallStrainIsLinearElastic) {
  const Material mr = rubber(3.0, 0.0);
  Material nh = mr;
  nh.strength = NeoHookean{};
  const SymTensor a = stress_at<MooneyRivlin>(mr, general_f()),
                  b = stress_at<NeoHookean>(nh, general_f());
  const double scale = mr.shear_modulus() + mr.bulk_modulus();
  EXPECT_LT(std::sqrt(double_dot(a - b, a - b)), 1e-13 * scale);
  // Small strain with C01 > 0: shear modulus 2 (C10 + C01) = 6 (the material's G).
  const Material m = rubber(2.0, 1.0);
  EXPECT_NEAR(m.shear_modulus(), 6.0, 1e-12);
  const double e[3][3] = {{1e-6, 3e-7, 0}, {3e-7, -5e-7, 2e-7}, {0, 2e-7, 4e-7}};
  Mat3 f;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.m[i][j] = (i == j ? 1.0 : 0.0) + e[i][j];
  const SymTensor s = stress_at<MooneyRivlin>(m, f);
  const SymTensor eps{e[0][0], e[1][1], e[2][2], e[1][2], e[0][2], e[0][1]};
  const SymTensor linear =
      (2.0 * 6.0) * eps.deviator() + (m.bulk_modulus() * eps.trace()) * SymTensor::identity();
  EXPECT_LT(std::sqrt(double_dot(s - linear, s - linear)), 1e-11 * (6.0 + m.bulk_modulus()));
  EXPECT_GT(std::sqrt(double_dot(linear, linear)), 1e-6 * 6.0);
}

TEST(MooneyRivlin, AShearModulusThatDisagreesWithEAndNuIsRefused) {
  const std::string text =
      "[run]\nend_time = 1.0\n[grid]\ncell = 1\nmin = [0, 0, 0]\nmax = [2, 2, 2]\n"
      "[materials.rubber]\ndensity = 1.1e-3\nE = 17\nnu = 0.45\n"
      "strength = { model = \"mooney-rivlin\", C10 = 2, C01 = 1 }\n"
      "[[bodies]]\nname = \"b\"\nmaterial = \"rubber\"\n"
      "shape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }\n";
  const std::string e = test::error_of(text, "rubber.toml");
  for (const std::string& part :
       {std::string("C10"), std::string("2 (C10 + C01) = 6"), std::string("set E = 17.4")})
    EXPECT_NE(e.find(part), std::string::npos) << part << " in: " << e;
  std::string good = text;
  good.replace(good.find("E = 17\n"), 7, "E = 17.4\n");
  EXPECT_NO_THROW(core::parse_scene(good, "rubber.toml"));
}

}  // namespace
}  // namespace afemp::core
