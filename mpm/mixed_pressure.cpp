// The pressure of the mixed displacement-pressure total-Lagrangian MPM (Zhang et al. 2022,
// "mixed u-p TLMPM for nearly incompressible soft materials", eqs 17-24; docs/references.md).
// A split strain energy W = W_dev(C) + K / 2 (J - 1)^2 gives the stress S = S_dev + p J C^-1
// (eq 17) with p = K (J - 1) (eq 18). Taken point by point, p locks a nearly incompressible
// body: every particle's own J must stay near 1. The mixed scheme asks it in the weak sense
// instead, over a pressure basis N^q one order below the displacement's (the LBB condition:
// the linear hat under quadratic or cubic B-splines, one constant per cell under the linear
// hat), after the displacement step has updated F:
//   J_I   = sum_p det F_p N^q_I(X_p) V0_p / sum_p N^q_I(X_p) V0_p       (eq 22)
//   Jbar_p = sum_I N^q_I(X_p) J_I                                       (eq 23)
//   p_I   = sum_p K_p (Jbar_p - 1) N^q_I(X_p) V0_p / sum_p N^q_I(X_p) V0_p  (eq 21, lumped)
//   p_p   = sum_I N^q_I(X_p) p_I                                        (eq 24)
// and the material takes p_p in place of K (J_p - 1) (stress_update.cpp, PointState::
// mixed_pressure). Under a uniform deformation every average returns its input, so the scheme
// is the point-wise one there (tests/mpm/test_mixed_pressure.cpp). The scatters sweep the
// colour layers of the displacement stencil, which reach every node of N^q: sums without
// atomics, in the same order at any thread count. On ranks each rank sweeps its own particles
// and the nodes' sums are made whole over the shared blocks before each division.
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/stencil.hpp"

namespace afemp::mpm {

namespace {

// The pressure basis of one particle: the slots and weights of the nodes N^q reaches (8 for
// the linear hat, 1, the cell's first node, standing for the cell, for the constant).
template <bool Constant>
void pressure_basis(const core::BackgroundGrid& g, const Vec3& x, std::array<std::int32_t, 8>& slot,
                    std::array<double, 8>& w) {
  const std::array<int, 3> c = g.cell_of(x);
  g.node_slots(c, slot);
  if constexpr (Constant) {
    w[0] = 1.0;
  } else {
    const core::CellWeights cw = g.weights(x, c);
    for (std::size_t n = 0; n < 8; ++n) w[n] = cw.w[n];
  }
}

}  // namespace

template <int Colours, bool Constant>
void MpmSolver::mixed_pressure_kernel() {
  const core::BackgroundGrid& g = grid_;
  const Particles& p = particles_;
  const std::vector<Vec3>& x = weight_positions();
  const std::size_t n = p.size();
  const std::size_t slots = g.slot_count();
  constexpr std::size_t k = Constant ? 1 : 8;  // nodes of the pressure basis per particle
  // Per node slot: sum N V0, then J_I, then p_I.
  pressure_nodes_.assign(3 * slots, 0.0);
  double* weight = pressure_nodes_.data();
  double* ratio = weight + slots;
  double* pressure = ratio + slots;
  mixed_pressure_.resize(n);
  pressure_slots_.resize(n);
  pressure_weights_.resize(n);
  // Reference volume V0 = m / rho0 and bulk modulus K of each material.
  pressure_inv_rho0_.resize(materials_.size());
  pressure_bulk_.resize(materials_.size());
  for (std::size_t m = 0; m < materials_.size(); ++m) {
    pressure_inv_rho0_[m] = 1.0 / materials_[m]->density;
    pressure_bulk_[m] = materials_[m]->bulk_modulus();
  }
  auto v0 = [&](std::size_t i) {
    return p.mass[i] * pressure_inv_rho0_[static_cast<std::size_t>(p.material[i])];
  };
  // Eq 22: det F weighted by N^q V0; each particle's basis kept for the sweeps below.
  sweep_layers<Colours>(layer_offsets_, [&](std::size_t b, std::size_t e) {
    for (std::size_t q = b; q < e; ++q) {
      const auto i = static_cast<std::size_t>(layer_order_[q]);
      std::array<std::int32_t, 8>& slot = pressure_slots_[i];
      std::array<double, 8>& w = pressure_weights_[i];
      pressure_basis<Constant>(g, x[i], slot, w);
      const double vol = v0(i), j = core::determinant(p.deformation_gradient[i]);
      for (std::size_t a = 0; a < k; ++a) {
        const auto s = static_cast<std::size_t>(slot[a]);
        weight[s] += w[a] * vol;
        ratio[s] += w[a] * vol * j;
      }
    }
  });
  // On ranks the nodes' sums are made whole before they are divided (one velocity field's
  // slots each: the pressure is shared by the fields).
  if (ranks_) {
    const core::NodalArray sums[] = {{weight, 1, false, false, true},
                                     {ratio, 1, false, false, true}};
    sum_shared_blocks(sums);
  }
  [[maybe_unused]] const bool threads = core::worth_threads(slots);
#pragma omp parallel for schedule(static) if (threads)
  for (std::size_t s = 0; s < slots; ++s)
    if (weight[s] > 0.0) ratio[s] /= weight[s];
  // Eqs 23 and 21: Jbar_p back at the particle, K (Jbar_p - 1) weighted to the nodes.
  sweep_layers<Colours>(layer_offsets_, [&](std::size_t b, std::size_t e) {
    for (std::size_t q = b; q < e; ++q) {
      const auto i = static_cast<std::size_t>(layer_order_[q]);
      const std::array<std::int32_t, 8>& slot = pressure_slots_[i];
      const std::array<double, 8>& w = pressure_weights_[i];
      double jbar = 0.0;
      for (std::size_t a = 0; a < k; ++a) jbar += w[a] * ratio[static_cast<std::size_t>(slot[a])];
      const double load =
          v0(i) * pressure_bulk_[static_cast<std::size_t>(p.material[i])] * (jbar - 1.0);
      for (std::size_t a = 0; a < k; ++a)
        pressure[static_cast<std::size_t>(slot[a])] += w[a] * load;
    }
  });
  if (ranks_) {
    const core::NodalArray sums[] = {{pressure, 1, false, false, true}};
    sum_shared_blocks(sums);
  }
#pragma omp parallel for schedule(static) if (threads)
  for (std::size_t s = 0; s < slots; ++s)
    if (weight[s] > 0.0) pressure[s] /= weight[s];
      // Eq 24: p_p.
#pragma omp parallel for schedule(static) if (core::worth_threads(n))
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<std::int32_t, 8>& slot = pressure_slots_[i];
    const std::array<double, 8>& w = pressure_weights_[i];
    double pp = 0.0;
    for (std::size_t a = 0; a < k; ++a) pp += w[a] * pressure[static_cast<std::size_t>(slot[a])];
    mixed_pressure_[i] = pp;
  }
}

void MpmSolver::project_mixed_pressure() {
  // The displacement stencil's colour layers: two apart for the linear hat (whose pressure is
  // constant per cell), four for the wider ones (whose pressure is the linear hat).
  if (plan_.shape == core::ShapeFunction::linear)
    mixed_pressure_kernel<LinearStencil::colours, true>();
  else
    mixed_pressure_kernel<TensorStencil<3>::colours, false>();
}

}  // namespace afemp::mpm
