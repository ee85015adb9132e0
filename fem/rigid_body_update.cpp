// The rigid bodies' part of the FE step (rigid_body.hpp): after the nodal update, each body
// takes the resultant of its nodes' loads (program loads, gravity; its elements carry none)
// and their moment about its centre, advances its momenta, and gives its nodes v + omega x r.
// Mesh contacts hand it their impulses directly (mesh_contact.cpp); then the body moves and its
// nodes follow exactly: x = c + R r0.
#include "core/parallel.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {

void FeSolver::setup_rigid_bodies() {
  std::vector<std::vector<std::int32_t>> nodes(scene_.bodies.size());
  for (std::size_t n = 0; n < nodes_.size(); ++n) {
    const int b = nodes_.body[n];
    if (b >= 0 && scene_.bodies[static_cast<std::size_t>(b)].rigid && nodes_.mass[n] > 0.0)
      nodes[static_cast<std::size_t>(b)].push_back(static_cast<std::int32_t>(n));
  }
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const core::BodySpec& body = scene_.bodies[b];
    if (!body.rigid) continue;
    if (rigid_of_node_.empty()) rigid_of_node_.assign(nodes_.size(), -1);
    for (std::int32_t n : nodes[b])
      rigid_of_node_[static_cast<std::size_t>(n)] = static_cast<std::int32_t>(rigid_bodies_.size());
    rigid_bodies_.push_back(make_rigid_body(static_cast<int>(b), body.rigid->fixed,
                                            std::move(nodes[b]), nodes_.position, nodes_.mass,
                                            body.velocity));
    RigidBody& r = rigid_bodies_.back();
    for (std::size_t k = 0; k < r.nodes.size(); ++k)
      nodes_.velocity[static_cast<std::size_t>(r.nodes[k])] = point_velocity(r, r.offset0[k]);
  }
}

void FeSolver::advance_rigid_bodies(double dt) {
  const double dt_force = force_step(dt);
  const Vec3 g = scene_.run.gravity;
  // A program's held loads and the scene's [[loads]] on a node.
  auto load = [&](std::size_t i) {
    Vec3 f;
    if (!nodes_.external_force.empty()) f += nodes_.external_force[i];
    if (!load_force_.empty()) f += load_force_[i];
    return f;
  };
  for (RigidBody& r : rigid_bodies_) {
    Vec3 force = r.mass * g, moment;
    for (std::size_t k = 0; k < r.nodes.size(); ++k) {
      const auto i = static_cast<std::size_t>(r.nodes[k]);
      const Vec3 f = load(i);
      force += f;
      moment += core::cross(nodes_.position[i] - r.centre, f);
    }
    external_work_ += advance_momenta(r, force, moment, dt_force);
    // Gravity and loads work on the body's motion over the step ahead (as in the nodal update):
    // each load at its node's velocity, so that the work of a load's moment is booked too.
    external_work_ += core::dot(r.mass * g, r.velocity) * dt;
    for (std::size_t k = 0; k < r.nodes.size(); ++k) {
      const auto i = static_cast<std::size_t>(r.nodes[k]);
      nodes_.velocity[i] = point_velocity(r, nodes_.position[i] - r.centre);
      external_work_ += core::dot(load(i), nodes_.velocity[i]) * dt;
    }
  }
}

void FeSolver::move_rigid_bodies(double dt) {
  for (RigidBody& r : rigid_bodies_) {
    advance_pose(r, dt);
    for (std::size_t k = 0; k < r.nodes.size(); ++k) {
      const auto i = static_cast<std::size_t>(r.nodes[k]);
      const Vec3 offset = node_offset(r, k);
      nodes_.position[i] = r.centre + offset;
      nodes_.velocity[i] = point_velocity(r, offset);
    }
  }
}

}  // namespace afemp::fem
