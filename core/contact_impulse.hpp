// One contact pair's update in the projected Gauss-Seidel sweeps that resolve the impulse
// contacts (meshes, fem/mesh_contact.cpp; particles at mesh faces,
// coupling/particle_surface_contact.cpp; particles at rigid walls, mpm/particle_wall_contact.cpp):
// the non-smooth contact dynamics of Jean 1999 on accumulated impulses. Each visit of a pair
// corrects its accumulated normal impulse P and clamps it >= 0 (surfaces separate freely), then
// its accumulated tangential impulse T toward stick and caps it at Coulomb's limit |T| <= mu P;
// the caller applies the changes. Clamping the accumulated impulses, not each visit's change,
// lets a later sweep take back what an earlier one gave too much. The functions are forced
// inline (AFEMP_INLINE): left to the inliner, they changed which multiply-adds the compiler
// fused elsewhere in their caller (the velocity sum of the hit search with the GIMP stencil in
// particle_surface_contact.cpp), and with them the last bits of its results.
#pragma once

#include <algorithm>

#include "afemp/tensor.hpp"
#include "core/parallel.hpp"

namespace afemp::core {

// The tangential part of the relative velocity rel at a contact of unit normal n: the slip.
AFEMP_INLINE inline Vec3 tangential_part(const Vec3& rel, const Vec3& n) {
  return rel - dot(rel, n) * n;
}

// Coulomb's law on a tangential impulse (or velocity change) t: cut to the length `limit`
// (mu times the normal one) along its own direction when it exceeds it.
AFEMP_INLINE inline void coulomb_cap(Vec3& t, double limit) {
  const double size = norm(t);
  if (size > limit) t = (limit / size) * t;
}

// The normal correction: the impulse that moves the predicted gap by `closing` (the gap aimed at
// minus the predicted one) over the step dt, w the pair's inverse mass along the normal, added
// to the accumulated normal impulse, which stays >= 0. Returns the change to apply.
AFEMP_INLINE inline double add_normal_impulse(double& accumulated, double closing, double dt,
                                              double w) {
  const double total = std::max(0.0, accumulated + closing / (dt * w));
  const double change = total - accumulated;
  accumulated = total;
  return change;
}

// The friction correction: the impulse that stops the slip of the relative velocity rel
// (the pair's velocity as the caller predicts it, normal n, inverse mass w), added to the
// accumulated tangential impulse and capped at mu times the accumulated normal one. Returns
// the change to apply.
AFEMP_INLINE inline Vec3 add_friction_impulse(Vec3& accumulated, double normal, double mu,
                                              const Vec3& rel, const Vec3& n, double w) {
  Vec3 t = accumulated - (1.0 / w) * tangential_part(rel, n);
  coulomb_cap(t, mu * normal);
  const Vec3 change = t - accumulated;
  accumulated = t;
  return change;
}

// The work the final tangential impulse t does on the slip it left (rel the pair's relative
// velocity after the sweeps): friction dissipates its negative, which each contact books as
// Energies::friction (and as part of Energies::sliding).
AFEMP_INLINE inline double slip_work(const Vec3& t, const Vec3& rel, const Vec3& n) {
  return dot(t, tangential_part(rel, n));
}

}  // namespace afemp::core
