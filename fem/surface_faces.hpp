// The surface of meshes: the boundary faces of live hexahedra (faces no other live hexahedron
// shares) and of every element set with faces, a face's outward area vector, and the outward
// unit normal at each surface node, the area-weighted mean of its faces' normals. Grid contact
// of FE bodies (coupling/coupled_model.hpp), mesh contact (mesh_contact.cpp) and the absorbing
// boundaries (absorbing_boundary.cpp) use them.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "fem/fe_solver.hpp"

namespace afemp::fem {

// Sets hexes.across and its groups from the node lists (once, when the mesh is built).
void link_faces(HexElements& hexes);

// Appends the boundary faces of the live hexahedra of the bodies with selected[body] != 0, in
// element order (each element's faces in the order of core::CellKind::hexahedron's), named as
// of set `set`. Linear in the elements once link_faces has run (elements that have not been
// linked are compared by sorting, as link_faces does).
void boundary_faces(const HexElements& hexes, const std::vector<char>& selected, std::int32_t set,
                    SurfaceFaces& faces);
// The same as a list of its own (the hexahedra being FeSolver's first set).
SurfaceFaces boundary_faces(const HexElements& hexes, const std::vector<char>& selected);
// The boundary faces of every set's live elements of the selected bodies, set after set.
SurfaceFaces boundary_faces(std::span<ElementSet* const> sets, const std::vector<char>& selected);

// The outward area vector of the face with nodes q at positions x: half the cross product of
// its diagonals, turned to point away from its element's centroid.
core::Vec3 face_area_vector(const std::array<std::int32_t, 4>& q, const core::Vec3& centroid,
                            const std::vector<core::Vec3>& x);
// That of face f of the hexahedra's faces.
core::Vec3 face_area_vector(const SurfaceFaces& faces, std::size_t f, const HexElements& hexes,
                            const std::vector<core::Vec3>& x);

// Outward unit normals at the FE nodes (size: all nodes) from the faces at positions x; nodes
// on no face get 0.
void surface_normals(const SurfaceFaces& faces, const HexElements& hexes,
                     const std::vector<core::Vec3>& x, std::vector<core::Vec3>& normal);

}  // namespace afemp::fem
