// Outflow faces: the free-outflow boundary of the MPM paper on explosion and impact in
// *Journal of Harbin Engineering University* (2020, issue 8; docs/references.md, item 3),
// eq 13: at the start of each step a particle takes part only while it lies inside the grid
// domain, x_min <= x_p <= x_max. A particle beyond a face declared "outflow" stops taking
// part: it is taken out of the particle arrays, and its mass, momentum, kinetic and internal
// energy are booked (Energies::outflow*), so mass + outflow mass and the energy balance
// still close; its plastic work and viscous heat leave the plastic and viscous totals. So does
// one beyond an outflow face that is also past a symmetric or far-field face (at their corner),
// which binning would bring back past the latter only. A particle beyond any other face stops
// the run as before (binning names it). In the reproducible mode the books are summed exactly
// too (reproducible_sums.cpp), so that they do not depend on which rank a particle leaves from.
#include <cmath>
#include <span>
#include <vector>

#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

bool MpmSolver::left_through_outflow(const Vec3& x) const {
  if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z))) return false;
  const std::array<int, 3> c = grid_.cell_of(x);
  bool beyond = false;
  for (int a = 0; a < 3; ++a) {
    const auto k = static_cast<std::size_t>(a);
    const int side = c[k] < 0 ? 0 : c[k] >= grid_.cells()[k] ? 1 : -1;
    if (side < 0) continue;
    const auto f = static_cast<std::size_t>(2 * a + side);
    // Past a symmetric or far-field face as well (a jet's particle on a quarter model's axis
    // at the outflow face at its end): binning would bring it back past that face, still
    // beyond the outflow face, and stop the run; it leaves here instead.
    if (outflow_[f])
      beyond = true;
    else if (!returns_past_face(f))
      return false;  // past a face that stops the run: binning names it
  }
  return beyond;
}

void MpmSolver::remove_outflow() {
  Particles& p = particles_;
  const std::size_t n = p.size();
  long leaving = 0;
#pragma omp parallel for schedule(static) reduction(+ : leaving) if (core::worth_threads(n))
  for (std::size_t i = 0; i < n; ++i) leaving += left_through_outflow(p.position[i]) ? 1 : 0;
  // On ranks each rank takes out its own particles and books them (energies() sums the ranks'
  // books); the whole run's count falls by every rank's.
  if (ranks_) {
    double count = static_cast<double>(leaving);  // a step's sum: no buffer to allocate
    ranks_->sum_in_rank_order(std::span<double>(&count, 1));
    whole_count_ -= static_cast<std::size_t>(count);
  }
  if (leaving == 0) return;
  // In particle order, on one thread: the same sums for any thread count.
  const bool exact = reproducible();
  std::vector<std::int32_t> kept;
  kept.reserve(n - static_cast<std::size_t>(leaving));
  for (std::size_t i = 0; i < n; ++i) {
    if (!left_through_outflow(p.position[i])) {
      kept.push_back(static_cast<std::int32_t>(i));
      continue;
    }
    const double m = p.mass[i];
    const Vec3& v = p.velocity[i];
    outflow_mass_ += m;
    outflow_momentum_ += m * v;
    outflow_energy_ += 0.5 * m * core::dot(v, v) + m * p.energy[i];
    // Its plastic work and viscous heat leave the totals with it.
    plastic_work_ -= m * p.plastic_heat[i];
    viscous_work_ -= m * p.viscous_heat[i];
    if (!exact) continue;
    exact_[exact_outflow_mass].add(m);
    for (int c = 0; c < 3; ++c)
      exact_[exact_outflow_momentum + static_cast<std::size_t>(c)].add(m * v[c]);
    exact_[exact_outflow_energy].add(0.5 * m * core::dot(v, v) + m * p.energy[i]);
    exact_[exact_plastic].add(-(m * p.plastic_heat[i]));
    exact_[exact_viscous].add(-(m * p.viscous_heat[i]));
  }
  outflow_count_ += leaving;
  p.select(kept);
  if (!fused_kinematics()) velocity_gradient_.resize(p.size());
  // The kept particles keep their order, so each material batch stays contiguous and only its
  // bounds move; no re-sort (a full reorder on every step that lost a particle took a quarter
  // of V3's run).
  rebuild_batches();
}

}  // namespace afemp::mpm
