// Choosing a mesh reader by file extension, and the text handling the readers share
// (fem/mesh_import.hpp): numbered lines, strict number parsing, node labels to indices.
#include "fem/mesh_import.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fem/lsdyna_keywords.hpp"

namespace afemp::fem {

namespace import_detail {

void NodeNumbering::add(MeshData& mesh, std::int64_t label, const core::Vec3& x,
                        const core::SourceLocation& at, const std::string& key) {
  const auto index = static_cast<std::int32_t>(mesh.nodes.size());
  const auto [it, added] = index_.emplace(label, index);
  if (!added)
    throw core::InputError(at, key,
                           "node " + std::to_string(label) + " is already defined on line " +
                               std::to_string(defined_on_line_.at(label)));
  defined_on_line_.emplace(label, at.line);
  mesh.nodes.push_back(x);
  mesh.node_labels.push_back(label);
}

std::int32_t NodeNumbering::index(std::int64_t label, const core::SourceLocation& at,
                                  const std::string& key, const std::string& who) const {
  const auto it = index_.find(label);
  if (it == index_.end())
    throw core::InputError(at, key,
                           who + " lists node " + std::to_string(label) + ", which is not defined");
  return it->second;
}

namespace {

// `degenerate` says what a repeated node means for this shape.
template <std::size_t N>
std::array<std::int32_t, N> resolve(const NodeNumbering& numbering, const RawElement& e,
                                    const char* shape, const char* degenerate) {
  const std::string who = "element " + std::to_string(e.label);
  if (e.nodes.size() != N)
    throw core::InputError(e.at, e.key,
                           who + " lists " + std::to_string(e.nodes.size()) + " nodes; a " + shape +
                               " has " + std::to_string(N));
  std::array<std::int32_t, N> out{};
  for (std::size_t a = 0; a < N; ++a) {
    out[a] = numbering.index(e.nodes[a], e.at, e.key, who);
    for (std::size_t b = 0; b < a; ++b)
      if (e.nodes[a] == e.nodes[b])
        throw core::InputError(
            e.at, e.key, who + " repeats node " + std::to_string(e.nodes[a]) + ": " + degenerate);
  }
  return out;
}

}  // namespace

Hexahedron NodeNumbering::hexahedron(const RawElement& e) const {
  return resolve<8>(*this, e, "hexahedron",
                    "wedges and tetrahedra written as degenerate hexahedra are not supported");
}

Line NodeNumbering::line(const RawElement& e) const {
  return resolve<2>(*this, e, "line", "a line needs two distinct ends");
}

std::int32_t part_index(MeshData& mesh, const std::string& name) {
  const auto it = std::find(mesh.part_names.begin(), mesh.part_names.end(), name);
  if (it != mesh.part_names.end()) return static_cast<std::int32_t>(it - mesh.part_names.begin());
  mesh.part_names.push_back(name);
  return static_cast<std::int32_t>(mesh.part_names.size() - 1);
}

std::int32_t single_node_set(MeshData& mesh, std::int64_t label, std::int32_t node) {
  const std::string name = "node " + std::to_string(label);
  const auto it = std::find_if(mesh.node_sets.begin(), mesh.node_sets.end(),
                               [&](const NamedSet& s) { return s.name == name; });
  if (it != mesh.node_sets.end()) return static_cast<std::int32_t>(it - mesh.node_sets.begin());
  mesh.node_sets.push_back({name, {node}});
  return static_cast<std::int32_t>(mesh.node_sets.size() - 1);
}

void add_constraint(MeshData& mesh, std::int32_t node_set, const std::array<bool, 3>& fixed) {
  if (!fixed[0] && !fixed[1] && !fixed[2]) return;
  auto c = std::find_if(mesh.constraints.begin(), mesh.constraints.end(),
                        [&](const ImportedConstraint& x) { return x.node_set == node_set; });
  if (c == mesh.constraints.end()) {
    mesh.constraints.push_back({node_set, {false, false, false}});
    c = mesh.constraints.end() - 1;
  }
  for (std::size_t i = 0; i < 3; ++i) c->fixed[i] = c->fixed[i] || fixed[i];
}

}  // namespace import_detail

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::InputError({path, 0}, "mesh", "cannot open the mesh file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

MeshData read_gmsh(const std::string& path) {
  return parse_gmsh(read_text(path), path);
}
MeshData read_abaqus(const std::string& path) {
  return parse_abaqus(read_text(path), path);
}
MeshData read_lsdyna(const std::string& path) {
  return lsdyna_mesh(LsDynaDeck::read(path));
}

MeshData read_mesh(const std::string& path) {
  const std::string ext = import_detail::upper(std::filesystem::path(path).extension().string());
  if (ext == ".MSH") return read_gmsh(path);
  if (ext == ".INP") return read_abaqus(path);
  if (ext == ".K" || ext == ".KEY" || ext == ".DYN") return read_lsdyna(path);
  throw core::InputError({path, 0}, "mesh",
                         "unknown mesh file extension '" +
                             std::filesystem::path(path).extension().string() +
                             "'; allowed: .msh (Gmsh 4.1 ASCII), .inp (Abaqus), .k, .key, .dyn "
                             "(LS-DYNA keyword)");
}

}  // namespace afemp::fem
