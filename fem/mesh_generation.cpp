// Structured mesh generators (fem/mesh_generation.hpp). The cylinder is the usual O-grid
// (Thompson, Soni & Weatherill, Handbook of Grid Generation, ch. 3, transfinite interpolation):
// a core patch from its four bowed sides, a ring blended linearly from the core's side to the arc.
#include "fem/mesh_generation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace afemp::fem {

namespace {

constexpr const char* kAxisName[3] = {"x", "y", "z"};

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

// Node and element indices are 32-bit (fem/mesh.hpp).
void require_32bit_indices(std::int64_t count, const char* generator) {
  require(count <= std::numeric_limits<std::int32_t>::max(),
          std::string(generator) + ": " + std::to_string(count) +
              " nodes exceed the 32-bit indices of a mesh; use fewer divisions");
}

MeshData one_part_mesh() {
  MeshData m;
  m.part_names = {"mesh"};
  return m;
}

// Straight 2-node trusses from a to b, appended to m in part `part`.
void append_bar(MeshData& m, core::Vec3 a, core::Vec3 b, int segments, double area,
                std::int32_t part) {
  const auto first = static_cast<std::int32_t>(m.nodes.size());
  for (int s = 0; s <= segments; ++s) {
    const double f = static_cast<double>(s) / segments;
    m.nodes.push_back({std::lerp(a.x, b.x, f), std::lerp(a.y, b.y, f), std::lerp(a.z, b.z, f)});
  }
  for (int s = 0; s < segments; ++s) {
    m.lines.push_back({first + s, first + s + 1});
    m.line_part.push_back(part);
    m.line_area.push_back(area);
  }
}

// The cross-section of an O-grid cylinder in its local (x, y) plane.
struct Section {
  std::vector<std::array<double, 2>> points;
  std::vector<std::array<std::int32_t, 4>> quads;  // counter-clockwise seen from +z
  std::vector<bool> on_surface, on_cut_0, on_cut_1;
};

// Lays out the whole disc, n = n_core: core node (i, j) at i + (n + 1) j; ring node (k, r),
// r = 1..n_ring outward, k = 0..4n - 1 counter-clockwise from the core corner at -45 degrees, at
// (n + 1)^2 + k n_ring + r - 1. Then keeps the quads of the sector and the nodes they use.
Section o_grid_section(double radius, int n, int n_ring, int sectors) {
  // Bowing each core side by this fraction of the half-width at its middle opens the core's
  // corners to 120 degrees, so the three elements meeting there share the turn equally
  // (corner scaled Jacobian sin 120 = 0.87, against sin 135 = 0.71 for a straight square core).
  const double bulge = 1.0 - std::sqrt(3.0) / 2.0;
  // Half-width a that makes the core spacing 2 a (1 + 2/3 bulge) / n_core equal the mean ring
  // thickness (R - a (1 + bulge + sqrt 2) / 2) / n_ring; kept within 0.35..0.6 R so that neither
  // the core nor the ring's corner elements (thickness R - a sqrt 2) are squeezed.
  const double core_spacing = 2.0 * (1.0 + 2.0 * bulge / 3.0) / n;
  const double ring_inner = (1.0 + bulge + std::numbers::sqrt2) / 2.0;
  const double a = radius * std::clamp(1.0 / (ring_inner + core_spacing * n_ring), 0.35, 0.6);

  const int core_nodes = (n + 1) * (n + 1);
  const int around = 4 * n;
  const int full = core_nodes + around * n_ring;
  std::vector<std::array<double, 2>> p(static_cast<std::size_t>(full));
  std::vector<bool> surface(p.size()), cut_0(p.size()), cut_1(p.size());
  // (2i - n) / n is exactly antisymmetric about the midline, so mirrored nodes mirror exactly.
  auto logical = [n](int i) { return static_cast<double>(2 * i - n) / n; };
  auto core = [n](int i, int j) { return i + (n + 1) * j; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double s = logical(i), t = logical(j);
      // Transfinite interpolation of the four parabolic sides x = +-a (1 + bulge (1 - t^2)).
      p[core(i, j)] = {a * s * (1.0 + bulge * (1.0 - t * t)),
                       a * t * (1.0 + bulge * (1.0 - s * s))};
      cut_0[core(i, j)] = 2 * j == n;
      cut_1[core(i, j)] = 2 * i == n;
    }
  // Each side is built as the side at +x (local angle -45..45 degrees), turned by quarter turns
  // (x, y) -> (-y, x), which are exact: the cut-plane nodes get exact zeros.
  for (int k = 0; k < around; ++k) {
    const int side = k / n;
    const double t = logical(k % n);
    const std::array<double, 2> inner{a * (1.0 + bulge * (1.0 - t * t)), a * t};
    const double angle = std::numbers::pi / 4.0 * t;
    const std::array<double, 2> outer{radius * std::cos(angle), radius * std::sin(angle)};
    for (int r = 1; r <= n_ring; ++r) {
      const double f = static_cast<double>(r) / n_ring;
      std::array<double, 2> q{std::lerp(inner[0], outer[0], f), std::lerp(inner[1], outer[1], f)};
      for (int turn = 0; turn < side; ++turn) q = {-q[1], q[0]};
      const int index = core_nodes + k * n_ring + r - 1;
      p[index] = q;
      surface[index] = r == n_ring;
      cut_0[index] = 2 * k == n || 2 * k == 5 * n;
      cut_1[index] = 2 * k == 3 * n;
    }
  }
  auto ring = [&](int k, int r) {
    k %= around;
    if (r > 0) return core_nodes + k * n_ring + r - 1;
    const int m = k % n;
    switch (k / n) {  // the core's boundary, walked counter-clockwise
      case 0:
        return core(n, m);
      case 1:
        return core(n - m, n);
      case 2:
        return core(0, n - m);
      default:
        return core(m, 0);
    }
  };

  std::vector<std::array<std::int32_t, 4>> quads;
  const int i0 = sectors == 1 ? n / 2 : 0;
  const int j0 = sectors == 4 ? 0 : n / 2;
  const int k0 = sectors == 4 ? 0 : n / 2;  // local angle 0 is the middle of the +x side
  for (int j = j0; j < n; ++j)
    for (int i = i0; i < n; ++i)
      quads.push_back({core(i, j), core(i + 1, j), core(i + 1, j + 1), core(i, j + 1)});
  for (int k = k0; k < k0 + sectors * n; ++k)
    for (int r = 0; r < n_ring; ++r)
      quads.push_back({ring(k, r), ring(k, r + 1), ring(k + 1, r + 1), ring(k + 1, r)});

  std::vector<std::int32_t> renumber(p.size(), -1);
  for (const auto& q : quads)
    for (std::int32_t v : q) renumber[v] = 0;
  Section section;
  for (std::size_t v = 0; v < p.size(); ++v) {
    if (renumber[v] < 0) continue;
    renumber[v] = static_cast<std::int32_t>(section.points.size());
    section.points.push_back(p[v]);
    section.on_surface.push_back(surface[v]);
    section.on_cut_0.push_back(cut_0[v]);
    section.on_cut_1.push_back(cut_1[v]);
  }
  for (auto q : quads) {
    for (std::int32_t& v : q) v = renumber[v];
    section.quads.push_back(q);
  }
  return section;
}

}  // namespace

MeshData box_mesh(const core::BoxShape& box, std::array<int, 3> n) {
  std::array<std::vector<double>, 3> lines;
  for (int d = 0; d < 3; ++d) {
    require(n[d] >= 1, std::string("box mesh: divisions must be at least 1 along each axis; got ") +
                           std::to_string(n[d]) + " along " + kAxisName[d]);
    require(box.max[d] > box.min[d],
            std::string("box mesh: the box's max must exceed its min along ") + kAxisName[d]);
    lines[static_cast<std::size_t>(d)] = graded_lines(box.min[d], {{box.max[d], double(n[d])}});
  }
  return box_mesh(lines);
}

std::vector<double> graded_lines(double lo, const std::vector<std::array<double, 2>>& segments) {
  std::vector<double> lines{lo};
  double start = lo;
  for (const auto& [end, elements] : segments) {
    const int n = static_cast<int>(elements);
    for (int i = 1; i <= n; ++i) lines.push_back(std::lerp(start, end, static_cast<double>(i) / n));
    start = end;
  }
  return lines;
}

MeshData box_mesh(const std::array<std::vector<double>, 3>& lines) {
  std::array<int, 3> n{};
  for (int d = 0; d < 3; ++d) {
    const std::vector<double>& l = lines[static_cast<std::size_t>(d)];
    require(l.size() >= 2, std::string("box mesh: at least one element along ") + kAxisName[d]);
    for (std::size_t i = 1; i < l.size(); ++i)
      require(l[i] > l[i - 1],
              std::string("box mesh: the node planes must increase along ") + kAxisName[d]);
    n[d] = static_cast<int>(l.size()) - 1;
  }
  require_32bit_indices(std::int64_t{n[0] + 1} * (n[1] + 1) * (n[2] + 1), "box mesh");
  MeshData m = one_part_mesh();
  for (const char* name : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"})
    m.node_sets.push_back({name, {}});
  auto node = [&n](int i, int j, int k) { return i + (n[0] + 1) * (j + (n[1] + 1) * k); };
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) {
        const std::array<int, 3> ijk{i, j, k};
        core::Vec3 x;
        for (int d = 0; d < 3; ++d) {
          x[d] = lines[static_cast<std::size_t>(d)][static_cast<std::size_t>(ijk[d])];
          if (ijk[d] == 0) m.node_sets[2 * d].members.push_back(node(i, j, k));
          if (ijk[d] == n[d]) m.node_sets[2 * d + 1].members.push_back(node(i, j, k));
        }
        m.nodes.push_back(x);
      }
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        m.hexahedra.push_back({node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                               node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                               node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)});
        m.hexahedron_part.push_back(0);
      }
  return m;
}

MeshData sphere_mesh(const core::SphereShape& s, int n, int sectors) {
  require(s.radius > 0.0 && std::isfinite(s.radius), "sphere mesh: the radius must be positive");
  require(n >= 4 && n % 4 == 0, "sphere mesh: the divisions across must be a multiple of 4");
  require(sectors == 1 || sectors == 2 || sectors == 4,
          "sphere mesh: sectors must be 1 (quarter), 2 (half) or 4 (whole)");
  const int nc = n / 2, nr = n / 4, h = nc / 2;  // core lattice, shell layers
  require_32bit_indices(
      std::int64_t{nc + 1} * (nc + 1) * (nc + 1) + std::int64_t{6} * (nc + 1) * (nc + 1) * nr,
      "sphere mesh");
  const double a = 0.5 * s.radius;  // the core's half-width (before the bow)
  // Nodes by key: a core lattice point (i, j, k) in [-h, h]^3 and a layer l (0: the core; 1..nr:
  // along the ray from a core-surface point to the sphere).
  std::map<std::array<int, 4>, std::int32_t> id;
  std::vector<core::Vec3> x;
  auto node = [&](int i, int j, int k, int l) {
    const std::array<int, 4> key{i, j, k, l};
    const auto it = id.find(key);
    if (it != id.end()) return it->second;
    const core::Vec3 q{static_cast<double>(i) / h, static_cast<double>(j) / h,
                       static_cast<double>(k) / h};
    const double t = static_cast<double>(l) / nr;
    // The core bowed halfway to a sphere at its surface (cubic at the centre), so the rays from
    // its corners are not much shorter than those from its faces' centres.
    const double mq = std::max({std::abs(q.x), std::abs(q.y), std::abs(q.z)}), len = core::norm(q);
    const core::Vec3 c = len > 0.0 ? (a * ((1.0 - 0.5 * mq) + 0.5 * mq * mq / len)) * q : q;
    const core::Vec3 p = l == 0 ? c : (1.0 - t) * c + (t * s.radius / len) * q;
    const auto n_id = static_cast<std::int32_t>(x.size());
    x.push_back(s.centre + p);
    id.emplace(key, n_id);
    return n_id;
  };
  std::vector<std::array<std::int32_t, 8>> hexes;
  std::vector<core::Vec3> centroid;
  auto add = [&](std::array<std::int32_t, 8> e) {
    // Node order of a positive volume: the first face counter-clockwise seen from the second.
    const core::Vec3 d1 = x[static_cast<std::size_t>(e[1])] - x[static_cast<std::size_t>(e[0])];
    const core::Vec3 d2 = x[static_cast<std::size_t>(e[3])] - x[static_cast<std::size_t>(e[0])];
    const core::Vec3 d3 = x[static_cast<std::size_t>(e[4])] - x[static_cast<std::size_t>(e[0])];
    if (core::dot(core::cross(d1, d2), d3) < 0.0) {
      std::swap(e[1], e[3]);
      std::swap(e[5], e[7]);
    }
    core::Vec3 c;
    for (std::int32_t k : e) c += 0.125 * x[static_cast<std::size_t>(k)];
    hexes.push_back(e);
    centroid.push_back(c);
  };
  for (int k = -h; k < h; ++k)
    for (int j = -h; j < h; ++j)
      for (int i = -h; i < h; ++i)
        add({node(i, j, k, 0), node(i + 1, j, k, 0), node(i + 1, j + 1, k, 0), node(i, j + 1, k, 0),
             node(i, j, k + 1, 0), node(i + 1, j, k + 1, 0), node(i + 1, j + 1, k + 1, 0),
             node(i, j + 1, k + 1, 0)});
  // The six shells: face (axis d, side +-h), its quads (u, v) in the other two axes.
  for (int d = 0; d < 3; ++d)
    for (int side : {-h, h})
      for (int u = -h; u < h; ++u)
        for (int v = -h; v < h; ++v)
          for (int l = 0; l < nr; ++l) {
            auto at = [&](int du, int dv, int dl) {
              std::array<int, 3> c{};
              c[static_cast<std::size_t>(d)] = side;
              c[static_cast<std::size_t>((d + 1) % 3)] = u + du;
              c[static_cast<std::size_t>((d + 2) % 3)] = v + dv;
              return node(c[0], c[1], c[2], l + dl);
            };
            add({at(0, 0, 0), at(1, 0, 0), at(1, 1, 0), at(0, 1, 0), at(0, 0, 1), at(1, 0, 1),
                 at(1, 1, 1), at(0, 1, 1)});
          }
  // Keep the sectors' elements and the nodes they use.
  MeshData m = one_part_mesh();
  std::vector<std::int32_t> renumber(x.size(), -1);
  for (std::size_t e = 0; e < hexes.size(); ++e) {
    const core::Vec3 c = centroid[e] - s.centre;
    if ((sectors == 1 && c.x < 0.0) || (sectors != 4 && c.y < 0.0)) continue;
    std::array<std::int32_t, 8> kept;
    for (std::size_t a8 = 0; a8 < 8; ++a8) {
      std::int32_t& r = renumber[static_cast<std::size_t>(hexes[e][a8])];
      if (r < 0) {
        r = static_cast<std::int32_t>(m.nodes.size());
        m.nodes.push_back(x[static_cast<std::size_t>(hexes[e][a8])]);
      }
      kept[a8] = r;
    }
    m.hexahedra.push_back(kept);
    m.hexahedron_part.push_back(0);
  }
  m.node_sets.push_back({"surface", {}});
  if (sectors != 4) m.node_sets.push_back({"cut_0", {}});
  if (sectors == 1) m.node_sets.push_back({"cut_1", {}});
  const double tol = 1e-9 * s.radius;
  for (std::size_t k = 0; k < m.nodes.size(); ++k) {
    const core::Vec3 p = m.nodes[k] - s.centre;
    const auto kk = static_cast<std::int32_t>(k);
    if (std::abs(core::norm(p) - s.radius) < tol) m.node_sets[0].members.push_back(kk);
    if (sectors != 4 && std::abs(p.y) < tol) m.node_sets[1].members.push_back(kk);
    if (sectors == 1 && std::abs(p.x) < tol) m.node_sets[2].members.push_back(kk);
  }
  return m;
}

CylinderFrame cylinder_frame(const core::Vec3& axis) {
  const double length = core::norm(axis);
  require(length > 0.0 && std::isfinite(length), "cylinder: the axis must be a non-zero vector");
  const core::Vec3 z = (1.0 / length) * axis;
  // Near -z: the half turn about (1, 1, 0), which swaps x and y, so that a quarter pointing
  // down -z occupies x >= 0, y >= 0 as one pointing up +z does (a projectile in a quarter model).
  core::Vec3 x{0.0, 1.0, 0.0};
  if (1.0 + z.z > 1e-6) {
    x = {1.0, 0.0, 0.0};
    // Rodrigues' rotation R v = v + w x v + w x (w x v) / (1 + cos) with w = e_z x axis.
    const core::Vec3 w = core::cross({0.0, 0.0, 1.0}, z);
    x = x + core::cross(w, x) + (1.0 / (1.0 + z.z)) * core::cross(w, core::cross(w, x));
  }
  x -= core::dot(x, z) * z;  // removes the rounding of the rotation (and serves the -z case)
  x *= 1.0 / core::norm(x);
  return {x, core::cross(z, x), z};
}

MeshData cylinder_mesh(const core::CylinderShape& c, int n_core, int n_ring, int n_axial,
                       int sectors) {
  require(c.radius > 0.0 && std::isfinite(c.radius), "cylinder mesh: the radius must be positive");
  require(c.length > 0.0 && std::isfinite(c.length), "cylinder mesh: the length must be positive");
  require(n_core >= 1 && n_ring >= 1 && n_axial >= 1,
          "cylinder mesh: core, ring and axial divisions must each be at least 1; got " +
              std::to_string(n_core) + ", " + std::to_string(n_ring) + ", " +
              std::to_string(n_axial));
  require(sectors == 1 || sectors == 2 || sectors == 4,
          "cylinder mesh: sectors must be 1 (quarter), 2 (half) or 4 (full); got " +
              std::to_string(sectors));
  require(sectors == 4 || n_core % 2 == 0,
          "cylinder mesh: a quarter or half cylinder needs an even number of core divisions (the "
          "cut planes run along the core's midlines); got " +
              std::to_string(n_core));
  require(c.nose.crh == 0.0 ||
              (c.nose.crh >= 0.5 && c.nose.meplat > 0.0 && c.nose.meplat < 2.0 * c.radius &&
               core::ogive_nose_length(c.nose, c.radius) < c.length),
          "cylinder mesh: an ogive nose needs crh >= 0.5, a meplat between 0 and the diameter "
          "(both exclusive) and a length shorter than the cylinder's");
  const CylinderFrame frame = cylinder_frame(c.axis);
  require_32bit_indices(
      (std::int64_t{n_core + 1} * (n_core + 1) + std::int64_t{4} * n_core * n_ring) * (n_axial + 1),
      "cylinder mesh");
  const Section s = o_grid_section(c.radius, n_core, n_ring, sectors);
  const auto layer = static_cast<std::int32_t>(s.points.size());

  MeshData m = one_part_mesh();
  m.node_sets = {{"base", {}}, {"top", {}}, {"surface", {}}};
  if (sectors != 4) m.node_sets.push_back({"cut_0", {}});
  if (sectors == 1) m.node_sets.push_back({"cut_1", {}});
  // An ogive nose scales the section of each layer beyond the shank by r(t) / R.
  const double shank =
      c.nose.crh > 0.0 ? c.length - core::ogive_nose_length(c.nose, c.radius) : c.length;
  for (int l = 0; l <= n_axial; ++l) {
    const double w = std::lerp(0.0, c.length, static_cast<double>(l) / n_axial);
    const double scale =
        w > shank ? core::ogive_radius(c.nose, c.radius, w - shank) / c.radius : 1.0;
    for (std::int32_t v = 0; v < layer; ++v) {
      const std::int32_t node = l * layer + v;
      const auto& q = s.points[v];
      m.nodes.push_back(c.base + scale * q[0] * frame.x + scale * q[1] * frame.y + w * frame.z);
      if (l == 0) m.node_sets[0].members.push_back(node);
      if (l == n_axial) m.node_sets[1].members.push_back(node);
      if (s.on_surface[v]) m.node_sets[2].members.push_back(node);
      if (sectors != 4 && s.on_cut_0[v]) m.node_sets[3].members.push_back(node);
      if (sectors == 1 && s.on_cut_1[v]) m.node_sets[4].members.push_back(node);
    }
  }
  // A counter-clockwise quad seen from +axis, extruded along +axis, is kHexNatural order.
  for (int l = 0; l < n_axial; ++l)
    for (const auto& q : s.quads) {
      const std::int32_t lo = l * layer, hi = lo + layer;
      m.hexahedra.push_back(
          {lo + q[0], lo + q[1], lo + q[2], lo + q[3], hi + q[0], hi + q[1], hi + q[2], hi + q[3]});
      m.hexahedron_part.push_back(0);
    }
  return m;
}

MeshData truss_line(core::Vec3 a, core::Vec3 b, int segments, double area) {
  require(segments >= 1,
          "truss line: segments must be at least 1; got " + std::to_string(segments));
  require(area > 0.0 && std::isfinite(area), "truss line: the cross-section area must be positive");
  require(core::norm(b - a) > 0.0, "truss line: the end points must differ");
  require_32bit_indices(std::int64_t{segments} + 1, "truss line");
  MeshData m = one_part_mesh();
  append_bar(m, a, b, segments, area, 0);
  m.node_sets = {{"start", {0}}, {"end", {segments}}};
  return m;
}

MeshData rebar_mat(const RebarMat& mat) {
  require(mat.normal_axis >= 0 && mat.normal_axis <= 2,
          "rebar mat: normal_axis must be 0 (x), 1 (y) or 2 (z); got " +
              std::to_string(mat.normal_axis));
  for (int d = 0; d < 3; ++d)
    require(mat.max[d] > mat.min[d],
            std::string("rebar mat: the box's max must exceed its min along ") + kAxisName[d]);
  const int normal = mat.normal_axis;
  require(!mat.positions.empty(), "rebar mat: give at least one plane position");
  for (double p : mat.positions)
    require(p >= mat.min[normal] && p <= mat.max[normal],
            std::string("rebar mat: every plane's position must lie inside the box along ") +
                kAxisName[normal]);
  require(mat.spacing > 0.0, "rebar mat: the bar spacing must be positive");
  require(mat.diameter > 0.0, "rebar mat: the bar diameter must be positive");
  require(mat.segment_length > 0.0, "rebar mat: the segment length must be positive");
  require(mat.cover >= 0.0, "rebar mat: the cover must not be negative");
  const std::array<int, 2> in_plane{normal == 0 ? 1 : 0, normal == 2 ? 1 : 2};
  for (int d : in_plane)
    require(2.0 * mat.cover < mat.max[d] - mat.min[d],
            std::string("rebar mat: the cover must be less than half the box's extent along ") +
                kAxisName[d]);

  // Counts are rounded with a relative allowance, so that a span of exactly k spacings (as
  // written in decimal) gives k + 1 bars, not k.
  constexpr double kRoundoff = 1e-9;
  const double area = std::numbers::pi * mat.diameter * mat.diameter / 4.0;
  MeshData m;
  std::int64_t total_nodes = 0;
  for (int part = 0; part < 2; ++part) {
    const int along = in_plane[part], across = in_plane[1 - part];
    m.part_names.push_back(std::string("bars along ") + kAxisName[along]);
    const double lo = mat.min[across] + mat.cover, span = mat.max[across] - mat.cover - lo;
    const auto bars = static_cast<std::int64_t>(std::floor(span / mat.spacing + kRoundoff)) + 1;
    const double first = lo + 0.5 * (span - static_cast<double>(bars - 1) * mat.spacing);
    const double start = mat.min[along] + mat.cover, end = mat.max[along] - mat.cover;
    const auto segments = std::max<std::int64_t>(
        1, static_cast<std::int64_t>(std::ceil((end - start) / mat.segment_length - kRoundoff)));
    total_nodes += static_cast<std::int64_t>(mat.positions.size()) * bars * (segments + 1);
    require_32bit_indices(total_nodes, "rebar mat");
    for (double position : mat.positions)
      for (std::int64_t b = 0; b < bars; ++b) {
        core::Vec3 a, z;
        a[normal] = z[normal] = position;
        a[across] = z[across] = first + static_cast<double>(b) * mat.spacing;
        a[along] = start;
        z[along] = end;
        append_bar(m, a, z, static_cast<int>(segments), area, part);
      }
  }
  return m;
}

}  // namespace afemp::fem
