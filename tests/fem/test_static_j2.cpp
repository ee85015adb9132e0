// The static solve with J2 plasticity (linear isotropic hardening): the consistent tangent of
// the radial return against finite differences of the update itself, uniaxial stress in a
// block against the bilinear closed form, and Newton's quadratic convergence on a plastic load
// step of the thick cylinder (Simo & Taylor 1985: the consistent tangent keeps it quadratic),
// and the perfectly plastic thick cylinder against Hill's elastic-plastic closed form. The
// Johnson-Cook tangent (rate and temperature frozen) likewise: against finite differences and
// in uniaxial stress against its own curve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

#include "core/materials/small_strain_tangent.hpp"
#include "hexahedron_test_support.hpp"
#include "static_test_support.hpp"

namespace afemp::fem {
namespace {

core::SymTensor from_voigt(const std::array<double, 6>& e) {  // engineering shear strains
  return {e[0], e[1], e[2], 0.5 * e[3], 0.5 * e[4], 0.5 * e[5]};
}

// d sigma / d eps by central differences (step 1e-8 of a strain of about 3e-3) against the
// consistent tangent, from a virgin point and from one already on a hardened yield surface:
// equal to 1e-5 of the largest entry (the differences' truncation and round-off).
void expect_tangent_matches_differences(const core::Material& m) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 4; ++trial) {
    // Loading along a random direction, from a virgin point or from one that an earlier
    // plastic update along the same direction left on a hardened yield surface.
    const core::SymTensor direction = test::random_stress(rng, 1.0);
    core::SmallStrainPoint from;
    if (trial % 2 == 1) {
      const core::SymTensor pre = 2e-3 * direction;
      const core::SmallStrainResult r = core::small_strain_update(m, {}, pre);
      from = {pre, r.stress.deviator(), r.plastic_strain};
    }
    const core::SymTensor load = 3e-3 * direction + 3e-4 * test::random_stress(rng, 1.0);
    const std::array<double, 6> e = {load.xx,       load.yy,       load.zz,
                                     2.0 * load.yz, 2.0 * load.xz, 2.0 * load.xy};
    const core::SmallStrainResult at = core::small_strain_update(m, from, from_voigt(e));
    ASSERT_GT(at.plastic_strain, from.plastic_strain) << "trial " << trial << " is elastic";
    double scale = 0.0, error = 0.0;
    for (int j = 0; j < 6; ++j) {
      const double step = 1e-8;
      std::array<double, 6> plus = e, minus = e;
      plus[j] += step;
      minus[j] -= step;
      const core::SymTensor sp = core::small_strain_update(m, from, from_voigt(plus)).stress;
      const core::SymTensor sm = core::small_strain_update(m, from, from_voigt(minus)).stress;
      const double fd[6] = {sp.xx - sm.xx, sp.yy - sm.yy, sp.zz - sm.zz,
                            sp.yz - sm.yz, sp.xz - sm.xz, sp.xy - sm.xy};
      for (int i = 0; i < 6; ++i) {
        scale = std::max(scale, std::abs(at.tangent[i][j]));
        error = std::max(error, std::abs(fd[i] / (2.0 * step) - at.tangent[i][j]));
      }
    }
    std::printf("tangent of '%s', trial %d: largest difference %.2e of the largest entry\n",
                m.name.c_str(), trial, error / scale);
    EXPECT_LT(error, 1e-5 * scale) << "trial " << trial;
  }
}

// A block on symmetry planes x, y, z = 0, its face x = 1 moved to `strain` (uniaxial stress).
void hold_uniaxial(const MeshData& mesh, double strain, StaticProblem& problem) {
  for (std::int32_t n : test::node_set(mesh, "xmin")) problem.prescribed.push_back({n, 0, 0.0});
  for (std::int32_t n : test::node_set(mesh, "ymin")) problem.prescribed.push_back({n, 1, 0.0});
  for (std::int32_t n : test::node_set(mesh, "zmin")) problem.prescribed.push_back({n, 2, 0.0});
  for (std::int32_t n : test::node_set(mesh, "xmax")) problem.prescribed.push_back({n, 0, strain});
}

TEST(StaticJ2, ConsistentTangentMatchesFiniteDifferences) {
  expect_tangent_matches_differences(test::j2_steel(2000.0));
}

// The same for Johnson-Cook, whose H = d sigma_y / d eps_p = B n eps_p^(n-1) (1 - T*^m) varies
// along the increment: the tangent takes it at the increment's end, as its return does.
TEST(StaticJohnsonCook, ConsistentTangentMatchesFiniteDifferences) {
  expect_tangent_matches_differences(test::jc_steel());
}

// The block of UniaxialStressFollowsTheBilinearCurve in Johnson-Cook steel, stretched to 5 times
// its yield strain in 5 load steps: uniaxial stress, so sigma = (A + B eps_p^n)(1 - T*^m) with
// eps = sigma / E + eps_p (the equivalent plastic strain is the axial one), solved for sigma
// by bisection; every Gauss point's sigma_xx and plastic strain within 1e-9 of it (radial
// return is exact on this proportional path). Each step converges in at most 8 Newton solves.
TEST(StaticJohnsonCook, UniaxialStressFollowsItsCurve) {
  const core::Material m = test::jc_steel();
  const core::JohnsonCook& jc = std::get<core::JohnsonCook>(m.strength);
  const double thermal = 1.0 - std::pow((600.0 - 293.0) / (1800.0 - 293.0), jc.m);
  const double e = m.youngs_modulus, strain = 5.0 * jc.A * thermal / e;
  double lo = 0.0, hi = strain;  // eps_p: E (strain - eps_p) - sigma_y(eps_p) falls with it
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (e * (strain - mid) > (jc.A + jc.B * std::pow(mid, jc.n)) * thermal ? lo : hi) = mid;
  }
  const double plastic = 0.5 * (lo + hi), expected = e * (strain - plastic);
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {1, 1, 1}}, {2, 2, 2});
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m};
  hold_uniaxial(mesh, strain, problem);
  NewtonSettings settings;
  settings.load_steps = 5;
  const StaticResult r = solve_static(problem, settings);
  double axial = 0.0, eps_p = 0.0;
  for (std::size_t el = 0; el < r.stress.size(); ++el)
    for (int g = 0; g < 8; ++g) {
      axial = std::max(axial, std::abs(r.stress[el][g].xx / expected - 1.0));
      eps_p = std::max(eps_p, std::abs(r.plastic_strain[el][g] / plastic - 1.0));
    }
  int solves = 0;
  for (const NewtonIteration& it : r.iterations) solves = std::max(solves, it.iteration);
  std::printf(
      "uniaxial Johnson-Cook: sigma_xx %.6g (error %.2e), eps_p %.6g (error %.2e), at most %d "
      "Newton solves a step\n",
      expected, axial, plastic, eps_p, solves);
  EXPECT_LT(axial, 1e-9);
  EXPECT_LT(eps_p, 1e-9);
  EXPECT_LE(solves, 8);
}

// A unit block stretched along x to 5 times the yield strain in 5 load steps, held by
// symmetry planes only (uniaxial stress): sigma_xx = sigma_y + Et (eps - sigma_y / E),
// Et = E H / (E + H), to 1e-9 at every Gauss point, and the lateral stresses zero.
TEST(StaticJ2, UniaxialStressFollowsTheBilinearCurve) {
  const double hardening = 2000.0;
  const core::Material m = test::j2_steel(hardening);
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {1, 1, 1}}, {2, 2, 2});
  const double e = m.youngs_modulus, yield_strain = 250.0 / e, strain = 5.0 * yield_strain;
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m};
  hold_uniaxial(mesh, strain, problem);
  NewtonSettings settings;
  settings.load_steps = 5;
  const StaticResult r = solve_static(problem, settings);
  const double expected = 250.0 + e * hardening / (e + hardening) * (strain - yield_strain);
  double axial = 0.0, lateral = 0.0;
  for (const auto& element : r.stress)
    for (const core::SymTensor& s : element) {
      axial = std::max(axial, std::abs(s.xx / expected - 1.0));
      lateral = std::max({lateral, std::abs(s.yy), std::abs(s.zz), std::abs(s.xy)});
    }
  std::printf("uniaxial J2: sigma_xx error %.2e (relative), lateral %.2e MPa\n", axial, lateral);
  EXPECT_LT(axial, 1e-9);
  EXPECT_LT(lateral, 1e-9 * expected);
}

// The thick cylinder (a = 1, b = 2, plane strain) of J2 steel loaded to p = 75 (elastic; first
// yield at about 108) and then to 150, which spreads the plastic zone into the wall. On the
// plastic step the relative residual falls below 1e-10 within 8 iterations and, once below
// 1e-2, quadratically: rho_{k+1} <= 10 rho_k^2.
TEST(StaticJ2, NewtonConvergesQuadraticallyOnAPlasticStep) {
  const MeshData ring = test::quarter_ring(1.0, 2.0, 0.1, 8, 16);
  std::ostringstream log;
  NewtonSettings settings;
  settings.load_steps = 2;
  settings.log = &log;
  const StaticResult r =
      solve_static(test::pressurised_ring(ring, test::j2_steel(1000.0), 150.0), settings);
  std::printf("%s", log.str().c_str());
  double plastic = 0.0;
  for (const auto& element : r.plastic_strain)
    for (double p : element) plastic = std::max(plastic, p);
  EXPECT_GT(plastic, 0.0);
  std::vector<double> rho;  // relative residuals of load step 2
  for (const NewtonIteration& it : r.iterations)
    if (it.load_step == 2) rho.push_back(it.residual / it.reference);
  ASSERT_GE(rho.size(), 3u);
  EXPECT_LE(rho.size(), 9u);  // 8 solves and the final check
  EXPECT_LT(rho.back(), 1e-10);
  for (std::size_t k = 0; k + 1 < rho.size(); ++k) {
    if (rho[k] < 1e-2 && rho[k + 1] > 1e-14) {  // below 1e-14: round-off, not convergence
      EXPECT_LT(rho[k + 1], 10.0 * rho[k] * rho[k]) << "iteration " << k;
    }
  }
}

// The thick cylinder a = 1, b = 2 (plane strain) of perfectly plastic von Mises steel under an
// internal pressure between first yield, k (1 - a^2 / b^2) = 108, and the limit 2 k ln(b / a) =
// 200, k = sigma_y / sqrt 3. Hill (1950, The Mathematical Theory of Plasticity, ch. V, sec. 2,
// incompressible plane strain, where the von Mises and Tresca conditions coincide as
// sigma_theta - sigma_r = 2 k): the plastic zone a <= r <= c carries
// sigma_r = -p + 2 k ln(r / a), the elastic zone sigma_r = -k (c^2 / b^2) (b^2 / r^2 - 1), and
// p = k (2 ln(c / a) + 1 - c^2 / b^2). The closed form needs nu = 1/2; nu = 0.499 here (B-bar
// does not lock), whose sigma_z departs from the mean stress by (1 - 2 nu) of it in the elastic
// zone, a 1e-6 change of the yield condition. The pressure of c = 1.5 (180) in 10 load steps
// on 40 x 16 elements: c, where the plastic strain (the mean of the Gauss points of each radial
// layer of elements, at the layer's mean centroid radius) falls to zero, extrapolated linearly
// from the last two plastic layers (the plastic strain grows as c - r near c), within 2 %
// (the layers' inner and outer Gauss points are too close, as B-bar shares the dilatation,
// to extrapolate from); the radial stress of the elements (the mean of their
// Gauss points, at their centroids) within 2 % of the closed form in the plastic zone (the
// elements more than an element from c), and within 2 % of p in the elastic zone (where it
// falls to 0 at b).
TEST(StaticJ2, PerfectlyPlasticThickCylinderMatchesHill) {
  const double a = 1.0, b = 2.0, sigma_y = 250.0, c = 1.5;
  const int n_r = 40;
  const double k = sigma_y / std::sqrt(3.0);
  const double p = k * (2.0 * std::log(c / a) + 1.0 - c * c / (b * b));
  core::Material m = test::steel();
  m.poisson_ratio = 0.499;
  m.strength = core::J2Plasticity{sigma_y, 0.0};
  const MeshData ring = test::quarter_ring(a, b, 0.1, n_r, 16);
  NewtonSettings settings;
  settings.load_steps = 10;
  const StaticResult r = solve_static(test::pressurised_ring(ring, m, p), settings);

  const double h = (b - a) / n_r;
  std::vector<double> layer_r(n_r, 0.0), layer_plastic(n_r, 0.0);
  std::vector<int> layer_elements(n_r, 0);
  double plastic_error = 0.0, elastic_error = 0.0;
  for (std::size_t e = 0; e < ring.hexahedra.size(); ++e) {
    core::Vec3 centroid;
    core::SymTensor mean;
    for (int g = 0; g < 8; ++g) {
      centroid += 0.125 * test::gauss_point(ring, e, g);
      mean += 0.125 * r.stress[e][g];
    }
    const double rc = std::hypot(centroid.x, centroid.y);
    const int layer = static_cast<int>((rc - a) / h);
    layer_r[layer] += rc;
    for (int g = 0; g < 8; ++g) layer_plastic[layer] += 0.125 * r.plastic_strain[e][g];
    ++layer_elements[layer];
    const double sr = test::polar(mean, centroid).radial;
    if (rc < c - h)
      plastic_error =
          std::max(plastic_error, std::abs(sr / (-p + 2.0 * k * std::log(rc / a)) - 1.0));
    else if (rc > c + h)
      elastic_error = std::max(elastic_error,
                               std::abs(sr + k * c * c / (b * b) * (b * b / (rc * rc) - 1.0)) / p);
  }
  for (int i = 0; i < n_r; ++i) {
    layer_r[i] /= layer_elements[i];
    layer_plastic[i] /= layer_elements[i];
  }
  int first_elastic = 0;
  while (first_elastic < n_r && layer_plastic[first_elastic] > 0.0) ++first_elastic;
  ASSERT_GE(first_elastic, 2);
  ASSERT_LT(first_elastic, n_r);
  const int i = first_elastic - 1;
  const double slope = (layer_plastic[i] - layer_plastic[i - 1]) / (layer_r[i] - layer_r[i - 1]);
  const double c_fe = layer_r[i] - layer_plastic[i] / slope;
  std::printf(
      "Hill cylinder: p = %.2f, c = %.4f (exact %.4f, error %+.2f %%), the last plastic layer "
      "at r = %.4f, the first elastic at %.4f; radial stress largest error %.2f %% (plastic zone), "
      "%.2f %% of p (elastic zone)\n",
      p, c_fe, c, 100.0 * (c_fe / c - 1.0), layer_r[i], layer_r[first_elastic],
      100.0 * plastic_error, 100.0 * elastic_error);
  EXPECT_LT(std::abs(c_fe / c - 1.0), 0.02);
  EXPECT_LT(plastic_error, 0.02);
  EXPECT_LT(elastic_error, 0.02);
}

}  // namespace
}  // namespace afemp::fem
