// The surface of hexahedral meshes: the boundary faces of their live hexahedra (faces no other
// live hexahedron shares), each face's outward area vector, and the outward unit normal at each
// surface node, the area-weighted mean of its faces' normals. Grid contact of FE bodies
// (coupling/coupled_model.hpp) and the absorbing boundaries (absorbing_boundary.cpp) use them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fem/fe_solver.hpp"

namespace afemp::fem {

struct SurfaceFaces {
  std::vector<std::array<std::int32_t, 4>> nodes;  // FE nodes of each boundary face
  std::vector<std::int32_t> element;               // its hexahedron
};

// Sets hexes.across and its groups from the node lists (once, when the mesh is built).
void link_faces(HexElements& hexes);

// Boundary faces of the live hexahedra of the bodies with selected[body] != 0, in element
// order (each element's faces in the order of core::CellKind::hexahedron's). Linear in the
// elements once link_faces has run (elements that have not been linked are compared by
// sorting, as link_faces does).
SurfaceFaces boundary_faces(const HexElements& hexes, const std::vector<char>& selected);

// Face f's outward area vector at positions x: half the cross product of its diagonals, turned
// to point away from its hexahedron's centroid.
core::Vec3 face_area_vector(const SurfaceFaces& faces, std::size_t f, const HexElements& hexes,
                            const std::vector<core::Vec3>& x);

// Outward unit normals at the FE nodes (size: all nodes) from the faces at positions x; nodes
// on no face get 0.
void surface_normals(const SurfaceFaces& faces, const HexElements& hexes,
                     const std::vector<core::Vec3>& x, std::vector<core::Vec3>& normal);

}  // namespace afemp::fem
