// Small fixed-size vectors and symmetric tensors for point-wise mechanics.
// Stress and strain are stored as six components (xx, yy, zz, yz, xz, xy), tensor
// (not engineering) shear components, so that a:b = sum of diagonal products
// + 2 * sum of off-diagonal products.
#pragma once

#include <algorithm>
#include <cmath>

namespace afemp::core {

/// A 3-vector (positions, velocities, forces).
struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;

  constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr Vec3& operator*=(double s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
};

constexpr Vec3 operator+(Vec3 a, const Vec3& b) {
  return a += b;
}
constexpr Vec3 operator-(Vec3 a, const Vec3& b) {
  return a -= b;
}
constexpr Vec3 operator*(double s, Vec3 a) {
  return a *= s;
}
constexpr Vec3 operator*(Vec3 a, double s) {
  return a *= s;
}
constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// The Euclidean length of a.
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

/// Full 3x3 matrix, row-major: m[i][j].
struct Mat3 {
  double m[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

/// a += u (x) v, i.e. a_ij += u_i v_j (a velocity gradient sum_I v_I (x) grad N_I).
constexpr void add_outer(Mat3& a, const Vec3& u, const Vec3& v) {
  for (int r = 0; r < 3; ++r) {
    a.m[r][0] += u[r] * v.x;
    a.m[r][1] += u[r] * v.y;
    a.m[r][2] += u[r] * v.z;
  }
}

/// det a.
constexpr double determinant(const Mat3& a) {
  return a.m[0][0] * (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) -
         a.m[0][1] * (a.m[1][0] * a.m[2][2] - a.m[1][2] * a.m[2][0]) +
         a.m[0][2] * (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]);
}

constexpr Vec3 operator*(const Mat3& a, const Vec3& v) {
  return {a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z,
          a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
          a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z};
}

/// A symmetric tensor as six components xx, yy, zz, yz, xz, xy (stress, strain increments).
struct SymTensor {
  double xx = 0.0, yy = 0.0, zz = 0.0, yz = 0.0, xz = 0.0, xy = 0.0;

  static constexpr SymTensor identity() { return {1.0, 1.0, 1.0, 0.0, 0.0, 0.0}; }
  constexpr double trace() const { return xx + yy + zz; }
  constexpr double mean() const { return trace() / 3.0; }
  constexpr SymTensor deviator() const {
    const double m = mean();
    return {xx - m, yy - m, zz - m, yz, xz, xy};
  }
  constexpr SymTensor& operator+=(const SymTensor& o) {
    xx += o.xx;
    yy += o.yy;
    zz += o.zz;
    yz += o.yz;
    xz += o.xz;
    xy += o.xy;
    return *this;
  }
  constexpr SymTensor& operator-=(const SymTensor& o) {
    xx -= o.xx;
    yy -= o.yy;
    zz -= o.zz;
    yz -= o.yz;
    xz -= o.xz;
    xy -= o.xy;
    return *this;
  }
  constexpr SymTensor& operator*=(double s) {
    xx *= s;
    yy *= s;
    zz *= s;
    yz *= s;
    xz *= s;
    xy *= s;
    return *this;
  }
};

constexpr SymTensor operator+(SymTensor a, const SymTensor& b) {
  return a += b;
}
constexpr SymTensor operator-(SymTensor a, const SymTensor& b) {
  return a -= b;
}
constexpr SymTensor operator*(double s, SymTensor a) {
  return a *= s;
}
constexpr SymTensor operator*(SymTensor a, double s) {
  return a *= s;
}

/// a : b
constexpr double double_dot(const SymTensor& a, const SymTensor& b) {
  return a.xx * b.xx + a.yy * b.yy + a.zz * b.zz + 2.0 * (a.yz * b.yz + a.xz * b.xz + a.xy * b.xy);
}

/// sqrt(3/2 s:s) for the deviator s of a.
inline double von_mises(const SymTensor& a) {
  const SymTensor s = a.deviator();
  return std::sqrt(1.5 * double_dot(s, s));
}

/// The largest principal value of a: its deviator's largest eigenvalue in the closed
/// (trigonometric) form, 2 sqrt(J2 / 3) cos(theta) with cos(3 theta) = (3 sqrt(3) / 2)
/// J3 / J2^(3/2), theta in [0, pi / 3], plus the mean.
inline double largest_principal(const SymTensor& a) {
  const SymTensor s = a.deviator();
  const double j2 = 0.5 * double_dot(s, s);
  if (!(j2 > 0.0)) return a.mean();
  const double j3 = s.xx * (s.yy * s.zz - s.yz * s.yz) - s.xy * (s.xy * s.zz - s.yz * s.xz) +
                    s.xz * (s.xy * s.yz - s.yy * s.xz);
  const double c = std::clamp(1.5 * std::sqrt(3.0) * j3 / (j2 * std::sqrt(j2)), -1.0, 1.0);
  return a.mean() + 2.0 * std::sqrt(j2 / 3.0) * std::cos(std::acos(c) / 3.0);
}

/// Pressure, positive in compression.
constexpr double pressure(const SymTensor& a) {
  return -a.mean();
}

/// Symmetric part of (L + L^T)/2 and skew part (L - L^T)/2 of a velocity gradient.
constexpr SymTensor sym_part(const Mat3& l) {
  return {l.m[0][0],
          l.m[1][1],
          l.m[2][2],
          0.5 * (l.m[1][2] + l.m[2][1]),
          0.5 * (l.m[0][2] + l.m[2][0]),
          0.5 * (l.m[0][1] + l.m[1][0])};
}

/// Jaumann rotation increment  W.s - s.W  (Ma 2005, eqs 2-17, 2-41) for the spin increment
/// W = (L - L^T) dt / 2 with L_ij = dv_i/dx_j; w23, w13, w12 are its components W_23, W_13, W_12.
/// Always inlined: it sits in every point loop, whose size reaches GCC's growth limits; a
/// call per point (each of its six results through memory) cost COLUMN-G's stress pass 15 %.
[[gnu::always_inline]] constexpr SymTensor jaumann_increment(const SymTensor& s, double w23,
                                                             double w13, double w12) {
  /// W = [[0, w12, w13], [-w12, 0, w23], [-w13, -w23, 0]]
  /// (W s - s W) is symmetric; its components:
  SymTensor r;
  r.xx = 2.0 * (w12 * s.xy + w13 * s.xz);
  r.yy = 2.0 * (-w12 * s.xy + w23 * s.yz);
  r.zz = 2.0 * (-w13 * s.xz - w23 * s.yz);
  r.xy = w12 * (s.yy - s.xx) + w13 * s.yz + w23 * s.xz;
  r.xz = w13 * (s.zz - s.xx) + w12 * s.yz - w23 * s.xy;
  r.yz = w23 * (s.zz - s.yy) - w12 * s.xz - w13 * s.xy;
  return r;
}

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::double_dot;
using core::Mat3;
using core::pressure;
using core::SymTensor;
using core::Vec3;
using core::von_mises;
}  // namespace afemp
