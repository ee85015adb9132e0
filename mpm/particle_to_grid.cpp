// Particle-to-grid transfers (seed 001 eqs 2-29..2-31, 2-10, 2-11, 2-37): lumped nodal mass,
// momentum, internal force -V sigma.grad N and body force m N g, summed without atomics by
// sweeping the colour layers of particle_binning.cpp (even layers, then odd layers).
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

namespace {

// Runs body(particle) for every particle, layer by layer: layers of one parity in parallel.
template <class Body>
void sweep_layers(const std::vector<std::int64_t>& offsets, const std::vector<std::int32_t>& order,
                  Body&& body) {
  const std::int64_t layers = static_cast<std::int64_t>(offsets.size()) - 1;
  for (int parity = 0; parity < 2; ++parity) {
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t l = parity; l < layers; l += 2) {
      const auto b = static_cast<std::size_t>(offsets[static_cast<std::size_t>(l)]);
      const auto e = static_cast<std::size_t>(offsets[static_cast<std::size_t>(l) + 1]);
      for (std::size_t k = b; k < e; ++k) body(static_cast<std::size_t>(order[k]));
    }
  }
}

}  // namespace

template <bool MassMomentum, bool Force, bool Gravity>
void MpmSolver::particle_to_grid() {
  core::BackgroundGrid& g = grid_;
  const std::size_t slots = g.slot_count();
#pragma omp parallel for schedule(static)
  for (std::size_t s = 0; s < slots; ++s) {
    if constexpr (MassMomentum) {
      g.mass[s] = 0.0;
      g.momentum[s] = {};
    }
    if constexpr (Force) g.force[s] = {};
  }
  const Particles& p = particles_;
  const Vec3 gravity = scene_.run.gravity;
  sweep_layers(layer_offsets_, layer_order_, [&](std::size_t i) {
    const Vec3& x = p.position[i];
    const auto c = g.cell_of(x);
    const core::CellWeights w = g.weights(x, c);
    std::array<std::int32_t, 8> slot;
    g.node_slots(c, slot);
    const double m = p.mass[i];
    const Vec3 mv = m * p.velocity[i];
    const double vol = p.volume[i];
    const core::SymTensor& s = p.stress[i];
    for (int n = 0; n < 8; ++n) {
      const auto k = static_cast<std::size_t>(slot[static_cast<std::size_t>(n)]);
      const double wn = w.w[static_cast<std::size_t>(n)];
      if constexpr (MassMomentum) {
        g.mass[k] += m * wn;
        g.momentum[k] += wn * mv;
      }
      if constexpr (Force) {
        const Vec3& d = w.grad[static_cast<std::size_t>(n)];
        Vec3 f{-vol * (s.xx * d.x + s.xy * d.y + s.xz * d.z),
               -vol * (s.xy * d.x + s.yy * d.y + s.yz * d.z),
               -vol * (s.xz * d.x + s.yz * d.y + s.zz * d.z)};
        if constexpr (Gravity) f += (m * wn) * gravity;
        g.force[k] += f;
      }
    }
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
#pragma omp parallel for schedule(static)
  for (std::size_t s = 0; s < slots; ++s) g.velocity_remap[s] = {};
  const Particles& p = particles_;
  sweep_layers(layer_offsets_, layer_order_, [&](std::size_t i) {
    const Vec3& x = p.position[i];
    const auto c = g.cell_of(x);
    const core::CellWeights w = g.weights(x, c);
    std::array<std::int32_t, 8> slot;
    g.node_slots(c, slot);
    const Vec3 mv = p.mass[i] * p.velocity[i];
    for (int n = 0; n < 8; ++n)
      g.velocity_remap[static_cast<std::size_t>(slot[static_cast<std::size_t>(n)])] +=
          w.w[static_cast<std::size_t>(n)] * mv;
  });
  apply_velocity_conditions(g.velocity_remap, true);
}

}  // namespace afemp::mpm
