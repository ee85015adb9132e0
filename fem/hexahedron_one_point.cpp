// One-point hexahedron of Flanagan & Belytschko (1981): B vectors, volume, mean velocity
// gradient, stress forces and the time-step length (fem/hexahedron_one_point.hpp).
#include "fem/hexahedron_one_point.hpp"

#include "fem/hexahedron_lanes.hpp"

namespace afemp::fem {

OnePointHex one_point_hex(const HexVectors& x) {
  double xl[3][8][1], c[3][8][1], b[3][8][1], volume[1];
  lanes::load<1>(x, xl, 0);
  lanes::b_vectors<1>(xl, c, b, volume);
  OnePointHex e;
  lanes::store<1>(b, 0, e.b);
  e.volume = volume[0];
  return e;
}

core::Mat3 velocity_gradient(const OnePointHex& e, const HexVectors& v) {
  double b[3][8][1], vl[3][8][1], grad[3][3][1];
  const double volume[1] = {e.volume};
  lanes::load<1>(e.b, b, 0);
  lanes::load<1>(v, vl, 0);
  lanes::velocity_gradient<1>(b, volume, vl, grad);
  core::Mat3 l;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) l.m[i][j] = grad[i][j][0];
  return l;
}

void add_stress_forces(const OnePointHex& e, const core::SymTensor& s, HexVectors& f) {
  double b[3][8][1], fl[3][8][1];
  const double sigma[6][1] = {{s.xx}, {s.yy}, {s.zz}, {s.yz}, {s.xz}, {s.xy}};
  lanes::load<1>(e.b, b, 0);
  lanes::stress_forces<1>(b, sigma, fl);
  for (int a = 0; a < 8; ++a) f[a] += core::Vec3{fl[0][a][0], fl[1][a][0], fl[2][a][0]};
}

double characteristic_length(const HexVectors& x, double volume) {
  double xl[3][8][1], length[1];
  const double v[1] = {volume};
  lanes::load<1>(x, xl, 0);
  lanes::characteristic_length<1>(xl, v, length);
  return length[0];
}

}  // namespace afemp::fem
