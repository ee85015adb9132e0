// The FE nodes' part of the grid step (node_points.hpp): contact coupling (CFEMP,
// Lian et al. 2013, §2.4) and bonded coupling (hybrid FEMP, Lian et al. 2013, §2.6). Each node is
// a point with the trilinear hat of its cell (Ma 2005, eq 2-5), whatever the particles use: FE
// nodes have no domain of their own. Mass and momentum map as for particles (eqs 2-29, 2-30), so
// the grid sums are exact by the partition of unity; the force is the one the caller gives (the
// elements' nodal force) instead of -V sigma.grad N. Bonded nodes take the particles' velocity
// update (the same PIC/FLIP blend, or the grid velocity with APIC) and move with the grid
// velocity; contact nodes take only sum N dv of the contact correction of their field. Where
// contact nodes share their body's field with its particles (a converting body), the
// particles and bonded nodes take the update of their own part of the field (SelfUpdatedShare in
// mpm/grid_points.hpp) plus the same contact correction, so each side keeps its own momentum
// balance and the contact's impulse is shared by mass.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <sstream>

#include "afemp/errors.hpp"
#include "coupling/node_points.hpp"
#include "mpm/stencil.hpp"

namespace afemp::coupling {

using mpm::GridStepAccess;
using mpm::LinearStencil;

namespace {

// Calls f(k, stencil, s) for every node point k on the grid with mass, s[n] being the slot of
// stencil node n in the node's velocity field (one field, or its body's).
template <class F>
void for_each_node_point(const NodePoints& q, const GridStepAccess& a, F&& f) {
  const core::BackgroundGrid& g = a.grid;
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (!q.on_grid[k] || !(q.mass[k] > 0.0)) continue;
    const LinearStencil st(g, a.particles, 0, q.position[k]);
    LinearStencil::Slots slot;
    st.slots(g, slot);
    const std::size_t field = a.field_offset(q.body[k]);
    std::array<std::size_t, LinearStencil::nodes> s;
    for (int n = 0; n < LinearStencil::nodes; ++n)
      s[static_cast<std::size_t>(n)] =
          static_cast<std::size_t>(slot[static_cast<std::size_t>(n)]) + field;
    f(k, st, s);
  }
}

// The reproducible mode (mpm/grid_points.hpp, FixedGridSums): a point's term into a fixed-point
// sum, a scalar or a vector's three components at the slot.
void add_fixed(std::vector<core::Fixed>& sum, std::size_t slot, double term,
               const core::FixedScale& scale, bool& ok) {
  sum[slot] += core::to_fixed(term, scale, ok);
}

void add_fixed(std::vector<core::Fixed>& sum, std::size_t slot, const Vec3& term,
               const core::FixedScale& scale, bool& ok) {
  for (int c = 0; c < 3; ++c)
    sum[3 * slot + static_cast<std::size_t>(c)] += core::to_fixed(term[c], scale, ok);
}

double largest_component(const Vec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

}  // namespace

void NodePoints::raise_fixed_bounds(const GridStepAccess& a, mpm::FixedBounds& b) const {
  // A weight is at most 1 and a weight's gradient at most 1 / h a component (the trilinear
  // hat); 2 / h as for the particles. The momentum's bound covers the remapped momentum, whose
  // terms remap() adds: a contact node's m v + dt f + m dv.
  const double gravity = largest_component(a.scene.run.gravity);
  const double grad = 2.0 * a.grid.inverse_cell();
  for (std::size_t k = 0; k < size(); ++k) {
    const double m = mass[k];
    if (!(m > 0.0)) continue;
    const Vec3 remapped =
        bonded[k] ? m * velocity[k] : m * velocity[k] + a.dt * force[k] + m * motion[k];
    b.mass = std::max(b.mass, m);
    b.momentum =
        std::max({b.momentum, m * largest_component(velocity[k]), largest_component(remapped)});
    b.force = std::max(b.force, largest_component(force[k]) + m * gravity);
    b.gradient = std::max(b.gradient, m * grad);
  }
}

void NodePoints::bin(const GridStepAccess& a, std::vector<std::int64_t>& cells) {
  const core::BackgroundGrid& g = a.grid;
  for (std::size_t k = 0; k < size(); ++k) {
    const Vec3& x = position[k];
    const auto c = g.cell_of(x);
    const bool inside = std::isfinite(x.x + x.y + x.z) && g.inside(c);
    on_grid[k] = inside && mass[k] > 0.0 && a.holds(c);
    if (on_grid[k]) cells.push_back(g.linear_cell(c));
    // A contact node off the grid moves by the FE update alone; a bonded one has lost its host.
    if (!inside && bonded[k] && mass[k] > 0.0) {
      std::ostringstream who, what;
      who << "node " << k << " of body '" << a.scene.bodies[static_cast<std::size_t>(body[k])].name
          << "' at (" << x.x << ", " << x.y << ", " << x.z << ")";
      what << (std::isfinite(x.x + x.y + x.z)
                   ? "a node bonded to the grid (a bonded_to body's node, or a node shared with "
                     "elements converted into particles) left the grid domain (enlarge [grid] "
                     "min/max to cover where the body goes)"
                   : "became NaN or Inf");
      throw core::SimulationError(a.step, a.time, who.str(), "position", what.str());
    }
  }
}

void NodePoints::to_grid(const GridStepAccess& a, bool mass_momentum, bool force_too) {
  NodePoints& q = *this;
  core::BackgroundGrid& g = a.grid;
  mpm::SelfUpdatedShare& shared = a.share;
  mpm::FixedGridSums* fixed = a.fixed;  // the reproducible mode's sums, or nullptr
  const Vec3 gravity = a.scene.run.gravity;
  const std::size_t stride = g.slot_count();
  // Contact nodes in a field that also holds particles or bonded nodes (SelfUpdatedShare).
  auto shares = [&](std::size_t k, std::size_t slot) {
    return !q.bonded[k] && !a.field_self_updated[slot / stride];
  };
  if (mass_momentum) {
    shared.any = false;
    for_each_node_point(q, a, [&](std::size_t k, const LinearStencil&, const auto& slots) {
      shared.any = shared.any || shares(k, slots[0]);
    });
    // On ranks every rank keeps the shares when any does (their blocks' sums are made whole).
    if (a.ranks) shared.any = a.ranks->max_over_ranks(shared.any ? 1.0 : 0.0) > 0.0;
    if (shared.any) {
      shared.mass.assign(g.field_slot_count(), 0.0);
      shared.start.assign(g.field_slot_count(), Vec3{});
      shared.updated.assign(g.field_slot_count(), Vec3{});
      if (fixed) {
        fixed->share_mass.assign(g.field_slot_count(), 0);
        fixed->share_start.assign(3 * g.field_slot_count(), 0);
        fixed->share_updated.assign(3 * g.field_slot_count(), 0);
      }
    }
  }
  bool ok = true;
  for_each_node_point(q, a, [&](std::size_t k, const LinearStencil& st, const auto& slots) {
    const double m = q.mass[k];
    const bool in_shared = shared.any && shares(k, slots[0]);
    for (int n = 0; n < LinearStencil::nodes; ++n) {
      const std::size_t s = slots[static_cast<std::size_t>(n)];
      const double w = st.w(n);
      if (mass_momentum && fixed) {
        add_fixed(fixed->mass, s, w * m, fixed->mass_scale, ok);
        add_fixed(fixed->momentum, s, (w * m) * q.velocity[k], fixed->momentum_scale, ok);
        if (in_shared) {
          add_fixed(fixed->share_mass, s, w * m, fixed->mass_scale, ok);
          add_fixed(fixed->share_start, s, (w * m) * q.velocity[k], fixed->momentum_scale, ok);
        }
      } else if (mass_momentum) {
        g.mass[s] += w * m;
        g.momentum[s] += (w * m) * q.velocity[k];
        if (in_shared) {
          shared.mass[s] += w * m;
          shared.start[s] += (w * m) * q.velocity[k];
        }
      }
      // Contact nodes bring their gravity in the FE update's force; bonded ones get it here.
      const bool gravity_here = q.bonded[k] && a.plan.gravity;
      if (force_too && fixed) {
        add_fixed(fixed->force, s, w * q.force[k], fixed->force_scale, ok);
        if (in_shared) add_fixed(fixed->share_updated, s, w * q.force[k], fixed->force_scale, ok);
        if (gravity_here) add_fixed(fixed->force, s, (w * m) * gravity, fixed->force_scale, ok);
      } else if (force_too) {
        g.force[s] += w * q.force[k];
        if (in_shared) shared.updated[s] += w * q.force[k];
        if (gravity_here) g.force[s] += (w * m) * gravity;
      }
    }
  });
  if (fixed && !ok) fixed->points_ok = false;
}

void NodePoints::from_grid(const GridStepAccess& a) {
  NodePoints& q = *this;
  const core::BackgroundGrid& g = a.grid;
  const double flip = a.scene.mpm.flip;
  const bool affine = a.plan.transfer == core::Transfer::apic;
  const bool changes = !a.contact_change.empty();
  std::fill(q.motion.begin(), q.motion.end(), Vec3{});
  for_each_node_point(q, a, [&](std::size_t k, const LinearStencil& st, const auto& slots) {
    Vec3 v_grid, dv;
    for (int n = 0; n < LinearStencil::nodes; ++n) {
      const std::size_t s = slots[static_cast<std::size_t>(n)];
      const double w = st.w(n);
      if (q.bonded[k]) {
        v_grid += w * g.velocity_new[s];
        dv += w * (g.velocity_new[s] - g.velocity[s]);
      } else if (changes) {
        dv += w * a.contact_change[s];
      }
    }
    if (q.bonded[k]) {
      // With APIC the particles take the grid velocity; so do the nodes (they carry no
      // affine part), which keeps the total momentum exact.
      q.velocity[k] = affine ? v_grid : flip * (q.velocity[k] + dv) + (1.0 - flip) * v_grid;
      q.motion[k] = v_grid;
    } else {
      q.motion[k] = dv;
    }
  });
  if (a.ranks) share_results(*a.ranks);
}

void NodePoints::share_results(core::RankLink& ranks) {
  // Each rank sends the velocity and motion of the points it took (those of its blocks; a point
  // lies in one rank's block), and takes every other rank's.
  struct Result {
    std::uint64_t point;
    Vec3 velocity, motion;
  };
  mine_.clear();
  for (std::size_t k = 0; k < size(); ++k) {
    if (!on_grid[k] || !(mass[k] > 0.0)) continue;
    const Result r{k, velocity[k], motion[k]};
    const auto* at = reinterpret_cast<const std::byte*>(&r);
    mine_.insert(mine_.end(), at, at + sizeof r);
  }
  ranks.gather_into(mine_, every_, false);
  for (std::size_t from = 0; from < every_.size(); ++from) {
    if (static_cast<int>(from) == ranks.rank()) continue;
    const std::vector<std::byte>& in = every_[from];
    for (std::size_t at = 0; at + sizeof(Result) <= in.size(); at += sizeof(Result)) {
      Result r;
      std::memcpy(&r, in.data() + at, sizeof r);
      velocity[r.point] = r.velocity;
      motion[r.point] = r.motion;
    }
  }
}

void NodePoints::remap(const GridStepAccess& a) {
  NodePoints& q = *this;
  core::BackgroundGrid& g = a.grid;
  mpm::FixedGridSums* fixed = a.fixed;
  bool ok = true;
  for_each_node_point(q, a, [&](std::size_t k, const LinearStencil& st, const auto& slots) {
    const double m = q.mass[k];
    // The updated momentum: bonded nodes hold their updated velocity; a contact node's is the
    // FE update's v^{n+1/2} plus the contact change.
    const Vec3 mv =
        q.bonded[k] ? m * q.velocity[k] : m * q.velocity[k] + a.dt * q.force[k] + m * q.motion[k];
    for (int n = 0; n < LinearStencil::nodes; ++n) {
      const std::size_t s = slots[static_cast<std::size_t>(n)];
      if (fixed)
        add_fixed(fixed->remap, s, st.w(n) * mv, fixed->momentum_scale, ok);
      else
        g.velocity_remap[s] += st.w(n) * mv;
    }
  });
  if (fixed && !ok) fixed->points_ok = false;
}

void NodePoints::contact_surfaces(const GridStepAccess& a, bool gradient) {
  NodePoints& q = *this;
  core::BackgroundGrid& g = a.grid;
  const std::size_t stride = g.slot_count();
  mpm::FixedGridSums* fixed = gradient ? a.fixed : nullptr;
  bool ok = true;
  for_each_node_point(q, a, [&](std::size_t k, const LinearStencil& st, const auto& slots) {
    if (!a.field_in_contact[slots[0] / stride]) return;
    const double m = q.mass[k];
    for (int n = 0; n < LinearStencil::nodes; ++n) {
      const std::size_t s = slots[static_cast<std::size_t>(n)];
      if (gradient) {
        // m n / h: the size of a mass gradient, for fields that also hold particles.
        const Vec3 term =
            q.surface[k] ? (st.w(n) * m * g.inverse_cell()) * q.normal[k] : m * st.grad(n);
        if (fixed)
          add_fixed(fixed->gradient, s, term, fixed->gradient_scale, ok);
        else
          g.mass_gradient[s] += term;
        continue;
      }
      const Vec3& towards = a.contact_normal[s];
      if (st.w(n) <= 0.0 || (towards.x == 0.0 && towards.y == 0.0 && towards.z == 0.0)) continue;
      const auto node = st.node(n);
      // Eq 42 measures from the particles' centres, which lie a quarter cell inside the
      // surface at 2 per cell (lambda = 0.5: the surfaces touch). FE nodes lie on the surface,
      // so they count as reaching a quarter cell less, and lambda keeps its meaning.
      const double r = mpm::reach_along(q.position[k] - g.node_position(node[0], node[1], node[2]),
                                        towards, g.cell()) -
                       0.25 * g.cell();
      if (r > g.reach[s]) g.reach[s] = r;
    }
  });
  if (fixed && !ok) fixed->points_ok = false;
}

}  // namespace afemp::coupling
