// Grid-to-particle velocity update (Ma 2005, eqs 2-33..2-36) with a PIC/FLIP blend:
// v_p <- flip (v_p + sum N (v_new - v)) + (1 - flip) sum N v_new. USF also moves the
// particle here with the updated grid velocity (eq 2-35); USL and MUSL move it in the
// strain pass, whose weights must still be those of the step's start position. With the
// affine transfer (APIC, Jiang et al. 2015, eqs 8-10) the particle takes the grid velocity
// v_p = sum S v_new and its affine part C_p = sum S v_new (x_I - x_p)^T D_p^-1 (X_I - X_p, the
// velocity's gradient in the reference configuration, in the total-Lagrangian form).
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/stencil.hpp"

namespace afemp::mpm {

template <class Stencil, bool Affine>
void MpmSolver::g2p_kernel(double dt, bool move_positions) {
  const core::BackgroundGrid& g = grid_;
  Particles& p = particles_;
  const double flip = scene_.mpm.flip;
  for_each_particle_stencil<Stencil>(g, p, [&](std::size_t i, const Stencil& st, const auto& slot) {
    VelocityUpdate<Stencil, Affine> update;
    const std::size_t field = field_offset(i);  // the particle's own velocity field
    for (int k = 0; k < Stencil::nodes; ++k) {
      const auto s = static_cast<std::size_t>(slot[static_cast<std::size_t>(k)]) + field;
      update.add(st, k, g.velocity_new[s], g.velocity[s]);
    }
    update.store(p, i, st, flip);
    if (move_positions) {
      p.position[i] += dt * update.v_grid;
      move_domain(p, i, st, slot, field, g.velocity_new.data(), dt);
    }
  });
}

void MpmSolver::grid_to_particle(double dt, bool move_positions) {
  apply_shared_shifts();
  with_stencil(
      [&]<class Stencil, bool Affine>() { g2p_kernel<Stencil, Affine>(dt, move_positions); });
  if (points_) points_->from_grid(access());
}

}  // namespace afemp::mpm
