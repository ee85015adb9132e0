// Gmsh "MSH file format" version 4.1, ASCII (Gmsh reference manual, section 10.1): nodes in
// entity blocks, 8-node hexahedra (type 5) and 2-node lines (type 1); physical groups give the
// parts and the named sets. Gmsh's type-5 node order is the one of fem/mesh.hpp.
#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include "fem/mesh_import.hpp"

namespace afemp::fem {

namespace {

using namespace import_detail;

constexpr int kGmshHexahedron = 5;
constexpr int kGmshLine = 1;

using DimTag = std::pair<int, int>;  // (dimension, tag): entity and group tags are per dimension

const char* dimension_name(int dim) {
  static const char* names[] = {"point", "curve", "surface", "volume"};
  return names[dim];
}

class GmshReader {
 public:
  explicit GmshReader(const SourceText& src) : src_(src) {}

  MeshData read() {
    skip_blank();
    if (line_ == src_.size() || trim(src_.line(line_)) != "$MeshFormat")
      throw core::InputError(src_.at(std::min(line_, src_.size())), "$MeshFormat",
                             "not a Gmsh file: the first section must be $MeshFormat");
    while (skip_blank(), line_ < src_.size()) {
      const std::string section(trim(src_.line(line_++)));
      if (section.empty() || section.front() != '$' || section.starts_with("$End"))
        throw core::InputError(here(), section,
                               "expected a section name such as $Nodes, found '" + section + "'");
      if (section == "$MeshFormat")
        read_format();
      else if (section == "$PhysicalNames")
        read_physical_names();
      else if (section == "$Entities")
        read_entities();
      else if (section == "$Nodes")
        read_nodes();
      else if (section == "$Elements")
        read_elements();
      else
        skip_section(section);
    }
    add_sets();
    validate(mesh_, src_.path());
    return std::move(mesh_);
  }

 private:
  core::SourceLocation here() const { return src_.at(line_ - 1); }  // the line last taken

  void skip_blank() {
    while (line_ < src_.size() && trim(src_.line(line_)).empty()) ++line_;
  }

  std::vector<std::string_view> next_words(const std::string& key, std::size_t at_least,
                                           const std::string& what) {
    if (line_ == src_.size())
      throw core::InputError(src_.at(line_ - 1), key, "the file ends before " + what);
    const auto words = split_words(src_.line(line_++));
    if (words.size() < at_least)
      throw core::InputError(here(), key,
                             "expected " + what + " (" + std::to_string(at_least) +
                                 " values), found " + std::to_string(words.size()) + " values");
    return words;
  }

  std::int64_t integer(std::string_view word, const std::string& key, const std::string& what) {
    return to_integer(word, here(), key, what);
  }

  void expect_end(const std::string& section) {
    const std::string end = "$End" + section.substr(1);
    if (line_ == src_.size() || trim(src_.line(line_)) != end)
      throw core::InputError(
          src_.at(std::min(line_, src_.size() - 1)), section,
          "expected " + end + " (do the counts in the section match its " + "contents?)");
    ++line_;
  }

  void skip_section(const std::string& section) {
    const std::string end = "$End" + section.substr(1);
    const core::SourceLocation start = here();
    while (line_ < src_.size())
      if (trim(src_.line(line_++)) == end) return;
    throw core::InputError(start, section, "section is not closed by " + end);
  }

  void read_format() {
    const std::string key = "$MeshFormat";
    const auto w = next_words(key, 3, "'version file-type data-size'");
    if (w[0] != "4.1")
      throw core::InputError(here(), key,
                             "Gmsh format version " + std::string(w[0]) +
                                 " is not supported; save the mesh as version 4.1 ASCII "
                                 "(Mesh.MshFileVersion = 4.1)");
    if (integer(w[1], key, "the file type") != 0)
      throw core::InputError(here(), key,
                             "binary Gmsh files are not supported; save the mesh as ASCII "
                             "(Mesh.Binary = 0)");
    expect_end(key);
  }

  void read_physical_names() {
    const std::string key = "$PhysicalNames";
    const auto count = integer(next_words(key, 1, "the number of names")[0], key, "the count");
    for (std::int64_t i = 0; i < count; ++i) {
      const auto w = next_words(key, 3, "'dimension tag \"name\"'");
      const int dim = dimension(w[0], key);
      const auto tag = static_cast<int>(integer(w[1], key, "the physical tag"));
      // The name is quoted and may contain blanks: everything after the tag.
      const std::string_view line = src_.line(line_ - 1);
      std::string_view name =
          trim(line.substr(static_cast<std::size_t>(w[1].data() - line.data()) + w[1].size()));
      if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
        name = name.substr(1, name.size() - 2);
      physical_names_[{dim, tag}] = std::string(name);
    }
    expect_end(key);
  }

  int dimension(std::string_view word, const std::string& key) {
    const auto dim = integer(word, key, "the dimension");
    if (dim < 0 || dim > 3)
      throw core::InputError(here(), key, "dimension " + std::to_string(dim) + " is outside 0..3");
    return static_cast<int>(dim);
  }

  void read_entities() {
    const std::string key = "$Entities";
    const auto w = next_words(key, 4, "'numPoints numCurves numSurfaces numVolumes'");
    std::int64_t count[4];
    for (int d = 0; d < 4; ++d) count[d] = integer(w[d], key, "an entity count");
    for (int dim = 0; dim < 4; ++dim)
      for (std::int64_t i = 0; i < count[dim]; ++i) {
        // Points: tag x y z; the others: tag and a bounding box; then the physical tags.
        const std::size_t first = dim == 0 ? 4 : 7;
        const std::string what = std::string(dimension_name(dim)) + " entity";
        const auto e = next_words(key, first + 1, "a " + what);
        const auto tag = static_cast<int>(integer(e[0], key, "the entity tag"));
        const auto n = integer(e[first], key, "the number of physical tags");
        if (n < 0 || first + 1 + static_cast<std::size_t>(n) > e.size())
          throw core::InputError(here(), key,
                                 what + " " + std::to_string(tag) + " lists " + std::to_string(n) +
                                     " physical tags but gives fewer");
        std::vector<int>& groups = entity_groups_[{dim, tag}];
        for (std::int64_t k = 0; k < n; ++k) {
          const auto g = static_cast<int>(
              integer(e[first + 1 + static_cast<std::size_t>(k)], key, "a physical tag"));
          groups.push_back(g);
          group_nodes_[{dim, g}];
        }
      }
    expect_end(key);
  }

  // The first line of $Nodes and $Elements: entity blocks and the total item count, which
  // the blocks must add up to.
  struct SectionHeader {
    std::int64_t blocks = 0, total = 0;
    core::SourceLocation where;
    const char* items;
    void check_count(std::int64_t read, const std::string& key) const {
      if (read != total)
        throw core::InputError(where, key,
                               "the header announces " + std::to_string(total) + " " + items +
                                   ", the blocks hold " + std::to_string(read));
    }
  };

  SectionHeader section_header(const std::string& key, const char* layout, const char* items) {
    const auto h = next_words(key, 4, layout);
    SectionHeader s;
    s.blocks = integer(h[0], key, "the number of entity blocks");
    s.total = integer(h[1], key, std::string("the number of ") + items);
    s.where = here();
    s.items = items;
    return s;
  }

  void read_nodes() {
    const std::string key = "$Nodes";
    const SectionHeader section =
        section_header(key, "'numEntityBlocks numNodes minNodeTag maxNodeTag'", "nodes");
    std::int64_t read = 0;
    for (std::int64_t b = 0; b < section.blocks; ++b) {
      const auto w = next_words(key, 4, "'entityDim entityTag parametric numNodesInBlock'");
      const DimTag entity{dimension(w[0], key),
                          static_cast<int>(integer(w[1], key, "the entity tag"))};
      const auto parametric = integer(w[2], key, "the parametric flag");
      if (parametric != 0 && parametric != 1)
        throw core::InputError(here(), key, "the parametric flag must be 0 or 1");
      const auto n = integer(w[3], key, "the number of nodes in the block");
      std::vector<std::int64_t> labels;
      for (std::int64_t i = 0; i < n; ++i)
        labels.push_back(integer(next_words(key, 1, "a node tag")[0], key, "the node tag"));
      // Parametric nodes carry as many parametric coordinates as their entity has dimensions.
      const std::size_t values = 3 + static_cast<std::size_t>(parametric * entity.first);
      for (std::int64_t label : labels) {
        const auto c = next_words(key, values, "the coordinates of node " + std::to_string(label));
        const std::string what = "a coordinate of node " + std::to_string(label);
        numbering_.add(mesh_, label,
                       {to_real(c[0], here(), key, what), to_real(c[1], here(), key, what),
                        to_real(c[2], here(), key, what)},
                       here(), key);
        for (int g : groups_of(entity))
          group_nodes_[{entity.first, g}].insert(static_cast<std::int32_t>(mesh_.nodes.size() - 1));
      }
      read += n;
    }
    section.check_count(read, key);
    expect_end(key);
  }

  void read_elements() {
    const std::string key = "$Elements";
    const SectionHeader section =
        section_header(key, "'numEntityBlocks numElements minTag maxTag'", "elements");
    std::int64_t read = 0;
    for (std::int64_t b = 0; b < section.blocks; ++b) {
      const auto w = next_words(key, 4, "'entityDim entityTag elementType numElementsInBlock'");
      const DimTag entity{dimension(w[0], key),
                          static_cast<int>(integer(w[1], key, "the entity tag"))};
      const auto type = integer(w[2], key, "the element type");
      const auto n = integer(w[3], key, "the number of elements in the block");
      const std::int32_t part =
          type == kGmshHexahedron || type == kGmshLine ? part_index(mesh_, part_name(entity)) : -1;
      for (std::int64_t i = 0; i < n; ++i) {
        const auto e = next_words(key, 2, "'elementTag nodeTag ...'");
        RawElement raw{integer(e[0], key, "the element tag"), {}, here(), key, part};
        for (std::size_t a = 1; a < e.size(); ++a)
          raw.nodes.push_back(integer(e[a], key, "a node tag"));
        add_element(raw, entity, type);
      }
      read += n;
    }
    section.check_count(read, key);
    expect_end(key);
  }

  void add_element(const RawElement& raw, const DimTag& entity, std::int64_t type) {
    const auto& groups = groups_of(entity);
    if (type == kGmshHexahedron) {
      mesh_.hexahedra.push_back(numbering_.hexahedron(raw));
      mesh_.hexahedron_part.push_back(raw.part);
      for (int g : groups)
        group_elements_[{entity.first, g}].push_back(
            static_cast<std::int32_t>(mesh_.hexahedra.size() - 1));
    } else if (type == kGmshLine) {
      mesh_.lines.push_back(numbering_.line(raw));
      mesh_.line_part.push_back(raw.part);
      mesh_.line_area.push_back(0.0);
      for (int g : groups)
        group_elements_[{entity.first, g}].push_back(
            static_cast<std::int32_t>(mesh_.lines.size() - 1));
    }
    // Every element, kept or not, brings its nodes into the node sets of its groups, so that a
    // physical surface meshed with quadrangles still names the nodes of that face.
    const std::string who = "element " + std::to_string(raw.label);
    for (std::int64_t label : raw.nodes) {
      const std::int32_t index = numbering_.index(label, raw.at, raw.key, who);
      for (int g : groups) group_nodes_[{entity.first, g}].insert(index);
    }
  }

  const std::vector<int>& groups_of(const DimTag& entity) const {
    static const std::vector<int> none;
    const auto it = entity_groups_.find(entity);
    return it == entity_groups_.end() ? none : it->second;
  }

  std::string group_name(const DimTag& group) const {
    const auto it = physical_names_.find(group);
    if (it != physical_names_.end()) return it->second;
    return "physical " + std::string(dimension_name(group.first)) + " " +
           std::to_string(group.second);
  }

  // The element's part is its entity's first physical group, or the entity itself.
  std::string part_name(const DimTag& entity) const {
    const auto& groups = groups_of(entity);
    if (!groups.empty()) return group_name({entity.first, groups.front()});
    return std::string(dimension_name(entity.first)) + " entity " + std::to_string(entity.second);
  }

  void add_sets() {
    for (const auto& [group, name] : physical_names_) group_nodes_[group];
    for (const auto& [group, nodes] : group_nodes_) {
      const std::string name = group_name(group);
      mesh_.node_sets.push_back({name, {nodes.begin(), nodes.end()}});
      const auto elements = group_elements_.find(group);
      NamedSet set{
          name, elements == group_elements_.end() ? std::vector<std::int32_t>{} : elements->second};
      if (group.first == 3) mesh_.hexahedron_sets.push_back(std::move(set));
      if (group.first == 1) mesh_.line_sets.push_back(std::move(set));
    }
  }

  const SourceText& src_;
  std::size_t line_ = 0;
  MeshData mesh_;
  NodeNumbering numbering_;
  std::map<DimTag, std::string> physical_names_;
  std::map<DimTag, std::vector<int>> entity_groups_;            // entity -> its physical tags
  std::map<DimTag, std::set<std::int32_t>> group_nodes_;        // group -> node indices
  std::map<DimTag, std::vector<std::int32_t>> group_elements_;  // group -> hexahedra or lines
};

}  // namespace

MeshData parse_gmsh(const std::string& text, const std::string& path) {
  const SourceText src(text, path);
  return GmshReader(src).read();
}

}  // namespace afemp::fem
