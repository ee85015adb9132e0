// Two-node truss kernels (fem/truss.hpp): axial kinematics along the current axis, nodal
// forces N e, the mass-conserving cross-section and the bar-wave time step L / sqrt(E_t / rho).
#include "fem/truss.hpp"

#include <cassert>
#include <cmath>

namespace afemp::fem {

TrussKinematics truss_kinematics(const core::Vec3& xa, const core::Vec3& xb, const core::Vec3& va,
                                 const core::Vec3& vb) {
  const core::Vec3 axis = xb - xa;
  const double length = core::norm(axis);
  assert(length > 0.0);
  const core::Vec3 e = (1.0 / length) * axis;
  return {length, e, core::dot(vb - va, e) / length};
}

void add_truss_forces(const TrussKinematics& k, double axial_force, core::Vec3& fa,
                      core::Vec3& fb) {
  const core::Vec3 f = axial_force * k.direction;
  fa += f;
  fb -= f;
}

double current_area(double area0, double length0, double density0, double length, double density) {
  return area0 * length0 * density0 / (length * density);
}

double truss_time_step(double length, double youngs_modulus_tangent, double density) {
  return length / std::sqrt(youngs_modulus_tangent / density);
}

}  // namespace afemp::fem
