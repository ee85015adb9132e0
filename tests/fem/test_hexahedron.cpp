// The one-point (Flanagan-Belytschko 1981) and fully integrated B-bar (Hughes 1980) hexahedra
// against exact kinematics: trilinear volumes, linear completeness, rigid rotation, the patch
// test on a distorted mesh and the power consistency of their nodal forces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_one_point.hpp"
#include "hexahedron_test_support.hpp"

namespace afemp::fem {
namespace {

using test::cube;
using test::distorted_hex;
using test::linear_field;
using test::Patch;

constexpr int kSeeds = 20;  // distorted elements tried by the tests that loop over seeds

double max_abs_difference(const core::Mat3& a, const core::Mat3& b) {
  double d = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) d = std::max(d, std::abs(a.m[i][j] - b.m[i][j]));
  return d;
}

double max_abs(const core::SymTensor& s) {
  return std::max({std::abs(s.xx), std::abs(s.yy), std::abs(s.zz), std::abs(s.yz), std::abs(s.xz),
                   std::abs(s.xy)});
}

double stress_power(const core::SymTensor& s, const core::Mat3& l) {
  return core::double_dot(s, core::sym_part(l));
}

double nodal_power(const HexVectors& f, const HexVectors& v) {
  double p = 0.0;
  for (int a = 0; a < 8; ++a) p += core::dot(f[a], v[a]);
  return p;
}

// Frustum of a square pyramid: bottom square of side s0 at z = 0, top of side s1 at z = height,
// both centred on the z axis; the trilinear map fills it exactly.
HexVectors frustum(double s0, double s1, double height) {
  HexVectors x;
  for (int a = 0; a < 8; ++a) {
    const double side = kHexNatural[a][2] < 0 ? s0 : s1;
    x[a] = {0.5 * side * kHexNatural[a][0], 0.5 * side * kHexNatural[a][1],
            0.5 * height * (1.0 + kHexNatural[a][2])};
  }
  return x;
}

// The skew tensor W with W x = omega x x.
core::Mat3 spin(const core::Vec3& w) {
  core::Mat3 s;
  s.m[0][1] = -w.z;
  s.m[0][2] = w.y;
  s.m[1][0] = w.z;
  s.m[1][2] = -w.x;
  s.m[2][0] = -w.y;
  s.m[2][1] = w.x;
  return s;
}

TEST(OnePointHex, UnitCubeHasUnitVolumeAndCornerBVectors) {
  // Reference: V = 1 and b_a = (1/4) (xi_a, eta_a, zeta_a) (each corner owns a quarter of the
  // three faces it touches), to round-off 1e-15.
  const OnePointHex e = one_point_hex(cube(1.0));
  EXPECT_NEAR(e.volume, 1.0, 1e-15);
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(e.b[a][i], 0.25 * kHexNatural[a][i], 1e-15);
}

TEST(OnePointHex, FrustumVolumeMatchesClosedForm) {
  // Reference: V = H (s0^2 + s0 s1 + s1^2) / 3 for a frustum, a non-parallelepiped trilinear
  // element; relative tolerance 1e-13.
  const double s0 = 2.0, s1 = 0.7, height = 1.3;
  const double exact = height * (s0 * s0 + s0 * s1 + s1 * s1) / 3.0;
  EXPECT_NEAR(one_point_hex(frustum(s0, s1, height)).volume, exact, 1e-13 * exact);
  EXPECT_NEAR(full_hex(frustum(s0, s1, height)).volume, exact, 1e-13 * exact);
}

TEST(OnePointHex, BVectorsAreTheExactIntegralsOfTheShapeFunctionGradients) {
  // Reference: 2x2x2 Gauss integration of det J and of det J grad N_a, exact for trilinear maps
  // (full_hex, an independent computation). Volume and B vectors agree to 1e-12 on 20
  // distorted elements.
  for (int seed = 0; seed < kSeeds; ++seed) {
    const HexVectors x = distorted_hex(seed);
    const OnePointHex e = one_point_hex(x);
    const FullHex gauss = full_hex(x);
    EXPECT_NEAR(e.volume, gauss.volume, 1e-12 * gauss.volume) << "seed " << seed;
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(e.b[a][i], gauss.volume * gauss.mean_grad[a][i], 1e-12) << "seed " << seed;
  }
}

TEST(OnePointHex, BVectorsSumToZeroAndReproduceTheIdentity) {
  // Reference: sum_a b_a = integral of grad(sum N_a) = 0 (to 1e-14 of |b|), and linear
  // completeness sum_a b_a (x) x_a = V I (to 1e-12), on 20 distorted elements.
  for (int seed = 0; seed < kSeeds; ++seed) {
    const HexVectors x = distorted_hex(seed);
    const OnePointHex e = one_point_hex(x);
    core::Vec3 sum;
    double largest = 0.0;
    core::Mat3 bx;
    for (int a = 0; a < 8; ++a) {
      sum += e.b[a];
      largest = std::max(largest, core::norm(e.b[a]));
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) bx.m[i][j] += e.b[a][i] * x[a][j];
    }
    EXPECT_LT(core::norm(sum), 1e-14 * largest) << "seed " << seed;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(bx.m[i][j], i == j ? e.volume : 0.0, 1e-12) << "seed " << seed;
  }
}

TEST(OnePointHex, ElementFarFromTheOriginKeepsItsGeometry) {
  // Reference: a translation changes neither V nor b. At 1e4 edges from the origin the
  // coordinates themselves carry 2e-12 round-off; volume and B vectors agree to 1e-10.
  const HexVectors x = distorted_hex(7);
  HexVectors far = x;
  for (core::Vec3& p : far) p += core::Vec3{1e4, -2e4, 3e4};
  const OnePointHex e = one_point_hex(x), f = one_point_hex(far);
  EXPECT_NEAR(f.volume, e.volume, 1e-10 * e.volume);
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(f.b[a][i], e.b[a][i], 1e-10);
}

TEST(OnePointHex, LinearVelocityFieldGivesItsGradientOnADistortedElement) {
  // Reference: v = A x + c has L = A exactly (FB's mean gradient reproduces linear fields);
  // tolerance 1e-12 with |A_ij| <= 1, on 20 distorted elements.
  std::mt19937 rng(11);
  for (int seed = 0; seed < kSeeds; ++seed) {
    const HexVectors x = distorted_hex(seed);
    const core::Mat3 a = test::random_mat(rng);
    const HexVectors v = linear_field(x, a, test::random_vec(rng));
    EXPECT_LT(max_abs_difference(velocity_gradient(one_point_hex(x), v), a), 1e-12)
        << "seed " << seed;
  }
}

TEST(OnePointHex, RigidRotationGivesNoStrainRate) {
  // Reference: v = omega x x + c has D = 0 and L = W (the spin); D below 1e-14 |omega|.
  const HexVectors x = distorted_hex(3);
  const core::Vec3 omega{0.7, -1.3, 2.1};
  const core::Mat3 w = spin(omega);
  const core::Mat3 l = velocity_gradient(one_point_hex(x), linear_field(x, w, {0.4, 0.5, -0.6}));
  const core::SymTensor d = core::sym_part(l);
  EXPECT_LT(max_abs(d), 1e-14 * core::norm(omega));
  EXPECT_LT(max_abs_difference(l, w), 1e-14 * core::norm(omega));
}

TEST(OnePointHex, PatchTestWithUniformStress) {
  // VALIDATION W4. Reference: a uniform stress is in equilibrium, so the assembled force on the
  // interior node of a 2x2x2 patch with that node moved vanishes, and each boundary node's force
  // balances the traction integral of N_a sigma.n over the patch surface; both to 1e-12 of
  // |sigma| h^2.
  const Patch patch(0.5, 42);
  const core::SymTensor sigma{100.0, -50.0, 30.0, 20.0, -10.0, 40.0};
  std::array<core::Vec3, 27> force{};
  for (int el = 0; el < 8; ++el) {
    const HexVectors x = patch.element_nodes(el);
    HexVectors f{};
    add_stress_forces(one_point_hex(x), sigma, f);
    for (int a = 0; a < 8; ++a) force[patch.elements[el][a]] += f[a];
  }
  const double scale = max_abs(sigma) * patch.h * patch.h;
  EXPECT_LT(core::norm(force[13]), 1e-12 * scale);
  for (int n = 0; n < 27; ++n)
    EXPECT_LT(core::norm(force[n] + patch.traction_integral(n, sigma)), 1e-12 * scale)
        << "node " << n;
}

TEST(OnePointHex, StressPowerEqualsVolumeTimesStressDotStrainRate) {
  // Reference: for a linear field, -sum_a f_a . v_a = V sigma : D; relative tolerance 1e-12.
  std::mt19937 rng(5);
  for (int seed = 0; seed < kSeeds; ++seed) {
    const HexVectors x = distorted_hex(seed);
    const OnePointHex e = one_point_hex(x);
    const core::Mat3 a = test::random_mat(rng);
    const HexVectors v = linear_field(x, a, test::random_vec(rng));
    const core::SymTensor sigma = test::random_stress(rng, 1e3);
    HexVectors f{};
    add_stress_forces(e, sigma, f);
    const double expected = e.volume * stress_power(sigma, a);
    EXPECT_NEAR(-nodal_power(f, v), expected, 1e-12 * 1e3 * e.volume * 9.0) << "seed " << seed;
  }
}

TEST(CharacteristicLength, BoxGivesItsShortestEdge) {
  // Reference: V / largest face = a b c / (b c) = a for a box with a the shortest edge; 1e-14.
  HexVectors x = cube(1.0);
  for (core::Vec3& p : x) p = {2.0 * p.x, 0.5 * p.y, 3.0 * p.z};
  EXPECT_NEAR(characteristic_length(x, one_point_hex(x).volume), 0.5, 1e-14);
}

TEST(CharacteristicLength, WarpedFaceCountsAtLeastItsTrueArea) {
  // Reference: a 1 x 1 x 0.25 plate with two opposite top corners raised by 0.1 has a warped
  // top face of true (bilinear patch) area 1.00333 (midpoint quadrature here), vector area 1.
  // The length is conservative against the true area, V / L >= A, and within 1 % of V / A.
  HexVectors x = cube(1.0);
  for (core::Vec3& p : x) p.z *= 0.25;
  x[4].z += 0.1;
  x[6].z += 0.1;
  const core::Vec3 &p0 = x[4], &p1 = x[5], &p2 = x[6], &p3 = x[7];
  const int n = 200;
  double area = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double s = -1.0 + (2.0 * i + 1.0) / n, t = -1.0 + (2.0 * j + 1.0) / n;
      const core::Vec3 xs = 0.25 * ((1 - t) * (p1 - p0) + (1 + t) * (p2 - p3));
      const core::Vec3 xt = 0.25 * ((1 - s) * (p3 - p0) + (1 + s) * (p2 - p1));
      area += core::norm(core::cross(xs, xt)) * (4.0 / (n * n));
    }
  EXPECT_NEAR(area, 1.00333, 1e-5);
  const double volume = one_point_hex(x).volume;
  const double length = characteristic_length(x, volume);
  EXPECT_LE(length, volume / area);
  EXPECT_GT(length, 0.99 * volume / area);
}

TEST(FullHex, WeightsSumToTheVolumeOfAParallelepiped) {
  // Reference: V = det[e1 e2 e3] for the parallelepiped on edges e1, e2, e3, and det J = V / 8
  // at every point; relative tolerance 1e-14.
  const core::Vec3 e1{1.2, 0.1, -0.2}, e2{0.3, 0.9, 0.1}, e3{-0.2, 0.25, 1.1};
  HexVectors x;
  for (int a = 0; a < 8; ++a) {
    const double s = 0.5 * (1 + kHexNatural[a][0]), t = 0.5 * (1 + kHexNatural[a][1]),
                 u = 0.5 * (1 + kHexNatural[a][2]);
    x[a] = core::Vec3{5.0, -3.0, 2.0} + s * e1 + t * e2 + u * e3;
  }
  const double exact = core::dot(e1, core::cross(e2, e3));
  const FullHex e = full_hex(x);
  EXPECT_NEAR(e.volume, exact, 1e-14 * exact);
  for (double w : e.weight) EXPECT_NEAR(w, exact / 8.0, 1e-14 * exact);
  EXPECT_NEAR(min_jacobian(e), exact / 8.0, 1e-14 * exact);
}

TEST(FullHex, TangledElementHasANegativeJacobian) {
  // Reference: pushing node 6 through the opposite corner inverts the map near node 6: det J < 0
  // at Gauss point 6, which is what the caller checks (min_jacobian > 0 for the cube).
  HexVectors x = cube(1.0);
  EXPECT_GT(min_jacobian(full_hex(x)), 0.0);
  x[6] = {-0.5, -0.5, -0.5};
  const FullHex e = full_hex(x);
  EXPECT_LT(e.weight[6], 0.0);
  EXPECT_LT(min_jacobian(e), 0.0);
}

TEST(FullHex, LinearFieldAndRigidRotationAreExactAtEveryPoint) {
  // Reference: v = A x + c gives L_bar = A at all 8 points (1e-12, |A_ij| <= 1); a rigid
  // rotation gives D = 0 there (1e-14 |omega|). 20 distorted elements.
  std::mt19937 rng(17);
  for (int seed = 0; seed < kSeeds; ++seed) {
    const HexVectors x = distorted_hex(seed);
    const FullHex e = full_hex(x);
    const core::Mat3 a = test::random_mat(rng);
    const HexVectors v = linear_field(x, a, test::random_vec(rng));
    const core::Vec3 omega = test::random_vec(rng);
    const HexVectors rotation = linear_field(x, spin(omega), test::random_vec(rng));
    for (int g = 0; g < 8; ++g) {
      EXPECT_LT(max_abs_difference(velocity_gradient_bbar(e, g, v), a), 1e-12) << "seed " << seed;
      EXPECT_LT(max_abs(core::sym_part(velocity_gradient_bbar(e, g, rotation))),
                1e-14 * core::norm(omega))
          << "seed " << seed;
    }
  }
}

TEST(FullHex, PureDilatationIsReproducedExactly) {
  // Reference: v = alpha x + c gives L_bar = alpha I at every point; 1e-13 of alpha.
  const HexVectors x = distorted_hex(9);
  const FullHex e = full_hex(x);
  const double alpha = -0.35;
  core::Mat3 a;
  for (int i = 0; i < 3; ++i) a.m[i][i] = alpha;
  const HexVectors v = linear_field(x, a, {1.0, 2.0, 3.0});
  for (int g = 0; g < 8; ++g)
    EXPECT_LT(max_abs_difference(velocity_gradient_bbar(e, g, v), a), 1e-13 * std::abs(alpha));
}

TEST(FullHex, BbarForcesArePowerConsistentWithTheBbarGradient) {
  // Reference: sum_g w_g sigma_g : sym(L_bar_g) = -sum_a f_a . v_a for any nodal velocities and
  // any Gauss-point stresses (the forces are the transpose of the B-bar operator); relative
  // tolerance 1e-12 with random stresses and random, non-linear, velocities.
  std::mt19937 rng(23);
  for (int seed = 0; seed < kSeeds; ++seed) {
    const HexVectors x = distorted_hex(seed);
    const FullHex e = full_hex(x);
    HexVectors v;
    for (core::Vec3& va : v) va = test::random_vec(rng);
    std::array<core::SymTensor, 8> sigma;
    for (core::SymTensor& s : sigma) s = test::random_stress(rng, 1e3);
    double power = 0.0, magnitude = 0.0;
    for (int g = 0; g < 8; ++g) {
      const double p = e.weight[g] * stress_power(sigma[g], velocity_gradient_bbar(e, g, v));
      power += p;
      magnitude += std::abs(p);
    }
    HexVectors f{};
    add_stress_forces_bbar(e, sigma, f);
    EXPECT_NEAR(-nodal_power(f, v), power, 1e-12 * magnitude) << "seed " << seed;
  }
}

TEST(FullHex, PatchTestWithUniformStress) {
  // VALIDATION W4 for the B-bar element. Reference as for the one-point element: zero force on
  // the moved interior node and traction-integral forces on the boundary, to 1e-12 |sigma| h^2.
  const Patch patch(0.5, 42);
  const core::SymTensor sigma{100.0, -50.0, 30.0, 20.0, -10.0, 40.0};
  std::array<core::SymTensor, 8> uniform;
  uniform.fill(sigma);
  std::array<core::Vec3, 27> force{};
  for (int el = 0; el < 8; ++el) {
    HexVectors f{};
    add_stress_forces_bbar(full_hex(patch.element_nodes(el)), uniform, f);
    for (int a = 0; a < 8; ++a) force[patch.elements[el][a]] += f[a];
  }
  const double scale = max_abs(sigma) * patch.h * patch.h;
  EXPECT_LT(core::norm(force[13]), 1e-12 * scale);
  for (int n = 0; n < 27; ++n)
    EXPECT_LT(core::norm(force[n] + patch.traction_integral(n, sigma)), 1e-12 * scale)
        << "node " << n;
}

TEST(FullHex, DilatationIsUniformOverTheElement) {
  // Reference: what keeps a nearly incompressible material from locking is that B-bar imposes
  // one volume constraint per element: tr L_bar is the same at all 8 points (to 1e-14 of the
  // velocity gradient) and equals the element's mean dilatation (1/V) integral div v, while
  // the deviatoric part of L is the point's own. Tested with the bending field
  // v_x = (x - 1/2)(y - 1/2) on a distorted element, whose plain tr L varies by O(1).
  const HexVectors x = distorted_hex(13);
  const FullHex e = full_hex(x);
  HexVectors v{};
  for (int a = 0; a < 8; ++a) v[a].x = (x[a].x - 0.5) * (x[a].y - 0.5);
  double mean = 0.0;
  for (int a = 0; a < 8; ++a) mean += core::dot(v[a], e.mean_grad[a]);
  double plain_min = 1e300, plain_max = -1e300;
  for (int g = 0; g < 8; ++g) {
    const core::Mat3 l = velocity_gradient_bbar(e, g, v);
    EXPECT_NEAR(l.m[0][0] + l.m[1][1] + l.m[2][2], mean, 1e-14);
    double plain = 0.0, dvx_dy = 0.0;
    for (int a = 0; a < 8; ++a) {
      plain += v[a].x * e.grad[g][a].x;
      dvx_dy += v[a].x * e.grad[g][a].y;
    }
    plain_min = std::min(plain_min, plain);
    plain_max = std::max(plain_max, plain);
    EXPECT_NEAR(l.m[0][1], dvx_dy, 1e-15);
  }
  EXPECT_GT(plain_max - plain_min, 0.3);
}

}  // namespace
}  // namespace afemp::fem
