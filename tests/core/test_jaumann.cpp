// Objectivity of the Jaumann rate (Ma 2005, eqs 2-17, 2-41): under a pure spin (no rate of
// deformation) the stress must rotate with the material, sigma(t) = R sigma0 R^T, without
// changing its invariants. Eigen supplies the exact rotation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "afemp/tensor.hpp"

namespace afemp::core {
namespace {

Eigen::Matrix3d to_matrix(const SymTensor& s) {
  Eigen::Matrix3d m;
  m << s.xx, s.xy, s.xz, s.xy, s.yy, s.yz, s.xz, s.yz, s.zz;
  return m;
}

// Integrates d sigma = W sigma - sigma W over a quarter turn about `axis` in n steps and
// returns the error against R sigma0 R^T, relative to |sigma0|.
double quarter_turn_error(const Eigen::Vector3d& axis, int n) {
  const SymTensor s0{120.0, -40.0, 15.0, 30.0, -25.0, 55.0};
  const double angle = 0.5 * std::numbers::pi;
  const Eigen::Vector3d w = (angle / n) * axis.normalized();  // spin increment omega dt
  // W v = omega x v: W_12 = -w_z, W_13 = w_y, W_23 = -w_x.
  SymTensor s = s0;
  for (int k = 0; k < n; ++k) s += jaumann_increment(s, -w.x(), w.y(), -w.z());
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  const Eigen::Matrix3d exact = r * to_matrix(s0) * r.transpose();
  return (to_matrix(s) - exact).norm() / to_matrix(s0).norm();
}

TEST(Jaumann, SpinRotatesStressLikeTheMaterial) {
  // Reference: sigma = R sigma0 R^T after a quarter turn about an oblique axis. The explicit
  // increment of eq 2-41 is first-order accurate: error below 1e-3 of |sigma0| with 4000
  // steps, and halved (ratio 1.8 to 2.2) when the steps double.
  const Eigen::Vector3d axis(1.0, -2.0, 0.5);
  const double coarse = quarter_turn_error(axis, 4000), fine = quarter_turn_error(axis, 8000);
  EXPECT_LT(coarse, 1e-3);
  EXPECT_GT(coarse / fine, 1.8);
  EXPECT_LT(coarse / fine, 2.2);
}

TEST(Jaumann, SpinLeavesStressInvariantsNearlyUnchanged) {
  // Reference: a rotation keeps the trace exactly (tr(W s - s W) = 0, to round-off 1e-12)
  // and the von Mises stress up to the explicit increment's growth, at most 2 (omega dt)^2
  // per step: 1.2e-3 over a quarter turn in 4000 steps (measured 1.1e-3), bound 2e-3.
  const SymTensor s0{120.0, -40.0, 15.0, 30.0, -25.0, 55.0};
  SymTensor s = s0;
  const double dw = 0.5 * std::numbers::pi / 4000.0;
  for (int k = 0; k < 4000; ++k) s += jaumann_increment(s, 0.3 * dw, -0.5 * dw, 0.8 * dw);
  EXPECT_NEAR(s.trace(), s0.trace(), 1e-12 * std::abs(s0.xx));
  EXPECT_NEAR(von_mises(s), von_mises(s0), 2e-3 * von_mises(s0));
}

}  // namespace
}  // namespace afemp::core
