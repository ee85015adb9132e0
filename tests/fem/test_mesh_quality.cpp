// Hexahedron shape measures against hand-computed values: the Verdict scaled Jacobian (Knupp,
// SAND2007-2853), edge aspect ratio, the time-step length V / A_max, and the exact volume of a
// trilinear element checked by the divergence theorem.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <utility>

#include "fem/mesh_generation.hpp"
#include "fem/mesh_quality.hpp"

namespace afemp::fem {
namespace {

using core::Vec3;

// An a x b x c box with node 0 at the origin, in kHexNatural order.
std::array<Vec3, 8> brick(double a, double b, double c) {
  std::array<Vec3, 8> x;
  for (int n = 0; n < 8; ++n)
    x[n] = {a * (1 + kHexNatural[n][0]) / 2, b * (1 + kHexNatural[n][1]) / 2,
            c * (1 + kHexNatural[n][2]) / 2};
  return x;
}

// V = 1/3 sum over faces of the integral of x . (x_u x x_v) du dv, each face bilinear in (u, v)
// with its corners counter-clockwise seen from outside. The integrand has degree 2 in u and in v,
// so 2x2 Gauss points integrate it exactly.
double divergence_theorem_volume(const std::array<Vec3, 8>& x) {
  constexpr int kOutwardFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  double flux = 0.0;
  for (const auto& f : kOutwardFaces) {
    const Vec3 &c0 = x[f[0]], &c1 = x[f[1]], &c2 = x[f[2]], &c3 = x[f[3]];
    for (double u : g)
      for (double v : g) {
        const Vec3 p = (1 - u) * (1 - v) * c0 + u * (1 - v) * c1 + u * v * c2 + (1 - u) * v * c3;
        const Vec3 du = (1 - v) * (c1 - c0) + v * (c2 - c3);
        const Vec3 dv = (1 - u) * (c3 - c0) + u * (c2 - c1);
        flux += 0.25 * core::dot(p, core::cross(du, dv));  // weight 1/4 on the unit square
      }
  }
  return flux / 3.0;
}

TEST(HexahedronQuality, UnitCubeIsIdeal) {
  // Reference: a unit cube has orthonormal corner edges (scaled Jacobian 1), equal edges (aspect
  // 1), V = 1 and face area 1 (length 1). Tolerance 1e-14 (roundoff of a few products).
  const ElementQuality q = hexahedron_quality(brick(1, 1, 1));
  EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-14);
  EXPECT_NEAR(q.aspect_ratio, 1.0, 1e-14);
  EXPECT_NEAR(q.characteristic_length, 1.0, 1e-14);
  EXPECT_NEAR(q.volume, 1.0, 1e-14);
}

TEST(HexahedronQuality, StretchedBoxHasAspectFourAndLengthVolumeOverLargestFace) {
  // Reference: 1 x 1 x 4: edges 4 / 1, V = 4, largest face 1 x 4 = 4, so L = 4 / 4 = 1; still a
  // right-angled box (scaled Jacobian 1). Tolerance 1e-14.
  const ElementQuality q = hexahedron_quality(brick(1, 1, 4));
  EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-14);
  EXPECT_NEAR(q.aspect_ratio, 4.0, 1e-14);
  EXPECT_NEAR(q.volume, 4.0, 1e-14);
  EXPECT_NEAR(q.characteristic_length, 1.0, 1e-14);
}

TEST(HexahedronQuality, ShearedElementScaledJacobianIsSineOfShearAngle) {
  // Reference: a parallelepiped with edges (1,0,0), (1,1,0), (0,0,1) has at every corner
  // det = 1 over edge lengths 1 * sqrt 2 * 1: scaled Jacobian sin 45 deg = 1/sqrt 2; V = 1; edges
  // sqrt 2 / 1; largest face (1,1,0) x (0,0,1) of area sqrt 2, so L = 1/sqrt 2. Tolerance 1e-14.
  std::array<Vec3, 8> x = brick(1, 1, 1);
  for (Vec3& p : x) p.x += p.y;
  const ElementQuality q = hexahedron_quality(x);
  EXPECT_NEAR(q.min_scaled_jacobian, 1.0 / std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(q.volume, 1.0, 1e-14);
  EXPECT_NEAR(q.aspect_ratio, std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(q.characteristic_length, 1.0 / std::sqrt(2.0), 1e-14);
}

TEST(HexahedronQuality, RaisedCornerGivesHandComputedJacobianAndWarpedVolume) {
  // Unit cube with node 6 lifted from (1,1,1) to (1,1,2). By hand: corner 6 has edges (1,0,1),
  // (0,1,1), (0,0,2): det 2 over sqrt2 sqrt2 2 = 0.5, the minimum (corners 5 and 7: 1/sqrt 2).
  // The top face is warped, z = 1 + x y, so V = integral of (1 + x y) over the unit square = 5/4.
  // Tolerance 1e-14.
  std::array<Vec3, 8> x = brick(1, 1, 1);
  x[6].z = 2.0;
  const ElementQuality q = hexahedron_quality(x);
  EXPECT_NEAR(q.min_scaled_jacobian, 0.5, 1e-14);
  EXPECT_NEAR(q.volume, 1.25, 1e-14);
  EXPECT_NEAR(divergence_theorem_volume(x), 1.25, 1e-14);
}

TEST(HexahedronQuality, FrustumVolumeMatchesTheIntegralOfItsSectionArea) {
  // A 2 x 2 base tapering to a centred 1 x 1 top at height 1: the section at height z has side
  // 2 - z, V = integral_0^1 (2 - z)^2 dz = 7/3. Tolerance 1e-14.
  std::array<Vec3, 8> x = brick(2, 2, 1);
  for (int a = 4; a < 8; ++a) {
    x[a].x = 0.5 + 0.5 * x[a].x;
    x[a].y = 0.5 + 0.5 * x[a].y;
  }
  EXPECT_NEAR(hexahedron_quality(x).volume, 7.0 / 3.0, 1e-14);
}

TEST(HexahedronQuality, DistortedElementVolumeMatchesDivergenceTheorem) {
  // Every node moved off the box, all faces warped: the 2x2x2 Gauss volume against the surface
  // flux of x / 3 (an independent formula). Tolerance 1e-13 relative.
  const std::array<Vec3, 8> x = {Vec3{0.1, -0.2, 0.05}, Vec3{2.3, 0.1, -0.3}, Vec3{2.0, 1.7, 0.2},
                                 Vec3{-0.3, 1.2, 0.1},  Vec3{0.2, 0.1, 1.4},  Vec3{1.9, -0.2, 1.1},
                                 Vec3{2.4, 1.9, 1.8},   Vec3{0.05, 1.5, 1.2}};
  const ElementQuality q = hexahedron_quality(x);
  ASSERT_GT(q.min_scaled_jacobian, 0.0);
  const double reference = divergence_theorem_volume(x);
  EXPECT_NEAR(q.volume, reference, 1e-13 * reference);
}

TEST(MeshQuality, BoxMeshReportsIdealElementsAndItsVolume) {
  // A 2 x 1 x 1 box in 4 x 2 x 2 cubes of side 0.5: scaled Jacobian 1, aspect 1, length
  // 0.125 / 0.25 = 0.5, volume 2; no lines, so their minimum stays +inf. Tolerance 1e-14.
  const MeshQualityReport r = mesh_quality(box_mesh({{0, 0, 0}, {2, 1, 1}}, {4, 2, 2}));
  EXPECT_EQ(r.hexahedra, 16u);
  EXPECT_EQ(r.inverted, 0u);
  EXPECT_NEAR(r.min_scaled_jacobian, 1.0, 1e-14);
  EXPECT_NEAR(r.max_aspect_ratio, 1.0, 1e-14);
  EXPECT_NEAR(r.min_characteristic_length, 0.5, 1e-14);
  EXPECT_NEAR(r.total_volume, 2.0, 1e-14);
  EXPECT_EQ(r.lines, 0u);
  EXPECT_EQ(r.shortest_line, -1);
  EXPECT_TRUE(std::isinf(r.min_line_length));
}

TEST(MeshQuality, SwappedNodesAreCountedAsInvertedAndNamed) {
  // Swapping nodes 0 and 1 of element 2 turns corners of it inside out (non-positive corner
  // Jacobians); exchanging the bottom and top faces of element 0 mirrors it: scaled Jacobian -1 at
  // every corner and a negative volume. Both are counted; element 0 is the worst.
  MeshData m = box_mesh({{0, 0, 0}, {3, 1, 1}}, {3, 1, 1});
  std::swap(m.hexahedra[2][0], m.hexahedra[2][1]);
  const MeshQualityReport one = mesh_quality(m);
  EXPECT_EQ(one.inverted, 1u);
  EXPECT_EQ(one.worst_jacobian_element, 2);
  EXPECT_LE(one.min_scaled_jacobian, 0.0);
  for (int a = 0; a < 4; ++a) std::swap(m.hexahedra[0][a], m.hexahedra[0][a + 4]);
  const MeshQualityReport two = mesh_quality(m);
  EXPECT_EQ(two.inverted, 2u);
  EXPECT_EQ(two.worst_jacobian_element, 0);
  EXPECT_NEAR(two.min_scaled_jacobian, -1.0, 1e-14);
  std::array<Vec3, 8> x;
  for (int a = 0; a < 8; ++a) x[a] = m.nodes[m.hexahedra[0][a]];
  EXPECT_NEAR(hexahedron_quality(x).volume, -1.0, 1e-14);
}

TEST(MeshQuality, ReportsTheShortestLineAndTheStretchedElement) {
  // A 10-segment truss of length 1 (segments 0.1) next to a mesh whose second element is 1 x 1 x 3:
  // shortest line 0.1 (the first, all equal to roundoff), worst aspect 3 in element 1.
  MeshData m = box_mesh({{0, 0, 0}, {1, 1, 1}}, {1, 1, 1});
  append(m, box_mesh({{2, 0, 0}, {3, 1, 3}}, {1, 1, 1}));
  append(m, truss_line({0, 0, 5}, {1, 0, 5}, 10, 1e-4));
  const MeshQualityReport r = mesh_quality(m);
  EXPECT_EQ(r.lines, 10u);
  EXPECT_NEAR(r.min_line_length, 0.1, 1e-15);
  EXPECT_GE(r.shortest_line, 0);
  EXPECT_EQ(r.worst_aspect_element, 1);
  EXPECT_NEAR(r.max_aspect_ratio, 3.0, 1e-14);
  EXPECT_NEAR(r.total_volume, 4.0, 1e-14);
}

}  // namespace
}  // namespace afemp::fem
