// Particles carried past a face that keeps them (one pass at the start of binning):
//
// - A symmetric face stands for the mirrored half of the model: the grid holds the normal
//   velocity at its nodes to zero, but a particle within a cell of it moves with velocities
//   interpolated from nodes that are not on it, so in a strong flow towards the plane (a liner
//   collapsing on the axis of a quarter model) it can step past it. Its mirror twin then steps
//   past the other way: the particle is reflected back, position mirrored about the face, the
//   normal velocity component and the shear components of stress and strain that involve the
//   normal reversed (the mirror image of the state).
// - A far-field face (absorbing_faces.hpp) stands for the fluid beyond it, which the flow
//   through the face joins. The grid is fixed, so a particle that the outgoing flow carries
//   past the face's plane (the water a growing bubble displaces: 0.5-1 mm at the faces in the
//   bubble trial of docs/explosives.md) is put back on the plane, keeping its mass, momentum
//   and state; when the flow turns (the bubble collapses) it moves in again. Taking such
//   particles out instead (as an outflow face does) left the face nodes without mass once the
//   outermost layer had gone: the water then had a free surface at the ambient pressure,
//   released it, and cavitated through the domain.
//
// A particle past any other face is left to binning, which stops the run (or to the outflow
// stage, which took it out before).
#include <array>
#include <cmath>

#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {
namespace {

// Mirror of a symmetric tensor (xx, yy, zz, yz, xz, xy) about the plane normal to axis a.
void mirror(core::SymTensor& s, int a) {
  if (a == 0) {
    s.xz = -s.xz;
    s.xy = -s.xy;
  }
  if (a == 1) {
    s.yz = -s.yz;
    s.xy = -s.xy;
  }
  if (a == 2) {
    s.yz = -s.yz;
    s.xz = -s.xz;
  }
}

enum class Crossing : unsigned char { none, mirror, hold };

}  // namespace

bool MpmSolver::returns_past_face(std::size_t f) const {
  // Total-Lagrangian: the grid holds the reference configuration, which stays put.
  return !plan_.total_lagrangian &&
         (grid_.settings().faces[f] == core::FaceCondition::symmetric || absorbing_[f].far);
}

void MpmSolver::return_particles_past_faces() {
  const core::GridSettings& g = grid_.settings();
  std::array<Crossing, 6> action{};
  std::array<double, 6> plane{};
  bool any = false;
  for (std::size_t f = 0; f < 6; ++f) {
    const std::size_t a = f / 2;
    plane[f] = f % 2 == 0 ? g.min[static_cast<int>(a)]
                          : g.min[static_cast<int>(a)] + grid_.cells()[a] * grid_.cell();
    action[f] = !returns_past_face(f)                          ? Crossing::none
                : g.faces[f] == core::FaceCondition::symmetric ? Crossing::mirror
                                                               : Crossing::hold;
    any = any || action[f] != Crossing::none;
  }
  if (!any) return;
  Particles& p = particles_;
  const std::size_t n = p.size();
  const bool strain = !p.strain.empty(), affine = !p.affine.empty();
  const bool domain = !p.domain.empty(), corners = !p.corners.empty();
  // A held particle goes just inside the plane, so that its cell is the last one.
  const double inset = 1e-9 * grid_.cell();
#pragma omp parallel for schedule(static) if (core::worth_threads(n))
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      double& x = p.position[i][a];
      const auto lo = static_cast<std::size_t>(2 * a), hi = lo + 1;
      const std::size_t f = x < plane[lo] ? lo : x > plane[hi] ? hi : 6;
      if (f == 6 || action[f] == Crossing::none) continue;
      if (action[f] == Crossing::hold) {
        const double held = plane[f] + (f == lo ? inset : -inset);
        if (corners)  // CPDI2's domain goes with its particle
          for (Vec3& c : p.corners[i]) c[a] += held - x;
        x = held;
        continue;
      }
      x = 2.0 * plane[f] - x;
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
      // CPDI1's edge vectors r' = M r M: the same corners, mirrored, and det r kept positive.
      if (domain)
        for (int k = 0; k < 3; ++k) {
          if (k == a) continue;
          p.domain[i].m[a][k] = -p.domain[i].m[a][k];
          p.domain[i].m[k][a] = -p.domain[i].m[k][a];
        }
      // CPDI2's corners mirrored, corner c taking the image of corner c with its natural
      // coordinate along a reversed, so that the hexahedron keeps its orientation.
      if (corners) {
        std::array<Vec3, 8>& xc = p.corners[i];
        const std::array<Vec3, 8> old = xc;
        for (int c = 0; c < 8; ++c) {
          Vec3& to = xc[static_cast<std::size_t>(c)];
          to = old[static_cast<std::size_t>(c ^ (1 << a))];
          to[a] = 2.0 * plane[f] - to[a];
        }
      }
    }
  }
}

}  // namespace afemp::mpm
