// Shape-function choices a scene is refused for, shared by the parser (file, line and key) and
// check_scene (scenes built in code).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "core/grid/bspline.hpp"
#include "core/scene.hpp"

namespace afemp::core {

// B-splines reach Order + 1 nodes per axis and are modified in the cells next to each face
// (core/grid/bspline.hpp): with fewer than bspline_min_cells cells along an axis every cell is
// a face cell and the basis is no longer the B-spline.
inline std::optional<std::string> spline_grid_refusal(const GridSettings& grid,
                                                      ShapeFunction shape) {
  if (!(grid.cell > 0.0)) return std::nullopt;  // no grid: refused elsewhere
  int order = 0;
  if (shape == ShapeFunction::bspline2) order = 2;
  if (shape == ShapeFunction::bspline3) order = 3;
  if (order == 0) return std::nullopt;
  const int need = bspline_min_cells(order);
  for (int a = 0; a < 3; ++a) {
    // As BackgroundGrid counts them: a domain that is not a whole number of cells is extended.
    const int cells =
        std::max(1, static_cast<int>(std::ceil((grid.max[a] - grid.min[a]) / grid.cell - 1e-9)));
    if (cells < need)
      return std::string("\"") + to_string(shape) + "\" needs at least " + std::to_string(need) +
             " cells along each axis (its support is " + std::to_string(order + 1) +
             " nodes wide); the grid has " + std::to_string(cells) + " along " + "xyz"[a] +
             "; allowed: a finer cell or a wider domain, or shape_function = \"linear\" or "
             "\"gimp\"";
  }
  return std::nullopt;
}

// Absorbing faces (Lysmer-Kuhlemeyer dashpots on the face's nodes) with the B-splines: a plane
// wave in an elastic column came back at 26 % (quadratic) and 35 % (cubic) of its amplitude,
// against 10.5 % with the linear hat (tests/mpm/test_absorbing_faces.cpp). Until the dashpots
// are worked out for the spline's face cells, the combination is refused.
inline std::optional<std::string> absorbing_face_shape_refusal(const GridSettings& grid,
                                                               ShapeFunction shape) {
  if (!grid.has_face(FaceCondition::absorbing) ||
      (shape != ShapeFunction::bspline2 && shape != ShapeFunction::bspline3))
    return std::nullopt;
  return std::string("\"") + to_string(shape) +
         "\" does not take absorbing faces (their dashpots let 26-35 % of a plane wave back "
         "with the B-splines, against 10 % with the linear hat); allowed: shape_function = "
         "\"linear\" or \"gimp\", or free, fixed, symmetric, wall or outflow faces";
}

// The affine transfer with the linear hat: a node at the far side of a particle's cell gets a
// tiny mass but a full-size gradient; the affine transfer carries its velocity back undamped
// and the run blows up (measured: the Taylor bar at step 382). uGIMP's and the B-splines'
// weights fade with their gradients, which is what the affine transfer needs.
// With CPDI the affine transfer is not built: its moment matrix D_p is full (the weights are
// not products of one per axis) and afemp's APIC inverts the diagonal one only.
inline std::optional<std::string> apic_shape_refusal(ShapeFunction shape, Transfer transfer) {
  if (transfer != Transfer::apic) return std::nullopt;
  if (shape == ShapeFunction::linear)
    return "\"apic\" needs shape_function = \"gimp\", \"bspline2\" or \"bspline3\" (the "
           "affine transfer is unstable with linear weights); allowed with \"linear\": \"flip\"";
  if (shape == ShapeFunction::cpdi1 || shape == ShapeFunction::cpdi2)
    return std::string("\"apic\" is not built for \"") + to_string(shape) +
           "\" (CPDI's weights are not products of one per axis, and afemp's affine transfer "
           "inverts the diagonal moment of those); allowed with \"" +
           to_string(shape) +
           "\": \"flip\", or \"apic\" with \"gimp\", \"bspline2\" or \"bspline3\"";
  return std::nullopt;
}

// Particle splitting halves a particle's axis-aligned lengths; a CPDI domain is a deformed
// parallelepiped or hexahedron that the split does not carry, so the two are not combined.
inline std::optional<std::string> cpdi_splitting_refusal(ShapeFunction shape) {
  if (shape != ShapeFunction::cpdi1 && shape != ShapeFunction::cpdi2) return std::nullopt;
  return std::string(
             "[mpm] splitting halves particles along x, y and z and does not split a "
             "CPDI domain; with shape_function = \"") +
         to_string(shape) +
         "\" leave it out (a domain that outgrows its stencil stops the run, naming the "
         "particle), or split with \"linear\", \"gimp\", \"bspline2\" or \"bspline3\"";
}

}  // namespace afemp::core
