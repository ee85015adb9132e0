// Quadratic and cubic B-spline weights, modified at the grid's faces (core/grid/bspline.hpp;
// Steffen, Kirby & Berzins 2008; de Vaucorbeil et al. 2020). References: away from the faces the
// weights are the uniform B-splines' closed forms; everywhere in the domain, the face cells
// included, they reproduce constants and linear fields (sum S = 1, sum S x_I = x_p,
// sum grad S = 0, sum x_I (x) grad S = I); the gradient is the derivative of the weight
// (central differences) and both are continuous across every knot (the quadratic is C1, the
// cubic C2: a particle crossing a cell face sees no jump in its gradient); S_0 = 1 on the face
// and no node beyond a face takes a weight; the APIC moment recovers an affine field's gradient.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/grid/background_grid.hpp"
#include "core/grid/bspline.hpp"
#include "core/scene.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

constexpr double h = 0.5;  // cell size
constexpr int cells = 10;  // along the axis of the 1-D checks

// The uniform B-splines centred on the node, r in cells.
double quadratic(double r) {
  const double a = std::abs(r);
  if (a < 0.5) return 0.75 - a * a;
  if (a < 1.5) return 0.5 * (1.5 - a) * (1.5 - a);
  return 0.0;
}
double cubic(double r) {
  const double a = std::abs(r);
  if (a < 1.0) return 2.0 / 3.0 - a * a + 0.5 * a * a * a;
  if (a < 2.0) return (2.0 - a) * (2.0 - a) * (2.0 - a) / 6.0;
  return 0.0;
}

// Weight and gradient of node `node` at xi (0 when the node is outside the stencil).
template <int Order>
std::pair<double, double> node_weight(double xi, int node) {
  const AxisWeights<Order + 1> a = bspline_axis<Order>(xi, cells, h);
  const int k = node - a.base;
  if (k < 0 || k > Order) return {0.0, 0.0};
  return {a.w[static_cast<std::size_t>(k)], a.grad[static_cast<std::size_t>(k)]};
}

template <int Order>
void check_axis() {
  SCOPED_TRACE("order " + std::to_string(Order));
  std::mt19937_64 rng(Order);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 4000; ++trial) {
    // A quarter of the points in the face cells, the rest anywhere.
    double xi = trial % 4 == 0 ? u(rng) : cells * u(rng);
    if (trial % 8 == 4) xi = cells - u(rng);
    const AxisWeights<Order + 1> a = bspline_axis<Order>(xi, cells, h);
    double sum = 0.0, first = 0.0, grad_sum = 0.0, grad_first = 0.0;
    for (int k = 0; k <= Order; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const int node = a.base + k;
      if (node < 0 || node > cells) {
        EXPECT_EQ(a.w[kk], 0.0) << "node " << node << " xi " << xi;
      }
      EXPECT_GE(a.w[kk], 0.0);
      EXPECT_DOUBLE_EQ(a.offset[kk], (node - xi) * h);
      sum += a.w[kk], first += a.w[kk] * node * h;
      grad_sum += a.grad[kk], grad_first += a.grad[kk] * node * h;
      // Away from the faces: the uniform B-spline.
      if (xi > Order && xi < cells - Order) {
        EXPECT_NEAR(a.w[kk], Order == 2 ? quadratic(xi - node) : cubic(xi - node), 1e-14);
      }
      // The gradient is the weight's derivative.
      const double d = 1e-6;
      const double fd =
          (node_weight<Order>(xi + d, node).first - node_weight<Order>(xi - d, node).first) /
          (2.0 * d * h);
      if (xi > d && xi < cells - d) {
        EXPECT_NEAR(a.grad[kk], fd, 1e-6 / h) << "xi " << xi;
      }
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_NEAR(first, xi * h, 1e-13);
    EXPECT_NEAR(grad_sum, 0.0, 1e-13 / h);
    EXPECT_NEAR(grad_first, 1.0, 1e-13);
  }
  // Continuity of weight and gradient across every knot (the quadratic's knots are the cell
  // middles, the cubic's the nodes), for every node that reaches it.
  for (int knot = 0; knot <= 2 * cells; ++knot) {
    const double x = (Order == 2 ? 0.5 : 1.0) * knot;
    if (x <= 0.0 || x >= cells) continue;
    for (int node = 0; node <= cells; ++node) {
      const double e = 1e-9;
      const auto lo = node_weight<Order>(x - e, node), hi = node_weight<Order>(x + e, node);
      EXPECT_NEAR(lo.first, hi.first, 1e-8) << "node " << node << " at " << x;
      EXPECT_NEAR(lo.second, hi.second, 1e-8 / h) << "node " << node << " at " << x;
    }
  }
  // On the faces the face node takes everything.
  EXPECT_DOUBLE_EQ(node_weight<Order>(0.0, 0).first, 1.0);
  EXPECT_DOUBLE_EQ(node_weight<Order>(cells, cells).first, 1.0);
}

TEST(Bspline, QuadraticWeightsAreTheBsplineInsideAndKeepLinearFieldsUpToTheFaces) {
  check_axis<2>();
}

TEST(Bspline, CubicWeightsAreTheBsplineInsideAndKeepLinearFieldsUpToTheFaces) {
  check_axis<3>();
}

// In 3-D, on a grid of 9 x 6 x 4 cells (the cubic's faces meet): S, grad S and the APIC moment
// D_p (Jiang et al. 2015): for nodal velocities v_I = A x_I + b, sum S v_I = A x_p + b and
// sum S v_I (x_I - x_p)^T D_p^-1 = A.
template <int Order>
void check_3d() {
  SCOPED_TRACE("order " + std::to_string(Order));
  GridSettings settings;
  settings.cell = h;
  settings.min = {-1.0, 0.0, 2.0};
  settings.max = {3.5, 3.0, 4.0};
  const BackgroundGrid grid(settings, 1);
  std::mt19937_64 rng(10 + Order);
  std::uniform_real_distribution<double> u(0.0, 1.0), s(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 x{-1.0 + 4.5 * u(rng), 3.0 * u(rng), 2.0 + 2.0 * u(rng)};
    const SplineWeights<Order> w = grid.spline_weights<Order>(x);
    Mat3 a_true;
    for (auto& row : a_true.m)
      for (double& v : row) v = 10.0 * s(rng);
    const Vec3 b{s(rng), s(rng), s(rng)};
    double sum = 0.0;
    Vec3 grad_sum, v_p;
    Mat3 moment;
    double identity[3][3] = {};
    for (int n = 0; n < SplineWeights<Order>::nodes; ++n) {
      const auto k = static_cast<std::size_t>(n);
      const Vec3 node = x + w.offset(n);
      sum += w.w[k];
      grad_sum += w.grad[k];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) identity[r][c] += node[r] * w.grad[k][c];
      const Vec3 v = a_true * node + b;
      v_p += w.w[k] * v;
      add_outer(moment, w.w[k] * v, w.offset(n));
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    const Vec3 expected = a_true * x + b;
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(grad_sum[r], 0.0, 1e-13 / h);
      EXPECT_NEAR(v_p[r], expected[r], 1e-12);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(identity[r][c], r == c ? 1.0 : 0.0, 1e-12);
        EXPECT_NEAR(moment.m[r][c] * w.axis[static_cast<std::size_t>(c)].inverse_moment,
                    a_true.m[r][c], 1e-9);
      }
    }
  }
}

TEST(Bspline, WeightsReproduceLinearFieldsAndAffineMomentsIn3D) {
  check_3d<2>();
  check_3d<3>();
}

// Bad input: a grid with fewer cells along an axis than the spline needs is refused with the
// file, the key and the cells it has.
TEST(Bspline, GridTooSmallForTheSplineIsRefused) {
  auto scene = [](const char* shape) {
    return std::string(
               "[run]\nend_time = 1.0\n"
               "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [8, 2, 8]\n"
               "[mpm]\nshape_function = \"") +
           shape +
           "\"\n"
           "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
           "[[bodies]]\nname = \"b\"\nmaterial = \"steel\"\n"
           "shape = { box = { min = [2, 0.5, 2], max = [6, 1.5, 6] } }\n";
  };
  const std::string text = scene("bspline3");
  const std::string e = test::error_of(text, "small.toml");
  const std::string at = "small.toml:" + std::to_string(test::line_of(text, "shape_function"));
  for (const std::string& part :
       {at, std::string("shape_function"), std::string("\"bspline3\" needs at least 3 cells"),
        std::string("2 along y")})
    EXPECT_NE(e.find(part), std::string::npos) << part << " in: " << e;
  EXPECT_NO_THROW((void)parse_scene(scene("bspline2"), "small.toml"));
}

}  // namespace
}  // namespace afemp::core
