// What a total-Lagrangian MPM scene is refused for, shared by the parser (file, line and key)
// and check_scene (scenes built in code). Its weights live in the reference configuration
// (mpm/stencil.hpp, ReferenceStencil): a grid node stands for the material around a reference
// point, not for a place in space. What acts on a place in space has no meaning there: walls
// and outflow or absorbing faces (a place the material may not pass or leaves through), grid
// contact between bodies (two bodies meet where they are, not where they started), elements
// and rebar coupled through the grid, particle walls. A fixed or symmetric face holds the
// material on the reference face, which is what such a face means for a body that starts on
// it. Splitting and CPDI deform the particle domains the reference weights stand for. The
// affine transfer is not refused: there its offsets are the reference ones, X_I - X_p, and its
// affine velocity the velocity's gradient in the reference configuration.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "core/scene.hpp"

namespace afemp::core {

// The [mpm] key and the message, or nothing.
inline std::optional<std::pair<std::string, std::string>> total_lagrangian_mpm_refusal(
    const MpmSettings& mpm) {
  if (mpm.formulation != Formulation::total_lagrangian) return std::nullopt;
  const std::string tl = "formulation = \"total-lagrangian\"";
  if (mpm.shape == ShapeFunction::cpdi1 || mpm.shape == ShapeFunction::cpdi2)
    return std::pair{std::string("shape_function"),
                     std::string("\"") + to_string(mpm.shape) + "\" with " + tl +
                         ": CPDI deforms the domains that the reference weights stand for; "
                         "allowed: \"linear\", \"gimp\", \"bspline2\", \"bspline3\""};
  if (mpm.splitting)
    return std::pair{std::string("splitting"),
                     "splitting with " + tl +
                         ": a split particle has no reference domain of its own; leave it out"};
  for (int f = 0; f < 6; ++f) {
    const FaceCondition c = mpm.grid.faces[static_cast<std::size_t>(f)];
    if (c == FaceCondition::wall || c == FaceCondition::outflow || c == FaceCondition::absorbing)
      return std::pair{std::string("formulation"),
                       std::string("grid face ") + to_string(static_cast<Face>(f)) + " is \"" +
                           to_string(c) + "\", a place in space, and " + tl +
                           "'s grid stands for the reference configuration; allowed there: "
                           "\"free\", \"fixed\", \"symmetric\""};
  }
  return std::nullopt;
}

// What the rest of the scene may not hold with the total-Lagrangian form: the key and the
// message, or nothing.
inline std::optional<std::pair<std::string, std::string>> total_lagrangian_scene_refusal(
    const Scene& scene) {
  if (scene.mpm.formulation != Formulation::total_lagrangian) return std::nullopt;
  const std::string tl = "[mpm] formulation = \"total-lagrangian\"";
  for (const BodySpec& b : scene.bodies)
    if (b.discretisation != Discretisation::particles)
      return std::pair{"bodies." + b.name,
                       "body \"" + b.name + "\" is of " + to_string(b.discretisation) + ", and " +
                           tl +
                           " runs bodies of particles only (elements and rebar couple through a "
                           "grid in space); use the updated-Lagrangian form"};
  if (!scene.contacts.empty())
    return std::pair{std::string("contact"),
                     "contact with " + tl +
                         ": bodies meet where they are, and the total-Lagrangian grid holds "
                         "where they started; use the updated-Lagrangian form"};
  if (!scene.walls.empty())
    return std::pair{std::string("walls"), "[[walls]] with " + tl +
                                               ": a wall is a place in space; use a fixed or "
                                               "symmetric grid face, or the updated-Lagrangian "
                                               "form"};
  return std::nullopt;
}

}  // namespace afemp::core
