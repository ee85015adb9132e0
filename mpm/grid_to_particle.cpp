// Grid-to-particle velocity update (seed 001 eqs 2-33..2-36) with a PIC/FLIP blend:
// v_p <- flip (v_p + sum N (v_new - v)) + (1 - flip) sum N v_new. USF also moves the
// particle here with the updated grid velocity (eq 2-35); USL and MUSL move it in the
// strain pass, whose weights must still be those of the step's start position.
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

void MpmSolver::grid_to_particle(double dt, bool move_positions) {
  const core::BackgroundGrid& g = grid_;
  Particles& p = particles_;
  const double flip = scene_.mpm.flip;
  const std::size_t n = p.size();
#pragma omp parallel for schedule(static) if (core::worth_threads(n))
  for (std::size_t i = 0; i < n; ++i) {
    Vec3& x = p.position[i];
    const auto c = g.cell_of(x);
    const core::CellWeights w = g.weights(x, c);
    std::array<std::int32_t, 8> slot;
    g.node_slots(c, slot);
    Vec3 v_grid, dv;
    for (int k = 0; k < 8; ++k) {
      const auto s = static_cast<std::size_t>(slot[static_cast<std::size_t>(k)]);
      const double wk = w.w[static_cast<std::size_t>(k)];
      v_grid += wk * g.velocity_new[s];
      dv += wk * (g.velocity_new[s] - g.velocity[s]);
    }
    p.velocity[i] = flip * (p.velocity[i] + dv) + (1.0 - flip) * v_grid;
    if (move_positions) x += dt * v_grid;
  }
}

}  // namespace afemp::mpm
