// Newton-Raphson static solve of B-bar and one-point hexahedra (fem/static_solve.hpp): residual
// and consistent tangent per Gauss point from core::small_strain_update, the one-point elements'
// hourglass stiffness fixed at the initial geometry (small strain), the tangent assembled on
// the pattern of fem/sparse_assembly.hpp and factorised by CHOLMOD, whose ordering and symbolic
// factorisation are computed once for the whole solve.
#include "fem/static_solve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <variant>

#include "core/materials/small_strain_tangent.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_one_point.hpp"
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
  char buf[160];
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

// Throws when a connected body has rigid-body modes that its fixed dofs and the walls it rests
// on do not hold: the null space of sum over held directions d of phi phi^T, phi the six
// modes' components d . mode there (translations along x, y, z; rotations about the axes
// through the body's centroid, scaled by its radius of gyration so that the six are
// comparable); a fixed dof holds its axis, a wall (supports: node, normal) its normal.
void check_rigid_body_modes(const MeshData& mesh, const std::vector<char>& fixed,
                            const std::vector<std::pair<std::int32_t, core::Vec3>>& supports,
                            bool walls, std::span<const TiedNode> tied) {
  std::vector<std::int32_t> parent(mesh.nodes.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](std::int32_t n) {
    while (parent[n] != n) n = parent[n] = parent[parent[n]];
    return n;
  };
  // Bodies: the nodes that hexahedra and lines (trusses) connect.
  auto join = [&](const auto& element) {
    for (std::int32_t a : element) parent[root(a)] = root(element[0]);
  };
  for (const Hexahedron& h : mesh.hexahedra) join(h);
  for (const Line& l : mesh.lines) join(l);
  for (const TiedNode& t : tied) {  // a tied node is one body with its host
    join(t.host);
    parent[root(t.node)] = root(t.host[0]);
  }
  std::vector<std::vector<std::int32_t>> bodies(mesh.nodes.size());  // nodes, by root
  std::vector<std::vector<std::int32_t>> parts(mesh.nodes.size());   // parts, by root
  std::vector<char> seen(mesh.nodes.size(), 0);
  auto collect = [&](const auto& element, std::int32_t part) {
    for (std::int32_t a : element)
      if (!seen[a]) {
        seen[a] = 1;
        bodies[root(a)].push_back(a);
      }
    std::vector<std::int32_t>& p = parts[root(element[0])];
    if (std::find(p.begin(), p.end(), part) == p.end()) p.push_back(part);
  };
  for (std::size_t e = 0; e < mesh.hexahedra.size(); ++e)
    collect(mesh.hexahedra[e], mesh.hexahedron_part[e]);
  for (std::size_t e = 0; e < mesh.lines.size(); ++e) collect(mesh.lines[e], mesh.line_part[e]);
  std::vector<std::vector<core::Vec3>> held(mesh.nodes.size());  // per node, what holds it
  for (std::size_t d = 0; d < fixed.size(); ++d)
    if (fixed[d]) {
      core::Vec3 axis;
      axis[d % 3] = 1.0;
      held[d / 3].push_back(axis);
    }
  for (const auto& [node, normal] : supports) held[node].push_back(normal);
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
    // gram over the held directions; motion over all of the body's dofs, whose null space is
    // what moves no node (the turn about the line of a straight chain of trusses): no mode.
    double gram[6][6] = {}, motion[6][6] = {};
    for (std::int32_t n : nodes) {
      const core::Vec3 d = (1.0 / gyration) * (mesh.nodes[n] - centroid);
      auto add = [&](const core::Vec3& direction, double(&g)[6][6]) {
        double phi[6];
        for (int k = 0; k < 3; ++k) {
          core::Vec3 axis;
          axis[k] = 1.0;
          phi[k] = direction[k];
          phi[3 + k] = core::dot(direction, core::cross(axis, d));
        }
        for (int p = 0; p < 6; ++p)
          for (int q = 0; q < 6; ++q) g[p][q] += phi[p] * phi[q];
      };
      for (const core::Vec3& direction : held[n]) add(direction, gram);
      for (int i = 0; i < 3; ++i) {
        core::Vec3 axis;
        axis[i] = 1.0;
        add(axis, motion);
      }
    }
    double trace = 0.0, motion_trace = 0.0, v[6][6];
    for (int p = 0; p < 6; ++p) {
      trace += gram[p][p];
      motion_trace += motion[p][p];
    }
    symmetric_eigen(motion, v);
    for (int m = 0; m < 6; ++m)
      if (motion[m][m] <= 1e-9 * motion_trace)
        for (int p = 0; p < 6; ++p)
          for (int q = 0; q < 6; ++q) gram[p][q] += std::max(trace, 1.0) * v[p][m] * v[q][m];
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
               centroid.x, centroid.y, centroid.z) +
        (walls ? " (a wall holds a body only where its nodes touch the wall at the start)" : ""));
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

namespace {

// What the static and the dynamic solve share: the equations of the free dofs, the element
// geometry, the consistent mass and the Gauss points' converged and current states. Trusses
// (mesh lines) are bars at small strain: strain e . (u_b - u_a) / L0 along their initial axis
// e, axial force A sigma (core::small_strain_bar_update: elastic, or the 1-D return map),
// stiffness (E_t A / L0) [e e^T, -e e^T; -e e^T, e e^T] with the update's tangent E_t, and
// consistent mass (rho A L0 / 6) [2 1; 1 2] per component. The equations of a node that a wall
// holds are its components in its frame (fem/wall_constraints.hpp), the held ones kept as
// equations whose corrections are zero, so that the sparsity pattern and CHOLMOD's analysis
// stay those of the whole solve whatever the walls' active set.
struct Body {
  const StaticProblem& problem;
  const MeshData& mesh;
  std::size_t nodes = 0, elements = 0;
  std::vector<char> in_element;
  std::vector<int> equation, dof_of;  // dof_of[equation] = 3 node + component
  int equations = 0;
  std::vector<core::Vec3> f_ext;  // at full load
  std::vector<FullHex> geometry;
  // Per element, its index into one_point_geometry and hourglass, or -1 when fully integrated.
  // A one-point element keeps its one point's state in slot 0 of converged, strain and current.
  std::vector<int> one_point;
  std::vector<OnePointHex> one_point_geometry;
  std::vector<HourglassStiffness> hourglass;
  std::vector<std::array<core::SmallStrainPoint, 8>> converged;
  std::vector<std::array<core::SymTensor, 8>> strain;  // at the displacement last evaluated
  // The elastic strain of the initial stress, added to B u (empty: a virgin start); trusses:
  // line_strain0.
  std::vector<std::array<core::SymTensor, 8>> strain0;
  std::vector<double> line_strain0;
  std::vector<std::array<core::SmallStrainResult, 8>> current;
  // Per point, the stress of the last converged state and the work per unit volume int sigma :
  // d eps taken to it, by the trapezoidal rule over the converged states (trusses: line_work).
  std::vector<std::array<core::SymTensor, 8>> committed_stress;
  std::vector<std::array<double, 8>> work;
  std::vector<core::Vec3> line_axis;  // unit, initial
  std::vector<double> line_length;    // initial
  std::vector<double> line_mass;      // rho A L0
  std::vector<core::SmallStrainBarPoint> line_converged;
  std::vector<double> line_strain;  // at the displacement last evaluated
  std::vector<core::SmallStrainBarResult> line_current;
  std::vector<double> line_work;
  std::optional<WallConstraints> walls;
  // Per node, its index in problem.tied, or -1; per line, the nodes its matrix couples when a
  // node of it is tied (its untied node and the hosts of its tied ones; empty otherwise).
  std::vector<int> tie_of;
  std::vector<std::vector<std::int32_t>> line_group;
  mutable std::vector<core::Vec3> folded;

  // Validates the problem (`who` starts the messages); a static solve also needs the body held
  // against its rigid-body modes, by its prescribed dofs and the walls its nodes touch at the
  // start.
  Body(const StaticProblem& p, const char* who, bool check_support);

  // r on the equations from a per-node vector (a residual), in the nodes' frames, zero on the
  // components the walls hold; returns the sum of squares of what the prescribed and the held
  // components carry (the reactions).
  double gather(const std::vector<core::Vec3>& nodal, std::vector<double>& r) const;
  // u += s du, du on the equations; the tied nodes follow.
  void add_correction(const std::vector<double>& du, double s, std::vector<core::Vec3>& u) const;
  // The tied nodes' values from their hosts', x_s = sum_a N_a x_a (displacements, velocities,
  // accelerations alike: the constraint is linear).
  void follow(std::vector<core::Vec3>& x) const;
  // force = -f_int(at) per node (external minus internal, without the loads), the current
  // states updated from the converged ones.
  void internal_forces(const std::vector<core::Vec3>& at, std::vector<core::Vec3>& force);
  // Assembles stiffness_factor K_t + mass_factor M (K_t of the current states).
  void assemble(SparseAssembly& assembly, double stiffness_factor, double mass_factor) const;
  // The consistent mass of element e, m_ab = rho sum_g w_g N_a(x_g) N_b(x_g) (each component).
  std::array<std::array<double, 8>, 8> mass(std::size_t e) const;
  void commit();
  // Takes the problem's initial state as the converged one (Body's constructor).
  void start_from_initial_state(const char* who);
  int points(std::size_t e) const { return one_point[e] < 0 ? 8 : 1; }
  // The points' states last evaluated, or with converged_only the last committed ones.
  void write_states(std::vector<std::array<core::SymTensor, 8>>& stress,
                    std::vector<std::array<double, 8>>& plastic_strain,
                    std::vector<double>& line_stress, std::vector<double>& line_plastic_strain,
                    bool converged_only = false) const;
  // The element whose plastic strain the current states raised most above the converged ones.
  YieldingElement most_yielding() const;
  // The work per unit volume of each point and line, and each one-point element's stored
  // hourglass energy at displacement u.
  void write_work(const std::vector<core::Vec3>& u, StaticWork& out) const;
};

Body::Body(const StaticProblem& p, const char* who, bool check_support)
    : problem(p),
      mesh(p.mesh ? *p.mesh : throw std::invalid_argument(std::string(who) + ": no mesh")) {
  validate(mesh, who);
  if (problem.materials.size() != mesh.part_names.size())
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(problem.materials.size()) +
                                " materials for " + std::to_string(mesh.part_names.size()) +
                                " parts (one per part)");
  nodes = mesh.nodes.size();
  elements = mesh.hexahedra.size();
  std::vector<char> part_used(mesh.part_names.size(), 0);
  for (std::int32_t part : mesh.hexahedron_part) part_used[part] = 1;
  for (std::int32_t part : mesh.line_part) part_used[part] = 1;
  for (std::size_t part = 0; part < part_used.size(); ++part)
    if (part_used[part]) core::check_small_strain_tangent(problem.materials[part]);
  if (!problem.hexahedra.empty() && problem.hexahedra.size() != mesh.part_names.size())
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(problem.hexahedra.size()) +
                                " hexahedron formulations for " +
                                std::to_string(mesh.part_names.size()) +
                                " parts (one per part, or none for full integration)");
  auto is_one_point = [&](std::int32_t part) {
    return !problem.hexahedra.empty() &&
           problem.hexahedra[part].element == core::HexFormulation::one_point;
  };
  std::vector<char> one_point_used(mesh.part_names.size(), 0);
  for (std::int32_t part : mesh.hexahedron_part) one_point_used[part] = is_one_point(part);
  for (std::size_t part = 0; part < one_point_used.size(); ++part) {
    if (!one_point_used[part]) continue;
    const core::HourglassSettings& hg = problem.hexahedra[part].hourglass;
    const std::string head = std::string(who) + ": part '" + mesh.part_names[part] +
                             "' has one-point hexahedra with the " + core::to_string(hg.form) +
                             " hourglass form";
    if (hg.form == core::HourglassForm::viscous)
      throw std::invalid_argument(
          head +
          ", which resists only rates (the implicit solves take no hourglass damping) and so "
          "leaves their hourglass modes without stiffness: a singular tangent. Use the stiffness "
          "or assumed_strain hourglass form, or full integration (B-bar)");
    if (!(hg.effective_coefficient() > 0.0))
      throw std::invalid_argument(head +
                                  format(" and coefficient %g", hg.effective_coefficient(), 0, 0) +
                                  ", which leaves their hourglass modes without stiffness: a "
                                  "singular tangent. Give it a positive coefficient, or use full "
                                  "integration (B-bar)");
  }
  if (!problem.nodal_forces.empty() && problem.nodal_forces.size() != nodes)
    throw std::invalid_argument(std::string(who) + ": nodal_forces needs one force per node");

  std::vector<char> fixed(3 * nodes, 0);
  tie_of.assign(nodes, -1);
  for (std::size_t k = 0; k < problem.tied.size(); ++k) {
    const TiedNode& t = problem.tied[k];
    bool in_range = t.node >= 0 && static_cast<std::size_t>(t.node) < nodes;
    for (std::int32_t h : t.host)
      in_range = in_range && h >= 0 && static_cast<std::size_t>(h) < nodes && h != t.node;
    if (!in_range || tie_of[static_cast<std::size_t>(t.node)] >= 0)
      throw std::invalid_argument(std::string(who) + ": tied node " + std::to_string(k) +
                                  " names a node out of range, itself as a host, or a node "
                                  "tied twice");
    tie_of[static_cast<std::size_t>(t.node)] = static_cast<int>(k);
  }
  for (const TiedNode& t : problem.tied)
    for (std::int32_t h : t.host)
      if (tie_of[static_cast<std::size_t>(h)] >= 0)
        throw std::invalid_argument(std::string(who) + ": a tied node's host node " +
                                    std::to_string(h) + " is tied itself");
  in_element.assign(nodes, 0);
  for (const Hexahedron& h : mesh.hexahedra)
    for (std::int32_t a : h) in_element[a] = 1;
  for (const Line& l : mesh.lines)
    for (std::int32_t a : l) in_element[a] = 1;
  for (const PrescribedDisplacement& d : problem.prescribed) {
    if (d.node < 0 || static_cast<std::size_t>(d.node) >= nodes || d.component < 0 ||
        d.component > 2)
      throw std::invalid_argument(std::string(who) + ": prescribed displacement of node " +
                                  std::to_string(d.node) + ", component " +
                                  std::to_string(d.component) + " out of range");
    if (tie_of[static_cast<std::size_t>(d.node)] >= 0)
      throw std::invalid_argument(std::string(who) + ": node " + std::to_string(d.node) +
                                  " is tied into a hexahedron and moves with it; prescribe its "
                                  "host's nodes");
    fixed[3 * d.node + d.component] = 1;
  }
  // A node of no element has no equations: no wall moves it; nor a tied node (its host's do).
  std::vector<char> unmoved = fixed;
  for (std::size_t d = 0; d < 3 * nodes; ++d)
    if (!in_element[d / 3] || tie_of[d / 3] >= 0) unmoved[d] = 1;
  walls.emplace(mesh, problem.walls, std::move(unmoved), who);
  if (check_support) {
    walls->start(std::vector<core::Vec3>(nodes));
    check_rigid_body_modes(mesh, fixed, walls->supports(), !walls->empty(), problem.tied);
  }
  equation.assign(3 * nodes, -1);
  for (std::size_t d = 0; d < 3 * nodes; ++d)
    if (in_element[d / 3] && !fixed[d] && tie_of[d / 3] < 0) {
      equation[d] = static_cast<int>(dof_of.size());
      dof_of.push_back(static_cast<int>(d));
    }
  equations = static_cast<int>(dof_of.size());

  f_ext.assign(nodes, core::Vec3{});
  if (!problem.nodal_forces.empty()) f_ext = problem.nodal_forces;
  for (const PressureFace& face : problem.pressures) add_pressure_forces(face, mesh.nodes, f_ext);

  geometry.resize(elements);
  for (std::size_t e = 0; e < elements; ++e) {
    HexVectors x;
    for (int a = 0; a < 8; ++a) x[a] = mesh.nodes[mesh.hexahedra[e][a]];
    geometry[e] = full_hex(x);
    if (min_jacobian(geometry[e]) <= 0.0)
      throw std::invalid_argument(std::string(who) + ": hexahedron " + std::to_string(e) +
                                  " has a non-positive Jacobian (tangled or inverted)");
    const std::int32_t part = mesh.hexahedron_part[e];
    one_point.push_back(is_one_point(part) ? static_cast<int>(hourglass.size()) : -1);
    if (one_point.back() < 0) continue;
    one_point_geometry.push_back(one_point_hex(x));
    hourglass.push_back(hourglass_stiffness(x, one_point_geometry.back(), problem.materials[part],
                                            problem.hexahedra[part].hourglass));
  }
  converged.resize(elements);
  strain.resize(elements);
  current.resize(elements);
  committed_stress.resize(elements);
  work.assign(elements, {});
  for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
    const core::Vec3 d = mesh.nodes[mesh.lines[l][1]] - mesh.nodes[mesh.lines[l][0]];
    const double length = core::norm(d), area = mesh.line_area[l];
    if (!(length > 0.0) || !(area > 0.0))
      throw std::invalid_argument(std::string(who) + ": line " + std::to_string(l) +
                                  " (a truss) needs a positive length and cross-section area");
    const core::Material& m = problem.materials[mesh.line_part[l]];
    line_axis.push_back((1.0 / length) * d);
    line_length.push_back(length);
    line_mass.push_back(m.density * area * length);
  }
  line_group.resize(mesh.lines.size());
  for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
    std::vector<std::int32_t>& g = line_group[l];
    for (std::int32_t a : mesh.lines[l]) {
      const int t = tie_of[static_cast<std::size_t>(a)];
      if (t < 0) {
        g.push_back(a);
        continue;
      }
      for (std::int32_t h : problem.tied[static_cast<std::size_t>(t)].host)
        if (std::find(g.begin(), g.end(), h) == g.end()) g.push_back(h);
    }
    if (tie_of[static_cast<std::size_t>(mesh.lines[l][0])] < 0 &&
        tie_of[static_cast<std::size_t>(mesh.lines[l][1])] < 0)
      g.clear();
  }
  line_converged.resize(mesh.lines.size());
  line_strain.assign(mesh.lines.size(), 0.0);
  line_work.assign(mesh.lines.size(), 0.0);
  line_current.resize(mesh.lines.size());
  start_from_initial_state(who);

  // Gravity's consistent nodal forces, integral of rho N_a g dV = sum_b M_ab g.
  if (core::dot(problem.gravity, problem.gravity) > 0.0) {
    for (std::size_t e = 0; e < elements; ++e) {
      const auto m = mass(e);
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) f_ext[mesh.hexahedra[e][a]] += m[a][b] * problem.gravity;
    }
    for (std::size_t l = 0; l < mesh.lines.size(); ++l)
      for (std::int32_t a : mesh.lines[l]) f_ext[a] += (0.5 * line_mass[l]) * problem.gravity;
  }
}

double Body::gather(const std::vector<core::Vec3>& nodal_in, std::vector<double>& r) const {
  // A tied node's force goes to its host's nodes, f_a += N_a f_s.
  const std::vector<core::Vec3>* source = &nodal_in;
  if (!problem.tied.empty()) {
    folded = nodal_in;
    for (const TiedNode& t : problem.tied) {
      const core::Vec3 f = folded[static_cast<std::size_t>(t.node)];
      for (std::size_t a = 0; a < 8; ++a)
        folded[static_cast<std::size_t>(t.host[a])] += t.weight[a] * f;
      folded[static_cast<std::size_t>(t.node)] = core::Vec3{};
    }
    source = &folded;
  }
  const std::vector<core::Vec3>& nodal = *source;
  double reactions = 0.0;
  for (std::size_t n = 0; n < nodes; ++n) {
    if (!in_element[n]) continue;
    const NodeFrame* f = walls->frame(n);
    for (int i = 0; i < 3; ++i) {
      const double v = f ? core::dot(f->basis[i], nodal[n]) : nodal[n][i];
      const int q = equation[3 * n + i];
      const bool held = f && f->holds(i);
      if (q >= 0) r[q] = held ? 0.0 : v;
      if (q < 0 || held) reactions += v * v;
    }
  }
  return reactions;
}

void Body::add_correction(const std::vector<double>& du, double s,
                          std::vector<core::Vec3>& u) const {
  for (int q = 0; q < equations; ++q) {
    const std::size_t n = static_cast<std::size_t>(dof_of[q]) / 3;
    const int i = dof_of[q] % 3;
    if (const NodeFrame* f = walls->frame(n)) {
      if (!f->holds(i)) u[n] += (s * du[q]) * f->basis[i];
    } else
      u[n][i] += s * du[q];
  }
  follow(u);
}

void Body::follow(std::vector<core::Vec3>& x) const {
  for (const TiedNode& t : problem.tied) {
    core::Vec3 v;
    for (std::size_t a = 0; a < 8; ++a) v += t.weight[a] * x[static_cast<std::size_t>(t.host[a])];
    x[static_cast<std::size_t>(t.node)] = v;
  }
}

void Body::internal_forces(const std::vector<core::Vec3>& at, std::vector<core::Vec3>& force) {
  std::fill(force.begin(), force.end(), core::Vec3{});
  for (std::size_t e = 0; e < elements; ++e) {
    const Hexahedron& h = mesh.hexahedra[e];
    HexVectors ue, fe{};
    for (int a = 0; a < 8; ++a) ue[a] = at[h[a]];
    const core::Material& material = problem.materials[mesh.hexahedron_part[e]];
    if (one_point[e] >= 0) {
      const OnePointHex& geo = one_point_geometry[one_point[e]];
      strain[e][0] = strain_one_point(geo, ue);
      if (!strain0.empty()) strain[e][0] += strain0[e][0];
      current[e][0] = core::small_strain_update(material, converged[e][0], strain[e][0]);
      add_stress_forces(geo, current[e][0].stress, fe);  // -f_int
      add_hourglass_forces(hourglass[one_point[e]], ue, fe);
      for (int a = 0; a < 8; ++a) force[h[a]] += fe[a];
      continue;
    }
    std::array<core::SymTensor, 8> sigma;
    for (int g = 0; g < 8; ++g) {
      strain[e][g] = strain_bbar(geometry[e], g, ue);
      if (!strain0.empty()) strain[e][g] += strain0[e][g];
      current[e][g] = core::small_strain_update(material, converged[e][g], strain[e][g]);
      sigma[g] = current[e][g].stress;
    }
    add_stress_forces_bbar(geometry[e], sigma, fe);  // -f_int
    for (int a = 0; a < 8; ++a) force[h[a]] += fe[a];
  }
  for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
    const Line& n = mesh.lines[l];
    line_strain[l] = core::dot(line_axis[l], at[n[1]] - at[n[0]]) / line_length[l];
    if (!line_strain0.empty()) line_strain[l] += line_strain0[l];
    line_current[l] = core::small_strain_bar_update(problem.materials[mesh.line_part[l]],
                                                    line_converged[l], line_strain[l]);
    const core::Vec3 f = (mesh.line_area[l] * line_current[l].stress) * line_axis[l];
    force[n[0]] += f;
    force[n[1]] -= f;
  }
}

std::array<std::array<double, 8>, 8> Body::mass(std::size_t e) const {
  const double r = 1.0 / std::sqrt(3.0);
  const double rho = problem.materials[mesh.hexahedron_part[e]].density;
  std::array<std::array<double, 8>, 8> m{};
  for (int g = 0; g < 8; ++g) {
    double n[8];
    for (int a = 0; a < 8; ++a) {
      n[a] = 0.125;
      for (int i = 0; i < 3; ++i) n[a] *= 1.0 + kHexNatural[a][i] * kHexNatural[g][i] * r;
    }
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b) m[a][b] += rho * geometry[e].weight[g] * n[a] * n[b];
  }
  return m;
}

void Body::assemble(SparseAssembly& assembly, double stiffness_factor, double mass_factor) const {
  assembly.clear();
  std::vector<double> t, kg;  // a tied line's T and T^T k T, reused line to line
  for (std::size_t e = 0; e < elements; ++e) {
    HexMatrix ke;
    if (one_point[e] >= 0) {
      hexahedron_stiffness_one_point(one_point_geometry[one_point[e]], current[e][0].tangent, ke);
      add_hourglass_stiffness_matrix(hourglass[one_point[e]], ke);
    } else {
      std::array<core::VoigtMatrix, 8> d;
      for (int g = 0; g < 8; ++g) d[g] = current[e][g].tangent;
      hexahedron_stiffness_bbar(geometry[e], d, ke);
    }
    for (double& k : ke) k *= stiffness_factor;
    if (mass_factor != 0.0) {
      const auto m = mass(e);
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b)
          for (int i = 0; i < 3; ++i) ke[24 * (3 * a + i) + 3 * b + i] += mass_factor * m[a][b];
    }
    walls->transform(mesh.hexahedra[e].data(), 8, ke.data());
    assembly.add(mesh.hexahedra[e], ke);
  }
  for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
    const double stiffness = line_current[l].tangent * mesh.line_area[l] / line_length[l];
    LineMatrix kl{};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j)
            kl[6 * (3 * a + i) + 3 * b + j] = (a == b ? 1.0 : -1.0) * stiffness_factor * stiffness *
                                              line_axis[l][i] * line_axis[l][j];
          kl[6 * (3 * a + i) + 3 * b + i] +=
              mass_factor * line_mass[l] * (a == b ? 2.0 : 1.0) / 6.0;
        }
    const std::vector<std::int32_t>& g = line_group[l];
    if (g.empty()) {
      walls->transform(mesh.lines[l].data(), 2, kl.data());
      assembly.add(mesh.lines[l], kl);
      continue;
    }
    // A tied node's dofs are its host's, weighted: k_g = T^T k T, T the line's dofs from the
    // group's (rows 3 a + i: its node's own column, or its host's with the weights).
    const std::size_t m = g.size();
    t.assign(6 * 3 * m, 0.0);
    kg.assign(9 * m * m, 0.0);
    for (std::size_t a = 0; a < 2; ++a) {
      const std::int32_t node = mesh.lines[l][a];
      const int tie = tie_of[static_cast<std::size_t>(node)];
      auto put = [&](std::int32_t n, double w) {
        const auto c = static_cast<std::size_t>(std::find(g.begin(), g.end(), n) - g.begin());
        for (std::size_t i = 0; i < 3; ++i) t[(3 * a + i) * 3 * m + 3 * c + i] += w;
      };
      if (tie < 0)
        put(node, 1.0);
      else
        for (std::size_t h = 0; h < 8; ++h)
          put(problem.tied[static_cast<std::size_t>(tie)].host[h],
              problem.tied[static_cast<std::size_t>(tie)].weight[h]);
    }
    for (std::size_t p = 0; p < 6; ++p)
      for (std::size_t q = 0; q < 6; ++q) {
        const double k = kl[6 * p + q];
        if (k == 0.0) continue;
        for (std::size_t r = 0; r < 3 * m; ++r) {
          const double tr = t[p * 3 * m + r];
          if (tr == 0.0) continue;
          for (std::size_t c = 0; c < 3 * m; ++c) kg[3 * m * r + c] += tr * k * t[q * 3 * m + c];
        }
      }
    walls->transform(g.data(), static_cast<int>(m), kg.data());
    assembly.add_group(g, kg.data());
  }
}

void Body::start_from_initial_state(const char* who) {
  const bool hexes = !problem.initial_stress.empty(), lines = !problem.initial_line_stress.empty();
  if ((hexes && (problem.initial_stress.size() != elements ||
                 problem.initial_plastic_strain.size() != elements)) ||
      (lines && (problem.initial_line_stress.size() != mesh.lines.size() ||
                 problem.initial_line_plastic_strain.size() != mesh.lines.size())))
    throw std::invalid_argument(std::string(who) +
                                ": the initial state needs a stress and a plastic strain per "
                                "hexahedron and per line (or none)");
  if (hexes) {
    // The stress sigma_0 = s_0 + m_0 I is reached from the elastic strain
    // eps_0 = m_0 / 3K I + s_0 / 2G (the bulk law K tr(eps) and the deviator kept).
    strain0.resize(elements);
    for (std::size_t e = 0; e < elements; ++e) {
      const core::Material& m = problem.materials[mesh.hexahedron_part[e]];
      const double k = m.bulk_modulus(), g = m.shear_modulus();
      for (int p = 0; p < points(e); ++p) {
        const core::SymTensor& sigma = problem.initial_stress[e][p];
        const core::SymTensor dev = sigma.deviator();
        strain0[e][p] =
            (sigma.trace() / (9.0 * k)) * core::SymTensor::identity() + (1.0 / (2.0 * g)) * dev;
        converged[e][p] = {strain0[e][p], dev, problem.initial_plastic_strain[e][p]};
        strain[e][p] = strain0[e][p];
        committed_stress[e][p] = sigma;
        current[e][p].stress = sigma;
        current[e][p].plastic_strain = problem.initial_plastic_strain[e][p];
      }
    }
  }
  if (lines) {
    line_strain0.resize(mesh.lines.size());
    for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
      const double sigma = problem.initial_line_stress[l];
      line_strain0[l] = sigma / problem.materials[mesh.line_part[l]].youngs_modulus;
      line_converged[l] = {line_strain0[l], sigma, problem.initial_line_plastic_strain[l]};
      line_strain[l] = line_strain0[l];
      line_current[l].stress = sigma;
      line_current[l].plastic_strain = problem.initial_line_plastic_strain[l];
    }
  }
}

void Body::commit() {
  for (std::size_t e = 0; e < elements; ++e)
    for (int g = 0; g < points(e); ++g) {
      work[e][g] += 0.5 * core::double_dot(committed_stress[e][g] + current[e][g].stress,
                                           strain[e][g] - converged[e][g].strain);
      committed_stress[e][g] = current[e][g].stress;
      converged[e][g] = {strain[e][g], current[e][g].stress.deviator(),
                         current[e][g].plastic_strain};
    }
  for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
    line_work[l] += 0.5 * (line_converged[l].stress + line_current[l].stress) *
                    (line_strain[l] - line_converged[l].strain);
    line_converged[l] = {line_strain[l], line_current[l].stress, line_current[l].plastic_strain};
  }
}

void Body::write_work(const std::vector<core::Vec3>& u, StaticWork& out) const {
  out.points.resize(elements);
  out.hourglass.assign(elements, 0.0);
  for (std::size_t e = 0; e < elements; ++e) {
    for (int g = 0; g < 8; ++g) out.points[e][g] = work[e][points(e) == 1 ? 0 : g];
    if (one_point[e] < 0) continue;
    HexVectors ue;
    for (int a = 0; a < 8; ++a) ue[a] = u[mesh.hexahedra[e][a]];
    out.hourglass[e] = hourglass_energy(hourglass[one_point[e]], ue);
  }
  out.lines = line_work;
}

void Body::write_states(std::vector<std::array<core::SymTensor, 8>>& stress,
                        std::vector<std::array<double, 8>>& plastic_strain,
                        std::vector<double>& line_stress, std::vector<double>& line_plastic_strain,
                        bool converged_only) const {
  stress.resize(elements);
  plastic_strain.resize(elements);
  for (std::size_t e = 0; e < elements; ++e)
    for (int g = 0; g < 8; ++g) {
      const int p = points(e) == 1 ? 0 : g;
      stress[e][g] = converged_only ? committed_stress[e][p] : current[e][p].stress;
      plastic_strain[e][g] =
          converged_only ? converged[e][p].plastic_strain : current[e][p].plastic_strain;
    }
  line_stress.resize(mesh.lines.size());
  line_plastic_strain.resize(mesh.lines.size());
  for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
    line_stress[l] = converged_only ? line_converged[l].stress : line_current[l].stress;
    line_plastic_strain[l] =
        converged_only ? line_converged[l].plastic_strain : line_current[l].plastic_strain;
  }
}

YieldingElement Body::most_yielding() const {
  YieldingElement out;
  auto consider = [&](YieldingElement::Kind kind, std::size_t index, std::int32_t part,
                      double increment) {
    if (increment <= out.plastic_strain_increment) return;
    out = {kind, static_cast<std::int32_t>(index), mesh.part_names[part], increment};
  };
  for (std::size_t e = 0; e < elements; ++e)
    for (int g = 0; g < points(e); ++g)
      consider(YieldingElement::Kind::hexahedron, e, mesh.hexahedron_part[e],
               current[e][g].plastic_strain - converged[e][g].plastic_strain);
  for (std::size_t l = 0; l < mesh.lines.size(); ++l)
    consider(YieldingElement::Kind::truss, l, mesh.line_part[l],
             line_current[l].plastic_strain - line_converged[l].plastic_strain);
  return out;
}

// Why a step's Newton solve failed: what happened ("did not converge in 25 iterations", "the
// tangent stiffness is not positive definite at ...") and the residual then. Caught by the
// solves, which add the step and the element that yields most.
struct NewtonFailure {
  int round = 0, iteration = 0;
  double residual = 0.0, reference = 0.0;
  std::string what;
};

// Newton-Raphson with line search to r(u) = 0 for one step: residual(at) sets r on the
// equations at displacement `at` and returns the force scale of the convergence test; the
// tangent is assembled by assemble(). Appends its rows to `iterations`; `log_name` ("static",
// "newmark") and steps name the step in the log. Returns the force scale at convergence.
// Throws NewtonFailure.
template <class Residual, class Assemble>
double newton(const Body& body, const NewtonSettings& settings, const char* log_name, int step,
              int steps, int round, SparseAssembly& assembly, SparseCholesky& cholesky,
              std::vector<core::Vec3>& u, std::vector<double>& r, Residual&& residual,
              Assemble&& assemble, std::vector<NewtonIteration>& iterations) {
  const int equations = body.equations;
  const int contacts = body.walls->contacts();
  std::vector<double> du(equations), b(equations);
  std::vector<core::Vec3> trial(u.size());
  auto record = [&](const NewtonIteration& it) {
    iterations.push_back(it);
    if (!settings.log) return;
    *settings.log << log_name << " step " << it.load_step << "/" << steps << " iteration "
                  << it.iteration << ": residual " << it.residual << " (relative "
                  << (it.reference > 0.0 ? it.residual / it.reference : 0.0) << "), energy "
                  << it.energy << ", step length " << it.step_length;
    if (!body.walls->empty())
      *settings.log << " (solve " << it.round << ", " << it.contacts << " nodes on walls)";
    *settings.log << '\n';
  };
  double reference = residual(u), first_energy = 0.0, last_energy = 0.0;
  bool moved = true;  // whether the last correction changed u: below round-off it cannot
  // A residual this small is round-off (the sums that form it cancel to it): no iteration can
  // lower it, nor the energy of its correction, whose ratio to a first energy that was itself
  // small (a step the predictor nearly solved) may then stay above the energy tolerance.
  constexpr double kRoundOff = 1e3 * std::numeric_limits<double>::epsilon();
  for (int k = 0;; ++k) {
    const double rnorm = norm(r), scale = reference;
    if (rnorm <= settings.residual_tolerance * reference &&
        (k == 0 || last_energy <= settings.energy_tolerance * first_energy || !moved ||
         rnorm <= kRoundOff * reference)) {
      record({step, round, k, rnorm, scale, 0.0, 0.0, contacts});
      return scale;
    }
    if (k == settings.max_iterations)
      throw NewtonFailure{round, k, rnorm, scale,
                          "did not converge in " + std::to_string(k) + " iterations" +
                              format(" (last energy %.3g, %.3g of the first)", last_energy,
                                     last_energy / first_energy, 0.0)};

    assemble();
    try {
      cholesky.factorise(assembly.matrix());
    } catch (const NotPositiveDefinite& npd) {
      const int dof = body.dof_of[npd.column()];
      const std::size_t node = static_cast<std::size_t>(dof) / 3;
      throw NewtonFailure{
          round, k, rnorm, scale,
          "the tangent stiffness is not positive definite at " + node_name(body.mesh, node) +
              ", component " +
              (body.walls->frame(node) ? std::to_string(dof % 3) + " of its frame on a wall"
                                       : std::string(kAxis[dof % 3])) +
              " (a mechanism, a material that softens, or a load past the limit load)"};
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
      body.add_correction(du, s, trial);
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
    moved = !std::equal(u.begin(), u.end(), trial.begin(),
                        [](const core::Vec3& p, const core::Vec3& q) {
                          return p.x == q.x && p.y == q.y && p.z == q.z;
                        });
    u.swap(trial);
    record({step, round, k, rnorm, scale, energy, s, contacts});
  }
}

// One step to equilibrium with the walls' active set settled: Newton solves, each from the
// nodes of the set moved onto their planes, until the converged state changes the set no more
// (`nodal` is the residual per node that residual() leaves, the walls' reactions read from
// it; start() runs before each solve, the set then known). Returns the force scale at
// convergence. Throws NewtonFailure.
template <class Residual, class Assemble, class Start>
double settle(Body& body, const NewtonSettings& settings, const char* log_name, int step, int steps,
              SparseAssembly& assembly, SparseCholesky& cholesky, std::vector<core::Vec3>& u,
              std::vector<double>& r, const std::vector<core::Vec3>& nodal, Residual&& residual,
              Assemble&& assemble, Start&& start, std::vector<NewtonIteration>& iterations) {
  for (int round = 0;; ++round) {
    body.walls->project(u);
    start();
    const double scale = newton(body, settings, log_name, step, steps, round, assembly, cholesky, u,
                                r, residual, assemble, iterations);
    std::string change;
    if (!body.walls->update(u, nodal, settings.residual_tolerance * scale, change)) return scale;
    if (round + 1 == settings.max_contact_rounds)
      throw NewtonFailure{round, iterations.back().iteration, iterations.back().residual, scale,
                          "the walls' active set did not settle in " +
                              std::to_string(settings.max_contact_rounds) +
                              " Newton solves (the last: " + change + ")"};
  }
}

// "hexahedron 12 of part 'bar' (plastic strain increment 0.0123 in this step)".
std::string describe(const YieldingElement& y) {
  if (y.kind == YieldingElement::Kind::none) return "no element yields in this step";
  return std::string("the element that yields most: ") +
         (y.kind == YieldingElement::Kind::hexahedron ? "hexahedron " : "truss (line) ") +
         std::to_string(y.index) + " of part '" + y.part + "'" +
         format(" (plastic strain increment %.3g in this step)", y.plastic_strain_increment, 0, 0);
}

// "static solve: load step 3 of 5, iteration 25: did not converge ...; residual ... (... of the
// force scale; tolerance ...); the element that yields most: ...".
std::string step_failure(const char* who, const char* step_name, int step, int steps,
                         const NewtonFailure& f, double tolerance, const YieldingElement& y) {
  return std::string(who) + ": " + step_name + " " + std::to_string(step) + " of " +
         std::to_string(steps) + ", iteration " + std::to_string(f.iteration) +
         (f.round > 0 ? " of Newton solve " + std::to_string(f.round + 1) +
                            " (the walls' set changed before it)"
                      : std::string()) +
         ": " + f.what +
         format("; residual %.3g (%.3g of the force scale; tolerance %.3g); ", f.residual,
                f.reference > 0.0 ? f.residual / f.reference : 0.0, tolerance) +
         describe(y);
}

}  // namespace

StaticFailure::StaticFailure(const std::string& what, StaticFailureDetails details)
    : std::runtime_error(what),
      details_(std::make_shared<const StaticFailureDetails>(std::move(details))) {}

NewmarkFailure::NewmarkFailure(const std::string& what, NewmarkResult last_converged)
    : std::runtime_error(what),
      last_(std::make_shared<const NewmarkResult>(std::move(last_converged))) {}

StaticResult solve_static(const StaticProblem& problem, const NewtonSettings& settings) {
  Body body(problem, "static solve", true);
  std::vector<core::Vec3> u(body.nodes), force(body.nodes), nodal(body.nodes);
  std::vector<double> r(body.equations);
  double load = 0.0;

  // r = load f_ext - f_int(u) on the equations; returns max(||load f_ext||, ||reactions||).
  // The loads at load factor `load`: load f_ext from a virgin start; from an initial state,
  // (1 - load) f_int(0) + load f_ext, the start's own internal forces turned into the loads over
  // the steps (LS-DYNA's springback imbalance), so that no step unloads what the state holds.
  body.internal_forces(u, force);
  const std::vector<core::Vec3> start_force = force;  // -f_int(0)
  auto residual = [&](const std::vector<core::Vec3>& at) {
    body.internal_forces(at, force);
    double external = 0.0;
    for (std::size_t n = 0; n < body.nodes; ++n) {
      const core::Vec3 f = load * body.f_ext[n] - (1.0 - load) * start_force[n];
      external += core::dot(f, f);
      nodal[n] = f + force[n];
    }
    return std::sqrt(std::max(external, body.gather(nodal, r)));
  };
  // Per prescribed dof, f_int - f_ext there (the reaction) at the state that nodal holds.
  auto reactions = [&](std::vector<double>& out) {
    out.resize(problem.prescribed.size());
    for (std::size_t k = 0; k < out.size(); ++k)
      out[k] = -nodal[problem.prescribed[k].node][problem.prescribed[k].component];
  };

  SparseAssembly assembly(problem.mesh->hexahedra, problem.mesh->lines, body.equation,
                          body.equations, body.line_group);
  SparseCholesky cholesky(settings.blas_threads);
  cholesky.analyse(assembly.matrix());
  // The state after the last converged step (the virgin one before the first).
  StaticResult last;
  last.displacement = u;
  body.write_states(last.stress, last.plastic_strain, last.line_stress, last.line_plastic_strain);
  body.write_work(u, last.work);  // none yet: a first load step that fails hands on this state
  last.wall_force.assign(body.walls->size(), core::Vec3{});
  for (std::size_t n = 0; n < body.nodes; ++n) nodal[n] = body.f_ext[n] + start_force[n];
  reactions(last.start_reaction);
  last.reaction.assign(problem.prescribed.size(), 0.0);
  std::vector<NewtonIteration> iterations;
  for (int step = 1; step <= settings.load_steps; ++step) {
    load = static_cast<double>(step) / settings.load_steps;
    for (const PrescribedDisplacement& p : problem.prescribed)
      u[p.node][p.component] = load * p.value;
    body.follow(u);
    try {
      settle(
          body, settings, "static", step, settings.load_steps, assembly, cholesky, u, r, nodal,
          residual, [&] { body.assemble(assembly, 1.0, 0.0); }, [] {}, iterations);
    } catch (const NewtonFailure& f) {
      StaticFailureDetails details{step,
                                   settings.load_steps,
                                   f.round,
                                   f.iteration,
                                   f.residual,
                                   f.reference,
                                   settings.residual_tolerance,
                                   body.most_yielding(),
                                   last};
      details.last_converged.iterations = iterations;
      const std::string what =
          step_failure("static solve", "load step", step, settings.load_steps, f,
                       settings.residual_tolerance, details.most_yielding) +
          format(". Load factor %.4g; the last converged step's (load factor %.4g) state is kept",
                 load, last.load_factor, 0.0);
      throw StaticFailure(what, std::move(details));
    }
    body.commit();
    last.load_factor = load;
    last.displacement = u;
    body.write_states(last.stress, last.plastic_strain, last.line_stress, last.line_plastic_strain);
    body.write_work(u, last.work);
    last.wall_force = body.walls->forces(nodal);
    reactions(last.reaction);
  }
  last.iterations = std::move(iterations);
  return last;
}

NewmarkResult solve_newmark(const StaticProblem& problem, const NewmarkSettings& settings) {
  if (!(settings.time_step > 0.0) || settings.steps < 0)
    throw std::invalid_argument("newmark solve: needs a positive time step and steps >= 0");
  if (!(settings.alpha >= -1.0 / 3.0 && settings.alpha <= 0.0))
    throw std::invalid_argument(
        format("newmark solve: HHT alpha %g outside [-1/3, 0]", settings.alpha, 0, 0));
  Body body(problem, "newmark solve", false);
  const std::size_t nodes = body.nodes;
  if ((!settings.initial_displacement.empty() && settings.initial_displacement.size() != nodes) ||
      (!settings.initial_velocity.empty() && settings.initial_velocity.size() != nodes))
    throw std::invalid_argument(
        "newmark solve: initial displacement and velocity need one "
        "vector per node (or none)");
  const double dt = settings.time_step, alpha = settings.alpha;
  const double beta = 0.25 * (1.0 - alpha) * (1.0 - alpha), gamma = 0.5 - alpha;

  std::vector<core::Vec3> u(nodes), v(nodes), a(nodes), u_star(nodes), force(nodes), force_n(nodes),
      ma(nodes), accel(nodes), nodal(nodes), predicted(nodes);
  if (!settings.initial_displacement.empty()) u = settings.initial_displacement;
  if (!settings.initial_velocity.empty()) v = settings.initial_velocity;
  // The prescribed dofs at their values at t = 0: held there at rest, or moving from there at
  // their initial velocities.
  std::vector<double> values(problem.prescribed.size());
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = problem.prescribed[k].value;
  if (settings.prescribed_values) {
    settings.prescribed_values(0.0, values);
    if (values.size() != problem.prescribed.size())
      throw std::invalid_argument("newmark solve: prescribed_values gave " +
                                  std::to_string(values.size()) + " values for " +
                                  std::to_string(problem.prescribed.size()) + " prescribed dofs");
  }
  for (std::size_t k = 0; k < values.size(); ++k) {
    const PrescribedDisplacement& p = problem.prescribed[k];
    u[p.node][p.component] = values[k];
    if (!settings.prescribed_values) v[p.node][p.component] = 0.0;
  }
  body.walls->start(u);
  body.walls->project(u);
  body.follow(u);
  body.follow(v);
  std::vector<double> r(body.equations);

  auto mass_times = [&](const std::vector<core::Vec3>& x, std::vector<core::Vec3>& mx) {
    std::fill(mx.begin(), mx.end(), core::Vec3{});
    for (std::size_t e = 0; e < body.elements; ++e) {
      const Hexahedron& h = problem.mesh->hexahedra[e];
      const auto m = body.mass(e);
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) mx[h[i]] += m[i][j] * x[h[j]];
    }
    for (std::size_t l = 0; l < problem.mesh->lines.size(); ++l) {
      const Line& n = problem.mesh->lines[l];
      const double m = body.line_mass[l] / 6.0;
      mx[n[0]] += m * (2.0 * x[n[0]] + x[n[1]]);
      mx[n[1]] += m * (x[n[0]] + 2.0 * x[n[1]]);
    }
  };
  auto energies = [&](double time) {
    mass_times(v, ma);
    NewmarkState state{time, 0.0, 0.0, 0.0, {}};
    for (std::size_t n = 0; n < nodes; ++n) state.kinetic_energy += 0.5 * core::dot(v[n], ma[n]);
    // Stored elastic energy p^2 / (2K) + s:s / (4G) per unit volume, and a one-point element's
    // hourglass energy.
    for (std::size_t e = 0; e < body.elements; ++e) {
      const core::Material& m = problem.materials[problem.mesh->hexahedron_part[e]];
      const int one_point = body.one_point[e];
      for (int g = 0; g < body.points(e); ++g) {
        const core::SymTensor& s = body.current[e][g].stress;
        const double p = s.trace() / 3.0;
        const core::SymTensor dev = s.deviator();
        const double volume =
            one_point >= 0 ? body.one_point_geometry[one_point].volume : body.geometry[e].weight[g];
        state.strain_energy += volume * (p * p / (2.0 * m.bulk_modulus()) +
                                         core::double_dot(dev, dev) / (4.0 * m.shear_modulus()));
      }
      if (one_point >= 0) {
        HexVectors ue;
        for (int corner = 0; corner < 8; ++corner)
          ue[corner] = u[problem.mesh->hexahedra[e][corner]];
        state.strain_energy += hourglass_energy(body.hourglass[one_point], ue);
      }
    }
    for (std::size_t l = 0; l < problem.mesh->lines.size(); ++l) {
      const double sigma = body.line_current[l].stress;
      state.strain_energy += problem.mesh->line_area[l] * body.line_length[l] * sigma * sigma /
                             (2.0 * problem.materials[problem.mesh->line_part[l]].youngs_modulus);
    }
    return state;
  };

  SparseAssembly assembly(problem.mesh->hexahedra, problem.mesh->lines, body.equation,
                          body.equations, body.line_group);
  SparseCholesky cholesky(settings.newton.blas_threads);
  cholesky.analyse(assembly.matrix());

  // a_0 = M^-1 (f_ext - f_int(u_0)) on the free dofs (zero along the walls' held normals).
  body.internal_forces(u, force);
  force_n = force;
  body.assemble(assembly, 0.0, 1.0);
  cholesky.factorise(assembly.matrix());
  {
    std::vector<double> b(body.equations), x(body.equations);
    for (std::size_t n = 0; n < nodes; ++n) nodal[n] = body.f_ext[n] + force[n];
    body.gather(nodal, b);
    cholesky.solve(b, x);
    body.add_correction(x, 1.0, a);
    mass_times(a, ma);
    for (std::size_t n = 0; n < nodes; ++n) nodal[n] -= ma[n];
  }
  body.commit();

  // The reactions at the prescribed dofs at the state reached, M a + f_int - f_ext there (not
  // HHT's residual, whose internal force is a mix of the step's two ends), for their work.
  std::vector<double> reaction(values.size()), reaction_before(values.size());
  auto reactions = [&](std::vector<double>& out) {
    for (std::size_t k = 0; k < values.size(); ++k) {
      const PrescribedDisplacement& p = problem.prescribed[k];
      const auto n = static_cast<std::size_t>(p.node);
      out[k] = body.in_element[n]
                   ? ma[n][p.component] - force[n][p.component] - body.f_ext[n][p.component]
                   : 0.0;
    }
  };
  reactions(reaction);
  double external_work = 0.0;
  std::vector<core::Vec3> u_before(nodes);

  NewmarkResult out;
  out.states.push_back(energies(0.0));
  out.states.back().wall_force = body.walls->forces(nodal);
  if (settings.observe) settings.observe(0.0, u);
  // r = f_ext + (1 + alpha) (-f_int(u)) - alpha (-f_int(u_n)) - M a(u),
  // a(u) = (u - u_star) / (beta dt^2), u_star = u_n + dt v_n + dt^2 (1/2 - beta) a_n (but along
  // the normals of the nodes on walls: stop_on_walls).
  auto residual = [&](const std::vector<core::Vec3>& at) {
    body.internal_forces(at, force);
    for (std::size_t n = 0; n < nodes; ++n)
      accel[n] = (1.0 / (beta * dt * dt)) * (at[n] - u_star[n]);
    mass_times(accel, ma);
    double external = 0.0, internal = 0.0, inertia = 0.0;
    for (std::size_t n = 0; n < nodes; ++n) {
      if (!body.in_element[n]) continue;
      const core::Vec3 &f = body.f_ext[n], &fi = force[n], &mi = ma[n];
      external += core::dot(f, f);
      internal += core::dot(fi, fi);
      inertia += core::dot(mi, mi);
      nodal[n] = f + (1.0 + alpha) * fi - alpha * force_n[n] - mi;
    }
    body.gather(nodal, r);
    return std::sqrt(std::max({external, internal, inertia}));
  };
  // u_star of the step's set (before each of its Newton solves): a node on a wall stops on it
  // within the step, along its held normals h the acceleration that brings its velocity to zero
  // at the step's end, a.h = -(v_n + (1 - gamma) dt a_n).h / (gamma dt) (zero for a node at
  // rest on the wall), set through u_star so that a(u) = (u - u_star) / (beta dt^2) gives it at
  // the held displacement. A node that arrives thus couples to its neighbours through the
  // consistent mass as a stopping node, not with the rule's rebound from its unheld predictor
  // (which reverses its velocity, then chatters, and gains energy).
  auto stop_on_walls = [&] {
    u_star = predicted;
    for (std::size_t n = 0; n < nodes; ++n) {
      const NodeFrame* f = body.walls->frame(n);
      for (int j = 0; f && j < f->held; ++j) {
        const core::Vec3& h = f->basis[f->slot[j]];
        const double stop =
            -(core::dot(h, v[n]) + (1.0 - gamma) * dt * core::dot(h, a[n])) / (gamma * dt);
        u_star[n] += (core::dot(h, u[n] - u_star[n]) - beta * dt * dt * stop) * h;
      }
    }
  };
  for (int step = 1; step <= settings.steps; ++step) {
    u_before = u;
    for (std::size_t n = 0; n < nodes; ++n)
      predicted[n] = u[n] + dt * v[n] + ((0.5 - beta) * dt * dt) * a[n];
    for (std::size_t n = 0; n < nodes; ++n) u[n] = predicted[n] + (beta * dt * dt) * a[n];
    if (settings.prescribed_values) {
      settings.prescribed_values(step * dt, values);
      for (std::size_t k = 0; k < values.size(); ++k)
        u[problem.prescribed[k].node][problem.prescribed[k].component] = values[k];
    }
    body.follow(u);
    try {
      settle(
          body, settings.newton, "newmark", step, settings.steps, assembly, cholesky, u, r, nodal,
          residual, [&] { body.assemble(assembly, 1.0 + alpha, 1.0 / (beta * dt * dt)); },
          stop_on_walls, out.iterations);
    } catch (const NewtonFailure& f) {
      // The state after the last converged step: its displacements and velocities, and the
      // points' converged states.
      out.displacement = u_before;
      out.velocity = v;
      body.write_states(out.stress, out.plastic_strain, out.line_stress, out.line_plastic_strain,
                        true);
      body.write_work(u_before, out.work);
      const std::string what =
          step_failure("newmark solve", "time step", step, settings.steps, f,
                       settings.newton.residual_tolerance, body.most_yielding()) +
          "; the state after time step " + std::to_string(step - 1) +
          format(" (t = %.6g) is kept", (step - 1) * dt, 0.0, 0.0);
      throw NewmarkFailure(what, std::move(out));
    }
    for (std::size_t n = 0; n < nodes; ++n) {
      const core::Vec3 a_next = (1.0 / (beta * dt * dt)) * (u[n] - u_star[n]);
      v[n] += dt * ((1.0 - gamma) * a[n] + gamma * a_next);
      a[n] = a_next;
    }
    body.walls->stop(v, a);
    body.follow(v);
    body.follow(a);
    force_n = force;
    body.commit();
    // The work of the loads (constant) and of the reactions (linear over the step).
    reaction_before.swap(reaction);
    reactions(reaction);
    for (std::size_t n = 0; n < nodes; ++n)
      if (body.in_element[n]) external_work += core::dot(body.f_ext[n], u[n] - u_before[n]);
    for (std::size_t k = 0; k < values.size(); ++k) {
      const PrescribedDisplacement& p = problem.prescribed[k];
      external_work += 0.5 * (reaction_before[k] + reaction[k]) *
                       (u[p.node][p.component] - u_before[p.node][p.component]);
    }
    out.states.push_back(energies(step * dt));
    out.states.back().external_work = external_work;
    out.states.back().wall_force = body.walls->forces(nodal);
    if (settings.observe) settings.observe(step * dt, u);
  }
  out.displacement = u;
  out.velocity = v;
  body.write_states(out.stress, out.plastic_strain, out.line_stress, out.line_plastic_strain);
  body.write_work(u, out.work);
  return out;
}

}  // namespace afemp::fem
