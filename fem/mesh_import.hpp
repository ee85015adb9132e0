// Readers that turn meshes written by other tools into fem::MeshData: Gmsh "MSH file format"
// 4.1 ASCII, Abaqus .inp (Keywords Reference: *NODE, *ELEMENT, *NSET, *ELSET, *SOLID SECTION,
// *BOUNDARY) and the LS-DYNA keyword subset of fem/mesh.hpp (Keyword User's Manual, Vol. I).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "afemp/errors.hpp"
#include "core/source_text.hpp"
#include "fem/mesh.hpp"

namespace afemp::fem {

// Each reader keeps the file's node numbers in MeshData::node_labels, calls fem::validate and
// throws core::InputError naming the file, the line and the keyword (or Gmsh section) of the
// first problem. Elements other than 8-node hexahedra and 2-node lines are skipped.
MeshData read_gmsh(const std::string& path);    // .msh, version 4.1 ASCII
MeshData read_abaqus(const std::string& path);  // .inp
MeshData read_lsdyna(const std::string& path);  // .k, .key, .dyn
// Chooses the reader by the extension (case-insensitive); any other extension is an InputError
// listing the allowed ones.
MeshData read_mesh(const std::string& path);

// The same readers on text already in memory; `path` is the name used in messages.
MeshData parse_gmsh(const std::string& text, const std::string& path);
MeshData parse_abaqus(const std::string& text, const std::string& path);
MeshData parse_lsdyna(const std::string& text, const std::string& path);
// The mesh of a deck already cut into keywords (its *PART ids in MeshData::part_labels).
class LsDynaDeck;
MeshData lsdyna_mesh(const LsDynaDeck& deck);

// What the three readers share: numbered lines and numbers that must parse completely
// (core/source_text.hpp), and node labels that elements and sets refer to (which may be
// defined later in the file).
namespace import_detail {

using core::SourceText;
using core::split_fields;
using core::split_words;
using core::to_integer;
using core::to_real;
using core::trim;
using core::upper;

// An element as the file lists it, resolved to node indices once every node is known.
struct RawElement {
  std::int64_t label = 0;
  std::vector<std::int64_t> nodes;
  core::SourceLocation at;
  std::string key;
  std::int32_t part = 0;
};

// The file's node labels and the 0-based indices they got in MeshData::nodes.
class NodeNumbering {
 public:
  // Appends the node to mesh.nodes and mesh.node_labels; a label defined twice is an error.
  void add(MeshData& mesh, std::int64_t label, const core::Vec3& x, const core::SourceLocation& at,
           const std::string& key);
  // `who` ("element 7", "node set 'TOP'") starts the message when the label is not defined.
  std::int32_t index(std::int64_t label, const core::SourceLocation& at, const std::string& key,
                     const std::string& who) const;
  // The element's nodes as indices; an undefined node, a wrong node count or a repeated node
  // (a degenerate element) is an error at the element's line.
  Hexahedron hexahedron(const RawElement& e) const;
  Line line(const RawElement& e) const;

 private:
  std::unordered_map<std::int64_t, std::int32_t> index_;
  std::unordered_map<std::int64_t, int> defined_on_line_;
};

// Index of `name` in mesh.part_names, appended when new.
std::int32_t part_index(MeshData& mesh, const std::string& name);

// Index of the node set "node LABEL" holding only that node (for constraints the file puts on
// a single node), appended when new.
std::int32_t single_node_set(MeshData& mesh, std::int64_t label, std::int32_t node);

// Fixes translations on a node set; a set constrained twice keeps the union of the dofs, and
// a line fixing no translation (only rotations) adds nothing.
void add_constraint(MeshData& mesh, std::int32_t node_set, const std::array<bool, 3>& fixed);

}  // namespace import_detail

}  // namespace afemp::fem
