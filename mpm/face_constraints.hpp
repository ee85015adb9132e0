// The grid faces' conditions at a node (fixed, symmetric, wall, absorbing), as the momentum
// update applies them (grid_momentum_update.cpp) and the particle walls respect them
// (particle_wall_contact.cpp).
#pragma once

#include <algorithm>
#include <array>

#include "core/grid/background_grid.hpp"
#include "mpm/absorbing_faces.hpp"

namespace afemp::mpm {

// The velocity components constrained at a node (bit a: component a): always, and only
// when the velocity points out of the domain through a wall face.
struct NodeConstraint {
  unsigned always = 0;
  unsigned wall_low = 0;   // walls at a min face: constrain if v_a < 0
  unsigned wall_high = 0;  // walls at a max face: constrain if v_a > 0
  // Absorbing faces (absorbing_faces.hpp): 2 c / h per component, c_L along the normal of each
  // absorbing face the node lies on, c_S across it (the largest where faces meet).
  bool damped = false;
  Vec3 damping{};
  // Far-field faces whose plane the node lies on (bit f: face f, xmin, xmax, ...): their normal
  // component takes far_field_update instead of the damping.
  unsigned far = 0;
  bool any() const { return (always | wall_low | wall_high) != 0; }
  // The mask to apply for the (unconstrained) updated velocity v.
  unsigned mask_for(const Vec3& v) const {
    unsigned m = always;
    for (int a = 0; a < 3; ++a) {
      if ((wall_low >> a) & 1u && v[a] < 0.0) m |= 1u << a;
      if ((wall_high >> a) & 1u && v[a] > 0.0) m |= 1u << a;
    }
    return m;
  }
};

class FaceConstraints {
 public:
  // absorbing: the solver's absorbing faces (their damping is applied by the momentum update
  // only), or nullptr.
  explicit FaceConstraints(const core::BackgroundGrid& g,
                           const std::array<AbsorbingFace, 6>* absorbing = nullptr)
      : last_(g.nodes()), two_over_h_(2.0 * g.inverse_cell()) {
    if (absorbing)
      for (const AbsorbingFace& f : *absorbing) any_absorbing_ = any_absorbing_ || f.on;
    if (any_absorbing_) absorbing_ = *absorbing;
    const auto& f = g.settings().faces;
    for (int a = 0; a < 3; ++a) {
      lo_[a] = f[static_cast<std::size_t>(2 * a)];
      hi_[a] = f[static_cast<std::size_t>(2 * a + 1)];
      last_[static_cast<std::size_t>(a)] -= 1;
    }
  }
  NodeConstraint operator()(const std::array<int, 3>& node) const {
    NodeConstraint c;
    for (int a = 0; a < 3; ++a) {
      // Halo nodes beyond a face (uGIMP) take the face's condition.
      if (node[static_cast<std::size_t>(a)] <= 0) {
        add(c, lo_[a], a, false);
        if (any_absorbing_)
          damp(c, absorbing_[static_cast<std::size_t>(2 * a)], 2 * a,
               node[static_cast<std::size_t>(a)] == 0);
      }
      if (node[static_cast<std::size_t>(a)] >= last_[static_cast<std::size_t>(a)]) {
        add(c, hi_[a], a, true);
        if (any_absorbing_)
          damp(c, absorbing_[static_cast<std::size_t>(2 * a + 1)], 2 * a + 1,
               node[static_cast<std::size_t>(a)] == last_[static_cast<std::size_t>(a)]);
      }
    }
    return c;
  }

 private:
  static void add(NodeConstraint& c, core::FaceCondition f, int axis, bool high) {
    switch (f) {
      case core::FaceCondition::fixed:
        c.always |= 7u;
        break;
      case core::FaceCondition::symmetric:
        c.always |= 1u << axis;
        break;
      case core::FaceCondition::wall:
        (high ? c.wall_high : c.wall_low) |= 1u << axis;
        break;
      case core::FaceCondition::free:
      case core::FaceCondition::outflow:  // particles beyond it leave (outflow.cpp)
      case core::FaceCondition::absorbing:
        break;  // damped after the update (absorbing_faces.cpp)
    }
  }
  // on_plane: the node lies on the face's plane (not in the halo beyond it).
  void damp(NodeConstraint& c, const AbsorbingFace& f, int face, bool on_plane) const {
    if (!f.on) return;
    const int axis = face / 2;
    const bool far = f.far && on_plane;
    if (far) c.far |= 1u << face;
    for (int b = 0; b < 3; ++b) {
      if (b == axis && far) continue;
      const double rate = two_over_h_ * (b == axis ? f.c_longitudinal : f.c_shear);
      if (rate > 0.0) c.damped = true;
      c.damping[b] = std::max(c.damping[b], rate);
    }
  }
  core::FaceCondition lo_[3], hi_[3];
  std::array<int, 3> last_;
  double two_over_h_;
  bool any_absorbing_ = false;
  std::array<AbsorbingFace, 6> absorbing_{};
};

inline void constrain(Vec3& v, unsigned mask) {
  if (mask & 1u) v.x = 0.0;
  if (mask & 2u) v.y = 0.0;
  if (mask & 4u) v.z = 0.0;
}

}  // namespace afemp::mpm
