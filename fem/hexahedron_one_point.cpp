// One-point hexahedron of Flanagan & Belytschko (1981): B vectors, volume, mean velocity
// gradient, stress forces and the time-step length (fem/hexahedron_one_point.hpp).
#include "fem/hexahedron_one_point.hpp"

#include <algorithm>

namespace afemp::fem {

namespace {

// FB's node permutation: row a lists, for node a, the nodes that take the places of nodes
// 0..7 in the formula written for node 0, so that one expression gives every B vector.
constexpr int kPermutation[8][8] = {{0, 1, 2, 3, 4, 5, 6, 7}, {1, 2, 3, 0, 5, 6, 7, 4},
                                    {2, 3, 0, 1, 6, 7, 4, 5}, {3, 0, 1, 2, 7, 4, 5, 6},
                                    {4, 7, 6, 5, 0, 3, 2, 1}, {5, 4, 7, 6, 1, 0, 3, 2},
                                    {6, 5, 4, 7, 2, 1, 0, 3}, {7, 6, 5, 4, 3, 2, 1, 0}};

double triangle_area(const core::Vec3& a, const core::Vec3& b, const core::Vec3& c) {
  return 0.5 * core::norm(core::cross(b - a, c - a));
}

}  // namespace

OnePointHex one_point_hex(const HexVectors& x) {
  core::Vec3 centroid;
  for (const core::Vec3& p : x) centroid += p;
  centroid *= 0.125;
  double c[3][8];  // coordinates relative to the centroid, by component
  for (int a = 0; a < 8; ++a) {
    c[0][a] = x[a].x - centroid.x;
    c[1][a] = x[a].y - centroid.y;
    c[2][a] = x[a].z - centroid.z;
  }

  double b[3][8];
  for (int a = 0; a < 8; ++a) {
    const int* p = kPermutation[a];
    for (int i = 0; i < 3; ++i) {
      // b_a,i = dV/dx_a,i involves only the two other components j, k (cyclic after i).
      const double* yc = c[(i + 1) % 3];
      const double* zc = c[(i + 2) % 3];
      const double y2 = yc[p[1]], y3 = yc[p[2]], y4 = yc[p[3]], y5 = yc[p[4]], y6 = yc[p[5]],
                   y8 = yc[p[7]];
      const double z2 = zc[p[1]], z3 = zc[p[2]], z4 = zc[p[3]], z5 = zc[p[4]], z6 = zc[p[5]],
                   z8 = zc[p[7]];
      b[i][a] = (y2 * ((z6 - z3) - (z4 - z5)) + y3 * (z2 - z4) + y4 * ((z3 - z8) - (z5 - z2)) +
                 y5 * ((z8 - z6) - (z2 - z4)) + y6 * (z5 - z2) + y8 * (z4 - z5)) /
                12.0;
    }
  }
  OnePointHex e;
  double volume = 0.0;
  for (int a = 0; a < 8; ++a) {
    e.b[a] = {b[0][a], b[1][a], b[2][a]};
    volume += b[0][a] * c[0][a];
  }
  e.volume = volume;
  return e;
}

core::Mat3 velocity_gradient(const OnePointHex& e, const HexVectors& v) {
  core::Mat3 l;
  for (int a = 0; a < 8; ++a) {
    const double va[3] = {v[a].x, v[a].y, v[a].z}, ba[3] = {e.b[a].x, e.b[a].y, e.b[a].z};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) l.m[i][j] += va[i] * ba[j];
  }
  const double inv_v = 1.0 / e.volume;
  for (auto& row : l.m)
    for (double& lij : row) lij *= inv_v;
  return l;
}

void add_stress_forces(const OnePointHex& e, const core::SymTensor& s, HexVectors& f) {
  for (int a = 0; a < 8; ++a) {
    const core::Vec3& b = e.b[a];
    f[a].x -= s.xx * b.x + s.xy * b.y + s.xz * b.z;
    f[a].y -= s.xy * b.x + s.yy * b.y + s.yz * b.z;
    f[a].z -= s.xz * b.x + s.yz * b.y + s.zz * b.z;
  }
}

double characteristic_length(const HexVectors& x, double volume) {
  double largest = 0.0;
  for (const auto& face : kHexFaces) {
    const core::Vec3& p0 = x[face[0]];
    const core::Vec3& p1 = x[face[1]];
    const core::Vec3& p2 = x[face[2]];
    const core::Vec3& p3 = x[face[3]];
    const double split_02 = triangle_area(p0, p1, p2) + triangle_area(p0, p2, p3);
    const double split_13 = triangle_area(p1, p2, p3) + triangle_area(p1, p3, p0);
    largest = std::max(largest, 0.5 * (split_02 + split_13));
  }
  return volume / largest;
}

}  // namespace afemp::fem
