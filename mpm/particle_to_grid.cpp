// Particle-to-grid transfers (Ma 2005, eqs 2-29..2-31, 2-10, 2-11, 2-37): lumped nodal mass,
// momentum, internal force -V sigma.grad N and body force m N g, summed without atomics by
// sweeping the colour layers of particle_binning.cpp (one colour at a time). With the affine
// transfer the momentum is m N (v_p + C_p (x_I - x_p)) (Jiang et al. 2015), with the reference
// offsets X_I - X_p in the total-Lagrangian form (its stencil's offsets).
#include <array>

#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/stencil.hpp"

namespace afemp::mpm {

// The momentum a particle gives node n: m S (v_p + C_p (x_I - x_p)) with the affine (APIC)
// transfer (Jiang et al. 2015, eq 11), m S v_p without.
template <class Stencil, bool Affine>
inline Vec3 node_momentum(const Stencil& s, int n, double m, const Vec3& mv, const Particles& p,
                          std::size_t i) {
  if constexpr (Affine)
    return s.w(n) * (mv + m * (p.affine[i] * s.offset(n)));
  else
    return s.w(n) * mv;
}

template <class Stencil, bool Affine, bool MassMomentum, bool Force, bool Gravity, bool Exact>
void MpmSolver::p2g_kernel() {
  core::BackgroundGrid& g = grid_;
  const std::size_t slots = g.field_slot_count();
  // The reproducible mode: each particle's terms added to the fixed-point sums one by one
  // (reproducible_sums.cpp), which start_fixed_scatter cleared.
  constexpr bool exact = Exact;
  if constexpr (!exact) {
#pragma omp parallel for schedule(static) if (core::worth_threads(slots))
    for (std::size_t s = 0; s < slots; ++s) {
      if constexpr (MassMomentum) {
        g.mass[s] = 0.0;
        g.momentum[s] = {};
      }
      if constexpr (Force) g.force[s] = {};
    }
  }
  FixedNodes& fixed = fixed_;
  const Particles& p = particles_;
  const Vec3 gravity = scene_.run.gravity;
  const double ambient = ambient_pressure_;
  const bool axisymmetric = axisymmetric_;
  constexpr int N = Stencil::nodes;
  // Particles of one cell mostly follow each other (the arrays are kept in cell order), so
  // each sweep sums a run of particles that reach the same nodes locally and adds the sums
  // to the grid once per run: less grid traffic, same order every time. Each particle adds
  // to its body's velocity field (one field unless bodies are in grid contact).
  sweep_layers<Stencil::colours>(layer_offsets_, [&](std::size_t b, std::size_t e) {
    // Per node and component (structures of arrays), so that the loop over a particle's
    // nodes runs as vector instructions and the sums stay in registers through a run.
    alignas(64) double mass[N], mx[N], my[N], mz[N], fx[N], fy[N], fz[N];
    typename Stencil::Slots slot{};
    std::int64_t current = -1;
    std::size_t current_field = 0;
    bool ok = true;
    auto flush = [&] {
      if (current < 0) return;
      for (std::size_t n = 0; n < N; ++n) {
        const auto k = static_cast<std::size_t>(slot[n]) + current_field;
        if constexpr (exact) {
          if constexpr (MassMomentum) {
            fixed.mass[k] += core::to_fixed(mass[n], fixed.mass_scale, ok);
            fixed.momentum[3 * k] += core::to_fixed(mx[n], fixed.momentum_scale, ok);
            fixed.momentum[3 * k + 1] += core::to_fixed(my[n], fixed.momentum_scale, ok);
            fixed.momentum[3 * k + 2] += core::to_fixed(mz[n], fixed.momentum_scale, ok);
          }
          if constexpr (Force) {
            fixed.force[3 * k] += core::to_fixed(fx[n], fixed.force_scale, ok);
            fixed.force[3 * k + 1] += core::to_fixed(fy[n], fixed.force_scale, ok);
            fixed.force[3 * k + 2] += core::to_fixed(fz[n], fixed.force_scale, ok);
          }
          continue;
        }
        if constexpr (MassMomentum) {
          g.mass[k] += mass[n];
          g.momentum[k] += Vec3{mx[n], my[n], mz[n]};
        }
        if constexpr (Force) g.force[k] += Vec3{fx[n], fy[n], fz[n]};
      }
    };
    for (std::size_t q = b; q < e; ++q) {
      const auto i = static_cast<std::size_t>(layer_order_[q]);
      const Stencil st(g, p, i, p.position[i]);
      const std::size_t field = field_offset(i);
      // Each particle's terms on their own in the reproducible mode (not a run's sums).
      if (exact || st.key != current || field != current_field) {
        flush();
        current = st.key;
        current_field = field;
        st.slots(g, slot);
        for (std::size_t n = 0; n < N; ++n) {
          mass[n] = mx[n] = my[n] = mz[n] = 0.0;
          fx[n] = fy[n] = fz[n] = 0.0;
        }
      }
      const double m = p.mass[i];
      const Vec3 mv = m * p.velocity[i];
      // The bulk-viscous pressure acts with the stress (core/bulk_viscosity.hpp).
      // A far field's ambient pressure is taken off under its gauge form (absorbing_faces.hpp);
      // 0 otherwise.
      const core::SymTensor sv =
          p.volume[i] * (p.stress[i] - (p.bulk_q[i] - ambient) * core::SymTensor::identity());
#pragma omp simd
      for (int n = 0; n < N; ++n) {
        const double wn = st.w(n);
        const auto k = static_cast<std::size_t>(n);
        if constexpr (MassMomentum) {
          mass[k] += m * wn;
          const Vec3 mo = node_momentum<Stencil, Affine>(st, n, m, mv, p, i);
          mx[k] += mo.x;
          my[k] += mo.y;
          mz[k] += mo.z;
        }
        if constexpr (Force) {
          const Vec3& d = st.grad(n);
          fx[k] -= sv.xx * d.x + sv.xy * d.y + sv.xz * d.z;
          fy[k] -= sv.xy * d.x + sv.yy * d.y + sv.yz * d.z;
          fz[k] -= sv.xz * d.x + sv.yz * d.y + sv.zz * d.z;
          if constexpr (Gravity) {
            const double mw = m * wn;
            fx[k] += mw * gravity.x;
            fy[k] += mw * gravity.y;
            fz[k] += mw * gravity.z;
          }
        }
      }
      // Axisymmetric: the hoop stress's radial pull V sigma_thth N / r (mpm/axisymmetric.hpp;
      // sigma_yy is the hoop stress), in a loop of its own so that the 3-D one stays as it was.
      if constexpr (Force) {
        if (axisymmetric) {
          const double hoop = sv.yy / p.position[i].x;
          for (int n = 0; n < N; ++n) fx[static_cast<std::size_t>(n)] -= hoop * st.w(n);
        }
      }
    }
    flush();
    if (!ok) fixed_ok_[static_cast<std::size_t>(core::thread_index())] = 0;
  });
}

void MpmSolver::particle_to_grid(bool mass_momentum, bool force) {
  const FixedScatter fixed = mass_momentum && force ? FixedScatter::mass_momentum_force
                             : mass_momentum        ? FixedScatter::mass_momentum
                                                    : FixedScatter::force;
  if (reproducible()) start_fixed_scatter(fixed);
  // Every combination a plan asks for, each a loop with no branch per particle (the
  // reproducible mode's kernels for the stencils it takes: not CPDI).
  with_stencil([&]<class Stencil, bool Affine>() {
    auto kernel = [&]<bool MassMomentum, bool Force, bool Gravity>() {
      constexpr bool cpdi = requires {
        Stencil::tracks_corners;
      };
      if constexpr (!cpdi)
        if (reproducible())
          return p2g_kernel<Stencil, Affine, MassMomentum, Force, Gravity, true>();
      p2g_kernel<Stencil, Affine, MassMomentum, Force, Gravity, false>();
    };
    if (mass_momentum && force) {
      if (plan_.gravity)
        kernel.template operator()<true, true, true>();
      else
        kernel.template operator()<true, true, false>();
    } else if (mass_momentum) {
      kernel.template operator()<true, false, false>();
    } else if (plan_.gravity) {
      kernel.template operator()<false, true, true>();
    } else {
      kernel.template operator()<false, true, false>();
    }
  });
  // The mesh points and the loads on particles add theirs into the fixed-point sums before they
  // are made whole (in the reproducible mode).
  if (points_) points_->to_grid(access(), mass_momentum, force);
  if (force && !load_acceleration_.empty()) add_particle_loads();
  if (reproducible()) return finish_fixed_scatter(fixed);
  if (ranks_) {
    // The grid's sums, and those of the self-updating points' share of a field that also holds
    // particles (grid_points.hpp: a converting body's contact nodes), which they scattered.
    core::BackgroundGrid& g = grid_;
    std::array<core::NodalArray, 6> arrays;
    std::size_t n = 0;
    if (mass_momentum) {
      arrays[n++] = {g.mass.data(), 1};
      arrays[n++] = {reinterpret_cast<double*>(g.momentum.data()), 3};
    }
    if (force) arrays[n++] = {reinterpret_cast<double*>(g.force.data()), 3};
    if (shared_.any && mass_momentum) {
      arrays[n++] = {shared_.mass.data(), 1};
      arrays[n++] = {reinterpret_cast<double*>(shared_.start.data()), 3};
    }
    if (shared_.any && force) arrays[n++] = {reinterpret_cast<double*>(shared_.updated.data()), 3};
    sum_shared_blocks(std::span<const core::NodalArray>(arrays.data(), n));
  }
}

template <class Stencil, bool Affine, bool Exact>
void MpmSolver::remap_kernel() {
  // MUSL (eq 2-37): the updated particle momentum, mapped with the weights of the step's
  // start positions, gives the nodal velocity the strain rate is computed from.
  core::BackgroundGrid& g = grid_;
  const std::size_t slots = g.field_slot_count();
  constexpr bool exact = Exact;
  if constexpr (exact) {
    start_fixed_scatter(FixedScatter::remap);
  } else {
#pragma omp parallel for schedule(static) if (core::worth_threads(slots))
    for (std::size_t s = 0; s < slots; ++s) g.velocity_remap[s] = {};
  }
  FixedNodes& fixed = fixed_;
  const Particles& p = particles_;
  sweep_layers<Stencil::colours>(layer_offsets_, [&](std::size_t b, std::size_t e) {
    bool ok = true;
    for (std::size_t q = b; q < e; ++q) {
      const auto i = static_cast<std::size_t>(layer_order_[q]);
      const Stencil st(g, p, i, p.position[i]);
      typename Stencil::Slots slot;
      st.slots(g, slot);
      const std::size_t field = field_offset(i);
      const double m = p.mass[i];
      const Vec3 mv = m * p.velocity[i];
      for (int n = 0; n < Stencil::nodes; ++n) {
        const std::size_t k = static_cast<std::size_t>(slot[static_cast<std::size_t>(n)]) + field;
        const Vec3 mo = node_momentum<Stencil, Affine>(st, n, m, mv, p, i);
        if constexpr (exact) {
          for (std::size_t a = 0; a < 3; ++a)
            fixed.remap[3 * k + a] +=
                core::to_fixed(mo[static_cast<int>(a)], fixed.momentum_scale, ok);
        } else {
          g.velocity_remap[k] += mo;
        }
      }
    }
    if (!ok) fixed_ok_[static_cast<std::size_t>(core::thread_index())] = 0;
  });
  if (points_) points_->remap(access());
  if constexpr (exact) finish_fixed_scatter(FixedScatter::remap);
  if (ranks_ && !exact) {
    const core::NodalArray remapped[] = {{reinterpret_cast<double*>(g.velocity_remap.data()), 3}};
    sum_shared_blocks(remapped);
  }
  apply_velocity_conditions(g.velocity_remap, true);
  // A wall node held this step (its v or v_new pointed into the wall) did not move
  // normally (positions move with v_new): its remapped normal velocity is zeroed too, or
  // the strain would compress the material against a node that stayed put (energy created).
  for (std::size_t s = 0; s < slots && s < wall_contact_.size(); ++s)
    for (int a = 0; a < 3; ++a)
      if ((wall_contact_[s] >> a) & 1u) g.velocity_remap[s][a] = 0.0;
}

void MpmSolver::remap_to_grid() {
  with_stencil([&]<class Stencil, bool Affine>() {
    constexpr bool cpdi = requires {
      Stencil::tracks_corners;
    };
    if constexpr (!cpdi)
      if (reproducible()) return remap_kernel<Stencil, Affine, true>();
    remap_kernel<Stencil, Affine, false>();
  });
}

}  // namespace afemp::mpm
