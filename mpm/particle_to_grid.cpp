// Particle-to-grid transfers (seed 001 eqs 2-29..2-31, 2-10, 2-11, 2-37): lumped nodal mass,
// momentum, internal force -V sigma.grad N and body force m N g, summed without atomics by
// sweeping the colour layers of particle_binning.cpp (even layers, then odd layers).
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

namespace {

// Runs body(begin, end) on the particle range of every colour layer: the layers of one
// parity in parallel (they share no node), then the others.
template <class Body>
void sweep_layers(const std::vector<std::int64_t>& offsets, Body&& body) {
  const std::int64_t layers = static_cast<std::int64_t>(offsets.size()) - 1;
  const bool threads = core::worth_threads(static_cast<std::size_t>(offsets.back()));
  for (int parity = 0; parity < 2; ++parity) {
#pragma omp parallel for schedule(dynamic, 1) if (threads)
    for (std::int64_t l = parity; l < layers; l += 2)
      body(static_cast<std::size_t>(offsets[static_cast<std::size_t>(l)]),
           static_cast<std::size_t>(offsets[static_cast<std::size_t>(l) + 1]));
  }
}

}  // namespace

template <bool MassMomentum, bool Force, bool Gravity>
void MpmSolver::particle_to_grid() {
  core::BackgroundGrid& g = grid_;
  const std::size_t slots = g.slot_count();
#pragma omp parallel for schedule(static) if (core::worth_threads(slots))
  for (std::size_t s = 0; s < slots; ++s) {
    if constexpr (MassMomentum) {
      g.mass[s] = 0.0;
      g.momentum[s] = {};
    }
    if constexpr (Force) g.force[s] = {};
  }
  const Particles& p = particles_;
  const Vec3 gravity = scene_.run.gravity;
  // Particles of one cell mostly follow each other (the arrays are kept in cell order), so
  // each sweep sums a run of same-cell particles into the cell's 8 nodes locally and adds
  // the sums to the grid once per run: 8x less grid traffic, same order every time.
  sweep_layers(layer_offsets_, [&](std::size_t b, std::size_t e) {
    double mass[8];
    Vec3 momentum[8], force[8];
    std::array<std::int32_t, 8> slot{};
    std::int64_t current = -1;
    auto flush = [&] {
      if (current < 0) return;
      for (std::size_t n = 0; n < 8; ++n) {
        const auto k = static_cast<std::size_t>(slot[n]);
        if constexpr (MassMomentum) {
          g.mass[k] += mass[n];
          g.momentum[k] += momentum[n];
        }
        if constexpr (Force) g.force[k] += force[n];
      }
    };
    for (std::size_t q = b; q < e; ++q) {
      const auto i = static_cast<std::size_t>(layer_order_[q]);
      const Vec3& x = p.position[i];
      const auto c = g.cell_of(x);
      const std::int64_t cell = g.linear_cell(c);  // recomputed: cheaper than reading cell_
      if (cell != current) {
        flush();
        current = cell;
        g.node_slots(c, slot);
        for (std::size_t n = 0; n < 8; ++n) {
          mass[n] = 0.0;
          momentum[n] = {};
          force[n] = {};
        }
      }
      const core::CellWeights w = g.weights(x, c);
      const double m = p.mass[i];
      const Vec3 mv = m * p.velocity[i];
      const core::SymTensor sv = p.volume[i] * p.stress[i];
      for (std::size_t n = 0; n < 8; ++n) {
        const double wn = w.w[n];
        if constexpr (MassMomentum) {
          mass[n] += m * wn;
          momentum[n] += wn * mv;
        }
        if constexpr (Force) {
          const Vec3& d = w.grad[n];
          force[n] -= Vec3{sv.xx * d.x + sv.xy * d.y + sv.xz * d.z,
                           sv.xy * d.x + sv.yy * d.y + sv.yz * d.z,
                           sv.xz * d.x + sv.yz * d.y + sv.zz * d.z};
          if constexpr (Gravity) force[n] += (m * wn) * gravity;
        }
      }
    }
    flush();
  });
}

template void MpmSolver::particle_to_grid<true, false, false>();
template void MpmSolver::particle_to_grid<false, true, false>();
template void MpmSolver::particle_to_grid<false, true, true>();
template void MpmSolver::particle_to_grid<true, true, false>();
template void MpmSolver::particle_to_grid<true, true, true>();

void MpmSolver::remap_to_grid() {
  // MUSL (eq 2-37): the updated particle momentum, mapped with the weights of the step's
  // start positions, gives the nodal velocity the strain rate is computed from.
  core::BackgroundGrid& g = grid_;
  const std::size_t slots = g.slot_count();
#pragma omp parallel for schedule(static) if (core::worth_threads(slots))
  for (std::size_t s = 0; s < slots; ++s) g.velocity_remap[s] = {};
  const Particles& p = particles_;
  sweep_layers(layer_offsets_, [&](std::size_t b, std::size_t e) {
    for (std::size_t q = b; q < e; ++q) {
      const auto i = static_cast<std::size_t>(layer_order_[q]);
      const Vec3& x = p.position[i];
      const auto c = g.cell_of(x);
      const core::CellWeights w = g.weights(x, c);
      std::array<std::int32_t, 8> slot;
      g.node_slots(c, slot);
      const Vec3 mv = p.mass[i] * p.velocity[i];
      for (std::size_t n = 0; n < 8; ++n)
        g.velocity_remap[static_cast<std::size_t>(slot[n])] += w.w[n] * mv;
    }
  });
  apply_velocity_conditions(g.velocity_remap, true);
  // A wall node held this step (its v or v_new pointed into the wall) did not move
  // normally (positions move with v_new): its remapped normal velocity is zeroed too, or
  // the strain would compress the material against a node that stayed put (energy created).
  for (std::size_t s = 0; s < slots && s < wall_contact_.size(); ++s)
    for (int a = 0; a < 3; ++a)
      if ((wall_contact_[s] >> a) & 1u) g.velocity_remap[s][a] = 0.0;
}

}  // namespace afemp::mpm
