// Warnings for bodies that meet without a contact (core/contact_warnings.hpp).
#include "core/contact_warnings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "core/state_archive.hpp"

namespace afemp::core {

namespace {

struct Box {
  Vec3 lo, hi;
  bool empty = true;
};

Box box_of(const BodyPoints& p) {
  Box b;
  constexpr double inf = std::numeric_limits<double>::infinity();
  b.lo = {inf, inf, inf};
  b.hi = {-inf, -inf, -inf};
  for (std::size_t i = 0; i < p.position.size(); ++i) {
    const double h = p.half_size.empty() ? 0.0 : p.half_size[i];
    for (int d = 0; d < 3; ++d) {
      b.lo[d] = std::min(b.lo[d], p.position[i][d] - h);
      b.hi[d] = std::max(b.hi[d], p.position[i][d] + h);
    }
    b.empty = false;
  }
  return b;
}

// The largest separation of the boxes along an axis (<= 0: they overlap).
double gap(const Box& a, const Box& b) {
  double g = -std::numeric_limits<double>::infinity();
  for (int d = 0; d < 3; ++d) g = std::max({g, a.lo[d] - b.hi[d], b.lo[d] - a.hi[d]});
  return g;
}

// Whether something between bodies a and b says how they meet: a [[contact]] naming both, a
// bond, a conversion (its particles start inside the mesh), or overlap_allowed.
bool covered(const Scene& scene, std::size_t a, std::size_t b) {
  for (const ContactSpec& c : scene.contacts)
    if ((static_cast<std::size_t>(c.bodies[0]) == a &&
         static_cast<std::size_t>(c.bodies[1]) == b) ||
        (static_cast<std::size_t>(c.bodies[0]) == b && static_cast<std::size_t>(c.bodies[1]) == a))
      return true;
  const BodySpec& x = scene.bodies[a];
  const BodySpec& y = scene.bodies[b];
  auto allows = [](const BodySpec& body, std::size_t other) {
    return std::find(body.overlap_allowed.begin(), body.overlap_allowed.end(),
                     static_cast<int>(other)) != body.overlap_allowed.end();
  };
  return x.bonded_to == static_cast<int>(b) || y.bonded_to == static_cast<int>(a) || x.conversion ||
         y.conversion || allows(x, b) || allows(y, a);
}

bool of_particles(const BodySpec& b) {
  return b.discretisation == Discretisation::particles;
}

// The particles of `a` in a grid cell next to (or in) a cell that holds particles of `b`: with
// the linear weights a particle reaches its cell's nodes, and two such cells share nodes.
std::size_t sharing_grid_nodes(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                               const GridSettings& grid) {
  using Cell = std::array<long, 3>;
  auto cell_of = [&](const Vec3& p) {
    Cell c;
    for (int d = 0; d < 3; ++d)
      c[static_cast<std::size_t>(d)] =
          static_cast<long>(std::floor((p[d] - grid.min[d]) / grid.cell));
    return c;
  };
  std::vector<Cell> held;
  held.reserve(b.size());
  for (const Vec3& p : b) held.push_back(cell_of(p));
  std::sort(held.begin(), held.end());
  held.erase(std::unique(held.begin(), held.end()), held.end());
  std::size_t count = 0;
  for (const Vec3& p : a) {
    const Cell c = cell_of(p);
    bool shares = false;
    for (long k = -1; k <= 1 && !shares; ++k)
      for (long j = -1; j <= 1 && !shares; ++j)
        for (long i = -1; i <= 1 && !shares; ++i)
          shares = std::binary_search(held.begin(), held.end(), Cell{c[0] + i, c[1] + j, c[2] + k});
    count += shares ? 1 : 0;
  }
  return count;
}

}  // namespace

std::vector<std::string> contact_warnings(const Scene& scene, const Model& model) {
  const std::size_t n = scene.bodies.size();
  std::vector<Box> boxes;
  for (std::size_t b = 0; b < n; ++b)
    boxes.push_back(box_of(model.body_points(static_cast<int>(b))));
  const double cell = scene.has_grid ? scene.mpm.grid.cell : 0.0;
  std::vector<std::string> out;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      if (boxes[a].empty || boxes[b].empty || covered(scene, a, b)) continue;
      const BodySpec& x = scene.bodies[a];
      const BodySpec& y = scene.bodies[b];
      const bool px = x.discretisation == Discretisation::particles;
      const bool py = y.discretisation == Discretisation::particles;
      const double g = gap(boxes[a], boxes[b]);
      if (g > (px || py ? cell : 0.0)) continue;
      char where[80];
      if (g > 0.0)
        std::snprintf(where, sizeof where, "lie %.3g apart (within one cell, %.3g)", g, cell);
      else
        std::snprintf(where, sizeof where, "overlap or touch");
      const std::string pair = "bodies \"" + x.name + "\" and \"" + y.name + "\"";
      if (px && py) {
        if (x.material == y.material) continue;  // one material: a body made of parts
        out.push_back(pair + " (materials " +
                      scene.materials[static_cast<std::size_t>(x.material)].name + " and " +
                      scene.materials[static_cast<std::size_t>(y.material)].name + ") " + where +
                      " with no [[contact]] between them: they share the grid's velocity "
                      "field and weld where they meet (no slip, no separation); add [[contact]] "
                      "bodies = [\"" +
                      x.name + "\", \"" + y.name +
                      "\"], or method = \"weld\" "
                      "if welding is meant");
      } else {
        out.push_back(pair + " " + where + " with no [[contact]] between them: " +
                      (px || py ? "particles and a mesh" : "two meshes") +
                      " pass through each other; add [[contact]] bodies = [\"" + x.name + "\", \"" +
                      y.name + "\"]" +
                      (px || py ? " (method \"surface\" meets the mesh's faces at the "
                                  "particles' boundary; or bond the mesh: bonded_to)"
                                : ""));
      }
    }
  return out;
}

OverlapCheck::OverlapCheck(const Scene& scene) : scene_(scene) {
  using D = Discretisation;
  for (std::size_t a = 0; a < scene.bodies.size(); ++a)
    for (std::size_t b = a + 1; b < scene.bodies.size(); ++b) {
      const BodySpec& x = scene.bodies[a];
      const BodySpec& y = scene.bodies[b];
      const bool volumes = x.discretisation == D::hexahedra || y.discretisation == D::hexahedra;
      const bool welds = of_particles(x) && of_particles(y) && x.material != y.material;
      if (!(volumes || welds) || covered(scene, a, b)) continue;
      Pair& p = pairs_.emplace_back();
      p.a = a;
      p.b = b;
    }
}

void OverlapCheck::check(const Model& model) {
  const std::size_t n = scene_.bodies.size();
  std::vector<BodyPoints> points(n);
  std::vector<Box> boxes(n);
  std::vector<char> loaded(n, 0);
  auto load = [&](std::size_t b) {
    if (loaded[b]) return;
    points[b] = model.body_points(static_cast<int>(b));
    boxes[b] = box_of(points[b]);
    loaded[b] = 1;
  };
  const double cell = scene_.has_grid ? scene_.mpm.grid.cell : 0.0;
  for (Pair& pair : pairs_) {
    load(pair.a);
    load(pair.b);
    const BodySpec& x = scene_.bodies[pair.a];
    const BodySpec& y = scene_.bodies[pair.b];
    // Particles two cells apart may still reach shared nodes.
    const double reach = of_particles(x) && of_particles(y) ? 2.0 * cell : 0.0;
    if (boxes[pair.a].empty || boxes[pair.b].empty || gap(boxes[pair.a], boxes[pair.b]) > reach)
      continue;
    std::size_t count = 0;
    std::string what;
    auto inside = [&](const BodySpec& from, std::size_t f, const BodySpec& into, std::size_t i) {
      if (into.discretisation != Discretisation::hexahedra) return;
      const std::size_t k = model.points_inside(static_cast<int>(i), points[f].position);
      if (k == 0) return;
      count += k;
      what += std::string(what.empty() ? "" : ", and ") + std::to_string(k) +
              (of_particles(from) ? " particles" : " nodes") + " of \"" + from.name +
              "\" lie inside the elements of \"" + into.name + "\"";
    };
    inside(x, pair.a, y, pair.b);
    inside(y, pair.b, x, pair.a);
    if (of_particles(x) && of_particles(y)) {
      count = sharing_grid_nodes(points[pair.a].position, points[pair.b].position, scene_.mpm.grid);
      if (count > 0)
        what = std::to_string(count) + " particles of \"" + x.name +
               "\" lie in cells next to those of \"" + y.name + "\" (materials " +
               scene_.materials[static_cast<std::size_t>(x.material)].name + " and " +
               scene_.materials[static_cast<std::size_t>(y.material)].name +
               "): they share grid nodes and weld there";
    }
    if (count == 0) continue;
    if (pair.first_time < 0.0) {
      pair.first_time = model.time();
      pair.first_what = what;
      std::fprintf(stderr,
                   "afemp: warning: at t = %.6g (step %ld) bodies \"%s\" and \"%s\" overlap "
                   "with no [[contact]] between them: %s; %s\n",
                   model.time(), model.step_count(), x.name.c_str(), y.name.c_str(), what.c_str(),
                   remedy(pair).c_str());
    }
    if (count > pair.most_count) {
      pair.most_count = count;
      pair.most_time = model.time();
      pair.most_what = what;
    }
  }
}

std::string OverlapCheck::remedy(const Pair& p) const {
  const BodySpec& x = scene_.bodies[p.a];
  const BodySpec& y = scene_.bodies[p.b];
  const std::string contact = "add [[contact]] bodies = [\"" + x.name + "\", \"" + y.name + "\"]";
  const std::string allowed = "overlap_allowed = [\"" + y.name + "\"] in body \"" + x.name + "\"";
  if (of_particles(x) && of_particles(y))
    return contact + " (a grid contact: they slide and separate), or method = \"weld\" or " +
           allowed + " if welding is meant";
  return contact + (of_particles(x) || of_particles(y) ? " (method \"surface\")" : "") + ", or " +
         allowed + " if the overlap is meant";
}

std::vector<std::string> OverlapCheck::summary() const {
  std::vector<std::string> out;
  char when[80];
  for (const Pair& p : pairs_) {
    if (p.first_time < 0.0) continue;
    std::string w = "bodies \"" + scene_.bodies[p.a].name + "\" and \"" + scene_.bodies[p.b].name +
                    "\" overlap with no [[contact]] between them: ";
    std::snprintf(when, sizeof when, "from t = %.6g, ", p.first_time);
    w += when + p.first_what;
    if (p.most_what != p.first_what) {
      std::snprintf(when, sizeof when, "; the most at t = %.6g, ", p.most_time);
      w += when + p.most_what;
    }
    out.push_back(w + "; " + remedy(p));
  }
  return out;
}

void OverlapCheck::state(StateArchive& a) {
  const StateArchive::Group group(a, "overlaps");
  std::vector<double> first_time, most_time;
  std::vector<std::uint64_t> most_count;
  std::vector<std::string> first_what, most_what;
  for (const Pair& p : pairs_) {
    first_time.push_back(p.first_time);
    most_time.push_back(p.most_time);
    most_count.push_back(p.most_count);
    first_what.push_back(p.first_what);
    most_what.push_back(p.most_what);
  }
  a.item("first_time", first_time);
  a.item("most_time", most_time);
  a.item("most_count", most_count);
  a.item("first_what", first_what);
  a.item("most_what", most_what);
  if (!a.loading()) return;
  if (first_time.size() != pairs_.size() || most_time.size() != pairs_.size() ||
      most_count.size() != pairs_.size() || first_what.size() != pairs_.size() ||
      most_what.size() != pairs_.size())
    throw CheckpointError(a.where("first_time") + ": one per pair of bodies checked");
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    Pair& p = pairs_[k];
    p.first_time = first_time[k];
    p.most_time = most_time[k];
    p.most_count = most_count[k];
    p.first_what = first_what[k];
    p.most_what = most_what[k];
  }
}

}  // namespace afemp::core
