// Particle generation: a grid-aligned lattice clipped to each body's shape (symmetry faces cut
// the body, other faces must contain it), or points read from a plain-text list.
// The lattice offsets (k + 0.5)/n keep every point off the cell faces, hence off symmetry planes.
#include "mpm/particle_generation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

#include "core/materials/initial_pressure.hpp"
#include "mpm/axisymmetric.hpp"
#include "mpm/sphere_shells.hpp"

namespace afemp::mpm {

namespace {

using core::BodySpec;
using core::BoxShape;
using core::CylinderShape;
using core::Face;
using core::FaceCondition;
using core::GridSettings;
using core::InputError;
using core::Material;
using core::PointListShape;
using core::SphereShape;

struct Aabb {
  Vec3 lo, hi;
};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string fmt(const Vec3& v) {
  return "(" + fmt(v.x) + ", " + fmt(v.y) + ", " + fmt(v.z) + ")";
}

// Half-open in every direction so that two boxes sharing a face never both own a point.
struct BoxTest {
  BoxShape s;
  Aabb bounds() const { return {s.min, s.max}; }
  bool inside(const Vec3& x) const {
    for (int a = 0; a < 3; ++a)
      if (!(x[a] >= s.min[a] && x[a] < s.max[a])) return false;
    return true;
  }
};

// Axial extent half-open [0, length) for the same reason as the box; radial closed.
// With an ogive nose (core/ogive_nose.hpp) the radius falls along the last stretch of the axis;
// a cone's (top_radius >= 0) changes linearly from the base to the far end.
struct CylinderTest {
  Vec3 base, axis;
  double radius, length, top_radius;
  double wall_radial;  // a walled cone: wall / cos(half-angle) radially; 0: solid
  core::OgiveNose nose;
  double shank;  // axial distance at which the nose starts (length without one)
  explicit CylinderTest(const CylinderShape& c)
      : base(c.base),
        axis((1.0 / norm(c.axis)) * c.axis),
        radius(c.radius),
        length(c.length),
        top_radius(c.top_radius),
        wall_radial(c.top_radius >= 0.0 && c.wall > 0.0
                        ? c.wall * std::hypot(c.length, c.radius - c.top_radius) / c.length
                        : 0.0),
        nose(c.nose),
        shank(c.nose.crh > 0.0 ? c.length - core::ogive_nose_length(c.nose, c.radius) : c.length) {}
  Aabb bounds() const {
    const Vec3 top = base + length * axis;
    Aabb b;
    for (int a = 0; a < 3; ++a) {
      // The end discs reach radius * sqrt(1 - axis_a^2) from their centres along axis a.
      const double ext =
          std::max(radius, top_radius) * std::sqrt(std::max(0.0, 1.0 - axis[a] * axis[a]));
      b.lo[a] = std::min(base[a], top[a]) - ext;
      b.hi[a] = std::max(base[a], top[a]) + ext;
    }
    return b;
  }
  bool inside(const Vec3& x) const {
    const Vec3 v = x - base;
    const double s = dot(v, axis);
    if (!(s >= 0.0 && s < length)) return false;
    const Vec3 radial = v - s * axis;
    const double r = top_radius >= 0.0 ? radius + (top_radius - radius) * s / length
                     : s > shank       ? core::ogive_radius(nose, radius, s - shank)
                                       : radius;
    const double rr = dot(radial, radial);
    if (wall_radial > 0.0 && r > wall_radial && rr <= (r - wall_radial) * (r - wall_radial))
      return false;  // in the hollow of a walled cone
    return rr <= r * r;
  }
};

struct SphereTest {
  SphereShape s;
  Aabb bounds() const {
    const Vec3 r{s.radius, s.radius, s.radius};
    return {s.centre - r, s.centre + r};
  }
  bool inside(const Vec3& x) const {
    const Vec3 v = x - s.centre;
    return dot(v, v) <= s.radius * s.radius;
  }
};

FaceCondition face_condition(const GridSettings& g, int axis, bool max_side) {
  return g.faces[static_cast<std::size_t>(2 * axis + (max_side ? 1 : 0))];
}

Face face_of(int axis, bool max_side) {
  return static_cast<Face>(2 * axis + (max_side ? 1 : 0));
}

double initial_temperature(const BodySpec& body, const Material& m) {
  return body.temperature ? *body.temperature : m.thermal.initial_temperature;
}

// Whether a point of a body's shape lies in the grid: beyond a symmetric face it is the mirrored
// half the face stands for (dropped by design, false); beyond any other face the body crosses
// it, an error naming the face.
bool keep_in_grid(const Vec3& x, const GridSettings& grid, const core::SourceLocation& where,
                  const std::string& key, const char* what) {
  bool outside_grid = false;
  for (int a = 0; a < 3; ++a) {
    for (bool max_side : {false, true}) {
      const bool beyond = max_side ? x[a] > grid.max[a] : x[a] < grid.min[a];
      if (!beyond) continue;
      outside_grid = true;
      const FaceCondition c = face_condition(grid, a, max_side);
      if (c == FaceCondition::symmetric) continue;
      throw InputError(
          where, key,
          std::string("the body crosses grid face ") + core::to_string(face_of(a, max_side)) +
              " (boundary \"" + core::to_string(c) + "\"): " + what + " " + fmt(x) +
              " lies inside the shape but outside the grid " + fmt(grid.min) + " - " +
              fmt(grid.max) + "; move the body inside the grid or make that face \"symmetric\"");
    }
  }
  return !outside_grid;
}

// Lattice points x_j = grid.min + (j + 0.5) h/n along each axis that fall inside the shape.
// The index range covers the shape's bounding box, clipped to the grid on symmetric sides (the
// part beyond is the mirrored half that the symmetry condition stands for) and left unclipped on
// other sides so that a body poking through a fixed or free face is caught, not silently cut.
template <class Test>
void generate_lattice(const Test& shape, const GridSettings& grid, const BodySpec& body,
                      int body_id, const Material& material, Particles& out) {
  const double d = grid.cell / body.particles_per_cell;
  const double volume = d * d * d;
  const double mass = material.density * volume;
  const double temperature = initial_temperature(body, material);
  const Aabb box = shape.bounds();
  // Axisymmetric (mpm/axisymmetric.hpp): one row of rings across, on y = 0.
  const bool rings = grid.axisymmetric;

  std::array<long long, 3> first{}, last{};
  double candidates = 1.0;
  for (int a = 0; a < 3; ++a) {
    // One extra index each side: the inside test, not the bounding box, decides.
    const double lo = std::floor((box.lo[a] - grid.min[a]) / d - 0.5) - 1.0;
    const double hi = std::ceil((box.hi[a] - grid.min[a]) / d - 0.5) + 1.0;
    const double grid_last = std::floor((grid.max[a] - grid.min[a]) / d - 0.5);
    double f = lo, l = hi;
    if (face_condition(grid, a, false) == FaceCondition::symmetric) f = std::max(f, 0.0);
    if (face_condition(grid, a, true) == FaceCondition::symmetric) l = std::min(l, grid_last);
    if (rings && a == 1) f = l = 0.0;
    // A shape wholly beyond a symmetric face leaves an empty range; zero-particle check below.
    if (l < f) return;
    candidates *= (l - f + 1.0);
    first[static_cast<std::size_t>(a)] = static_cast<long long>(f);
    last[static_cast<std::size_t>(a)] = static_cast<long long>(l);
  }
  const std::string key = "bodies." + body.name + ".shape";
  if (candidates > 4.0e9)
    throw InputError(body.where, key,
                     "the shape spans more than 4e9 lattice sites; it is far larger than the grid");

  for (long long k = first[2]; k <= last[2]; ++k) {
    for (long long j = first[1]; j <= last[1]; ++j) {
      for (long long i = first[0]; i <= last[0]; ++i) {
        const Vec3 x{grid.min.x + (static_cast<double>(i) + 0.5) * d,
                     rings ? 0.0 : grid.min.y + (static_cast<double>(j) + 0.5) * d,
                     grid.min.z + (static_cast<double>(k) + 0.5) * d};
        if (!shape.inside(x)) continue;
        if (!keep_in_grid(x, grid, body.where, key, "lattice point")) continue;
        if (rings) {
          const double v = ring_volume(x.x, d * d);
          out.push_back(x, body.velocity, material.density * v, v, temperature, body_id,
                        body.material);
          continue;
        }
        out.push_back(x, body.velocity, mass, volume, temperature, body_id, body.material);
      }
    }
  }
}

// Splits "x y z [volume]" into numbers; false when a token is not a whole number.
bool parse_numbers(const std::string& line, std::vector<double>& values) {
  values.clear();
  const char* p = line.c_str();
  while (true) {
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == ',') ++p;
    if (*p == '\0') return true;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p) return false;
    if (*end != '\0' && *end != ' ' && *end != '\t' && *end != '\r' && *end != ',') return false;
    values.push_back(v);
    p = end;
  }
}

// A sphere's particles in shells that follow its surface (mpm/sphere_shells.hpp).
void generate_sphere_shells(const SphereShape& sphere, const GridSettings& grid,
                            const BodySpec& body, int body_id, const Material& material,
                            Particles& out) {
  const double temperature = initial_temperature(body, material);
  const std::string key = "bodies." + body.name + ".shape";
  for (const ShellParticle& q :
       sphere_shell_particles(sphere, grid.cell / body.particles_per_cell)) {
    if (!keep_in_grid(q.position, grid, body.where, key, "particle")) continue;
    out.push_back(q.position, body.velocity, material.density * q.volume, q.volume, temperature,
                  body_id, body.material);
  }
}

// Particles at a program's points (PointListShape arrays), checked as a file's lines are.
void generate_point_arrays(const PointListShape& shape, const GridSettings& grid,
                           const BodySpec& body, int body_id, const Material& material,
                           Particles& out) {
  const double d = grid.cell / body.particles_per_cell;
  const double temperature = initial_temperature(body, material);
  const core::SourceLocation where = body.where;
  const std::string key = "bodies." + body.name + ".shape.points";
  for (std::size_t i = 0; i < shape.points.size(); ++i) {
    const Vec3& x = shape.points[i];
    const double volume = shape.volumes.empty() ? d * d * d : shape.volumes[i];
    if (!std::isfinite(x.x + x.y + x.z + volume) || !(volume > 0.0))
      throw InputError(where, key,
                       "point " + std::to_string(i) + ": non-finite number or volume <= 0");
    for (int a = 0; a < 3; ++a)
      if (x[a] < grid.min[a] || x[a] > grid.max[a])
        throw InputError(where, key,
                         "point " + std::to_string(i) + " " + fmt(x) + " lies outside the grid " +
                             fmt(grid.min) + " - " + fmt(grid.max));
    out.push_back(x, body.velocity, material.density * volume, volume, temperature, body_id,
                  body.material);
  }
}

void generate_point_list(const PointListShape& shape, const GridSettings& grid,
                         const BodySpec& body, int body_id, const Material& material,
                         Particles& out) {
  if (shape.path.empty()) return generate_point_arrays(shape, grid, body, body_id, material, out);
  std::ifstream in(shape.path);
  if (!in)
    throw InputError(body.where, "bodies." + body.name + ".shape.points.file",
                     "cannot open points file '" + shape.path + "'");
  const double d = grid.cell / body.particles_per_cell;
  const double default_volume = d * d * d;
  const double temperature = initial_temperature(body, material);
  std::string line;
  std::vector<double> v;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    const core::SourceLocation where{shape.path, line_no};
    if (!parse_numbers(line, v) || (v.size() != 0 && v.size() != 3 && v.size() != 4))
      throw InputError(where, "",
                       "points of body '" + body.name +
                           "': malformed line; expected \"x y z\" or "
                           "\"x y z volume\" (numbers separated by spaces)");
    if (v.empty()) continue;  // blank or comment-only line
    const Vec3 x{v[0], v[1], v[2]};
    const double volume = v.size() == 4 ? v[3] : default_volume;
    for (double c : v)
      if (!std::isfinite(c))
        throw InputError(where, "", "points of body '" + body.name + "': non-finite number");
    if (!(volume > 0.0))
      throw InputError(
          where, "", "points of body '" + body.name + "': volume " + fmt(volume) + " must be > 0");
    for (int a = 0; a < 3; ++a)
      if (x[a] < grid.min[a] || x[a] > grid.max[a])
        throw InputError(where, "",
                         "points of body '" + body.name + "': point " + fmt(x) +
                             " lies outside the grid " + fmt(grid.min) + " - " + fmt(grid.max));
    out.push_back(x, body.velocity, material.density * volume, volume, temperature, body_id,
                  body.material);
  }
  if (in.bad())
    throw InputError(core::SourceLocation{shape.path, line_no}, "",
                     "read error in points file of body '" + body.name + "'");
}

// A box of an axisymmetric grid stands for its r-z section, whatever its y extent: it takes
// the particles on y = 0 (mpm/axisymmetric.hpp).
BoxShape ring_section(BoxShape s, const GridSettings& grid) {
  if (grid.axisymmetric) s.min.y = -1.0, s.max.y = 1.0;
  return s;
}

// Whether x lies inside a box, cylinder or sphere shape (the parser lets `outside` name no
// other). A walled cone counts with its hollow: a charge outside a liner leaves the liner's
// cavity empty.
bool inside_shape(const core::Shape& shape, const Vec3& x, const GridSettings& grid) {
  if (const auto* s = std::get_if<BoxShape>(&shape))
    return BoxTest{ring_section(*s, grid)}.inside(x);
  if (const auto* s = std::get_if<CylinderShape>(&shape)) {
    CylinderShape solid = *s;
    solid.wall = 0.0;
    return CylinderTest{solid}.inside(x);
  }
  if (const auto* s = std::get_if<SphereShape>(&shape)) return SphereTest{*s}.inside(x);
  return false;
}

}  // namespace

Particles generate_particles(const core::Scene& scene) {
  Particles out;
  const GridSettings& grid = scene.mpm.grid;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& body = scene.bodies[b];
    if (body.material < 0 || static_cast<std::size_t>(body.material) >= scene.materials.size())
      throw InputError(body.where, "bodies." + body.name + ".material",
                       "material index " + std::to_string(body.material) + " is not defined");
    if (body.discretisation != core::Discretisation::particles) continue;
    if (body.particles_per_cell < 1)
      throw InputError(body.where, "bodies." + body.name + ".particles_per_cell", "must be >= 1");
    const Material& material = scene.materials[static_cast<std::size_t>(body.material)];
    const int body_id = static_cast<int>(b);
    const std::size_t before = out.size();
    std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<S, BoxShape>)
            generate_lattice(BoxTest{ring_section(s, grid)}, grid, body, body_id, material, out);
          else if constexpr (std::is_same_v<S, CylinderShape>) {
            if (!(norm(s.axis) > 0.0))
              throw InputError(body.where, "bodies." + body.name + ".shape.cylinder.axis",
                               "the axis must be a non-zero vector");
            generate_lattice(CylinderTest{s}, grid, body, body_id, material, out);
          } else if constexpr (std::is_same_v<S, SphereShape>) {
            if (body.layout == BodySpec::Layout::shells)
              generate_sphere_shells(s, grid, body, body_id, material, out);
            else
              generate_lattice(SphereTest{s}, grid, body, body_id, material, out);
          } else if constexpr (std::is_same_v<S, PointListShape>)
            generate_point_list(s, grid, body, body_id, material, out);
          else  // the parser gives particle bodies particle shapes only
            throw InputError(body.where, "bodies." + body.name + ".shape",
                             "this shape makes a mesh, not particles");
        },
        body.shape);
    // Left out: what lies inside the shapes of the bodies named by `outside`.
    if (!body.outside.empty()) {
      std::vector<std::int32_t> kept;
      for (std::size_t p = 0; p < out.size(); ++p) {
        bool inside = false;
        for (int o : body.outside)
          if (p >= before)
            inside = inside || inside_shape(scene.bodies[static_cast<std::size_t>(o)].shape,
                                            out.position[p], grid);
        if (!inside) kept.push_back(static_cast<std::int32_t>(p));
      }
      out.select(kept);
    }
    for (std::size_t p = before; p < out.size(); ++p) out.energy[p] = body.internal_energy;
    // An initial pressure: the density at which the EOS gives it (the mass grows with it, the
    // volume is the lattice's), and the stress -p I that goes with it.
    if (body.pressure) {
      const std::optional<double> mu =
          core::compression_at_pressure(material, *body.pressure, body.internal_energy);
      if (!mu)
        throw InputError(
            body.where, "bodies." + body.name + ".pressure",
            *core::initial_pressure_refusal(material, *body.pressure, body.internal_energy));
      for (std::size_t p = before; p < out.size(); ++p) {
        out.mass[p] *= 1.0 + *mu;
        out.stress[p] = -*body.pressure * core::SymTensor::identity();
      }
    }
    // Soil at rest: the weight above each particle (the parser checked gravity and material),
    // and the elastic energy it holds.
    if (body.initial_stress) {
      for (std::size_t p = before; p < out.size(); ++p) {
        out.stress[p] =
            core::geostatic_stress(body.initial_stress->surface, body.initial_stress->k0,
                                   scene.run.gravity, material.density, out.position[p]);
        out.energy[p] += core::elastic_energy(material, out.stress[p]);
      }
    }
    if (out.size() == before)
      throw InputError(body.where, "bodies." + body.name + ".shape",
                       "the body has no particle: the shape lies outside the grid or is smaller "
                       "than a particle spacing (cell / particles_per_cell = " +
                           fmt(grid.cell / body.particles_per_cell) + ")");
  }
  return out;
}

}  // namespace afemp::mpm
