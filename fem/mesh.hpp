// A mesh as generated from the scene or read from a file, before it becomes part of a model:
// nodes, 8-node hexahedra and 2-node lines (trusses), with the parts, named sets and
// constraints the file carries. Importers and generators fill it; fem::FeModel is built from it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::fem {

// Hexahedron node order (the common one of LS-DYNA, Abaqus C3D8 and Gmsh type 5): nodes 0-3
// go round the face zeta = -1 and nodes 4-7 round zeta = +1, node a at the natural
// coordinates (xi, eta, zeta) of kHexNatural[a]. A well-formed element has a positive
// Jacobian in this order.
inline constexpr double kHexNatural[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                             {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

using Hexahedron = std::array<std::int32_t, 8>;  // 0-based indices into MeshData::nodes
using Line = std::array<std::int32_t, 2>;

// A named list of 0-based indices (into nodes, hexahedra or lines, as the field says).
struct NamedSet {
  std::string name;
  std::vector<std::int32_t> members;
};

// Translational degrees of freedom fixed on a node set (LS-DYNA *BOUNDARY_SPC_SET, Abaqus
// *BOUNDARY with dofs 1-3).
struct ImportedConstraint {
  std::int32_t node_set = -1;  // index into MeshData::node_sets
  std::array<bool, 3> fixed{false, false, false};
};

struct MeshData {
  std::vector<core::Vec3> nodes;
  std::vector<std::int64_t> node_labels;  // the source's node numbers (for messages); may be empty

  std::vector<Hexahedron> hexahedra;
  std::vector<std::int32_t> hexahedron_part;  // one per hexahedron, index into part_names

  std::vector<Line> lines;
  std::vector<std::int32_t> line_part;  // one per line, index into part_names
  std::vector<double> line_area;        // one per line; 0 where the source gives none

  std::vector<std::string> part_names;    // "part 1", "PLATE", ...: at least one when any element
  std::vector<std::int64_t> part_labels;  // the source's part ids (LS-DYNA *PART); may be empty

  std::vector<NamedSet> node_sets;
  std::vector<NamedSet> hexahedron_sets;
  std::vector<NamedSet> line_sets;
  std::vector<ImportedConstraint> constraints;
};

// Checks that every index is in range, that per-element vectors have one entry per element,
// and that no element repeats a node. Throws core::InputError naming `source` (the file or
// scene body the mesh came from) and the first offending element or set.
void validate(const MeshData& mesh, const std::string& source);

// Appends `other` to `mesh`, renumbering its nodes, parts and sets (names are kept).
void append(MeshData& mesh, const MeshData& other);

}  // namespace afemp::fem
