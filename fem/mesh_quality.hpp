// Shape measures of hexahedra and lines, and a mesh-wide summary: the checks a starter makes
// before a run (scaled Jacobian as in the Verdict library, Knupp, SAND2007-2853; the explicit
// time-step length V / A_max of LS-DYNA's solid elements).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "afemp/tensor.hpp"
#include "fem/mesh.hpp"

namespace afemp::fem {

struct ElementQuality {
  // min over the 8 corners of det(J) / (|e1| |e2| |e3|), e_i the corner's three edges oriented
  // as the natural axes: 1 for a rectangular box, <= 0 for an inverted corner.
  double min_scaled_jacobian = 0.0;
  double aspect_ratio = 0.0;           // longest edge / shortest edge
  double characteristic_length = 0.0;  // volume / largest face area
  double volume = 0.0;                 // of the trilinear element, exact
};

// x in kHexNatural order. A face's area is half the norm of its diagonals' cross product (exact
// for a plane face, the projected area of a warped one).
ElementQuality hexahedron_quality(const std::array<core::Vec3, 8>& x);

// Worst values over a mesh, with the 0-based index of the element that has them. With no element
// of a kind, its minima stay +infinity, its maxima 0 and its indices -1.
struct MeshQualityReport {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  std::size_t hexahedra = 0, lines = 0;
  double min_scaled_jacobian = kNone;
  std::int32_t worst_jacobian_element = -1;
  double max_aspect_ratio = 0.0;
  std::int32_t worst_aspect_element = -1;
  double min_characteristic_length = kNone;
  std::int32_t smallest_element = -1;
  double min_line_length = kNone;
  std::int32_t shortest_line = -1;
  std::size_t inverted = 0;   // hexahedra with a non-positive corner Jacobian
  double total_volume = 0.0;  // of the hexahedra
};

MeshQualityReport mesh_quality(const MeshData& mesh);

}  // namespace afemp::fem
