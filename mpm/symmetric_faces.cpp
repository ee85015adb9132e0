// Particles carried across a symmetric face. A symmetric face stands for the mirrored half of
// the model: the grid holds the normal velocity at its nodes to zero, but a particle within a
// cell of it moves with velocities interpolated from nodes that are not on it, so in a strong
// flow towards the plane (a liner collapsing on the axis of a quarter model) it can step past
// it. Its mirror twin then steps past the other way: the particle is reflected back, position
// mirrored about the face, the normal velocity component and the shear components of stress
// and strain that involve the normal reversed (the mirror image of the state).
#include <cmath>

#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {
namespace {

// Mirror of a symmetric tensor (xx, yy, zz, yz, xz, xy) about the plane normal to axis a.
void mirror(core::SymTensor& s, int a) {
  if (a == 0) { s.xz = -s.xz; s.xy = -s.xy; }
  if (a == 1) { s.yz = -s.yz; s.xy = -s.xy; }
  if (a == 2) { s.yz = -s.yz; s.xz = -s.xz; }
}

}  // namespace

void MpmSolver::reflect_at_symmetric_faces() {
  const core::GridSettings& g = grid_.settings();
  std::array<bool, 6> symmetric{};
  bool any = false;
  for (std::size_t f = 0; f < 6; ++f) {
    symmetric[f] = g.faces[f] == core::FaceCondition::symmetric;
    any = any || symmetric[f];
  }
  if (!any) return;
  Particles& p = particles_;
  const std::size_t n = p.size();
  const bool strain = !p.strain.empty(), affine = !p.affine.empty();
#pragma omp parallel for schedule(static) if (core::worth_threads(n))
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      const double lo = g.min[a];
      const double hi = g.min[a] + grid_.cells()[static_cast<std::size_t>(a)] * grid_.cell();
      double& x = p.position[i][a];
      double plane = 0.0;
      if (symmetric[static_cast<std::size_t>(2 * a)] && x < lo)
        plane = lo;
      else if (symmetric[static_cast<std::size_t>(2 * a + 1)] && x > hi)
        plane = hi;
      else
        continue;
      x = 2.0 * plane - x;
      p.velocity[i][a] = -p.velocity[i][a];
      mirror(p.stress[i], a);
      if (strain) mirror(p.strain[i], a);
      if (affine) {  // C' = M C M: the row and the column of axis a change sign
        for (int k = 0; k < 3; ++k) {
          if (k == a) continue;
          p.affine[i].m[a][k] = -p.affine[i].m[a][k];
          p.affine[i].m[k][a] = -p.affine[i].m[k][a];
        }
      }
    }
  }
}

}  // namespace afemp::mpm
