// Rigid bodies of hexahedra (LS-DYNA *MAT_RIGID): 6 degrees of freedom, the mass, centre of
// mass and inertia tensor summed from the lumped node masses of the body's elements (so the
// nodes' kinetic energy and momenta are exactly the body's). Newton-Euler by central
// differences: v^{n+1/2} = v^{n-1/2} + dt F / M for the centre, and for the rotation the
// angular momentum L^{n+1/2} = L^{n-1/2} + dt M_c (Euler's equations in their conserving form),
// omega = R I0^-1 R^T L, R^{n+1} = exp(dt [omega]) R^n (Rodrigues' formula). Fixed components
// keep their initial value. Contact impulses on the body's nodes join its momenta
// (add_impulse); no other stage changes a rigid node's velocity.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::fem {

using core::Mat3;
using core::Vec3;

struct RigidBody {
  int body = -1;
  std::array<bool, 6> fixed{};  // x y z rx ry rz
  Vec3 initial_velocity;        // what fixed translation components keep
  std::vector<std::int32_t> nodes;
  std::vector<Vec3> offset0;  // x_i - centre at the start
  double mass = 0.0;
  Mat3 inertia0;  // about the centre, in the initial axes
  Mat3 rotation{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  Vec3 centre, velocity, angular_momentum, angular_velocity;
  Mat3 inverse_inertia;  // current axes, fixed rotation components removed
  // The resultant of this step's forces on the body (contacts, loads, gravity) and their
  // moment about the centre; and the reaction of its fixed components (what holds them: the
  // change of momentum they undid, over the step), zero for a free body. A fixed anvil's
  // reaction is minus the contact force on it.
  Vec3 force, moment;
  Vec3 reaction, reaction_moment;
  double force_step = 0.0;  // dt^n of this step, which turns the impulses into forces
};

// The body's mass, centre and inertia from its nodes' masses and positions; its velocity.
RigidBody make_rigid_body(int body, const std::array<bool, 6>& fixed,
                          std::vector<std::int32_t> nodes, const std::vector<Vec3>& position,
                          const std::vector<double>& mass, const Vec3& velocity);

// Advances the momenta by the force and moment acting over dt_force (dt^n of the central
// difference), applies the fixed components, and returns the work the fixed components'
// reactions did (prescribed translation times the reaction impulse). Starts the step's force,
// moment and reactions.
double advance_momenta(RigidBody& r, const Vec3& force, const Vec3& moment, double dt_force);

// Adds a momentum impulse J and angular impulse H (about the centre) within a step and applies
// the fixed components again; returns the reactions' work as advance_momenta does. The
// impulses join the step's force and moment.
double add_impulse(RigidBody& r, const Vec3& impulse, const Vec3& angular_impulse);

// omega from L at the current rotation (fixed rotation components held at zero, the free ones
// solved from the inertia with them); returns the angular impulse the fixed components' reaction
// gave (L = I omega afterwards).
Vec3 update_angular_velocity(RigidBody& r);

// The inverse of the body's effective mass at a point (offset from the centre) along unit
// direction n: the free translations' share of 1/M plus (r x n) . I^-1 (r x n).
double rigid_inverse_mass(const RigidBody& r, const Vec3& offset, const Vec3& n);

// The velocity of a point of the body at offset x - centre.
inline Vec3 point_velocity(const RigidBody& r, const Vec3& offset) {
  return r.velocity + core::cross(r.angular_velocity, offset);
}

// Moves the centre and the rotation over dt (velocities at the half step).
void advance_pose(RigidBody& r, double dt);

// Multiplies the body's motion by `factor` (dynamic relaxation, core::Model::scale_velocities):
// its free translation components, and its angular momentum with the angular velocity (both
// linear in it at the current rotation, so L = I omega still holds, fixed rotations staying at
// zero); fixed translation components keep their initial value.
void scale_motion(RigidBody& r, double factor);

// The current offset of node k of the body (R offset0).
inline Vec3 node_offset(const RigidBody& r, std::size_t k) {
  return r.rotation * r.offset0[k];
}

}  // namespace afemp::fem
