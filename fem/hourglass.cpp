// Flanagan-Belytschko hourglass shape vectors and the viscous and stiffness resisting forces
// (fem/hourglass.hpp).
#include "fem/hourglass.hpp"

#include <cmath>

namespace afemp::fem {

namespace {

// q_ik = sum_a v_a,i gamma_k,a: the hourglass velocity of mode k in direction i.
std::array<core::Vec3, 4> hourglass_velocities(const HourglassModes& m, const HexVectors& v) {
  std::array<core::Vec3, 4> q{};
  for (int k = 0; k < 4; ++k)
    for (int a = 0; a < 8; ++a) q[k] += m.gamma[k][a] * v[a];
  return q;
}

// f_a -= sum_k g_k gamma_k,a for generalised forces g_k.
void subtract_modal_forces(const HourglassModes& m, const std::array<core::Vec3, 4>& g,
                           HexVectors& f) {
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 4; ++k) f[a] -= m.gamma[k][a] * g[k];
}

}  // namespace

HourglassModes hourglass_modes(const OnePointHex& e, const HexVectors& x) {
  HourglassModes m;
  const double inv_v = 1.0 / e.volume;
  for (int k = 0; k < 4; ++k) {
    core::Vec3 hx;  // sum_b h_k,b x_b
    for (int b = 0; b < 8; ++b) hx += kHourglassBase[k][b] * x[b];
    for (int a = 0; a < 8; ++a)
      m.gamma[k][a] = kHourglassBase[k][a] - inv_v * core::dot(hx, e.b[a]);
  }
  for (const core::Vec3& b : e.b) m.b_squared += core::dot(b, b);
  return m;
}

double add_hourglass_viscous(const HourglassModes& m, const HexVectors& v, double coefficient,
                             double density, double wave_speed, double volume, HexVectors& f) {
  const double v13 = std::cbrt(volume);
  const double a_h = 0.25 * coefficient * density * wave_speed * v13 * v13;
  std::array<core::Vec3, 4> g = hourglass_velocities(m, v);
  double power = 0.0;
  for (core::Vec3& gk : g) {
    power += a_h * core::dot(gk, gk);
    gk *= a_h;
  }
  subtract_modal_forces(m, g, f);
  return power;
}

double add_hourglass_stiffness(const HourglassModes& m, const HexVectors& v, double coefficient,
                               double modulus, double volume, double dt,
                               std::array<core::Vec3, 4>& hourglass_force, HexVectors& f) {
  const double k_h = coefficient * modulus * m.b_squared / (3.0 * volume);
  const std::array<core::Vec3, 4> q = hourglass_velocities(m, v);
  double power = 0.0;
  for (int k = 0; k < 4; ++k) {
    hourglass_force[k] += (k_h * dt) * q[k];
    power += core::dot(hourglass_force[k], q[k]);
  }
  subtract_modal_forces(m, hourglass_force, f);
  return power;
}

}  // namespace afemp::fem
