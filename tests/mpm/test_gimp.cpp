// uGIMP weights (core/grid/gimp.hpp; Bardenhagen & Kober 2004). References: the weight is
// the hat averaged over the particle's domain (checked against a numerical average), its
// gradient is the derivative of that average (central differences), the weights reproduce
// constants and linear fields (sum S = 1, sum S x_I = x_p, sum grad S = 0,
// sum x_I (x) grad S = I), the APIC moment D_p recovers the gradient of any affine nodal
// field exactly (Jiang et al. 2015), and |grad S|^2 h^2 / S <= 1 / a, the bound that keeps a
// barely reached node stable (the linear hat's 1 / f is unbounded).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/grid/background_grid.hpp"
#include "core/grid/gimp.hpp"

namespace afemp::core {
namespace {

constexpr double h = 0.5;  // cell size

double hat(double x_minus_node) {
  return std::max(0.0, 1.0 - std::abs(x_minus_node) / h);
}

// Midpoint-rule average of the hat of the node at node_x over [x - l, x + l]: the integrand
// is piecewise linear, so 200,000 points give about 1e-11.
double averaged_hat(double x, double l, double node_x) {
  const int n = 200000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) sum += hat(x - l + (k + 0.5) * (2.0 * l / n) - node_x);
  return sum / n;
}

TEST(Gimp, WeightIsTheHatAveragedOverTheParticleAndTheGradientItsDerivative) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double a : {0.125, 0.25, 0.5}) {
    for (int trial = 0; trial < 40; ++trial) {
      const double xi = 5.0 + 2.0 * u(rng);  // in cells
      const GimpAxis g = gimp_axis(xi, a, h);
      for (int k = 0; k < 3; ++k) {
        const double node_x = (g.base + k) * h;
        EXPECT_NEAR(g.w[static_cast<std::size_t>(k)], averaged_hat(xi * h, a * h, node_x), 1e-9);
        EXPECT_DOUBLE_EQ(g.offset[static_cast<std::size_t>(k)], node_x - xi * h);
        // Central difference of the weight of this node (its base may shift: look it up).
        const double d = 1e-6;
        auto weight_at = [&](double x_cells) {
          const GimpAxis q = gimp_axis(x_cells, a, h);
          const int j = g.base + k - q.base;
          return (j >= 0 && j < 3) ? q.w[static_cast<std::size_t>(j)] : 0.0;
        };
        const double fd = (weight_at(xi + d / h) - weight_at(xi - d / h)) / (2.0 * d);
        EXPECT_NEAR(g.grad[static_cast<std::size_t>(k)], fd, 1e-6 / h);
      }
      // Nodes outside base..base+2 get nothing.
      EXPECT_NEAR(averaged_hat(xi * h, a * h, (g.base - 1) * h), 0.0, 1e-15);
      EXPECT_NEAR(averaged_hat(xi * h, a * h, (g.base + 3) * h), 0.0, 1e-15);
    }
  }
}

TEST(Gimp, WeightsReproduceConstantsAndLinearFieldsIn3D) {
  GridSettings settings;
  settings.cell = h;
  settings.min = {-1.0, 0.0, 2.0};
  settings.max = {4.0, 5.0, 7.0};
  const BackgroundGrid grid(settings, 1);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double a = 0.05 + 0.45 * u(rng);
    const Vec3 x{-0.9 + 4.8 * u(rng), 0.1 + 4.8 * u(rng), 2.1 + 4.8 * u(rng)};
    const GimpWeights w = grid.gimp_weights(x, a);
    double sum = 0.0;
    Vec3 moment, grad_sum;
    double identity[3][3] = {};
    for (int n = 0; n < 27; ++n) {
      const auto k = static_cast<std::size_t>(n);
      const Vec3 node = x + w.offset(n);
      sum += w.w[k];
      moment += w.w[k] * node;
      grad_sum += w.grad[k];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) identity[r][c] += node[r] * w.grad[k][c];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(moment[c], x[c], 1e-13);
      EXPECT_NEAR(grad_sum[c], 0.0, 1e-13 / h);
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(identity[r][c], r == c ? 1.0 : 0.0, 1e-12);
    }
  }
}

// Reference (Jiang et al. 2015): for nodal velocities of an affine field v_I = A x_I + b,
// v_p = sum S v_I = A x_p + b and C_p = sum S v_I (x_I - x_p)^T D_p^-1 = A, because
// sum S (x_I - x_p) = 0 and D_p = sum S (x_I - x_p)(x_I - x_p)^T; D_p >= (a h)^2 / 3 per axis.
TEST(Gimp, AffineMomentRecoversTheGradientOfAnAffineField) {
  GridSettings settings;
  settings.cell = h;
  settings.min = {0.0, 0.0, 0.0};
  settings.max = {5.0, 5.0, 5.0};
  const BackgroundGrid grid(settings, 1);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    Mat3 a_true;
    for (auto& row : a_true.m)
      for (double& v : row) v = 10.0 * u(rng);
    const Vec3 b{u(rng), u(rng), u(rng)};
    const double a = 0.25 + 0.25 * u(rng);
    const Vec3 x{2.5 + 2.0 * u(rng), 2.5 + 2.0 * u(rng), 2.5 + 2.0 * u(rng)};
    const GimpWeights w = grid.gimp_weights(x, a);
    Vec3 v_p;
    Mat3 moment;
    for (int n = 0; n < 27; ++n) {
      const auto k = static_cast<std::size_t>(n);
      const Vec3 v = a_true * (x + w.offset(n)) + b;
      v_p += w.w[k] * v;
      add_outer(moment, w.w[k] * v, w.offset(n));
    }
    const Vec3 expected = a_true * x + b;
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(v_p[r], expected[r], 1e-12);
      const double d = 1.0 / w.axis[static_cast<std::size_t>(r)].inverse_moment;
      EXPECT_GE(d, (a * h) * (a * h) / 3.0 * (1.0 - 1e-12));
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(moment.m[r][c] * w.axis[static_cast<std::size_t>(c)].inverse_moment,
                    a_true.m[r][c], 1e-11);
    }
  }
}

// Reference: near the edge of a node's support S = t^2 / (4 a), dS/dx = t / (2 a h) with t the
// overlap in cells, so |dS/dx|^2 h^2 / S = 1 / a, and inside the support it is smaller.
// The force a barely reached node gets over its mass, (V sigma dS) / (m S), stays bounded;
// for the linear hat (weight f, gradient 1 / h) the same ratio is 1 / f.
TEST(Gimp, SquaredGradientOverWeightIsBoundedWhereTheLinearHatIsNot) {
  for (double a : {0.125, 0.25, 0.5}) {
    double worst = 0.0;
    for (int k = 1; k < 100000; ++k) {
      const double xi = 3.0 + k * 1e-5;
      const GimpAxis g = gimp_axis(xi, a, h);
      for (int n = 0; n < 3; ++n) {
        const auto j = static_cast<std::size_t>(n);
        if (g.w[j] > 0.0) worst = std::max(worst, g.grad[j] * g.grad[j] * h * h / g.w[j]);
      }
    }
    EXPECT_LE(worst, 1.0 / a * (1.0 + 1e-9)) << "a = " << a;
    EXPECT_GT(worst, 0.99 / a) << "a = " << a;  // the bound is reached at the support's edge
  }
}

}  // namespace
}  // namespace afemp::core
