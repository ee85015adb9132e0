// The hexahedron stage: for every live element, the strain increment from v^{n+1/2} on the
// mid-step geometry (Belytschko, Liu & Moran box 6.1), the Jaumann-rotated stress updated by
// the shared material law (Ma 2005, eq 2-41), artificial bulk viscosity
// q = rho l (C_q l eps_v'^2 - C_l c eps_v') in compression (core/bulk_viscosity.hpp, shared with
// the particles), hourglass forces for one-point elements (Flanagan & Belytschko 1981 viscous
// or stiffness forms, or Belytschko & Bindeman 1993 assumed strain), the nodal forces on the
// end-of-step geometry, the critical step l / (Q + sqrt(Q^2 + c^2)) with
// Q = C_l c + C_q l |eps_v'|, and the erosion criteria. One std::visit per batch; the passes
// of fem/hexahedron_passes.hpp run on packs of kLanes one-point elements or on one fully
// integrated element at a time, a trial state first and its commit after.
#include "core/parallel.hpp"
#include "fem/fe_solver.hpp"
#include "fem/hexahedron_passes.hpp"

namespace afemp::fem {

template <class Strength, class Eos, bool Thermal, bool Fails>
void FeSolver::hexahedron_batch(const ElementBatch& b, const Strength& strength, const Eos& eos,
                                double dt) {
  const HexahedronPasses<Strength, Eos, Thermal, Fails> passes(*this, b, strength, eos, dt);
  // This rank's elements (all of them in one process), split among the threads.
  sweep_share(b, [&](std::size_t first, std::size_t last, int t) {
    if (b.points_per_element == 8)
      passes.sweep_full(first, last, t);
    else
      passes.sweep_one_point(first, last, t);
  });
}

void HexahedronSet::update(FeSolver& fe, double dt) {
  fe.update_hexahedra(dt);
}

void FeSolver::update_hexahedra(double dt) {
  using namespace hexahedron_stage;
  std::fill(thread_sums_.begin(), thread_sums_.end(), 0.0);
  for (core::ExactSum& s : exact_mirror_) s.clear();
  for (auto& e : thread_errors_) e.clear();
  // The stabilisation energy per body (part of its internal energy): the threads' sums
  // grow batch by batch, so a batch's share is the growth over its sweep.
  auto stabilisation = [&] {
    double sum = 0.0;
    for (std::size_t t = 0; t < thread_errors_.size(); ++t)
      sum += thread_sums_[t * core::cache_line_doubles + kStabilisation];
    return sum;
  };
  for_each_batch(
      hexes_, [&]<class S, class E, bool Thermal>(const ElementBatch& b, const S& s, const E& e) {
        const double before = stabilisation();
        if (scene_.materials[static_cast<std::size_t>(b.material)].fails())
          hexahedron_batch<S, E, Thermal, true>(b, s, e, dt);
        else
          hexahedron_batch<S, E, Thermal, false>(b, s, e, dt);
        body_stabilisation_[static_cast<std::size_t>(b.body)] += stabilisation() - before;
        if (reproducible()) {  // the batch's stabilisation exactly, then cleared for the next
          const core::ExactSum batch = exact_threads(kStabilisation);
          exact_body_stabilisation_[static_cast<std::size_t>(b.body)] += batch;
          exact_[exact_stabilisation] += batch;
          clear_exact_threads(kStabilisation);
        }
        raise_thread_errors();
        collect_erosions(hexes_);
        collect_retirements();
      });
  for (std::size_t t = 0; t < thread_errors_.size(); ++t) {
    const double* s = &thread_sums_[t * core::cache_line_doubles];
    plastic_work_ += s[kPlastic];
    viscous_work_ += s[kViscous];
    hourglass_work_ += s[kHourglass];
    stabilisation_work_ += s[kStabilisation];
  }
  if (reproducible()) {
    exact_[exact_plastic] += exact_threads(kPlastic);
    exact_[exact_viscous] += exact_threads(kViscous);
    exact_[exact_hourglass] += exact_threads(kHourglass);
  }
}

}  // namespace afemp::fem
