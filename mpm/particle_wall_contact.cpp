// Rigid planar walls met at the particles' boundary. The grid's "wall" face holds a node once
// its velocity points into the face, so it stops a body about a cell before its particles
// reach the face (an elastic sphere stays in contact for about half the Hertz time at 20 cells
// per radius). Here the particle's own domain meets the wall: a particle of half width
// r = V^(1/3) / 2 whose predicted position x + dt v_p (v_p = sum N v_new, the position the
// step will give it) would bring its boundary behind the plane, n . (x + dt v_p - x_w) < r,
// gets the normal impulse that puts its boundary on the wall, spread over its nodes as N J
// (the nodal form of a contact force on a particle, as a traction enters the MPM momentum
// equation: Sulsky, Chen & Schreyer 1994, eq 20; the kinematic wall of LS-DYNA's
// *RIGIDWALL_PLANAR applied to the particle's boundary instead of a node). The particle's
// velocity moves by J sum N^2 / m_I, so J = dv_n / (sum N^2 / m_I) closes its own gap; the
// particles that share nodes are resolved by projected Gauss-Seidel sweeps on accumulated
// impulses (core/contact_impulse.hpp; J >= 0, so contact may release), in the order of the
// particles' ids (mpm/contact_nodes.hpp: on MPI ranks every rank sweeps every rank's contacts).
// Coulomb friction limits the tangential impulse to mu J. A penetration
// present at the step's start (an overlap in the scene) recedes by a tenth per step instead of
// being removed at once.
// Face conditions keep priority: a component a grid face holds stays held. Energy: a moving
// wall's work J . v_wall is external work (a fixed wall does none, and the kinetic energy its
// catch takes out shows in the balance, as for the FE walls: what the impulses do on the grid
// is not what the particles lose, since the nodes also carry the velocity of the particles
// behind the contact); friction dissipates J_t . (v_wall - v_p) (the slip after the impulse),
// booked as sliding and friction energy.
#include <cmath>

#include "core/contact_impulse.hpp"
#include "mpm/face_constraints.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/stencil.hpp"

namespace afemp::mpm {

namespace {
constexpr int kSweeps = 6;
constexpr double kRecede = 0.9;  // an existing penetration keeps 90 % of itself per step
}  // namespace

void MpmSolver::particle_wall_contact(double dt) {
  for (std::size_t w = 0; w < wall_bodies_.size(); ++w) {
    wall_force_[w] = Vec3{};
    if (wall_bodies_[w].empty()) continue;
    with_stencil([&]<class Stencil, bool>() { particle_wall_kernel<Stencil>(w, dt); });
  }
  // Particles at mesh faces (coupling/particle_surface_contact.cpp), on the same velocity.
  if (surface_contacts_) surface_contacts_->resolve(access());
}

template <class Stencil>
void MpmSolver::particle_wall_kernel(std::size_t w, double dt) {
  core::BackgroundGrid& g = grid_;
  const Particles& p = particles_;
  const core::WallSpec& spec = scene_.walls[w];
  const Vec3 n = spec.normal;
  const Vec3 start_point = spec.point + time_ * spec.velocity;
  const double wall_speed = core::norm(spec.velocity);
  const std::vector<char>& acts = wall_bodies_[w];
  constexpr int K = Stencil::nodes;

  // Candidates: particles of the wall's bodies within one cell plus their reach this step,
  // each with its gap at the step's start, n . (x - x_wall) - r, and its live stencil nodes.
  ContactNodes<WallContact>& cs = wall_contacts_;
  cs.begin(K);
  wall_slots_.resize(K);
  wall_weights_.resize(K);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!acts[static_cast<std::size_t>(p.body[i])]) continue;
    const double gap = core::dot(p.position[i] - start_point, n) - particle_half_width(p.volume[i]);
    const double reach = g.cell() + dt * (core::norm(p.velocity[i]) + wall_speed);
    if (!(gap < reach)) continue;
    const Stencil st(g, p, i, p.position[i]);
    typename Stencil::Slots slot;
    st.slots(g, slot);
    const std::size_t field = field_offset(i);
    for (int k = 0; k < K; ++k) {
      const double wk = st.w(k);
      const auto s = static_cast<std::int64_t>(slot[static_cast<std::size_t>(k)]) +
                     static_cast<std::int64_t>(field);
      const bool live = wk > 0.0 && g.mass[static_cast<std::size_t>(s)] > 0.0;
      wall_slots_[static_cast<std::size_t>(k)] = live ? s : -1;
      wall_weights_[static_cast<std::size_t>(k)] = live ? wk : 0.0;
    }
    WallContact contact;
    contact.id = p.id[i];
    contact.gap = gap;
    cs.add(contact, wall_slots_, wall_weights_);
  }
  cs.finish(g, ranks_);  // on ranks: every rank's, in id order
  const std::size_t nc = cs.size();
  if (nc == 0) return;
  for (std::size_t c = 0; c < nc; ++c) cs[c].inverse_mass = cs.particle_inverse_mass(c);

  Vec3 impulse_sum{};
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    for (std::size_t c = 0; c < nc; ++c) {
      WallContact& h = cs[c];
      if (!(h.inverse_mass > 0.0)) continue;
      const Vec3 v = cs.particle_velocity(c);
      // The predicted gap (the wall moves dt v_wall), and the one allowed at the step's end.
      const double gap = h.gap + dt * core::dot(v - spec.velocity, n);
      const double allowed = kRecede * std::min(h.gap, 0.0);
      // The normal velocity change that puts the boundary at the allowed gap; accumulated
      // impulses stay >= 0 (a wall pushes, never pulls).
      const double dj =
          core::add_normal_impulse(h.normal_impulse, allowed - gap, dt, h.inverse_mass);
      if (dj != 0.0) impulse_sum += cs.push(c, dj * n);
      if (!(spec.friction > 0.0)) continue;
      // Stick: the impulse that stops the slip the nodes have after the normal one, within the
      // Coulomb cone mu J.
      const Vec3 djt =
          core::add_friction_impulse(h.tangent_impulse, h.normal_impulse, spec.friction,
                                     cs.particle_velocity(c) - spec.velocity, n, h.inverse_mass);
      if (core::dot(djt, djt) > 0.0) impulse_sum += cs.push(c, djt);
    }
  }
  cs.write_back(g);
  // Friction's dissipation over the step: the final tangential impulses against the slip they
  // left (zero where the particle sticks).
  double dissipated = 0.0;
  if (spec.friction > 0.0)
    for (std::size_t c = 0; c < nc; ++c) {
      if (!(cs[c].inverse_mass > 0.0)) continue;
      dissipated -=
          core::slip_work(cs[c].tangent_impulse, cs.particle_velocity(c) - spec.velocity, n);
    }
  // Every rank swept every contact: the dissipation and force are whole on each, and the work,
  // which energies() adds over the ranks, is booked by rank 0.
  wall_sliding_ += dissipated;
  wall_friction_ += dissipated;
  if (ranks_ == nullptr || ranks_->rank() == 0) {
    external_work_ += core::dot(impulse_sum, spec.velocity);
    if (reproducible()) exact_[exact_external].add(core::dot(impulse_sum, spec.velocity));
  }
  wall_force_[w] = (1.0 / dt) * impulse_sum;
}

}  // namespace afemp::mpm
