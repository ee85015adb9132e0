// The static solve with J2 plasticity (linear isotropic hardening): the consistent tangent of
// the radial return against finite differences of the update itself, uniaxial stress in a
// block against the bilinear closed form, and Newton's quadratic convergence on a plastic load
// step of the thick cylinder (Simo & Taylor 1985: the consistent tangent keeps it quadratic).
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

core::Material j2_steel(double hardening) {
  core::Material m = test::steel();
  m.strength = core::J2Plasticity{250.0, hardening};  // yield 250 MPa, plastic modulus H
  return m;
}

core::SymTensor from_voigt(const std::array<double, 6>& e) {  // engineering shear strains
  return {e[0], e[1], e[2], 0.5 * e[3], 0.5 * e[4], 0.5 * e[5]};
}

// d sigma / d eps by central differences (step 1e-8 of a strain of about 3e-3) against the
// consistent tangent, from a virgin point and from one already on a hardened yield surface:
// equal to 1e-5 of the largest entry (the differences' truncation and round-off).
TEST(StaticJ2, ConsistentTangentMatchesFiniteDifferences) {
  const core::Material m = j2_steel(2000.0);
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
    EXPECT_LT(error, 1e-5 * scale) << "trial " << trial;
  }
}

// A unit block stretched along x to 5 times the yield strain in 5 load steps, held by
// symmetry planes only (uniaxial stress): sigma_xx = sigma_y + Et (eps - sigma_y / E),
// Et = E H / (E + H), to 1e-9 at every Gauss point, and the lateral stresses zero.
TEST(StaticJ2, UniaxialStressFollowsTheBilinearCurve) {
  const double hardening = 2000.0;
  const core::Material m = j2_steel(hardening);
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {1, 1, 1}}, {2, 2, 2});
  const double e = m.youngs_modulus, yield_strain = 250.0 / e, strain = 5.0 * yield_strain;
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m};
  for (std::int32_t n : test::node_set(mesh, "xmin")) problem.prescribed.push_back({n, 0, 0.0});
  for (std::int32_t n : test::node_set(mesh, "ymin")) problem.prescribed.push_back({n, 1, 0.0});
  for (std::int32_t n : test::node_set(mesh, "zmin")) problem.prescribed.push_back({n, 2, 0.0});
  for (std::int32_t n : test::node_set(mesh, "xmax")) problem.prescribed.push_back({n, 0, strain});
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
      solve_static(test::pressurised_ring(ring, j2_steel(1000.0), 150.0), settings);
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

}  // namespace
}  // namespace afemp::fem
