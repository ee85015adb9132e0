// A neutral hook of the MPM solver: points that are not its particles but join its grid step.
// Their owner (coupling/: FE nodes for the contact and bonded couplings, Lian et al. 2013,
// §2.4 and §2.6) scatters them to the grid and gathers from it at the stages of the step; the
// solver knows nothing of what they are. Each method is called once per stage, never per point,
// after the particles' part of the stage, so the sums keep their order (same bits for a given
// thread count).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "afemp/tensor.hpp"
#include "core/exact_sum.hpp"
#include "core/grid/background_grid.hpp"
#include "core/grid/block_partition.hpp"
#include "core/rank_link.hpp"
#include "core/scene.hpp"
#include "mpm/particles.hpp"
#include "mpm/step_plan.hpp"

namespace afemp::mpm {

using core::Vec3;

// Points that take their own update (their owner integrates them) yet map into a velocity field
// that also holds particles (a converting body's contact nodes share its field with its
// particles). The particles must then take their update from their own part of the field, or
// the points' velocity change would reach them as well (momentum created). Per slot: the
// self-updating points' mass, momentum (start) and force (updated), which the owner adds in
// GridPoints::to_grid; the grid momentum update replaces start and updated with the shift of
// the field's start and updated velocities to the particles' part (0 where that part has under
// `fraction` of the mass), which the solver adds after contact.
struct SelfUpdatedShare {
  static constexpr double fraction = 1e-9;
  bool any = false;  // some self-updating point maps into a shared field this step
  std::vector<double> mass;
  std::vector<Vec3> start, updated;
};

// The reproducible mode's nodal sums ([run] reproducible; mpm/reproducible_sums.cpp): per field
// slot, 1 or 3 a slot as the grid's doubles, in 128-bit fixed point with this scatter's scales;
// the self-updating points' share of a field (SelfUpdatedShare) the same way. The particles add
// their terms, then the points theirs (GridPoints); the solver adds the ranks' parts and makes
// the doubles once the sums are whole. `points_ok` false: a point's term passed its bound.
struct FixedGridSums {
  std::vector<core::Fixed> mass, momentum, force, remap, gradient;
  std::vector<core::Fixed> share_mass, share_start, share_updated;
  core::FixedScale mass_scale, momentum_scale, force_scale, gradient_scale;
  bool points_ok = true;
};

// The largest term a particle or point gives a node in each of the fixed-point sums, from
// which their scales are set: mass, momentum (the remapped momentum's too), force, mass
// gradient.
struct FixedBounds {
  double mass = 0.0, momentum = 0.0, force = 0.0, gradient = 0.0;
};

// What the solver lends the points' owner for one stage.
struct GridStepAccess {
  core::BackgroundGrid& grid;
  const core::Scene& scene;
  const StepPlan& plan;
  const Particles& particles;  // for the stencils' constructor (they read no particle)
  // The velocity field of each scene body (multi_field false: one field for all).
  const std::vector<int>& field_of_body;
  bool multi_field;
  // Per field: it meets a field it is in contact with; it holds self-updating points only.
  const std::vector<char>& field_in_contact;
  const std::vector<char>& field_self_updated;
  // Per field slot: each field's unit contact normal (0 where none), and the velocity change
  // grid contact made in the update pass (empty before the first update pass).
  const std::vector<Vec3>& contact_normal;
  const std::vector<Vec3>& contact_change;
  SelfUpdatedShare& share;
  double dt;    // this step's
  long step;    // steps done before this one
  double time;  // at the step's start
  // A run divided among MPI ranks (docs/parallel.md), else nullptr: the partition of the grid's
  // blocks and this rank. A point is scattered by the rank that owns its cell's block, as a
  // particle is; the solver then sums the shared blocks, so the grid holds the whole sums.
  const core::BlockPartition* partition = nullptr;
  core::RankLink* ranks = nullptr;
  // The reproducible mode: the points add their terms here instead of into the grid's doubles
  // (and the share's), before the solver makes the sums whole; nullptr without the mode.
  FixedGridSums* fixed = nullptr;

  // Whether this rank scatters a point in `cell` (every point in one process).
  bool holds(const std::array<int, 3>& cell) const {
    return partition == nullptr || partition->rank_of(grid.block_of_cell(cell)) == ranks->rank();
  }

  // Offset of a body's velocity field in the nodal arrays.
  std::size_t field_offset(int body) const {
    return multi_field ? static_cast<std::size_t>(field_of_body[static_cast<std::size_t>(body)]) *
                             grid.slot_count()
                       : 0;
  }
};

class GridPoints {
 public:
  virtual ~GridPoints() = default;
  // The body's points take their own update: their owner counts their gravity work, and a
  // field that holds only such points and no particle leaves it out of the grid's.
  virtual bool updates_itself(int body) const = 0;
  // Where the points meet the grid, for a run divided among ranks: their blocks weigh in the
  // partition as a particle's do (a scene whose particles all come from converted elements
  // starts with none).
  virtual std::span<const Vec3> positions() const = 0;
  // Binning: appends the linear cell of each point on the grid to `cells` (their grid blocks
  // become active); throws core::SimulationError for a point that must not leave the grid.
  // On ranks each rank takes the points of its own blocks (GridStepAccess::holds) into the
  // scatters, and from_grid hands every rank the result of every point (collective).
  virtual void bin(const GridStepAccess& access, std::vector<std::int64_t>& cells) = 0;
  // Mass and momentum (mass_momentum) and force (force) into the grid.
  virtual void to_grid(const GridStepAccess& access, bool mass_momentum, bool force) = 0;
  // The reproducible mode: raises `bounds` to the largest term any point gives a node (the same
  // on every rank: from every point, not only this rank's).
  virtual void raise_fixed_bounds(const GridStepAccess& access, FixedBounds& bounds) const = 0;
  // Grid contact's surfaces: the mass gradient (gradient), then the reach along the normals.
  virtual void contact_surfaces(const GridStepAccess& access, bool gradient) = 0;
  // The updated grid velocities back to the points (after contact's update pass).
  virtual void from_grid(const GridStepAccess& access) = 0;
  // The points' updated momentum into grid.velocity_remap (MUSL).
  virtual void remap(const GridStepAccess& access) = 0;
};

// Contacts their owner resolves on the updated grid velocity, once a step after grid contact
// and the particle walls (coupling/: particles at mesh faces, `[[contact]]` method "surface"):
// it reads the particles and changes the grid's updated velocity.
class SurfaceContacts {
 public:
  virtual ~SurfaceContacts() = default;
  virtual void resolve(const GridStepAccess& access) = 0;
};

}  // namespace afemp::mpm
