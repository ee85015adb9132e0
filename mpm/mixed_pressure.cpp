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
// and the nodes' sums are made whole over the shared blocks before each division. In the
// reproducible mode the three sums are 128-bit fixed point (core/exact_sum.hpp), each scaled by
// a bound on its terms over every rank's particles (V0, V0 |J|, |K V0 (Jbar - 1)|), so that they
// do not depend on the particles' order or rank either (docs/parallel.md).
#include <algorithm>
#include <cmath>

#include "core/exact_sum.hpp"
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
  // The reproducible mode: fixed-point sums (per node slot: sum N V0, sum N V0 J, sum N load),
  // each thread's flag that no term passed its bound.
  const bool exact = reproducible();
  core::FixedScale scale[3];
  core::Fixed* fixed = nullptr;
  std::vector<char> ok(exact ? static_cast<std::size_t>(core::thread_count()) : 0, 1);
  auto bound_over_ranks = [&](double b) { return ranks_ ? ranks_->max_over_ranks(b) : b; };
  // Makes sums[0, count) whole over the ranks' shared blocks and turns them into the doubles
  // at `into`; stops the run where a term passed its bound.
  auto finish_fixed = [&](int first, int count, double* into) {
    stop_past_fixed_bound(std::count(ok.begin(), ok.end(), 0) > 0 ? 1 : 0,
                          "the mixed pressure's nodal sums",
                          first == 2 ? "pressure" : "volume ratio", "deformation");
    core::Fixed* from = fixed + static_cast<std::size_t>(first) * slots;
    if (ranks_) {
      std::vector<core::NodalArray> arrays;
      for (int a = 0; a < count; ++a)
        arrays.push_back({reinterpret_cast<double*>(from + static_cast<std::size_t>(a) * slots), 2,
                          false, true, true});
      sum_shared_blocks(arrays);
    }
    for (int a = 0; a < count; ++a)
      for (std::size_t s = 0; s < slots; ++s)
        into[static_cast<std::size_t>(a) * slots + s] =
            core::from_fixed(from[static_cast<std::size_t>(a) * slots + s], scale[first + a]);
  };
  if (exact) {
    pressure_fixed_.assign(3 * slots, 0);
    fixed = pressure_fixed_.data();
    double b0 = 0.0, b1 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : b0, b1) if (core::worth_threads(n))
    for (std::size_t i = 0; i < n; ++i) {
      const double vol = v0(i);
      b0 = std::max(b0, vol);
      b1 = std::max(b1, vol * std::fabs(core::determinant(p.deformation_gradient[i])));
    }
    scale[0] = core::fixed_scale(bound_over_ranks(b0));
    scale[1] = core::fixed_scale(bound_over_ranks(b1));
  }
  // Eq 22: det F weighted by N^q V0; each particle's basis kept for the sweeps below.
  sweep_layers<Colours>(layer_offsets_, [&](std::size_t b, std::size_t e) {
    bool fine = true;
    for (std::size_t q = b; q < e; ++q) {
      const auto i = static_cast<std::size_t>(layer_order_[q]);
      std::array<std::int32_t, 8>& slot = pressure_slots_[i];
      std::array<double, 8>& w = pressure_weights_[i];
      pressure_basis<Constant>(g, x[i], slot, w);
      const double vol = v0(i), j = core::determinant(p.deformation_gradient[i]);
      for (std::size_t a = 0; a < k; ++a) {
        const auto s = static_cast<std::size_t>(slot[a]);
        if (exact) {
          fixed[s] += core::to_fixed(w[a] * vol, scale[0], fine);
          fixed[slots + s] += core::to_fixed(w[a] * vol * j, scale[1], fine);
          continue;
        }
        weight[s] += w[a] * vol;
        ratio[s] += w[a] * vol * j;
      }
    }
    if (!fine) ok[static_cast<std::size_t>(core::thread_index())] = 0;
  });
  // On ranks the nodes' sums are made whole before they are divided (one velocity field's
  // slots each: the pressure is shared by the fields).
  if (exact) {
    finish_fixed(0, 2, weight);
  } else if (ranks_) {
    const core::NodalArray sums[] = {{weight, 1, false, false, true},
                                     {ratio, 1, false, false, true}};
    sum_shared_blocks(sums);
  }
  [[maybe_unused]] const bool threads = core::worth_threads(slots);
#pragma omp parallel for schedule(static) if (threads)
  for (std::size_t s = 0; s < slots; ++s)
    if (weight[s] > 0.0) ratio[s] /= weight[s];
  // Eqs 23 and 21: Jbar_p back at the particle, K (Jbar_p - 1) weighted to the nodes.
  auto load_of = [&](std::size_t i) {
    const std::array<std::int32_t, 8>& slot = pressure_slots_[i];
    const std::array<double, 8>& w = pressure_weights_[i];
    double jbar = 0.0;
    for (std::size_t a = 0; a < k; ++a) jbar += w[a] * ratio[static_cast<std::size_t>(slot[a])];
    return v0(i) * pressure_bulk_[static_cast<std::size_t>(p.material[i])] * (jbar - 1.0);
  };
  if (exact) {  // the loads first, for their bound
    pressure_load_.resize(n);
    double b2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : b2) if (core::worth_threads(n))
    for (std::size_t i = 0; i < n; ++i) {
      pressure_load_[i] = load_of(i);
      b2 = std::max(b2, std::fabs(pressure_load_[i]));
    }
    scale[2] = core::fixed_scale(bound_over_ranks(b2));
  }
  sweep_layers<Colours>(layer_offsets_, [&](std::size_t b, std::size_t e) {
    bool fine = true;
    for (std::size_t q = b; q < e; ++q) {
      const auto i = static_cast<std::size_t>(layer_order_[q]);
      const std::array<std::int32_t, 8>& slot = pressure_slots_[i];
      const std::array<double, 8>& w = pressure_weights_[i];
      if (exact) {
        for (std::size_t a = 0; a < k; ++a)
          fixed[2 * slots + static_cast<std::size_t>(slot[a])] +=
              core::to_fixed(w[a] * pressure_load_[i], scale[2], fine);
        continue;
      }
      const double load = load_of(i);
      for (std::size_t a = 0; a < k; ++a)
        pressure[static_cast<std::size_t>(slot[a])] += w[a] * load;
    }
    if (!fine) ok[static_cast<std::size_t>(core::thread_index())] = 0;
  });
  if (exact) {
    finish_fixed(2, 1, pressure);
  } else if (ranks_) {
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
