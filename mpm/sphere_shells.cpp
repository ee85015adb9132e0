// Particles in shells that follow a sphere (mpm/sphere_shells.hpp).
#include "mpm/sphere_shells.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace afemp::mpm {
namespace {

// 4-point Gauss-Legendre on [-1, 1].
constexpr std::array<double, 4> kGaussX = {-0.8611363115940526, -0.3399810435848563,
                                           0.3399810435848563, 0.8611363115940526};
constexpr std::array<double, 4> kGaussW = {0.3478548451374538, 0.6521451548625461,
                                           0.6521451548625461, 0.3478548451374538};

// A cell of the unit sphere: its solid angle and the integral of the unit vector over it.
struct Cell {
  double solid_angle = 0.0;
  Vec3 moment{};
};

// The N x N cells of each of the six cube faces. On the face of axis d and side sgn a point is
// p[d] = sgn, p[d+1] = tan xi, p[d+2] = tan eta (xi, eta in [-pi/4, pi/4]), and
// dOmega = (1 + X^2)(1 + Y^2) / (1 + X^2 + Y^2)^(3/2) dxi deta.
std::vector<Cell> cubed_sphere_cells(int n) {
  std::vector<Cell> cells;
  cells.reserve(static_cast<std::size_t>(6 * n * n));
  const double dxi = 0.5 * std::numbers::pi / n;
  for (int d = 0; d < 3; ++d)
    for (const double sgn : {-1.0, 1.0})
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          Cell c;
          for (std::size_t gi = 0; gi < 4; ++gi) {
            const double X =
                std::tan(-0.25 * std::numbers::pi + (i + 0.5 * (kGaussX[gi] + 1.0)) * dxi);
            for (std::size_t gj = 0; gj < 4; ++gj) {
              const double Y =
                  std::tan(-0.25 * std::numbers::pi + (j + 0.5 * (kGaussX[gj] + 1.0)) * dxi);
              const double r2 = 1.0 + X * X + Y * Y;
              const double w = kGaussW[gi] * kGaussW[gj] * 0.25 * dxi * dxi * (1.0 + X * X) *
                               (1.0 + Y * Y) / (r2 * std::sqrt(r2));
              Vec3 p;
              p[d] = sgn;
              p[(d + 1) % 3] = X;
              p[(d + 2) % 3] = Y;
              c.solid_angle += w;
              c.moment += (w / std::sqrt(r2)) * p;
            }
          }
          cells.push_back(c);
        }
  return cells;
}

}  // namespace

std::vector<ShellParticle> sphere_shell_particles(const SphereShape& sphere, double s) {
  const double R = sphere.radius;
  const int shells = std::max(1, static_cast<int>(std::lround(R / s)));
  const double t = R / shells;
  std::vector<ShellParticle> out;
  for (int k = 0; k < shells; ++k) {
    const double ri = k * t, ro = (k + 1) * t, mid = 0.5 * (ri + ro);
    const int n = std::max(2, 2 * static_cast<int>(std::lround(0.25 * std::numbers::pi * mid / s)));
    const double r3 = ro * ro * ro - ri * ri * ri;
    // The centroid of a cell is at (3/4) (ro^4 - ri^4) / (ro^3 - ri^3) along moment / Omega.
    const double radius = 0.75 * (ro * ro * ro * ro - ri * ri * ri * ri) / r3;
    for (const Cell& c : cubed_sphere_cells(n))
      out.push_back(
          {sphere.centre + (radius / c.solid_angle) * c.moment, c.solid_angle * r3 / 3.0});
  }
  return out;
}

}  // namespace afemp::mpm
