// Rigid bodies (rigid_body.hpp): Newton-Euler with the angular momentum as the integrated
// variable (Simo & Wong 1991, "Unconditionally stable algorithms for rigid body dynamics that
// exactly preserve energy and momentum", IJNME 31, the explicit form), rotations by Rodrigues'
// formula.
#include "fem/rigid_body.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace afemp::fem {

namespace {

Eigen::Matrix3d to_eigen(const Mat3& a) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = a.m[i][j];
  return m;
}

Mat3 from_eigen(const Eigen::Matrix3d& m) {
  Mat3 a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a.m[i][j] = m(i, j);
  return a;
}

Eigen::Vector3d to_eigen(const Vec3& v) {
  return {v.x, v.y, v.z};
}
Vec3 from_eigen(const Eigen::Vector3d& v) {
  return {v(0), v(1), v(2)};
}

// Fixed translation components keep their initial value; returns the reaction's work
// (reaction impulse M (v_fixed - v_free) times the prescribed velocity) and the reaction impulse.
double hold_translation(RigidBody& r, Vec3& reaction) {
  double work = 0.0;
  for (int a = 0; a < 3; ++a)
    if (r.fixed[static_cast<std::size_t>(a)]) {
      const double target = r.initial_velocity[a];
      const double impulse = r.mass * (target - r.velocity[a]);
      reaction[a] += impulse;
      work += impulse * target;
      r.velocity[a] = target;
    }
  return work;
}

// Applies the fixed components after the momenta changed by the impulses J and H over the
// step; the reactions join the step's.
double hold(RigidBody& r) {
  Vec3 reaction;
  const double work = hold_translation(r, reaction);
  const Vec3 angular = update_angular_velocity(r);
  if (r.force_step > 0.0) {
    r.reaction += (1.0 / r.force_step) * reaction;
    r.reaction_moment += (1.0 / r.force_step) * angular;
  }
  return work;
}

}  // namespace

RigidBody make_rigid_body(int body, const std::array<bool, 6>& fixed,
                          std::vector<std::int32_t> nodes, const std::vector<Vec3>& position,
                          const std::vector<double>& mass, const Vec3& velocity) {
  RigidBody r;
  r.body = body;
  r.fixed = fixed;
  r.initial_velocity = velocity;
  r.nodes = std::move(nodes);
  Vec3 moment;
  for (std::int32_t k : r.nodes) {
    const double m = mass[static_cast<std::size_t>(k)];
    r.mass += m;
    moment += m * position[static_cast<std::size_t>(k)];
  }
  r.centre = (1.0 / r.mass) * moment;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (std::int32_t k : r.nodes) {
    const Vec3 d = position[static_cast<std::size_t>(k)] - r.centre;
    r.offset0.push_back(d);
    const Eigen::Vector3d e = to_eigen(d);
    inertia += mass[static_cast<std::size_t>(k)] *
               (e.squaredNorm() * Eigen::Matrix3d::Identity() - e * e.transpose());
  }
  r.inertia0 = from_eigen(inertia);
  r.velocity = velocity;
  Vec3 start;
  hold_translation(r, start);
  update_angular_velocity(r);
  return r;
}

Vec3 update_angular_velocity(RigidBody& r) {
  const Eigen::Matrix3d R = to_eigen(r.rotation);
  const Eigen::Matrix3d I = R * to_eigen(r.inertia0) * R.transpose();
  Eigen::Vector3d L = to_eigen(r.angular_momentum);
  // The free components solve I_ff w_f = L_f with the fixed ones at zero (a fixed component's
  // row and column replaced by the identity's); the fixed components' reaction moments make
  // L = I w again.
  Eigen::Matrix3d A = I;
  const double scale = std::max(I.diagonal().maxCoeff(), 1e-300);
  bool any_fixed = false;
  for (int a = 0; a < 3; ++a)
    if (r.fixed[static_cast<std::size_t>(3 + a)]) {
      any_fixed = true;
      A.row(a).setZero();
      A.col(a).setZero();
      A(a, a) = scale;
      L(a) = 0.0;
    }
  // The pseudo-inverse: a body whose nodes lie on one line has no inertia about it and does
  // not turn about it.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A);
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  Eigen::Vector3d inv = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    if (eig.eigenvalues()(a) > 1e-12 * largest) inv(a) = 1.0 / eig.eigenvalues()(a);
  Eigen::Matrix3d pinv = eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
  for (int a = 0; a < 3; ++a)
    if (r.fixed[static_cast<std::size_t>(3 + a)]) {
      pinv.row(a).setZero();
      pinv.col(a).setZero();
    }
  r.inverse_inertia = from_eigen(pinv);
  const Eigen::Vector3d w = pinv * L;
  r.angular_velocity = from_eigen(w);
  if (!any_fixed) return {};
  const Vec3 held = from_eigen(Eigen::Vector3d(I * w));
  const Vec3 reaction = held - r.angular_momentum;
  r.angular_momentum = held;
  return reaction;
}

double rigid_inverse_mass(const RigidBody& r, const Vec3& offset, const Vec3& n) {
  double w = 0.0;
  for (int a = 0; a < 3; ++a)
    if (!r.fixed[static_cast<std::size_t>(a)]) w += n[a] * n[a] / r.mass;
  const Vec3 rn = core::cross(offset, n);
  return w + core::dot(rn, r.inverse_inertia * rn);
}

double advance_momenta(RigidBody& r, const Vec3& force, const Vec3& moment, double dt_force) {
  r.force = force;
  r.moment = moment;
  r.reaction = r.reaction_moment = Vec3{};
  r.force_step = dt_force;
  r.velocity += (dt_force / r.mass) * force;
  r.angular_momentum += dt_force * moment;
  return hold(r);
}

double add_impulse(RigidBody& r, const Vec3& impulse, const Vec3& angular_impulse) {
  if (r.force_step > 0.0) {
    r.force += (1.0 / r.force_step) * impulse;
    r.moment += (1.0 / r.force_step) * angular_impulse;
  }
  r.velocity += (1.0 / r.mass) * impulse;
  r.angular_momentum += angular_impulse;
  return hold(r);
}

void advance_pose(RigidBody& r, double dt) {
  r.centre += dt * r.velocity;
  const Eigen::Vector3d w = to_eigen(r.angular_velocity);
  const double angle = dt * w.norm();
  if (angle > 0.0) {
    const Eigen::Matrix3d step = Eigen::AngleAxisd(angle, w.normalized()).toRotationMatrix();
    r.rotation = from_eigen(Eigen::Matrix3d(step * to_eigen(r.rotation)));
  }
}

void scale_motion(RigidBody& r, double factor) {
  for (int a = 0; a < 3; ++a)
    r.velocity[a] =
        r.fixed[static_cast<std::size_t>(a)] ? r.initial_velocity[a] : factor * r.velocity[a];
  r.angular_momentum *= factor;
  r.angular_velocity *= factor;
}

}  // namespace afemp::fem
