// Consistency checks and concatenation of meshes (fem/mesh.hpp).
#include "fem/mesh.hpp"

#include <algorithm>

#include "afemp/errors.hpp"

namespace afemp::fem {

namespace {

std::string node_name(const MeshData& m, std::int64_t i) {
  if (i >= 0 && static_cast<std::size_t>(i) < m.node_labels.size())
    return "node " + std::to_string(m.node_labels[static_cast<std::size_t>(i)]);
  return "node index " + std::to_string(i);
}

template <std::size_t N>
void check_element(const MeshData& m, const std::array<std::int32_t, N>& e, const char* kind,
                   std::size_t index, const std::string& source) {
  const auto n = static_cast<std::int64_t>(m.nodes.size());
  for (std::size_t a = 0; a < N; ++a) {
    if (e[a] < 0 || e[a] >= n)
      throw core::InputError({source, 0}, kind,
                             std::string(kind) + " " + std::to_string(index) + " refers to " +
                                 node_name(m, e[a]) + ", which does not exist");
    for (std::size_t b = 0; b < a; ++b)
      if (e[a] == e[b])
        throw core::InputError({source, 0}, kind,
                               std::string(kind) + " " + std::to_string(index) + " repeats " +
                                   node_name(m, e[a]) + " (degenerate element)");
  }
}

void check_set(const NamedSet& s, std::size_t count, const char* kind, const std::string& source) {
  for (std::int32_t i : s.members)
    if (i < 0 || static_cast<std::size_t>(i) >= count)
      throw core::InputError({source, 0}, s.name,
                             std::string(kind) + " set '" + s.name + "' lists index " +
                                 std::to_string(i) + ", outside 0.." + std::to_string(count));
}

}  // namespace

void validate(const MeshData& m, const std::string& source) {
  if (m.hexahedron_part.size() != m.hexahedra.size())
    throw core::InputError({source, 0}, "hexahedra", "one part index per hexahedron is required");
  if (m.line_part.size() != m.lines.size() || m.line_area.size() != m.lines.size())
    throw core::InputError({source, 0}, "lines", "one part index and area per line are required");
  if (!m.node_labels.empty() && m.node_labels.size() != m.nodes.size())
    throw core::InputError({source, 0}, "nodes", "node labels must be given for every node");
  for (std::size_t e = 0; e < m.hexahedra.size(); ++e)
    check_element(m, m.hexahedra[e], "hexahedron", e, source);
  for (std::size_t e = 0; e < m.lines.size(); ++e) check_element(m, m.lines[e], "line", e, source);
  const auto parts = static_cast<std::int32_t>(m.part_names.size());
  auto part_ok = [&](std::int32_t p) { return p >= 0 && p < parts; };
  if (!std::all_of(m.hexahedron_part.begin(), m.hexahedron_part.end(), part_ok) ||
      !std::all_of(m.line_part.begin(), m.line_part.end(), part_ok))
    throw core::InputError({source, 0}, "parts", "an element refers to a part that is not named");
  for (const NamedSet& s : m.node_sets) check_set(s, m.nodes.size(), "node", source);
  for (const NamedSet& s : m.hexahedron_sets)
    check_set(s, m.hexahedra.size(), "hexahedron", source);
  for (const NamedSet& s : m.line_sets) check_set(s, m.lines.size(), "line", source);
  for (const ImportedConstraint& c : m.constraints)
    if (c.node_set < 0 || static_cast<std::size_t>(c.node_set) >= m.node_sets.size())
      throw core::InputError({source, 0}, "constraints",
                             "a constraint refers to a missing node set");
}

void append(MeshData& m, const MeshData& o) {
  const auto node0 = static_cast<std::int32_t>(m.nodes.size());
  const auto hex0 = static_cast<std::int32_t>(m.hexahedra.size());
  const auto line0 = static_cast<std::int32_t>(m.lines.size());
  const auto part0 = static_cast<std::int32_t>(m.part_names.size());
  const auto nset0 = static_cast<std::int32_t>(m.node_sets.size());
  if (m.node_labels.size() == m.nodes.size() && o.node_labels.size() == o.nodes.size())
    m.node_labels.insert(m.node_labels.end(), o.node_labels.begin(), o.node_labels.end());
  else
    m.node_labels.clear();
  m.nodes.insert(m.nodes.end(), o.nodes.begin(), o.nodes.end());
  for (Hexahedron h : o.hexahedra) {
    for (auto& n : h) n += node0;
    m.hexahedra.push_back(h);
  }
  for (Line l : o.lines) {
    for (auto& n : l) n += node0;
    m.lines.push_back(l);
  }
  for (std::int32_t p : o.hexahedron_part) m.hexahedron_part.push_back(p + part0);
  for (std::int32_t p : o.line_part) m.line_part.push_back(p + part0);
  m.line_area.insert(m.line_area.end(), o.line_area.begin(), o.line_area.end());
  m.part_names.insert(m.part_names.end(), o.part_names.begin(), o.part_names.end());
  auto shifted = [](const std::vector<NamedSet>& sets, std::int32_t by) {
    std::vector<NamedSet> out = sets;
    for (NamedSet& s : out)
      for (auto& i : s.members) i += by;
    return out;
  };
  for (const NamedSet& s : shifted(o.node_sets, node0)) m.node_sets.push_back(s);
  for (const NamedSet& s : shifted(o.hexahedron_sets, hex0)) m.hexahedron_sets.push_back(s);
  for (const NamedSet& s : shifted(o.line_sets, line0)) m.line_sets.push_back(s);
  for (ImportedConstraint c : o.constraints) {
    c.node_set += nset0;
    m.constraints.push_back(c);
  }
}

}  // namespace afemp::fem
