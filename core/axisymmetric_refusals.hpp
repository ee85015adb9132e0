// What the axisymmetric grid ([grid] axisymmetric = true; mpm/axisymmetric.hpp) takes: bodies of
// particles whose shapes turn about the z axis, welded to each other or on one field, loaded by
// axial gravity, axial initial velocities, grid faces and detonations on the axis, with the linear
// hat and the FLIP/PIC transfer in the updated-Lagrangian form, splitting along z only. Anything
// else has no axisymmetric form here and is refused, naming the key, by the parser and by the check
// of a scene built in code alike.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <variant>

#include "afemp/scene.hpp"

namespace afemp::core {

struct AxisymmetricRefusal {
  SourceLocation where;
  std::string key;
  std::string why;
};

inline std::optional<AxisymmetricRefusal> axisymmetric_refusal(const Scene& scene) {
  const GridSettings& g = scene.mpm.grid;
  if (!g.axisymmetric) return std::nullopt;
  const SourceLocation grid_at = scene.grid_where;
  auto refuse = [](const SourceLocation& at, std::string key, std::string what) {
    return AxisymmetricRefusal{at, std::move(key),
                               what +
                                   " has no axisymmetric form; allowed with [grid] "
                                   "axisymmetric = true: bodies of particles turning about the "
                                   "z axis (docs/scene-format.md, \"Axisymmetric grids\")"};
  };
  const std::size_t ymin = static_cast<std::size_t>(Face::ymin);
  const std::size_t ymax = static_cast<std::size_t>(Face::ymax);
  const std::size_t xmin = static_cast<std::size_t>(Face::xmin);
  if (g.min.x != 0.0 || g.min.y != -0.5 * g.cell || g.max.y != 0.5 * g.cell ||
      g.faces[ymin] != FaceCondition::symmetric || g.faces[ymax] != FaceCondition::symmetric ||
      g.faces[xmin] != FaceCondition::symmetric)
    return AxisymmetricRefusal{grid_at, "grid.axisymmetric",
                               "an axisymmetric grid starts at the axis (min x = 0, face xmin "
                               "symmetric) and is one cell thick across the r-z plane (y from "
                               "-cell/2 to cell/2, faces ymin and ymax symmetric)"};
  for (FaceCondition f : g.faces)
    if (f == FaceCondition::absorbing) return refuse(grid_at, "grid.boundary", "an absorbing face");
  const MpmSettings& m = scene.mpm;
  if (m.shape != ShapeFunction::linear)
    return refuse(grid_at, "mpm.shape_function",
                  std::string("shape_function = \"") + to_string(m.shape) + "\"");
  if (m.transfer != Transfer::flip) return refuse(grid_at, "mpm.transfer", "the affine transfer");
  if (m.formulation != Formulation::updated_lagrangian)
    return refuse(grid_at, "mpm.formulation", "the total-Lagrangian formulation");
  if (m.pressure != PressureField::standard)
    return refuse(grid_at, "mpm.pressure", "the mixed u-p pressure");
  // A ring splits along z only: halves along x would share its mass equally at radii that
  // hold different ring volumes, and along y they would leave the plane. Near the axis it does
  // not split at all (mpm/particle_splitting.cpp).
  if (m.splitting && (m.splitting->axes[0] || m.splitting->axes[1]))
    return AxisymmetricRefusal{grid_at, "mpm.splitting.axes",
                               "an axisymmetric grid splits rings along z only (axes = [\"z\"]): "
                               "along x the halves would take equal masses at radii of unequal "
                               "ring volume, along y they would leave the r-z plane"};
  if (scene.run.gravity.x != 0.0 || scene.run.gravity.y != 0.0)
    return refuse(grid_at, "run.gravity", "gravity across the axis");
  if (scene.run.reproducible)
    return refuse(scene.run.reproducible_where, "run.reproducible", "the reproducible mode");
  auto on_axis = [](const Vec3& v) { return v.x == 0.0 && v.y == 0.0; };
  for (const BodySpec& b : scene.bodies) {
    const std::string key = "bodies." + b.name;
    if (b.discretisation != Discretisation::particles)
      return refuse(b.where, key + ".discretisation", "a mesh body");
    if (!on_axis(b.velocity))
      return refuse(b.where, key + ".velocity", "a velocity across the axis");
    if (b.layout == BodySpec::Layout::shells)
      return refuse(b.where, key + ".layout", "a sphere's shells");
    if (b.initial_stress) return refuse(b.where, key + ".initial_stress", "a geostatic stress");
    const bool turns = std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<S, BoxShape>)
            return true;  // its r-z section: a ring, or a disc from r = 0
          else if constexpr (std::is_same_v<S, CylinderShape>)
            return on_axis(s.base) && s.axis.x == 0.0 && s.axis.y == 0.0;
          else if constexpr (std::is_same_v<S, SphereShape>)
            return on_axis(s.centre);
          else
            return false;
        },
        b.shape);
    if (!turns)
      return refuse(b.where, key + ".shape",
                    "a shape that does not turn about the z axis (a point list, or a cylinder, "
                    "cone or sphere off it)");
  }
  if (!scene.constraints.empty())
    return refuse(scene.constraints.front().where, "constraints", "a constraint");
  if (!scene.absorbing.empty())
    return refuse(scene.absorbing.front().where, "absorbing", "an absorbing boundary");
  if (!scene.loads.empty()) return refuse(scene.loads.front().where, "loads", "a load");
  if (!scene.walls.empty()) return refuse(scene.walls.front().where, "walls", "a wall");
  for (const ContactSpec& c : scene.contacts)
    if (c.method != ContactMethod::weld)
      return refuse(c.where, "contact.method",
                    std::string("contact method \"") + to_string(c.method) + "\" (weld is taken)");
  for (const DetonationSpec& d : scene.detonations) {
    if (d.kind != DetonationSpec::Kind::point || !on_axis(d.point))
      return refuse(d.where, "detonations", "a detonation other than at a point on the axis");
    if (d.shadow) return refuse(d.where, "detonations.shadow", "a shadowed detonation");
  }
  if (!scene.phases.empty()) return refuse(scene.phases.front().where, "phases", "a phase");
  return std::nullopt;
}

}  // namespace afemp::core
