// The FE nodes' part of the grid step (node_points.hpp): contact coupling (CFEMP,
// Lian et al. 2013, §2.4) and bonded coupling (hybrid FEMP, Lian et al. 2013, §2.6). Each node is
// a point with the trilinear hat of its cell (Ma 2005, eq 2-5), whatever the particles use: FE
// nodes have no domain of their own. Mass and momentum map as for particles (eqs 2-29, 2-30), so
// the grid sums are exact by the partition of unity; the force is the one the caller gives (the
// elements' nodal force) instead of -V sigma.grad N. Bonded nodes take the particles' velocity
// update (the same PIC/FLIP blend, or the grid velocity with APIC) and move with the grid
// velocity; contact nodes take only sum N dv of the contact correction of their field. Where
// contact nodes share their body's field with its particles (a converting body), the
// particles and bonded nodes take the update of their own part of the field (SharedFields in
// mpm_solver.hpp) plus the same contact correction, so each side keeps its own momentum
// balance and the contact's impulse is shared by mass.
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "afemp/errors.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/stencil.hpp"

namespace afemp::mpm {

void MpmSolver::set_node_points(NodePoints* nodes) {
  if (nodes && plan_.scheme == core::UpdateScheme::USL)
    throw std::invalid_argument(
        "FE nodes on the grid need the MUSL or USF scheme (the scene parser says so too)");
  nodes_ = nodes;
  // A field that only FE contact nodes use: no particle and no bonded node of its own.
  field_nodes_only_.assign(static_cast<std::size_t>(grid_.field_count()), 1);
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const core::BodySpec& body = scene_.bodies[b];
    if (body.discretisation == core::Discretisation::particles || body.bonded_to >= 0)
      field_nodes_only_[static_cast<std::size_t>(field_of_body_[b])] = 0;
  }
}

namespace {

// Calls f(k, stencil, s) for every node point k on the grid with mass, s[n] being the slot of
// stencil node n in the node's velocity field (one field, or its body's).
template <class F>
void for_each_node_point(const NodePoints& q, const core::BackgroundGrid& g, const Particles& p,
                         const std::vector<int>& field_of_body, bool multi_field, F&& f) {
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (!q.on_grid[k] || !(q.mass[k] > 0.0)) continue;
    const LinearStencil st(g, p, 0, q.position[k]);
    LinearStencil::Slots slot;
    st.slots(g, slot);
    const std::size_t field =
        multi_field ? static_cast<std::size_t>(field_of_body[static_cast<std::size_t>(q.body[k])]) *
                          g.slot_count()
                    : 0;
    std::array<std::size_t, LinearStencil::nodes> s;
    for (int n = 0; n < LinearStencil::nodes; ++n)
      s[static_cast<std::size_t>(n)] = static_cast<std::size_t>(slot[static_cast<std::size_t>(n)]) + field;
    f(k, st, s);
  }
}

}  // namespace

void MpmSolver::nodes_to_grid(bool mass_momentum, bool force) {
  if (!nodes_) return;
  NodePoints& q = *nodes_;
  core::BackgroundGrid& g = grid_;
  const Vec3 gravity = scene_.run.gravity;
  const std::size_t stride = g.slot_count();
  // Contact nodes in a field that also holds particles or bonded nodes (SharedFields).
  auto shares = [&](std::size_t k, std::size_t slot) {
    return !q.bonded[k] && !field_nodes_only_[slot / stride];
  };
  if (mass_momentum) {
    shared_.any = false;
    for_each_node_point(q, g, particles_, field_of_body_, multi_field_,
                        [&](std::size_t k, const LinearStencil&, const auto& slots) {
      shared_.any = shared_.any || shares(k, slots[0]);
    });
    if (shared_.any) {
      shared_.mass.assign(g.field_slot_count(), 0.0);
      shared_.start.assign(g.field_slot_count(), Vec3{});
      shared_.updated.assign(g.field_slot_count(), Vec3{});
    }
  }
  for_each_node_point(q, g, particles_, field_of_body_, multi_field_,
                      [&](std::size_t k, const LinearStencil& st, const auto& slots) {
    const double m = q.mass[k];
    const bool shared = shared_.any && shares(k, slots[0]);
    for (int n = 0; n < LinearStencil::nodes; ++n) {
      const std::size_t s = slots[static_cast<std::size_t>(n)];
      const double w = st.w(n);
      if (mass_momentum) {
        g.mass[s] += w * m;
        g.momentum[s] += (w * m) * q.velocity[k];
        if (shared) {
          shared_.mass[s] += w * m;
          shared_.start[s] += (w * m) * q.velocity[k];
        }
      }
      if (force) {
        g.force[s] += w * q.force[k];
        if (shared) shared_.updated[s] += w * q.force[k];
        // Contact nodes bring their gravity in the FE update's force.
        if (q.bonded[k] && plan_.gravity) g.force[s] += (w * m) * gravity;
      }
    }
  });
}

void MpmSolver::apply_shared_shifts() {
  if (!shared_.any) return;
  core::BackgroundGrid& g = grid_;
  const std::size_t slots = g.field_slot_count();
#pragma omp parallel for schedule(static) if (core::worth_threads(slots))
  for (std::size_t s = 0; s < slots; ++s)
    if (shared_.mass[s] > 0.0) {
      g.velocity[s] += shared_.start[s];
      g.velocity_new[s] += shared_.updated[s];
    }
}

void MpmSolver::nodes_from_grid(double) {
  if (!nodes_) return;
  NodePoints& q = *nodes_;
  const core::BackgroundGrid& g = grid_;
  const double flip = scene_.mpm.flip;
  const bool affine = plan_.transfer == core::Transfer::apic;
  const bool changes = !contact_change_.empty();
  std::fill(q.motion.begin(), q.motion.end(), Vec3{});
  for_each_node_point(q, g, particles_, field_of_body_, multi_field_,
                      [&](std::size_t k, const LinearStencil& st, const auto& slots) {
    Vec3 v_grid, dv;
    for (int n = 0; n < LinearStencil::nodes; ++n) {
      const std::size_t s = slots[static_cast<std::size_t>(n)];
      const double w = st.w(n);
      if (q.bonded[k]) {
        v_grid += w * g.velocity_new[s];
        dv += w * (g.velocity_new[s] - g.velocity[s]);
      } else if (changes) {
        dv += w * contact_change_[s];
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
}

void MpmSolver::nodes_remap() {
  if (!nodes_) return;
  NodePoints& q = *nodes_;
  core::BackgroundGrid& g = grid_;
  for_each_node_point(q, g, particles_, field_of_body_, multi_field_,
                      [&](std::size_t k, const LinearStencil& st, const auto& slots) {
    const double m = q.mass[k];
    // The updated momentum: bonded nodes hold their updated velocity; a contact node's is the
    // FE update's v^{n+1/2} plus the contact change.
    const Vec3 mv = q.bonded[k] ? m * q.velocity[k]
                                : m * q.velocity[k] + step_dt_ * q.force[k] + m * q.motion[k];
    for (int n = 0; n < LinearStencil::nodes; ++n)
      g.velocity_remap[slots[static_cast<std::size_t>(n)]] += st.w(n) * mv;
  });
}

void MpmSolver::nodes_contact_surfaces(bool gradient) {
  if (!nodes_) return;
  NodePoints& q = *nodes_;
  core::BackgroundGrid& g = grid_;
  const std::size_t stride = g.slot_count();
  for_each_node_point(q, g, particles_, field_of_body_, multi_field_,
                      [&](std::size_t k, const LinearStencil& st, const auto& slots) {
    if (!field_in_contact_[slots[0] / stride]) return;
    const double m = q.mass[k];
    for (int n = 0; n < LinearStencil::nodes; ++n) {
      const std::size_t s = slots[static_cast<std::size_t>(n)];
      if (gradient) {
        // m n / h: the size of a mass gradient, for fields that also hold particles.
        g.mass_gradient[s] += q.surface[k] ? (st.w(n) * m * g.inverse_cell()) * q.normal[k]
                                           : m * st.grad(n);
        continue;
      }
      const Vec3& normal = contact_normal_[s];
      if (st.w(n) <= 0.0 || (normal.x == 0.0 && normal.y == 0.0 && normal.z == 0.0)) continue;
      const auto node = st.node(n);
      // Eq 42 measures from the particles' centres, which lie a quarter cell inside the
      // surface at 2 per cell (lambda = 0.5: the surfaces touch). FE nodes lie on the surface,
      // so they count as reaching a quarter cell less, and lambda keeps its meaning.
      const double r = reach_along(q.position[k] - g.node_position(node[0], node[1], node[2]),
                                   normal, g.cell()) -
                       0.25 * g.cell();
      if (r > g.reach[s]) g.reach[s] = r;
    }
  });
}

}  // namespace afemp::mpm
