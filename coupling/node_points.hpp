// FE nodes that take part in the grid step (the couplings of coupling/, Lian et al. 2013, §2.4 and
// §2.6). They are points with mass, momentum and a force the caller computes (the elements'),
// mapped with the trilinear hat into their body's velocity field, and:
//   - bonded nodes (HFEMP: rebar in concrete) share the field of the particles they are
//     embedded in and are moved by the grid solution exactly like particles (same PIC/FLIP
//     blend), so mass and momentum are conserved as for particles;
//   - contact nodes (CFEMP) have their own field; the caller advances them by the FE update,
//     and the grid step only returns the velocity change grid contact made at the nodes
//     around them, interpolated to each node: sum N_I dv_I. Since the field's nodal mass is
//     sum_n N_I m_n, the nodes receive exactly the impulse the contact gave their field.
// A node outside the grid takes no part in the step (contact) or stops the run (bonded). On MPI
// ranks a node is scattered by the rank that owns its cell's block, and every rank receives
// every node's result (from_grid), so the FE nodes stay the same on every rank.
// They join the MPM solver's step through its neutral grid-points hook (mpm/grid_points.hpp);
// the transfers are in node_transfers.cpp.
#pragma once

#include <cstdint>
#include <vector>

#include "afemp/tensor.hpp"
#include "core/scene.hpp"
#include "mpm/grid_points.hpp"

namespace afemp::coupling {

using core::Vec3;

class NodePoints final : public mpm::GridPoints {
 public:
  // Contact nodes take their own (FE) update; a bonded_to body's nodes move with the grid.
  explicit NodePoints(const core::Scene& scene) {
    for (const core::BodySpec& b : scene.bodies)
      updates_itself_.push_back(!core::bonded_to_particles(scene, b));
  }

  // Set by the caller before each step.
  std::vector<Vec3> position;  // x^n
  std::vector<Vec3> velocity;  // bonded: the node's velocity; contact: v^{n-1/2}
  // Bonded: the elements' force on the node (gravity is added on the grid). Contact: the
  // force of the FE update, m (v^{n+1/2} - v^{n-1/2}) / dt, gravity and conditions included.
  std::vector<Vec3> force;
  std::vector<double> mass;        // 0: the node takes no part (no live element)
  std::vector<std::int32_t> body;  // scene body: its velocity field
  std::vector<std::uint8_t> bonded;
  // Contact nodes of a body with a surface (hexahedra): the outward unit normal of the surface
  // at the node (0 inside the body), which sets the body's normal on the grid instead of its
  // mass gradient (surface = 1). FE nodes lie on a grid plane wherever mesh and grid align,
  // and there the one-sided hat gradient tilts the normal; the surface knows it exactly.
  std::vector<Vec3> normal;
  std::vector<std::uint8_t> surface;
  // Written by the step. Bonded: velocity is the updated one, position moved by `motion`,
  // the grid velocity at the node. Contact: `motion` is the contact's velocity change.
  std::vector<Vec3> motion;
  std::vector<std::uint8_t> on_grid;  // the node lay inside the grid at the step's start

  std::size_t size() const { return position.size(); }
  void resize(std::size_t n) {
    position.resize(n);
    velocity.resize(n);
    force.resize(n);
    mass.resize(n);
    body.resize(n);
    bonded.resize(n);
    normal.resize(n);
    surface.resize(n);
    motion.resize(n);
    on_grid.resize(n);
  }

  // The hook (node_transfers.cpp). A body's nodes that are not bonded take their own update,
  // even where conversion bonds some of them: the grid learns that from its particles.
  bool updates_itself(int b) const override {
    return updates_itself_[static_cast<std::size_t>(b)] != 0;
  }
  // The nodes of the mesh bodies that meet the grid (in contact, bonded or converting), as
  // the owner set them at the start: the blocks where their points are, or will be.
  std::vector<Vec3> partition_points;
  std::span<const Vec3> positions() const override { return partition_points; }
  void bin(const mpm::GridStepAccess& access, std::vector<std::int64_t>& cells) override;
  void to_grid(const mpm::GridStepAccess& access, bool mass_momentum, bool force) override;
  void raise_fixed_bounds(const mpm::GridStepAccess& access,
                          mpm::FixedBounds& bounds) const override;
  void contact_surfaces(const mpm::GridStepAccess& access, bool gradient) override;
  void from_grid(const mpm::GridStepAccess& access) override;
  void remap(const mpm::GridStepAccess& access) override;

 private:
  // On ranks, after from_grid: every rank's points' velocity and motion to every rank.
  void share_results(core::RankLink& ranks);

  std::vector<char> updates_itself_;  // per scene body
  std::vector<std::byte> mine_;       // share_results' buffers, kept from step to step
  std::vector<std::vector<std::byte>> every_;
};

}  // namespace afemp::coupling
