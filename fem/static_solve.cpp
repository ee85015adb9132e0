// Newton-Raphson static solve of B-bar hexahedra (fem/static_solve.hpp): residual and
// consistent tangent per Gauss point from core::small_strain_update, the tangent assembled on
// the pattern of fem/sparse_assembly.hpp and factorised by CHOLMOD, whose ordering and symbolic
// factorisation are computed once for the whole solve.
#include "fem/static_solve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <ostream>
#include <stdexcept>
#include <string>

#include "core/materials/small_strain_tangent.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_stiffness.hpp"
#include "fem/sparse_assembly.hpp"
#include "fem/sparse_cholesky.hpp"

namespace afemp::fem {
namespace {

constexpr const char* kAxis[3] = {"x", "y", "z"};

std::string node_name(const MeshData& mesh, std::size_t n) {
  std::string s = "node " + std::to_string(n);
  if (!mesh.node_labels.empty()) s += " (label " + std::to_string(mesh.node_labels[n]) + ")";
  return s;
}

std::string format(const char* fmt, double a, double b, double c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

// Consistent nodal forces of a pressure on a bilinear face, f_a = -p integral of
// N_a (x_xi x x_eta) dxi deta, by 2x2 Gauss (exact: the integrand is quadratic in each
// direction).
void add_pressure_forces(const PressureFace& face, const std::vector<core::Vec3>& x,
                         std::vector<core::Vec3>& f) {
  static constexpr double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  const double r = 1.0 / std::sqrt(3.0);
  for (double xi : {-r, r})
    for (double eta : {-r, r}) {
      core::Vec3 dxi, deta;
      for (int a = 0; a < 4; ++a) {
        dxi += (0.25 * corner[a][0] * (1.0 + corner[a][1] * eta)) * x[face.nodes[a]];
        deta += (0.25 * corner[a][1] * (1.0 + corner[a][0] * xi)) * x[face.nodes[a]];
      }
      const core::Vec3 area = core::cross(dxi, deta);
      for (int a = 0; a < 4; ++a) {
        const double n = 0.25 * (1.0 + corner[a][0] * xi) * (1.0 + corner[a][1] * eta);
        f[face.nodes[a]] -= (face.pressure * n) * area;
      }
    }
}

// The eigenvalues (on a's diagonal) and eigenvectors (v's columns) of the symmetric 6 x 6
// matrix a by cyclic Jacobi rotations (Golub & Van Loan 2013, sec. 8.5.2). Written out rather
// than Eigen's solvers, whose 6 x 6 forms draw false -Wmaybe-uninitialized warnings from GCC 12
// at -march=native.
void symmetric_eigen(double (&a)[6][6], double (&v)[6][6]) {
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) v[i][j] = i == j;
  double scale = 0.0;
  for (int i = 0; i < 6; ++i) scale += a[i][i] * a[i][i];
  for (int sweep = 0; sweep < 50; ++sweep) {
    double off = 0.0;
    for (int p = 0; p < 6; ++p)
      for (int q = p + 1; q < 6; ++q) off += a[p][q] * a[p][q];
    if (off <= 1e-32 * scale) return;
    for (int p = 0; p < 6; ++p)
      for (int q = p + 1; q < 6; ++q) {
        if (a[p][q] == 0.0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::hypot(theta, 1.0));
        const double c = 1.0 / std::hypot(t, 1.0), s = t * c;
        for (int k = 0; k < 6; ++k) {  // a = J^T a J, v = v J
          const double kp = a[k][p], kq = a[k][q];
          a[k][p] = c * kp - s * kq;
          a[k][q] = s * kp + c * kq;
        }
        for (int k = 0; k < 6; ++k) {
          const double pk = a[p][k], qk = a[q][k];
          a[p][k] = c * pk - s * qk;
          a[q][k] = s * pk + c * qk;
        }
        for (int k = 0; k < 6; ++k) {
          const double kp = v[k][p], kq = v[k][q];
          v[k][p] = c * kp - s * kq;
          v[k][q] = s * kp + c * kq;
        }
      }
  }
}

// Throws when a connected body has rigid-body modes that its fixed dofs do not hold: the null
// space of sum over fixed dofs of phi phi^T, phi the six modes' values there (translations
// along x, y, z; rotations about the axes through the body's centroid, scaled by its radius of
// gyration so that the six are comparable).
void check_rigid_body_modes(const MeshData& mesh, const std::vector<char>& fixed) {
  std::vector<std::int32_t> parent(mesh.nodes.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](std::int32_t n) {
    while (parent[n] != n) n = parent[n] = parent[parent[n]];
    return n;
  };
  for (const Hexahedron& h : mesh.hexahedra)
    for (std::int32_t a : h) parent[root(a)] = root(h[0]);
  std::vector<std::vector<std::int32_t>> bodies(mesh.nodes.size());  // nodes, by root
  std::vector<char> seen(mesh.nodes.size(), 0);
  for (const Hexahedron& h : mesh.hexahedra)
    for (std::int32_t a : h)
      if (!seen[a]) {
        seen[a] = 1;
        bodies[root(a)].push_back(a);
      }
  std::vector<std::vector<std::int32_t>> parts(mesh.nodes.size());  // parts, by root
  for (std::size_t e = 0; e < mesh.hexahedra.size(); ++e) {
    std::vector<std::int32_t>& p = parts[root(mesh.hexahedra[e][0])];
    if (std::find(p.begin(), p.end(), mesh.hexahedron_part[e]) == p.end())
      p.push_back(mesh.hexahedron_part[e]);
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::vector<std::int32_t>& nodes = bodies[b];
    if (nodes.empty()) continue;
    core::Vec3 centroid;
    for (std::int32_t n : nodes) centroid += mesh.nodes[n];
    centroid *= 1.0 / static_cast<double>(nodes.size());
    double gyration = 0.0;
    for (std::int32_t n : nodes)
      gyration += core::dot(mesh.nodes[n] - centroid, mesh.nodes[n] - centroid);
    gyration = std::sqrt(gyration / static_cast<double>(nodes.size()));
    double gram[6][6] = {};
    for (std::int32_t n : nodes) {
      const core::Vec3 d = (1.0 / gyration) * (mesh.nodes[n] - centroid);
      for (int i = 0; i < 3; ++i) {
        if (!fixed[3 * n + i]) continue;
        double phi[6] = {};
        phi[i] = 1.0;
        for (int k = 0; k < 3; ++k) {
          core::Vec3 axis;
          axis[k] = 1.0;
          phi[3 + k] = core::cross(axis, d)[i];
        }
        for (int p = 0; p < 6; ++p)
          for (int q = 0; q < 6; ++q) gram[p][q] += phi[p] * phi[q];
      }
    }
    double trace = 0.0, v[6][6];
    for (int p = 0; p < 6; ++p) trace += gram[p][p];
    symmetric_eigen(gram, v);
    std::string modes;
    for (int m = 0; m < 6; ++m) {
      if (gram[m][m] > 1e-9 * std::max(trace, 1.0)) continue;
      std::string mode;
      for (int k = 0; k < 6; ++k) {
        if (std::abs(v[k][m]) < 1e-3) continue;
        if (!mode.empty()) mode += " + ";
        if (std::abs(v[k][m]) < 0.999) mode += format("%.3g ", v[k][m], 0, 0);
        mode += std::string(k < 3 ? "translation along " : "rotation about ") + kAxis[k % 3];
      }
      modes += (modes.empty() ? "" : "; ") + mode;
    }
    if (modes.empty()) continue;
    std::string names;
    for (std::int32_t p : parts[b])
      names += (names.empty() ? "'" : ", '") + mesh.part_names[p] + "'";
    throw std::runtime_error(
        "static solve: the body of part " + names + " (" + std::to_string(nodes.size()) +
        " nodes) is not held: the prescribed displacements leave free its rigid-body modes " +
        modes +
        format(" (rotations about axes through its centroid (%g, %g, %g)): the system is singular",
               centroid.x, centroid.y, centroid.z));
  }
}

double norm(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

}  // namespace

std::vector<std::array<std::int32_t, 4>> faces_on_nodes(const MeshData& mesh,
                                                        std::span<const std::int32_t> nodes) {
  std::vector<char> in(mesh.nodes.size(), 0);
  for (std::int32_t n : nodes) in[n] = 1;
  std::vector<std::array<std::int32_t, 4>> faces;
  for (const Hexahedron& h : mesh.hexahedra)
    for (const auto& f : kHexFaces) {
      const std::array<std::int32_t, 4> q{h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
      if (in[q[0]] && in[q[1]] && in[q[2]] && in[q[3]]) faces.push_back(q);
    }
  return faces;
}

StaticResult solve_static(const StaticProblem& problem, const NewtonSettings& settings) {
  if (!problem.mesh) throw std::invalid_argument("static solve: no mesh");
  const MeshData& mesh = *problem.mesh;
  validate(mesh, "static solve");
  if (!mesh.lines.empty())
    throw std::invalid_argument("static solve: trusses (mesh lines) have no tangent stiffness yet");
  if (problem.materials.size() != mesh.part_names.size())
    throw std::invalid_argument("static solve: " + std::to_string(problem.materials.size()) +
                                " materials for " + std::to_string(mesh.part_names.size()) +
                                " parts (one per part)");
  const std::size_t nodes = mesh.nodes.size(), elements = mesh.hexahedra.size();
  std::vector<char> part_used(mesh.part_names.size(), 0);
  for (std::int32_t p : mesh.hexahedron_part) part_used[p] = 1;
  for (std::size_t p = 0; p < part_used.size(); ++p)
    if (part_used[p]) core::check_small_strain_tangent(problem.materials[p]);
  if (!problem.nodal_forces.empty() && problem.nodal_forces.size() != nodes)
    throw std::invalid_argument("static solve: nodal_forces needs one force per node");

  std::vector<char> fixed(3 * nodes, 0), in_element(nodes, 0);
  for (const Hexahedron& h : mesh.hexahedra)
    for (std::int32_t a : h) in_element[a] = 1;
  for (const PrescribedDisplacement& p : problem.prescribed) {
    if (p.node < 0 || static_cast<std::size_t>(p.node) >= nodes || p.component < 0 ||
        p.component > 2)
      throw std::invalid_argument("static solve: prescribed displacement of node " +
                                  std::to_string(p.node) + ", component " +
                                  std::to_string(p.component) + " out of range");
    fixed[3 * p.node + p.component] = 1;
  }
  check_rigid_body_modes(mesh, fixed);
  std::vector<int> equation(3 * nodes, -1), dof_of;  // dof_of[equation] = 3 node + component
  for (std::size_t d = 0; d < 3 * nodes; ++d)
    if (in_element[d / 3] && !fixed[d]) {
      equation[d] = static_cast<int>(dof_of.size());
      dof_of.push_back(static_cast<int>(d));
    }
  const int equations = static_cast<int>(dof_of.size());

  std::vector<core::Vec3> f_ext(nodes);
  if (!problem.nodal_forces.empty()) f_ext = problem.nodal_forces;
  for (const PressureFace& face : problem.pressures) add_pressure_forces(face, mesh.nodes, f_ext);

  std::vector<FullHex> geometry(elements);
  for (std::size_t e = 0; e < elements; ++e) {
    HexVectors x;
    for (int a = 0; a < 8; ++a) x[a] = mesh.nodes[mesh.hexahedra[e][a]];
    geometry[e] = full_hex(x);
    if (min_jacobian(geometry[e]) <= 0.0)
      throw std::invalid_argument("static solve: hexahedron " + std::to_string(e) +
                                  " has a non-positive Jacobian (tangled or inverted)");
  }

  // Per element and Gauss point: the converged state, and the strain and update at the
  // displacement last evaluated.
  std::vector<std::array<core::SmallStrainPoint, 8>> converged(elements);
  std::vector<std::array<core::SymTensor, 8>> strain(elements);
  std::vector<std::array<core::SmallStrainResult, 8>> current(elements);
  std::vector<core::Vec3> u(nodes), force(nodes);
  std::vector<double> r(equations);
  double load = 0.0;

  // r = load f_ext - f_int(u) on the free dofs; returns max(||load f_ext||, ||reactions||).
  auto residual = [&](const std::vector<core::Vec3>& at) {
    std::fill(force.begin(), force.end(), core::Vec3{});
    for (std::size_t e = 0; e < elements; ++e) {
      const Hexahedron& h = mesh.hexahedra[e];
      HexVectors ue, fe{};
      for (int a = 0; a < 8; ++a) ue[a] = at[h[a]];
      std::array<core::SymTensor, 8> sigma;
      const core::Material& material = problem.materials[mesh.hexahedron_part[e]];
      for (int g = 0; g < 8; ++g) {
        strain[e][g] = strain_bbar(geometry[e], g, ue);
        current[e][g] = core::small_strain_update(material, converged[e][g], strain[e][g]);
        sigma[g] = current[e][g].stress;
      }
      add_stress_forces_bbar(geometry[e], sigma, fe);  // -f_int
      for (int a = 0; a < 8; ++a) force[h[a]] += fe[a];
    }
    double external = 0.0, reactions = 0.0;
    for (std::size_t d = 0; d < 3 * nodes; ++d) {
      const double f = load * f_ext[d / 3][d % 3];
      external += f * f;
      const double rd = f + force[d / 3][d % 3];
      if (equation[d] >= 0)
        r[equation[d]] = rd;
      else if (in_element[d / 3])
        reactions += rd * rd;
    }
    return std::sqrt(std::max(external, reactions));
  };

  SparseAssembly assembly(mesh.hexahedra, equation, equations);
  SparseCholesky cholesky;
  cholesky.analyse(assembly.matrix());
  std::vector<double> du(equations), b(equations);
  std::vector<core::Vec3> trial(nodes);
  StaticResult out;
  auto record = [&](const NewtonIteration& it) {
    out.iterations.push_back(it);
    if (settings.log)
      *settings.log << "static step " << it.load_step << "/" << settings.load_steps << " iteration "
                    << it.iteration << ": residual " << it.residual << " (relative "
                    << (it.reference > 0.0 ? it.residual / it.reference : 0.0) << "), energy "
                    << it.energy << ", step length " << it.step_length << '\n';
  };

  for (int step = 1; step <= settings.load_steps; ++step) {
    load = static_cast<double>(step) / settings.load_steps;
    for (const PrescribedDisplacement& p : problem.prescribed)
      u[p.node][p.component] = load * p.value;
    double reference = residual(u), first_energy = 0.0, last_energy = 0.0;
    for (int k = 0;; ++k) {
      const double rnorm = norm(r), scale = reference;
      if (rnorm <= settings.residual_tolerance * reference &&
          (k == 0 || last_energy <= settings.energy_tolerance * first_energy)) {
        record({step, k, rnorm, scale, 0.0, 0.0});
        break;
      }
      if (k == settings.max_iterations)
        throw std::runtime_error("static solve: load step " + std::to_string(step) + " of " +
                                 std::to_string(settings.load_steps) + " did not converge in " +
                                 std::to_string(k) + " iterations: residual " +
                                 format("%.3g (%.3g of the force scale; tolerance %.3g)", rnorm,
                                        rnorm / scale, settings.residual_tolerance) +
                                 format(", last energy %.3g (%.3g of the first)", last_energy,
                                        last_energy / first_energy, 0.0));

      assembly.clear();
      for (std::size_t e = 0; e < elements; ++e) {
        std::array<core::VoigtMatrix, 8> d;
        for (int g = 0; g < 8; ++g) d[g] = current[e][g].tangent;
        HexMatrix ke;
        hexahedron_stiffness_bbar(geometry[e], d, ke);
        assembly.add(mesh.hexahedra[e], ke);
      }
      try {
        cholesky.factorise(assembly.matrix());
      } catch (const NotPositiveDefinite& npd) {
        const int dof = dof_of[npd.column()];
        throw std::runtime_error(
            "static solve: load step " + std::to_string(step) + ", iteration " + std::to_string(k) +
            ": the tangent stiffness is not positive definite at " + node_name(mesh, dof / 3) +
            ", component " + kAxis[dof % 3] + " (a mechanism, or a material that softens)");
      }
      b = r;
      cholesky.solve(b, du);
      const double g0 = dot(du, r), energy = std::abs(g0);
      if (k == 0) first_energy = energy;
      last_energy = energy;

      // Line search on G(s) = du . r(u + s du), G(0) = g0 > 0: s = 1 unless it overshoots
      // (G(1) < -ratio g0), then regula falsi in the bracket [0, 1].
      auto try_length = [&](double s) {
        trial = u;
        for (int q = 0; q < equations; ++q) trial[dof_of[q] / 3][dof_of[q] % 3] += s * du[q];
        reference = residual(trial);
        return dot(du, r);
      };
      double s = 1.0, g = try_length(1.0);
      double lo = 0.0, g_lo = g0, hi = 1.0, g_hi = g;
      for (int ls = 0; ls < settings.line_search_steps && g < -settings.line_search_ratio * g0;
           ++ls) {
        s = lo + (hi - lo) * g_lo / (g_lo - g_hi);
        g = try_length(s);
        if (g > 0.0) {
          lo = s;
          g_lo = g;
        } else {
          hi = s;
          g_hi = g;
        }
      }
      u.swap(trial);
      record({step, k, rnorm, scale, energy, s});
    }
    for (std::size_t e = 0; e < elements; ++e)
      for (int g = 0; g < 8; ++g)
        converged[e][g] = {strain[e][g], current[e][g].stress.deviator(),
                           current[e][g].plastic_strain};
  }

  out.displacement = u;
  out.stress.resize(elements);
  out.plastic_strain.resize(elements);
  for (std::size_t e = 0; e < elements; ++e)
    for (int g = 0; g < 8; ++g) {
      out.stress[e][g] = current[e][g].stress;
      out.plastic_strain[e][g] = current[e][g].plastic_strain;
    }
  return out;
}

}  // namespace afemp::fem
