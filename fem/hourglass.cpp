// Flanagan-Belytschko hourglass shape vectors and the viscous and stiffness resisting forces
// (fem/hourglass.hpp).
#include "fem/hourglass.hpp"

#include <cmath>

namespace afemp::fem {

namespace {

// q_ik = sum_a v_a,i gamma_k,a: the hourglass velocity of mode k in direction i.
std::array<core::Vec3, 4> hourglass_velocities(const HourglassModes& m, const HexVectors& v) {
  double gamma[4][8][1], vl[3][8][1], q[4][3][1];
  for (int k = 0; k < 4; ++k)
    for (int a = 0; a < 8; ++a) gamma[k][a][0] = m.gamma[k][a];
  lanes::load<1>(v, vl, 0);
  lanes::hourglass_velocities<1>(gamma, vl, q);
  std::array<core::Vec3, 4> out;
  for (int k = 0; k < 4; ++k) out[k] = {q[k][0][0], q[k][1][0], q[k][2][0]};
  return out;
}

// f_a -= sum_k g_k gamma_k,a for generalised forces g_k.
void subtract_modal_forces(const HourglassModes& m, const std::array<core::Vec3, 4>& g,
                           HexVectors& f) {
  double gamma[4][8][1], gl[4][3][1], fl[3][8][1];
  for (int k = 0; k < 4; ++k) {
    for (int a = 0; a < 8; ++a) gamma[k][a][0] = m.gamma[k][a];
    for (int i = 0; i < 3; ++i) gl[k][i][0] = g[k][i];
  }
  lanes::load<1>(f, fl, 0);
  lanes::subtract_hourglass_forces<1>(gamma, gl, fl);
  lanes::store<1>(fl, 0, f);
}

}  // namespace

HourglassModes hourglass_modes(const OnePointHex& e, const HexVectors& x) {
  HourglassModes m;
  double xl[3][8][1], b[3][8][1], gamma[4][8][1];
  const double volume[1] = {e.volume};
  lanes::load<1>(x, xl, 0);
  lanes::load<1>(e.b, b, 0);
  lanes::hourglass_shapes<1>(xl, b, volume, gamma);
  for (int k = 0; k < 4; ++k)
    for (int a = 0; a < 8; ++a) m.gamma[k][a] = gamma[k][a][0];
  for (const core::Vec3& ba : e.b) m.b_squared += core::dot(ba, ba);
  return m;
}

double add_hourglass_viscous(const HourglassModes& m, const HexVectors& v, double coefficient,
                             double density, double wave_speed, double volume, HexVectors& f) {
  const double a_h = viscous_hourglass_factor(coefficient, density, wave_speed, volume);
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
  const double k_h = stiffness_hourglass_factor(coefficient, modulus, m.b_squared, volume);
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
