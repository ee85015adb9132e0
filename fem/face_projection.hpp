// Closest-point projection on a bilinear quadrilateral face (mesh contact, fem/mesh_contact.cpp;
// particles at mesh surfaces, coupling/particle_surface_contact.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::fem {

using core::Vec3;

// The bilinear face: position, tangents and shape functions at (xi, eta), nodes counter-
// clockwise seen from outside: (-1,-1), (1,-1), (1,1), (-1,1).
struct FacePoint {
  Vec3 x, t1, t2;
  std::array<double, 4> n;
};

// How far outside [-1, 1] a projection may fall and still hold a point (a node or particle
// sliding over the edge between two faces stays in contact with one of them).
inline constexpr double kEdgeTolerance = 0.02;

// The four corner positions of a face from the node positions x.
inline std::array<Vec3, 4> corners(const std::array<std::int32_t, 4>& face,
                                   const std::vector<Vec3>& x) {
  return {x[static_cast<std::size_t>(face[0])], x[static_cast<std::size_t>(face[1])],
          x[static_cast<std::size_t>(face[2])], x[static_cast<std::size_t>(face[3])]};
}

inline FacePoint face_point(const std::array<Vec3, 4>& p, double xi, double eta) {
  FacePoint f;
  f.n = {0.25 * (1 - xi) * (1 - eta), 0.25 * (1 + xi) * (1 - eta), 0.25 * (1 + xi) * (1 + eta),
         0.25 * (1 - xi) * (1 + eta)};
  f.x = f.n[0] * p[0] + f.n[1] * p[1] + f.n[2] * p[2] + f.n[3] * p[3];
  f.t1 = 0.25 * ((1 - eta) * (p[1] - p[0]) + (1 + eta) * (p[2] - p[3]));
  f.t2 = 0.25 * ((1 - xi) * (p[3] - p[0]) + (1 + xi) * (p[2] - p[1]));
  return f;
}

// Closest-point projection of x on the face (Gauss-Newton from the centre): the point, its
// unit outward normal, (xi, eta) and the signed gap. False when the face is degenerate.
struct Projection {
  FacePoint at;
  Vec3 normal;
  double xi = 0.0, eta = 0.0, gap = 0.0;
};

inline bool project(const std::array<Vec3, 4>& p, const Vec3& x, Projection& out) {
  double xi = 0.0, eta = 0.0;
  FacePoint f = face_point(p, xi, eta);
  for (int it = 0; it < 4; ++it) {
    const Vec3 r = x - f.x;
    const double a11 = core::dot(f.t1, f.t1), a12 = core::dot(f.t1, f.t2),
                 a22 = core::dot(f.t2, f.t2);
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 0.0)) return false;
    const double b1 = core::dot(r, f.t1), b2 = core::dot(r, f.t2);
    const double dxi = (a22 * b1 - a12 * b2) / det, deta = (a11 * b2 - a12 * b1) / det;
    xi += dxi;
    eta += deta;
    // A flat parallelogram maps linearly: the first step is exact.
    const bool converged = std::abs(dxi) + std::abs(deta) < 1e-12;
    // Far outside the face the answer does not matter; keep the iteration bounded.
    xi = std::clamp(xi, -2.0, 2.0);
    eta = std::clamp(eta, -2.0, 2.0);
    f = face_point(p, xi, eta);
    if (converged) break;
  }
  const Vec3 c = core::cross(f.t1, f.t2);
  const double l = core::norm(c);
  if (!(l > 0.0)) return false;
  out.at = f;
  out.normal = (1.0 / l) * c;
  out.xi = xi;
  out.eta = eta;
  out.gap = core::dot(out.normal, x - f.x);
  return true;
}

}  // namespace afemp::fem
