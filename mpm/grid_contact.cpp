// Grid contact between bodies (Lian et al. 2013, §2.4, eqs 37-42; Bardenhagen et al. 2000 with the
// collinear normal of Huang et al. and the distance check of Ma et al.). Each body in a contact
// maps to its own velocity field on the grid (particle_to_grid.cpp) and every field is integrated
// on its own (grid_momentum_update.cpp, eq 38: the trial solution). Where two
// fields meet at a node:
//   - fields whose bodies are not in contact stick: both take the centre-of-mass velocity,
//     exactly what one shared field would give them;
//   - fields in contact are corrected only if they approach, (v_r - v_s) . n_r > 0 (eq 39),
//     and if their materials are within lambda h of each other (eq 42). The correction is the
//     normal force that makes the normal velocities equal (eqs 40-41) and a tangential one
//     that makes them stick, cut to the Coulomb limit mu |f_n| when it exceeds it. Both bodies
//     receive equal and opposite impulses, so momentum is conserved to round-off.
// Energy: in the update pass a pair whose start velocities (the particles' own) separate is
// left alone; without that rule, fields with little mass at a node, whose updated velocities
// carry f dt / m, drew impulses that created 12 % energy in a head-on impact of two elastic
// cubes (Ma 2005, §3.2.1 reports the same failure). The energy the contact dissipates is
// estimated from the impulses' work on the interface (Energies::contact).
// The normal n_r = -n_s is one vector for the pair, from both bodies' mass gradients
// (eq 37 for each, combined as m_s n_r - m_r n_s: pair_normal), so the two normals are collinear by
// construction: the condition Huang et al. showed is needed for momentum conservation.
// Eq 42's gap D is measured from the particles: along n_r, how far r's particles reach past
// the node, and s's along n_s; D = -(reach_r + reach_s), and contact needs D <= lambda h
// (lambda = 0.5 by default: particle centres half a cell apart at touching surfaces with two
// particles per cell).
#include <cmath>
#include <limits>

#include "core/contact_impulse.hpp"
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/stencil.hpp"

namespace afemp::mpm {

namespace {

constexpr int max_fields = 32;  // the plan refuses more contact bodies than this

// Zeroes the components of a normal across the symmetry and fixed faces the node lies on:
// a node on a symmetry plane sees only half of the material, and its mass gradient points out
// of the plane by that alone.
Vec3 face_projected(Vec3 n, const std::array<int, 3>& node, const core::BackgroundGrid& g) {
  const auto& faces = g.settings().faces;
  const auto nodes = g.nodes();
  for (int a = 0; a < 3; ++a) {
    const auto lo = faces[static_cast<std::size_t>(2 * a)];
    const auto hi = faces[static_cast<std::size_t>(2 * a + 1)];
    auto held = [](core::FaceCondition f) {
      return f == core::FaceCondition::symmetric || f == core::FaceCondition::fixed;
    };
    if ((node[static_cast<std::size_t>(a)] <= 0 && held(lo)) ||
        (node[static_cast<std::size_t>(a)] >= nodes[static_cast<std::size_t>(a)] - 1 && held(hi)))
      n[a] = 0.0;
  }
  return n;
}

Vec3 unit_or_zero(const Vec3& v) {
  const double l = core::norm(v);
  return l > 0.0 ? (1.0 / l) * v : Vec3{};
}

// The pair's normal, pointing out of a into b: the two unit outward normals (eq 37 for each
// body), each weighted by the other body's nodal mass, n = m_b n_a - m_a n_b. It is one vector
// for both bodies (collinear, as Huang et al. require), and the body that barely reaches the
// node, whose particles all lie across the contact plane from it, sets the direction there:
// at an edge where the heavier body also has a free face, an unweighted normal tilts toward
// that face and the gap check (eq 42) then sees the two bodies overlap when they do not.
Vec3 pair_normal(const Vec3& ga, double ma, const Vec3& gb, double mb,
                 const std::array<int, 3>& node, const core::BackgroundGrid& g) {
  return unit_or_zero(face_projected(mb * unit_or_zero(face_projected(ga, node, g)) -
                                         ma * unit_or_zero(face_projected(gb, node, g)),
                                     node, g));
}

}  // namespace

template <class Stencil>
void MpmSolver::contact_surfaces_kernel() {
  core::BackgroundGrid& g = grid_;
  const std::size_t stride = g.slot_count(), total = g.field_slot_count();
  const int fields = g.field_count();
  const double h = g.cell();
  contact_normal_.resize(total);
#pragma omp parallel for schedule(static) if (core::worth_threads(total))
  for (std::size_t s = 0; s < total; ++s) {
    g.mass_gradient[s] = {};
    g.reach[s] = -std::numeric_limits<double>::infinity();
  }
  const Particles& p = particles_;
  // Normals and reach matter only at nodes where two or more fields meet, one of them in
  // contact: a thin layer along the interfaces. Particles whose stencil reaches none of those
  // nodes are skipped (with the linear hat before their weights are computed): in V6 they
  // are nearly all of the concrete's, and this pass took a quarter of the step.
  contact_node_.assign(stride, 0);
#pragma omp parallel if (core::worth_threads(stride))
  g.for_each_slot([&](std::size_t slot, const std::array<int, 3>&) {
    int count = 0;
    bool contact = false;
    for (int f = 0; f < fields; ++f)
      if (g.mass[slot + static_cast<std::size_t>(f) * stride] > 0.0) {
        ++count;
        contact = contact || field_in_contact_[static_cast<std::size_t>(f)];
      }
    if (count >= 2 && contact) contact_node_[slot] = 1;
  });
  // Scatters from the particles of contact fields near a flagged node, colour by colour (no
  // two threads write a node): f(i, stencil, slot index of each node in the particle's field).
  auto scatter_contact_particles = [&](auto&& f) {
    sweep_layers<Stencil::colours>(layer_offsets_, [&](std::size_t b, std::size_t e) {
      for (std::size_t q = b; q < e; ++q) {
        const auto i = static_cast<std::size_t>(layer_order_[q]);
        const std::size_t field = field_offset(i);
        if (!field_in_contact_[field / stride]) continue;
        bool near = false;
        if constexpr (Stencil::nodes == 8) {
          std::array<std::int32_t, 8> corners;
          g.node_slots(g.cell_of(p.position[i]), corners);
          for (const std::int32_t c : corners)
            near = near || contact_node_[static_cast<std::size_t>(c)] != 0;
          if (!near) continue;
        }
        const Stencil st(g, p, i, p.position[i]);
        typename Stencil::Slots slot;
        st.slots(g, slot);
        if constexpr (Stencil::nodes != 8) {
          for (const std::int32_t c : slot)
            near = near || contact_node_[static_cast<std::size_t>(c)] != 0;
          if (!near) continue;
        }
        std::array<std::size_t, Stencil::nodes> s;
        for (int n = 0; n < Stencil::nodes; ++n)
          s[static_cast<std::size_t>(n)] =
              static_cast<std::size_t>(slot[static_cast<std::size_t>(n)]) + field;
        f(i, st, s);
      }
    });
  };
  // Eq 37 per field: grad m = sum_p m_p grad S_I(x_p), pointing out of the body.
  // The reproducible mode: in fixed point (reproducible_sums.cpp), the mesh points' terms too.
  const bool exact = reproducible();
  if (exact) {
    start_fixed_scatter(FixedScatter::gradient);
    FixedNodes& fixed = fixed_;
    scatter_contact_particles([&](std::size_t i, const Stencil& st, const auto& s) {
      bool ok = true;
      for (int n = 0; n < Stencil::nodes; ++n) {
        const std::size_t k = s[static_cast<std::size_t>(n)];
        const Vec3 term = p.mass[i] * st.grad(n);
        for (std::size_t a = 0; a < 3; ++a)
          fixed.gradient[3 * k + a] +=
              core::to_fixed(term[static_cast<int>(a)], fixed.gradient_scale, ok);
      }
      if (!ok) fixed_ok_[static_cast<std::size_t>(core::thread_index())] = 0;
    });
    if (points_) points_->contact_surfaces(access(), true);
    finish_fixed_scatter(FixedScatter::gradient);
  } else {
    scatter_contact_particles([&](std::size_t i, const Stencil& st, const auto& s) {
      for (int n = 0; n < Stencil::nodes; ++n)
        g.mass_gradient[s[static_cast<std::size_t>(n)]] += p.mass[i] * st.grad(n);
    });
    if (points_) points_->contact_surfaces(access(), true);
  }
  if (ranks_ && !exact) {  // the gradients of the blocks that several ranks' particles reach
    const core::NodalArray gradient[] = {{reinterpret_cast<double*>(g.mass_gradient.data()), 3}};
    sum_shared_blocks(gradient);
  }
  // Each field's outward normal against the fields it meets at the node, where it meets one
  // it is in contact with; zero elsewhere.
#pragma omp parallel if (core::worth_threads(stride))
  g.for_each_slot([&](std::size_t slot, const std::array<int, 3>& node) {
    int present[max_fields];
    int count = 0;
    Vec3 sum;  // of the mass-weighted unit outward normals of the fields present
    double mass = 0.0;
    for (int f = 0; f < fields; ++f) {
      const std::size_t s = slot + static_cast<std::size_t>(f) * stride;
      contact_normal_[s] = {};
      if (g.mass[s] > 0.0) {
        present[count++] = f;
        sum += g.mass[s] * unit_or_zero(face_projected(g.mass_gradient[s], node, g));
        mass += g.mass[s];
      }
    }
    if (count < 2) return;
    for (int k = 0; k < count; ++k) {
      const int f = present[k];
      bool partner = false;
      for (int j = 0; j < count; ++j)
        partner = partner || law_[static_cast<std::size_t>(f * fields + present[j])].contact;
      if (!partner) continue;
      const std::size_t s = slot + static_cast<std::size_t>(f) * stride;
      // pair_normal against the others taken together: (M - m_f) n_f - m_f sum_others m n / m.
      const double m = g.mass[s];
      const Vec3 own = unit_or_zero(face_projected(g.mass_gradient[s], node, g));
      const Vec3 others = sum - m * own;
      contact_normal_[s] = unit_or_zero((mass - m) * own - (m / (mass - m)) * others);
    }
  });
  // Eq 42: how far each field's particles reach past the node along its normal, counting the
  // particles within half a cell of the normal line through the node (reach_along). Counting
  // every particle the node sees let a particle off to the side reach far along a normal that
  // tilts at an edge, and contact fired there before the bodies met.
  scatter_contact_particles([&](std::size_t i, const Stencil& st, const auto& s) {
    for (int n = 0; n < Stencil::nodes; ++n) {
      const std::size_t k = s[static_cast<std::size_t>(n)];
      const Vec3& normal = contact_normal_[k];
      if (st.w(n) <= 0.0 || (normal.x == 0.0 && normal.y == 0.0 && normal.z == 0.0)) continue;
      const auto node = st.node(n);
      const double r =
          reach_along(p.position[i] - g.node_position(node[0], node[1], node[2]), normal, h);
      if (r > g.reach[k]) g.reach[k] = r;
    }
  });
  if (points_) points_->contact_surfaces(access(), false);
  if (ranks_) {  // the farthest reach over every rank's particles
    const core::NodalArray reach[] = {{g.reach.data(), 1, true}};
    sum_shared_blocks(reach);
  }
}

void MpmSolver::contact_surfaces() {
  with_stencil([&]<class Stencil, bool>() { contact_surfaces_kernel<Stencil>(); });
}

void MpmSolver::grid_contact(ContactPass pass) {
  core::BackgroundGrid& g = grid_;
  const std::size_t stride = g.slot_count();
  const int fields = g.field_count();
  std::vector<Vec3>& v = pass == ContactPass::start    ? g.velocity
                         : pass == ContactPass::update ? g.velocity_new
                                                       : g.velocity_remap;
  const bool update = pass == ContactPass::update;
  const double h = g.cell();
  const int nt = core::thread_count();
  thread_sums_.assign(static_cast<std::size_t>(nt) * core::cache_line_doubles, 0.0);
  // Self-updating grid points receive the change this pass makes to their field
  // (grid_points.hpp).
  const bool record = update && points_;
  if (record) contact_change_.assign(g.field_slot_count(), Vec3{});
  // The update pass's impulses are the contacts' forces over the step: summed per thread and
  // contact, on the contact's first body. They are all the momentum contact gives, whatever the
  // transfer: the start pass (USF, USAVG) corrects only the velocity the strain rate is taken
  // from (the grid update takes v and v_new from the momentum again), and the remap pass
  // (MUSL) only the remapped one.
  const std::size_t contacts = grid_contact_force_.size();
  if (update) contact_force_scratch_.assign(static_cast<std::size_t>(nt) * contacts, {});
  // The reproducible mode: per thread the exact sums of the dissipation and of each contact's
  // normal and tangential impulses (1 + 6 x contacts).
  const std::size_t per = 1 + 6 * contacts;
  core::ExactSum* exact = update && reproducible() ? exact_thread_sums(per) : nullptr;
#pragma omp parallel num_threads(nt) if (core::worth_threads(stride))
  {
    double dissipated = 0.0;
    core::ExactSum* exact_sums =
        exact ? exact + per * static_cast<std::size_t>(core::thread_index()) : nullptr;
    InterfaceForce* forces = update ? contact_force_scratch_.data() +
                                          static_cast<std::size_t>(core::thread_index()) * contacts
                                    : nullptr;
    // One instance with the reproducible mode's exact sums and one without, so that the plain
    // one keeps its arithmetic (a term shared with the exact sums rounds otherwise).
    auto sweep = [&]<bool Exact>() {
      g.for_each_slot([&](std::size_t slot, const std::array<int, 3>& node) {
        int present[max_fields];
        int count = 0;
        for (int f = 0; f < fields; ++f)
          if (g.mass[slot + static_cast<std::size_t>(f) * stride] > 0.0) present[count++] = f;
        // Pairs in a fixed order: each correction conserves momentum, so their sequence does
        // too (a node rarely holds more than two fields).
        for (int ka = 0; ka < count; ++ka)
          for (int kb = ka + 1; kb < count; ++kb) {
            const int fa = present[ka], fb = present[kb];
            const std::size_t a = slot + static_cast<std::size_t>(fa) * stride;
            const std::size_t b = slot + static_cast<std::size_t>(fb) * stride;
            const double ma = g.mass[a], mb = g.mass[b];
            const PairLaw& law = law_[static_cast<std::size_t>(fa * fields + fb)];
            if (!law.contact) {
              // Sticking fields share the start velocity too, or the FLIP increment v_new - v
              // of each would differ from the one shared field's.
              const double inv = 1.0 / (ma + mb);
              const Vec3 cm = inv * (ma * v[a] + mb * v[b]);
              if (record) {
                contact_change_[a] += cm - v[a];
                contact_change_[b] += cm - v[b];
              }
              v[a] = cm;
              v[b] = cm;
              if (update) {
                const Vec3 cm_old = inv * (ma * g.velocity[a] + mb * g.velocity[b]);
                g.velocity[a] = cm_old;
                g.velocity[b] = cm_old;
              }
              continue;
            }
            // One normal for the pair, pointing from a into b.
            const Vec3 n = pair_normal(g.mass_gradient[a], ma, g.mass_gradient[b], mb, node, g);
            const double gap = -(g.reach[a] + g.reach[b]);
            if (!(gap <= law.distance_factor * h)) continue;  // eq 42: not touching yet
            // Separation is free (eq 39). In the update pass it is judged on the start
            // velocities as well, the particles' own (mass-averaged): the updated velocity of a
            // field with little mass at the node carries f dt / m, which can point into the
            // other body while its particles move away from it. The particles' kinetic energy
            // changes by J . (v_a - v_b) at first order, with the start velocities, so an
            // impulse J there would create energy (as the contact of Ma 2005 did).
            const Vec3 rel_start = g.velocity[a] - g.velocity[b];
            if (update && core::dot(rel_start, n) < 0.0) continue;
            const Vec3 rel = v[a] - v[b];
            if (!(core::dot(rel, n) > 0.0)) continue;
            // The stick impulse's normal part (eq 41 times dt) and its tangential part cut to
            // the Coulomb limit: equal and opposite on the two fields. The particles receive it
            // through the FLIP increment v_new - v (the start velocity is left as it was), and
            // the strain of every scheme is taken from corrected velocities.
            const Vec3 stick = -(ma * mb / (ma + mb)) * rel;
            const double pn = core::dot(stick, n);  // < 0: pushes a back
            Vec3 t = stick - pn * n;
            core::coulomb_cap(t, law.friction * std::abs(pn));
            const Vec3 impulse = pn * n + t;
            v[a] += (1.0 / ma) * impulse;
            v[b] -= (1.0 / mb) * impulse;
            if (record) {
              contact_change_[a] += (1.0 / ma) * impulse;
              contact_change_[b] -= (1.0 / mb) * impulse;
            }
            // What the contact dissipates: the impulse's work on the interface at the mean of
            // the relative velocity at the start and after the correction. Its normal part is
            // >= 0, since the pair does not separate at the start and does not approach after.
            // On ranks a node that several ranks hold is booked by its block's owner.
            if (update && books_node(slot)) {
              dissipated -= 0.5 * core::dot(impulse, rel_start + v[a] - v[b]);
              const int k = contact_of_pair_[static_cast<std::size_t>(fa * fields + fb)];
              const double sign = k > 0 ? 1.0 : -1.0;  // the impulse on a, or on b (minus it)
              const auto c = static_cast<std::size_t>(k > 0 ? k - 1 : -1 - k);
              InterfaceForce& f = forces[c];
              f.normal += (sign * pn) * n;
              f.tangential += sign * t;
              if constexpr (Exact) {
                exact_sums[0].add(-0.5 * core::dot(impulse, rel_start + v[a] - v[b]));
                core::ExactSum* e = exact_sums + 1 + 6 * c;
                for (int j = 0; j < 3; ++j) {
                  e[j].add((sign * pn) * n[j]);
                  e[3 + j].add(sign * t[j]);
                }
              }
            }
          }
      });
    };
    if (exact_sums)
      sweep.template operator()<true>();
    else
      sweep.template operator()<false>();
    thread_sums_[static_cast<std::size_t>(core::thread_index()) * core::cache_line_doubles] =
        dissipated;
  }
  for (int t = 0; t < nt; ++t)
    contact_energy_ += thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
  if (!update) return;
  const double inv_dt = 1.0 / step_dt_;
  if (exact) {  // the threads' exact sums, then the ranks'
    std::vector<core::ExactSum> sums(per);
    add_exact_thread_sums(per, sums.data());
    exact_[exact_contact] += sums[0];
    const std::vector<double> impulse = core::exact_values(ranks_, std::span(sums).subspan(1));
    for (std::size_t k = 0; k < contacts; ++k) {
      const double* e = impulse.data() + 6 * k;
      grid_contact_force_[k] = {inv_dt * Vec3{e[0], e[1], e[2]}, inv_dt * Vec3{e[3], e[4], e[5]}};
    }
    return;
  }
  for (std::size_t k = 0; k < contacts; ++k) {
    InterfaceForce sum;
    for (int t = 0; t < nt; ++t) {
      const InterfaceForce& f = contact_force_scratch_[static_cast<std::size_t>(t) * contacts + k];
      sum.normal += f.normal;
      sum.tangential += f.tangential;
    }
    grid_contact_force_[k] = {inv_dt * sum.normal, inv_dt * sum.tangential};
  }
  // On ranks each rank booked the nodes of its own blocks: the forces are the ranks' sum, in
  // rank order (the same on every rank).
  if (ranks_ && contacts > 0) {
    static_assert(sizeof(InterfaceForce) == 6 * sizeof(double));
    ranks_->sum_in_rank_order(
        std::span<double>(reinterpret_cast<double*>(grid_contact_force_.data()), 6 * contacts));
  }
}

}  // namespace afemp::mpm
