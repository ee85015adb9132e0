// One-point hexahedra in the implicit solves (fem/hexahedron_stiffness.hpp): the tangent
// (one-point stiffness plus the hourglass stiffness of the stiffness and the assumed strain
// forms) against central differences of the explicit solver's own force routines.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "fem/hexahedron_stiffness.hpp"
#include "fem/hourglass.hpp"
#include "fem/hourglass_assumed_strain.hpp"
#include "fem/sparse_cholesky.hpp"
#include "hexahedron_test_support.hpp"
#include "static_test_support.hpp"

namespace afemp::fem {
namespace {

using test::steel;

core::SymTensor hooke(const core::Material& m, const core::SymTensor& eps) {
  const double g = m.shear_modulus(), lambda = m.bulk_modulus() - 2.0 * g / 3.0;
  return (lambda * eps.trace()) * core::SymTensor::identity() + (2.0 * g) * eps;
}

core::HourglassSettings form(core::HourglassForm f) {
  core::HourglassSettings s;
  s.form = f;
  return s;
}

// The explicit element's nodal forces (external minus internal) after one step of length 1 from
// rest with the velocities u, everything evaluated on the moved nodes x + u as the explicit
// solver does: the stress of the one-point strain rate (fem/hexahedron_one_point.hpp), and the
// hourglass force of the form (fem/hourglass.hpp's stiffness form with the modulus
// rho c^2 = K + 4G/3 of the elastic material at rest; fem/hourglass_assumed_strain.hpp).
HexVectors explicit_forces(const HexVectors& x0, const HexVectors& u, const core::Material& m,
                           core::HourglassForm f) {
  HexVectors x;
  for (int a = 0; a < 8; ++a) x[a] = x0[a] + u[a];
  const OnePointHex e = one_point_hex(x);
  const HourglassModes modes = hourglass_modes(e, x);
  HexVectors force{};
  add_stress_forces(e, hooke(m, core::sym_part(velocity_gradient(e, u))), force);
  const double q_hg = core::HourglassSettings::default_coefficient(f);
  if (f == core::HourglassForm::stiffness) {
    std::array<core::Vec3, 4> hourglass_force{};
    add_hourglass_stiffness(modes, u, q_hg, m.bulk_modulus() + 4.0 / 3.0 * m.shear_modulus(),
                            e.volume, 1.0, hourglass_force, force);
  } else {
    HourglassComponents stress{};
    add_hourglass_assumed_strain(x, u, e, modes, q_hg * m.shear_modulus(), m.poisson_ratio, 1.0,
                                 stress, force);
  }
  return force;
}

// The six rigid-body modes of the element's nodes (translations; rotations about the axes
// through the origin).
std::array<std::array<double, 24>, 6> rigid_modes(const HexVectors& x) {
  std::array<std::array<double, 24>, 6> modes{};
  for (int a = 0; a < 8; ++a)
    for (int d = 0; d < 3; ++d) {
      modes[d][3 * a + d] = 1.0;
      core::Vec3 axis;
      axis[d] = 1.0;
      const core::Vec3 rotation = core::cross(axis, x[a]);
      for (int i = 0; i < 3; ++i) modes[3 + d][3 * a + i] = rotation[i];
    }
  return modes;
}

// Whether k + scale sum phi phi^T over the rigid-body modes is positive definite, that is,
// whether the modes are k's whole null space.
bool only_rigid_modes_free(const HexMatrix& k, const HexVectors& x, double scale) {
  SymmetricCsc penalised;
  penalised.size = 24;
  penalised.column_start.push_back(0);
  const auto modes = rigid_modes(x);
  for (int q = 0; q < 24; ++q) {
    for (int p = 0; p <= q; ++p) {
      double v = k[24 * p + q];
      for (const auto& phi : modes) v += scale * phi[p] * phi[q];
      penalised.row.push_back(p);
      penalised.value.push_back(v);
    }
    penalised.column_start.push_back(static_cast<int>(penalised.row.size()));
  }
  SparseCholesky cholesky;
  cholesky.analyse(penalised);
  try {
    cholesky.factorise(penalised);
    return true;
  } catch (const NotPositiveDefinite&) {
    return false;
  }
}

// The one-point tangent plus the hourglass stiffness equals -d f / d u of the explicit routines
// at u = 0 by central differences (step 1e-6 of the unit element; the forces are linear in u up
// to the geometric terms, which vanish at u = 0 with the stress and hourglass force) to 1e-6 of
// its largest entry, on five distorted elements and for both forms; it is symmetric, its null
// space is exactly the six rigid-body modes, whereas the one-point stiffness alone leaves the
// twelve hourglass modes free as well (why the viscous form is refused).
TEST(StaticStiffness, OnePointTangentIsTheDerivativeOfTheExplicitForces) {
  const core::Material m = steel();
  const core::VoigtMatrix d = core::small_strain_update(m, {}, {}).tangent;
  for (core::HourglassForm f :
       {core::HourglassForm::stiffness, core::HourglassForm::assumed_strain})
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
      const HexVectors x = test::distorted_hex(seed);
      const OnePointHex e = one_point_hex(x);
      HexMatrix k, k_one_point;
      hexahedron_stiffness_one_point(e, d, k_one_point);
      k = k_one_point;
      add_hourglass_stiffness_matrix(hourglass_stiffness(x, e, m, form(f)), k);
      double scale = 0.0;
      for (double v : k) scale = std::max(scale, std::abs(v));
      const double step = 1e-6;
      double error = 0.0, asymmetry = 0.0;
      for (int q = 0; q < 24; ++q) {
        HexVectors plus{}, minus{};
        plus[q / 3][q % 3] = step;
        minus[q / 3][q % 3] = -step;
        const HexVectors fp = explicit_forces(x, plus, m, f), fm = explicit_forces(x, minus, m, f);
        for (int p = 0; p < 24; ++p) {
          const double fd = -(fp[p / 3][p % 3] - fm[p / 3][p % 3]) / (2.0 * step);
          error = std::max(error, std::abs(k[24 * p + q] - fd));
          asymmetry = std::max(asymmetry, std::abs(k[24 * p + q] - k[24 * q + p]));
        }
      }
      std::printf("one-point tangent, %s form, seed %u: finite-difference error %.2e of %.3g\n",
                  core::to_string(f), seed, error / scale, scale);
      EXPECT_LT(error, 1e-6 * scale) << core::to_string(f) << " seed " << seed;
      EXPECT_LT(asymmetry, 1e-12 * scale) << core::to_string(f) << " seed " << seed;
      EXPECT_TRUE(only_rigid_modes_free(k, x, scale)) << core::to_string(f) << " seed " << seed;
      EXPECT_FALSE(only_rigid_modes_free(k_one_point, x, scale)) << "seed " << seed;
    }
}

}  // namespace
}  // namespace afemp::fem
