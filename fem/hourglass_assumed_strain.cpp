// ASQBI assumed strain stabilisation of the one-point hexahedron, Belytschko & Bindeman (1993):
// corotational frame, closed-form stiffness and the rate-form update
// (fem/hourglass_assumed_strain.hpp).
#include "fem/hourglass_assumed_strain.hpp"

#include <algorithm>
#include <cmath>

namespace afemp::fem {

namespace {

// Polar factor by Newton's iteration X <- (X + X^-T) / 2 on the columns: the columns of X^-T are
// the dual basis (x_2 x x_3, x_3 x x_1, x_1 x x_2) / det X. Quadratic convergence; the bound on
// the count only guards against a pathological input.
constexpr int kMaxPolarIterations = 40;
constexpr double kPolarTolerance = 1e-15;

std::array<core::Vec3, 3> gram_schmidt(const core::Vec3& g1, const core::Vec3& g2) {
  const core::Vec3 e1 = (1.0 / core::norm(g1)) * g1;
  core::Vec3 e2 = g2 - core::dot(g2, e1) * e1;
  e2 *= 1.0 / core::norm(e2);
  return {e1, e2, core::cross(e1, e2)};
}

}  // namespace

AssumedStrainGeometry assumed_strain_geometry(const HexVectors& x) {
  // Centre Jacobian columns g_j = (1/8) sum_a xi_a,j x_a.
  std::array<core::Vec3, 3> g{};
  for (int a = 0; a < 8; ++a)
    for (int j = 0; j < 3; ++j) g[j] += (0.125 * kHexNatural[a][j]) * x[a];

  AssumedStrainGeometry out;
  const double det = core::dot(g[0], core::cross(g[1], g[2]));
  if (!(det > 0.0)) {
    out.axis = gram_schmidt(g[0], g[1]);
    for (int j = 0; j < 3; ++j) out.inverse_half_length[j] = 1.0 / core::norm(g[j]);
    return out;
  }
  // |grad xi_j| = |g_k x g_l| / det.
  for (int j = 0; j < 3; ++j)
    out.inverse_half_length[j] = core::norm(core::cross(g[(j + 1) % 3], g[(j + 2) % 3])) / det;

  std::array<core::Vec3, 3> r;
  for (int j = 0; j < 3; ++j) r[j] = (1.0 / core::norm(g[j])) * g[j];
  for (int it = 0; it < kMaxPolarIterations; ++it) {
    const double d = core::dot(r[0], core::cross(r[1], r[2]));
    const double inv_d = 1.0 / d;
    double change = 0.0;
    std::array<core::Vec3, 3> next;
    for (int j = 0; j < 3; ++j) {
      const core::Vec3 dual = inv_d * core::cross(r[(j + 1) % 3], r[(j + 2) % 3]);
      next[j] = 0.5 * (r[j] + dual);
      const core::Vec3 step = next[j] - r[j];
      change = std::max(change, core::dot(step, step));
    }
    r = next;
    if (change < kPolarTolerance * kPolarTolerance) break;
  }
  out.axis = r;
  return out;
}

HourglassComponents assumed_strain_stiffness_product(const core::Vec3& c, double volume,
                                                     double shear_modulus, double poisson_ratio,
                                                     const HourglassComponents& q) {
  const double k = shear_modulus * volume / 96.0;
  const double nu_bar = poisson_ratio / (1.0 - poisson_ratio);
  const double one_nu_bar = 1.0 + nu_bar;  // = 1 / (1 - nu)
  HourglassComponents out{};

  // Bending blocks: the two in-plane bending modes of each plane, coupled by nu_bar.
  auto bending = [&](double ci, double qi, double cj, double qj, double& out_i, double& out_j) {
    const double si = ci * qi, sj = cj * qj;
    out_i = k * ci * (one_nu_bar * si + nu_bar * sj);
    out_j = k * cj * (one_nu_bar * sj + nu_bar * si);
  };
  bending(c.x, q[1].x, c.y, q[0].y, out[1].x, out[0].y);  // zeta plane: q_x2, q_y1
  bending(c.x, q[2].x, c.z, q[0].z, out[2].x, out[0].z);  // eta plane:  q_x3, q_z1
  bending(c.y, q[2].y, c.z, q[1].z, out[2].y, out[1].z);  // xi plane:   q_y3, q_z2

  // Twist block: the three assumed shears (engineering, times 8 / (their monomial)).
  const double g_z = c.y * q[0].x + c.x * q[1].y;  // 2 eps_xy, zeta term
  const double g_y = c.z * q[0].x + c.x * q[2].z;  // 2 eps_xz, eta term
  const double g_x = c.z * q[1].y + c.y * q[2].z;  // 2 eps_yz, xi term
  const double half_k = 0.5 * k;
  out[0].x = half_k * (c.y * g_z + c.z * g_y);
  out[1].y = half_k * (c.x * g_z + c.z * g_x);
  out[2].z = half_k * (c.x * g_y + c.y * g_x);

  // The xi eta zeta mode: uniaxial, E = 2 mu (1 + nu).
  const double k4 = k * (1.0 + poisson_ratio) / 3.0;
  for (int i = 0; i < 3; ++i) out[3][i] = k4 * c[i] * c[i] * q[3][i];
  return out;
}

double assumed_strain_hourglass_forces(const AssumedStrainGeometry& geo, double volume,
                                       double shear_modulus, double poisson_ratio, double dt,
                                       const std::array<core::Vec3, 4>& q,
                                       HourglassComponents& hourglass_stress,
                                       std::array<core::Vec3, 4>& g) {
  HourglassComponents q_frame{};
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) q_frame[k][i] = core::dot(geo.axis[i], q[k]);
  const HourglassComponents rate = assumed_strain_stiffness_product(
      geo.inverse_half_length, volume, shear_modulus, poisson_ratio, q_frame);
  double power = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double old_power = core::dot(hourglass_stress[k], q_frame[k]);
    hourglass_stress[k] += dt * rate[k];
    power += 0.5 * (old_power + core::dot(hourglass_stress[k], q_frame[k]));
    const core::Vec3& s = hourglass_stress[k];
    g[k] = s.x * geo.axis[0] + s.y * geo.axis[1] + s.z * geo.axis[2];
  }
  return power;
}

double add_hourglass_assumed_strain(const HexVectors& x, const HexVectors& v, const OnePointHex& e,
                                    const HourglassModes& m, double shear_modulus,
                                    double poisson_ratio, double dt,
                                    HourglassComponents& hourglass_stress, HexVectors& f,
                                    double* midpoint_power) {
  std::array<core::Vec3, 4> q{}, g{};
  for (int k = 0; k < 4; ++k)
    for (int a = 0; a < 8; ++a) q[k] += m.gamma[k][a] * v[a];
  const double midpoint =
      assumed_strain_hourglass_forces(assumed_strain_geometry(x), e.volume, shear_modulus,
                                      poisson_ratio, dt, q, hourglass_stress, g);
  if (midpoint_power) *midpoint_power = midpoint;
  double power = 0.0;  // with the updated stresses
  for (int k = 0; k < 4; ++k) {
    power += core::dot(g[k], q[k]);
    for (int a = 0; a < 8; ++a) f[a] -= m.gamma[k][a] * g[k];
  }
  return power;
}

}  // namespace afemp::fem
