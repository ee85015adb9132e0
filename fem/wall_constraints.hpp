// Rigid planar walls as exact constraints of the implicit solves (fem/static_solve.hpp):
// frictionless unilateral contact of nodes with fixed planes (LS-DYNA *RIGIDWALL_PLANAR, the
// explicit solver's [[walls]]: fem/rigid_wall.cpp) by an active set. A node in contact has its
// displacement along the wall's normal prescribed so that it lies on the plane: its free
// components are rotated into a frame whose first axes are its walls' normals (a skew boundary
// condition), and those components are held as prescribed dofs are. Between Newton solves of
// one step the set changes: a node that has crossed a plane enters it, a node its wall pulls
// leaves it, until it no longer changes (the active-set strategy; Wriggers 2006).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "afemp/scene.hpp"
#include "afemp/tensor.hpp"
#include "fem/mesh.hpp"

namespace afemp::fem {

// A rigid planar wall (its point and normal: core::WallSpec, the normal pointing to the side
// the nodes stay on) and the nodes it may touch, as the explicit solver's WallState lists them.
// The implicit solves take fixed, frictionless walls: a velocity or a friction is refused.
struct PlanarWall {
  core::WallSpec spec;
  std::vector<std::int32_t> nodes;
};

// A node in contact: component i of its displacement in the frame is basis[i] . u. Its
// prescribed components keep their axes (basis[i] = e_i); its free ones are rotated so that the
// first `held` of them, at slot[0 .. held), are the orthonormalised normals h_j of its walls
// wall[0 .. held) (Gram-Schmidt on the normals with the prescribed components removed, p_w),
// and a[w][j] = p_w . h_j (lower triangular).
struct NodeFrame {
  std::array<core::Vec3, 3> basis{};
  int held = 0;
  std::array<int, 3> slot{}, wall{};
  std::array<std::array<double, 3>, 3> a{};
  bool holds(int component) const {
    for (int j = 0; j < held; ++j)
      if (slot[j] == component) return true;
    return false;
  }
};

class WallConstraints {
 public:
  // Validates the walls (`who` starts the messages): nodes in range, a non-zero normal (made
  // unit), no velocity, no friction. fixed: per node, its three components that no wall may
  // move (the prescribed ones; all three of a node of no element).
  WallConstraints(const MeshData& mesh, std::span<const PlanarWall> walls, std::vector<char> fixed,
                  const char* who);

  bool empty() const { return walls_.empty(); }
  std::size_t size() const { return walls_.size(); }
  // The set at displacement u: the nodes on or behind their walls' planes.
  void start(const std::vector<core::Vec3>& u);
  // Moves the nodes of the set onto their planes along their free components.
  void project(std::vector<core::Vec3>& u) const;
  // The set's (node, normal) pairs: what the walls hold.
  std::vector<std::pair<std::int32_t, core::Vec3>> supports() const;
  // How many (wall, node) pairs are in contact.
  int contacts() const;
  // The frame of node n, or null when no wall holds it.
  const NodeFrame* frame(std::size_t n) const {
    return frame_of_[n] < 0 ? nullptr : &frames_[static_cast<std::size_t>(frame_of_[n])];
  }
  // Rotates the symmetric element matrix k (3 rows per node of `nodes`, row-major) into the
  // nodes' frames and decouples their held components (their rows and columns zero but for
  // the diagonal), so that a correction leaves them as they are.
  void transform(const std::int32_t* nodes, int count, double* k) const;
  // Removes from v and a, per node of the set, their components along its held normals: a
  // node on a wall is at rest along them, as a prescribed dof is (the Newmark solve: a node
  // that arrived in the step keeps no stopping acceleration into the next).
  void stop(std::vector<core::Vec3>& v, std::vector<core::Vec3>& a) const;
  // Per wall, its force on the nodes, sum of lambda n over the set, from the residual
  // (external minus internal, minus inertia) per node at equilibrium: the held components of
  // the residual are what the walls balance, A^T lambda = -(h_j . r).
  std::vector<core::Vec3> forces(const std::vector<core::Vec3>& residual) const;
  // After a converged solve: the pairs whose wall pulls (lambda < -force_tolerance) leave the
  // set, the nodes behind a plane (by more than 1e-12 of the mesh's size) enter it. Returns
  // whether the set changed; `change` then names the first change, for messages.
  bool update(const std::vector<core::Vec3>& u, const std::vector<core::Vec3>& residual,
              double force_tolerance, std::string& change);

 private:
  double gap(std::size_t w, std::int32_t node, const std::vector<core::Vec3>& u) const;
  // n_w with node's prescribed components removed, and |p_w|^2 (0: the wall cannot move it).
  core::Vec3 free_normal(std::size_t w, std::int32_t node) const;
  void build_frames();
  // Per frame, the walls' multipliers lambda (in frame.wall order).
  std::array<double, 3> multipliers(const NodeFrame& f, const core::Vec3& residual) const;

  const MeshData& mesh_;
  std::vector<PlanarWall> walls_;
  std::vector<char> fixed_;
  std::vector<std::string> names_;  // "wall 0 (file:line)", for messages
  double length_tolerance_ = 0.0;
  std::vector<std::vector<char>> active_;  // per wall, per listed node
  std::vector<int> frame_of_;              // per node, into frames_, or -1
  std::vector<NodeFrame> frames_;
  std::vector<std::int32_t> frame_node_;  // per frame
};

}  // namespace afemp::fem
