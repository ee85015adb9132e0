// The static solve of elastic hexahedra (fem/static_solve.hpp) against exact solutions: the
// B-bar stiffness as the derivative of the nodal forces, the patch test on a distorted mesh,
// a cantilever's tip deflection (Timoshenko beam), the thick cylinder under internal pressure
// (Lame), trusses in parallel with hexahedra, and the refusals: an unheld body, a material
// without a tangent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>

#include "fem/hexahedron_stiffness.hpp"
#include "fem/sparse_cholesky.hpp"
#include "hexahedron_test_support.hpp"
#include "static_test_support.hpp"

namespace afemp::fem {
namespace {

using test::steel;

core::SymTensor hooke(const core::Material& m, const core::SymTensor& eps) {
  const double g = m.shear_modulus(), lambda = m.bulk_modulus() - 2.0 * g / 3.0;
  return (lambda * eps.trace()) * core::SymTensor::identity() + (2.0 * g) * eps;
}

double max_abs(const core::SymTensor& s) {
  return std::max({std::abs(s.xx), std::abs(s.yy), std::abs(s.zz), std::abs(s.yz), std::abs(s.xz),
                   std::abs(s.xy)});
}

std::array<core::VoigtMatrix, 8> elastic_tangents(const core::Material& m) {
  const core::VoigtMatrix d = core::small_strain_update(m, {}, {}).tangent;
  std::array<core::VoigtMatrix, 8> out;
  out.fill(d);
  return out;
}

// K u = f_int(u) for the elastic stress of the B-bar strain, to round-off, on distorted
// elements; K is symmetric with exactly the six rigid-body modes as its null space.
TEST(StaticStiffness, BbarStiffnessIsTheDerivativeOfTheNodalForces) {
  const core::Material m = steel();
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    const HexVectors x = test::distorted_hex(seed);
    const FullHex e = full_hex(x);
    HexMatrix k;
    hexahedron_stiffness_bbar(e, elastic_tangents(m), k);
    std::mt19937 rng(seed + 100);
    HexVectors u;
    for (core::Vec3& ua : u) ua = 1e-3 * test::random_vec(rng);
    std::array<core::SymTensor, 8> sigma;
    for (int g = 0; g < 8; ++g) sigma[g] = hooke(m, strain_bbar(e, g, u));
    HexVectors f{};
    add_stress_forces_bbar(e, sigma, f);  // -f_int
    double scale = 0.0, error = 0.0, asymmetry = 0.0;
    for (int p = 0; p < 24; ++p) {
      double ku = 0.0;
      for (int q = 0; q < 24; ++q) {
        ku += k[24 * p + q] * u[q / 3][q % 3];
        asymmetry = std::max(asymmetry, std::abs(k[24 * p + q] - k[24 * q + p]));
        scale = std::max(scale, std::abs(k[24 * p + q]));
      }
      error = std::max(error, std::abs(ku + f[p / 3][p % 3]));
    }
    EXPECT_LT(asymmetry, 1e-12 * scale) << "seed " << seed;
    EXPECT_LT(error, 1e-12 * scale * 1e-3) << "seed " << seed;
    // The six rigid-body modes (translations; rotations about the axes through the origin)
    // give no force, and K + scale sum phi phi^T is positive definite: they are its whole null
    // space (full integration, no hourglass modes).
    std::array<std::array<double, 24>, 6> modes{};
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d) {
        modes[d][3 * a + d] = 1.0;
        core::Vec3 axis;
        axis[d] = 1.0;
        const core::Vec3 rotation = core::cross(axis, x[a]);
        for (int i = 0; i < 3; ++i) modes[3 + d][3 * a + i] = rotation[i];
      }
    SymmetricCsc penalised;
    penalised.size = 24;
    penalised.column_start.push_back(0);
    for (int q = 0; q < 24; ++q) {
      for (int p = 0; p <= q; ++p) {
        double v = k[24 * p + q];
        for (const auto& phi : modes) v += scale * phi[p] * phi[q];
        penalised.row.push_back(p);
        penalised.value.push_back(v);
      }
      penalised.column_start.push_back(static_cast<int>(penalised.row.size()));
    }
    for (const auto& phi : modes)
      for (int p = 0; p < 24; ++p) {
        double kphi = 0.0;
        for (int q = 0; q < 24; ++q) kphi += k[24 * p + q] * phi[q];
        EXPECT_LT(std::abs(kphi), 1e-12 * scale) << "seed " << seed;
      }
    SparseCholesky cholesky;
    cholesky.analyse(penalised);
    EXPECT_NO_THROW(cholesky.factorise(penalised)) << "seed " << seed;
  }
}

// The CHOLMOD wrapper: the solution of an SPD tridiagonal system (the 1-D Laplacian plus the
// identity) to round-off, and a diagonal matrix with a negative entry refused at that column
// whatever the ordering.
TEST(SparseCholesky, SolvesAndNamesTheColumnThatIsNotPositiveDefinite) {
  SymmetricCsc a;
  a.size = 50;
  a.column_start.push_back(0);
  for (int j = 0; j < a.size; ++j) {
    if (j > 0) {
      a.row.push_back(j - 1);
      a.value.push_back(-1.0);
    }
    a.row.push_back(j);
    a.value.push_back(3.0);
    a.column_start.push_back(static_cast<int>(a.row.size()));
  }
  std::vector<double> x_exact(a.size), b(a.size), x(a.size);
  for (int i = 0; i < a.size; ++i) x_exact[i] = std::sin(0.3 * i);
  for (int i = 0; i < a.size; ++i)
    b[i] =
        3.0 * x_exact[i] - (i > 0 ? x_exact[i - 1] : 0.0) - (i + 1 < a.size ? x_exact[i + 1] : 0.0);
  SparseCholesky cholesky;
  cholesky.analyse(a);
  cholesky.factorise(a);
  cholesky.solve(b, x);
  for (int i = 0; i < a.size; ++i) EXPECT_NEAR(x[i], x_exact[i], 1e-14) << i;

  const SymmetricCsc d{3, {0, 1, 2, 3}, {0, 1, 2}, {1.0, -2.0, 3.0}};
  SparseCholesky indefinite;
  indefinite.analyse(d);
  try {
    indefinite.factorise(d);
    FAIL() << "no error";
  } catch (const NotPositiveDefinite& e) {
    EXPECT_EQ(e.column(), 1);
  }
}

// The patch test (MacNeal & Harder 1985): the 2x2x2 patch with its interior node moved by up to
// 20 % of the edge, the linear field u = A x + c prescribed on its 26 boundary nodes; the
// interior node's displacement and the stress at all 64 Gauss points are exact to 1e-10.
TEST(StaticSolve, PatchTestIsExactOnADistortedMesh) {
  const test::Patch patch(1.0, 7);
  MeshData mesh;
  mesh.nodes.assign(patch.nodes.begin(), patch.nodes.end());
  for (const auto& el : patch.elements)
    mesh.hexahedra.push_back({el[0], el[1], el[2], el[3], el[4], el[5], el[6], el[7]});
  mesh.hexahedron_part.assign(8, 0);
  mesh.part_names = {"patch"};
  std::mt19937 rng(11);
  core::Mat3 a = test::random_mat(rng);
  for (auto& row : a.m)
    for (double& aij : row) aij *= 1e-3;
  const core::Vec3 c = 1e-3 * test::random_vec(rng);
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {steel()};
  for (std::int32_t n = 0; n < 27; ++n)
    if (n != 13)
      for (int i = 0; i < 3; ++i)
        problem.prescribed.push_back({n, i, (test::times(a, mesh.nodes[n]) + c)[i]});
  const StaticResult r = solve_static(problem);

  const core::Vec3 exact = test::times(a, mesh.nodes[13]) + c;
  const double u_error = core::norm(r.displacement[13] - exact) / core::norm(exact);
  const core::SymTensor sigma = hooke(steel(), core::sym_part(a));
  double s_error = 0.0;
  for (const auto& element : r.stress)
    for (const core::SymTensor& s : element) s_error = std::max(s_error, max_abs(s - sigma));
  s_error /= max_abs(sigma);
  std::printf(
      "patch test: interior displacement error %.2e, stress error %.2e (relative), %zu "
      "Newton rows\n",
      u_error, s_error, r.iterations.size());
  EXPECT_LT(u_error, 1e-10);
  EXPECT_LT(s_error, 1e-10);
}

// A cantilever 10 x 1 x 1, a shear force P along z spread evenly over the end x = 10, its root
// x = 0 held as beam theory clamps it: u_x = 0 over the face (the section stays plane and
// unturned), its Poisson contraction free (u_y = 0 only on the line y = h/2, u_z = 0 only on
// z = h/2). Reference: Timoshenko beam, delta = P L^3 / (3 E I) + P L / (kappa G A),
// kappa = 10 (1 + nu) / (12 + 11 nu) (Cowper 1966, rectangle); the mean deflection of the end
// face within 1 %. Fully integrated hexahedra lock in bending when coarse (the error falls as
// 1 / n^2 with n elements through the depth), so the mesh is 60 x 6 x 6: -0.30 %. (Holding every
// component of the root face, which also stops its contraction, gives -1.06 % on this mesh.)
TEST(StaticSolve, CantileverTipDeflectionMatchesTimoshenkoBeam) {
  const test::Cantilever c = test::cantilever(60, 6);
  std::printf(
      "cantilever 60x6x6: tip deflection %.6g, Timoshenko %.6g (bending %.6g, shear "
      "%.6g): error %+.3f %%\n",
      c.deflection, c.bending + c.shear, c.bending, c.shear, 100.0 * c.error());
  EXPECT_LT(std::abs(c.error()), 0.01);
}

// The thick cylinder a = 1, b = 2 under internal pressure p in plane strain (Lame): sigma_r =
// A - B / r^2, sigma_theta = A + B / r^2, A = p a^2 / (b^2 - a^2), B = A b^2. A quarter ring of
// 12 x 24 elements; the radial and hoop stress of the mid-wall elements (centroid within 0.1 of
// r = 1.5), the means of their Gauss points, within 1 % of the exact values at their centroids.
// (Single Gauss points are off by up to 5 % in sigma_r: a trilinear element's radial strain is
// constant along its radial edges, so its points all see the element's mean radial gradient.)
TEST(StaticSolve, ThickCylinderMatchesLame) {
  const double a = 1.0, b = 2.0, p = 100.0;
  const MeshData ring = test::quarter_ring(a, b, 0.1, 12, 24);
  const StaticResult r = solve_static(test::pressurised_ring(ring, steel(), p));
  const double big_a = p * a * a / (b * b - a * a), big_b = big_a * b * b;
  double radial = 0.0, hoop = 0.0;
  int points = 0;
  for (std::size_t e = 0; e < ring.hexahedra.size(); ++e) {
    core::Vec3 centroid;
    core::SymTensor mean;
    for (int g = 0; g < 8; ++g) {
      centroid += 0.125 * test::gauss_point(ring, e, g);
      mean += 0.125 * r.stress[e][g];
    }
    const double rad = std::hypot(centroid.x, centroid.y);
    if (std::abs(rad - 0.5 * (a + b)) > 0.1) continue;
    const test::Polar s = test::polar(mean, centroid);
    radial = std::max(radial, std::abs(s.radial / (big_a - big_b / (rad * rad)) - 1.0));
    hoop = std::max(hoop, std::abs(s.hoop / (big_a + big_b / (rad * rad)) - 1.0));
    ++points;
  }
  std::printf("Lame 12x24: %d mid-wall elements, largest error radial %.3f %%, hoop %.3f %%\n",
              points, 100.0 * radial, 100.0 * hoop);
  EXPECT_GT(points, 0);
  EXPECT_LT(radial, 0.01);
  EXPECT_LT(hoop, 0.01);
}

// A body whose supports leave rigid-body modes free is refused before any factorisation, the
// message naming the body's part and the free modes.
TEST(StaticSolve, UnheldBodyIsNamedWithItsFreeModes) {
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {2, 1, 1}}, {2, 1, 1});
  mesh.part_names[0] = "block";
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {steel()};
  // x held on the face x = 0: translations along y and z and the rotation about x stay free.
  for (std::int32_t n : test::node_set(mesh, "xmin")) problem.prescribed.push_back({n, 0, 0.0});
  try {
    solve_static(problem);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    std::printf("%s\n", e.what());
    EXPECT_NE(what.find("'block'"), std::string::npos);
    for (const char* mode : {"translation along y", "translation along z", "rotation about x"})
      EXPECT_NE(what.find(mode), std::string::npos) << mode;
    for (const char* held : {"translation along x", "rotation about y", "rotation about z"})
      EXPECT_EQ(what.find(held), std::string::npos) << held;
  }
}

// A strength model without a consistent tangent is an error naming the material and the model,
// never a secant in its place.
TEST(StaticSolve, StrengthModelWithoutTangentIsNamed) {
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {1, 1, 1}}, {1, 1, 1});
  core::Material m = steel();
  m.strength = core::DruckerPrager{};
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m};
  try {
    solve_static(problem);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'steel'"), std::string::npos) << what;
    EXPECT_NE(what.find("'drucker-prager'"), std::string::npos) << what;
  }
}

// A bar 4 x 1 x 1 of hexahedra (steel, nu = 0.3) with a truss of aluminium (E = 70e3, area
// 0.05) along each of its four long edges, each truss of four segments between the edge's
// nodes; held by symmetry planes at x = 0, y = 0, z = 0 and pulled by F = 1000 spread evenly
// over the four nodes of the end x = 4. Hand solution (uniaxial stress, the trusses in
// parallel): the extension F L / (E A + 4 E_t A_t), the bar's stress E and the trusses' E_t
// times the strain, all to 1e-10.
TEST(StaticSolve, TrussesInParallelWithHexahedraAddTheirStiffness) {
  const double length = 4.0, force = 1000.0, truss_e = 70e3, truss_area = 0.05;
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {length, 1, 1}}, {4, 1, 1});
  mesh.part_names = {"bar", "rebar"};
  core::Material aluminium = steel();
  aluminium.name = "aluminium";
  aluminium.youngs_modulus = truss_e;
  for (double y : {0.0, 1.0})
    for (double z : {0.0, 1.0}) {
      std::vector<std::int32_t> edge;  // the nodes on the edge, by x
      for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
        if (mesh.nodes[n].y == y && mesh.nodes[n].z == z) edge.push_back(static_cast<int>(n));
      std::sort(edge.begin(), edge.end(),
                [&](int a, int b) { return mesh.nodes[a].x < mesh.nodes[b].x; });
      ASSERT_EQ(edge.size(), 5u);
      for (std::size_t i = 0; i + 1 < edge.size(); ++i) {
        mesh.lines.push_back({edge[i], edge[i + 1]});
        mesh.line_part.push_back(1);
        mesh.line_area.push_back(truss_area);
      }
    }
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {steel(), aluminium};
  for (std::int32_t n : test::node_set(mesh, "xmin")) problem.prescribed.push_back({n, 0, 0.0});
  for (std::int32_t n : test::node_set(mesh, "ymin")) problem.prescribed.push_back({n, 1, 0.0});
  for (std::int32_t n : test::node_set(mesh, "zmin")) problem.prescribed.push_back({n, 2, 0.0});
  problem.nodal_forces.assign(mesh.nodes.size(), core::Vec3{});
  for (std::int32_t n : test::node_set(mesh, "xmax")) problem.nodal_forces[n].x = force / 4.0;
  const StaticResult r = solve_static(problem);

  const double strain = force / (steel().youngs_modulus * 1.0 + 4.0 * truss_e * truss_area);
  double extension = 0.0, bar = 0.0, truss = 0.0;
  for (std::int32_t n : test::node_set(mesh, "xmax"))
    extension = std::max(extension, std::abs(r.displacement[n].x / (strain * length) - 1.0));
  for (const auto& element : r.stress)
    for (const core::SymTensor& s : element)
      bar = std::max(bar, std::abs(s.xx / (steel().youngs_modulus * strain) - 1.0));
  for (double s : r.line_stress) truss = std::max(truss, std::abs(s / (truss_e * strain) - 1.0));
  std::printf("trusses in parallel: extension error %.2e, bar stress %.2e, truss stress %.2e\n",
              extension, bar, truss);
  ASSERT_EQ(r.line_stress.size(), 16u);
  EXPECT_LT(extension, 1e-10);
  EXPECT_LT(bar, 1e-10);
  EXPECT_LT(truss, 1e-10);
}

}  // namespace
}  // namespace afemp::fem
