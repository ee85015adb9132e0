// The surface of FE contact bodies for grid contact (coupled_model.hpp): the boundary faces of
// their live hexahedra (faces no other live hexahedron shares) and the outward unit normal at
// each surface node, the area-weighted mean of its faces' normals.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fem/fe_solver.hpp"

namespace afemp::coupling {

struct SurfaceFaces {
  std::vector<std::array<std::int32_t, 4>> nodes;  // FE nodes of each boundary face
  std::vector<std::int32_t> element;               // its hexahedron
};

// Boundary faces of the live hexahedra of the bodies with selected[body] != 0.
SurfaceFaces boundary_faces(const fem::HexElements& hexes, const std::vector<char>& selected);

// Outward unit normals at the FE nodes (size: all nodes) from the faces at positions x; nodes
// on no face get 0.
void surface_normals(const SurfaceFaces& faces, const fem::HexElements& hexes,
                     const std::vector<core::Vec3>& x, std::vector<core::Vec3>& normal);

}  // namespace afemp::coupling
