// Warnings for bodies that meet without a contact (core/contact_warnings.hpp).
#include "core/contact_warnings.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

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

}  // namespace afemp::core
