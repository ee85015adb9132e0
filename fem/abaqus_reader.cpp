// Abaqus input files (.inp; Abaqus Keywords Reference): *NODE, *ELEMENT (C3D8R and C3D8 become
// hexahedra, T3D2 lines), *NSET and *ELSET (lists and GENERATE), the truss area of *SOLID SECTION
// and the fixed translations of *BOUNDARY. Other keywords are skipped, as other tools' are.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "fem/mesh_import.hpp"

namespace afemp::fem {

namespace {

using namespace import_detail;

struct DataLine {
  std::size_t index;  // in the SourceText
  std::string_view text;
};

struct Keyword {
  std::string name;                               // upper case, blanks collapsed: "SOLID SECTION"
  std::map<std::string, std::string> parameters;  // upper-case name -> value ("" for a flag)
  std::size_t index;
  std::vector<DataLine> data;
};

// Keyword lines start with one '*', comments with "**"; a keyword line ending in a comma
// continues on the next line. Lines before the first keyword are ignored, as Abaqus does.
std::vector<Keyword> split_keywords(const SourceText& src) {
  std::vector<Keyword> keywords;
  for (std::size_t i = 0; i < src.size(); ++i) {
    const std::string_view line = trim(src.line(i));
    if (line.empty() || line.starts_with("**")) continue;
    if (!line.starts_with('*')) {
      if (!keywords.empty()) keywords.back().data.push_back({i, line});
      continue;
    }
    Keyword k{{}, {}, i, {}};
    std::string text(line);
    while (text.back() == ',' && i + 1 < src.size()) text += trim(src.line(++i));
    const auto fields = split_fields(std::string_view(text).substr(1), ',');
    for (char c : upper(fields[0]))
      if (!std::isspace(static_cast<unsigned char>(c)))
        k.name += c;
      else if (!k.name.empty() && k.name.back() != ' ')
        k.name += ' ';
    for (std::size_t f = 1; f < fields.size(); ++f) {
      if (fields[f].empty()) continue;
      const std::size_t eq = fields[f].find('=');
      const std::string name = upper(trim(fields[f].substr(0, eq)));
      k.parameters[name] = eq == std::string_view::npos ? "" : trim(fields[f].substr(eq + 1));
    }
    keywords.push_back(std::move(k));
  }
  return keywords;
}

// The fields of a data line without the empty one a trailing comma leaves.
std::vector<std::string_view> data_fields(std::string_view text) {
  auto fields = split_fields(text, ',');
  if (fields.size() > 1 && fields.back().empty()) fields.pop_back();
  return fields;
}

enum class Kind { hexahedron, line, other };

struct Member {
  std::int64_t label;
  std::size_t index;  // the line that lists it
};

struct LabelSet {
  std::string name;  // as first written; Abaqus set names are case-insensitive
  std::vector<Member> members;
};

struct Section {
  std::string elset;
  double area;
  std::size_t index;
};

struct Boundary {
  std::string target;  // a node label or a node set name
  std::array<bool, 3> fixed;
  std::size_t index;
};

class AbaqusReader {
 public:
  explicit AbaqusReader(const SourceText& src) : src_(src) {}

  MeshData read() {
    for (const Keyword& k : split_keywords(src_)) {
      if (k.name == "NODE")
        read_nodes(k);
      else if (k.name == "ELEMENT")
        read_elements(k);
      else if (k.name == "NSET")
        read_set(k, "NSET", nsets_);
      else if (k.name == "ELSET")
        read_set(k, "ELSET", elsets_);
      else if (k.name == "SOLID SECTION")
        read_section(k);
      else if (k.name == "BOUNDARY")
        read_boundary(k);
      else if (k.name == "PART")
        part_ = parameter(k, "NAME").value_or("");
      else if (k.name == "END PART")
        part_.clear();
      else if (k.name == "INCLUDE")
        throw core::InputError(at(k.index), "*INCLUDE",
                               "included files are not read; merge them into one input file");
      else if (k.name == "INSTANCE" && !k.data.empty())
        throw core::InputError(src_.at(k.data.front().index), "*INSTANCE",
                               "instance translations and rotations are not supported; write "
                               "the nodes where they are");
    }
    add_elements();
    add_element_sets();
    add_sections();
    add_node_sets();
    add_boundaries();
    validate(mesh_, src_.path());
    return std::move(mesh_);
  }

 private:
  core::SourceLocation at(std::size_t index) const { return src_.at(index); }

  std::optional<std::string> parameter(const Keyword& k, const std::string& name) const {
    const auto it = k.parameters.find(name);
    if (it == k.parameters.end()) return std::nullopt;
    return it->second;
  }

  std::string required(const Keyword& k, const std::string& name) const {
    const auto value = parameter(k, name);
    if (!value || value->empty())
      throw core::InputError(at(k.index), "*" + k.name, "the parameter " + name + "= is required");
    return *value;
  }

  LabelSet& set_named(std::vector<LabelSet>& sets, const std::string& name) {
    for (LabelSet& s : sets)
      if (upper(s.name) == upper(name)) return s;
    sets.push_back({name, {}});
    return sets.back();
  }

  const LabelSet* find_set(const std::vector<LabelSet>& sets, const std::string& name) const {
    for (const LabelSet& s : sets)
      if (upper(s.name) == upper(name)) return &s;
    return nullptr;
  }

  void read_nodes(const Keyword& k) {
    const std::string key = "*NODE";
    const auto system = parameter(k, "SYSTEM");
    if (system && upper(*system) != "R")
      throw core::InputError(at(k.index), key,
                             "SYSTEM=" + *system + " is not supported; give Cartesian coordinates");
    const auto nset = parameter(k, "NSET");
    LabelSet* set = nset ? &set_named(nsets_, *nset) : nullptr;
    for (const DataLine& d : k.data) {
      const auto f = data_fields(d.text);
      if (f.size() < 2) throw core::InputError(at(d.index), key, "expected 'label, x[, y[, z]]'");
      const std::int64_t label = to_integer(f[0], at(d.index), key, "the node label");
      core::Vec3 x;
      for (int c = 0; c < 3 && static_cast<std::size_t>(c) + 1 < f.size(); ++c)
        x[c] = to_real(f[static_cast<std::size_t>(c) + 1], at(d.index), key,
                       "a coordinate of node " + std::to_string(label));
      numbering_.add(mesh_, label, x, at(d.index), key);
      if (set != nullptr) set->members.push_back({label, d.index});
    }
  }

  void read_elements(const Keyword& k) {
    const std::string key = "*ELEMENT";
    const std::string type = upper(required(k, "TYPE"));
    const Kind kind = type == "C3D8R" || type == "C3D8" ? Kind::hexahedron
                      : type == "T3D2"                  ? Kind::line
                                                        : Kind::other;
    const std::size_t nodes = kind == Kind::hexahedron ? 8 : 2;
    const auto elset = parameter(k, "ELSET");
    LabelSet* set = elset ? &set_named(elsets_, *elset) : nullptr;
    const std::int32_t part = kind == Kind::other ? -1
                                                  : part_index(mesh_, elset            ? *elset
                                                                      : !part_.empty() ? part_
                                                                                       : "part 1");
    for (std::size_t i = 0; i < k.data.size(); ++i) {
      const std::size_t first = k.data[i].index;
      // An element continues on the next line while its line ends with a comma (and, for the
      // types read here, while it still lacks nodes).
      std::vector<std::string_view> f;
      while (true) {
        auto more = split_fields(k.data[i].text, ',');
        const bool continues = more.back().empty();
        if (continues) more.pop_back();
        f.insert(f.end(), more.begin(), more.end());
        if (!continues || i + 1 == k.data.size() || (kind != Kind::other && f.size() > nodes))
          break;
        ++i;
      }
      const std::int64_t label = to_integer(f[0], at(first), key, "the element label");
      const auto [it, added] = element_of_label_.emplace(label, std::pair{kind, std::size_t{0}});
      if (!added)
        throw core::InputError(at(first), key,
                               "element " + std::to_string(label) + " is already defined");
      if (set != nullptr) set->members.push_back({label, first});
      if (kind == Kind::other) continue;
      RawElement raw{label, {}, at(first), key, part};
      for (std::size_t a = 1; a < f.size(); ++a)
        raw.nodes.push_back(
            to_integer(f[a], at(first), key, "a node of element " + std::to_string(label)));
      std::vector<RawElement>& list = kind == Kind::hexahedron ? hexahedra_ : lines_;
      it->second.second = list.size();
      list.push_back(std::move(raw));
    }
  }

  // *NSET/*ELSET: labels, names of sets defined before, or with GENERATE 'first, last[, step]'.
  void read_set(const Keyword& k, const std::string& parameter_name, std::vector<LabelSet>& sets) {
    const std::string key = "*" + k.name;
    if (k.name == "NSET" && parameter(k, "ELSET"))
      throw core::InputError(at(k.index), key,
                             "ELSET= on *NSET is not supported; list the nodes or use GENERATE");
    const std::string name = required(k, parameter_name);
    const bool generate = parameter(k, "GENERATE").has_value();
    std::vector<Member> members;
    for (const DataLine& d : k.data) {
      const auto f = data_fields(d.text);
      if (generate) {
        if (f.size() != 2 && f.size() != 3)
          throw core::InputError(at(d.index), key, "GENERATE expects 'first, last[, increment]'");
        const auto first = to_integer(f[0], at(d.index), key, "the first label");
        const auto last = to_integer(f[1], at(d.index), key, "the last label");
        const auto step = f.size() == 3 ? to_integer(f[2], at(d.index), key, "the increment") : 1;
        if (step <= 0 || last < first)
          throw core::InputError(at(d.index), key,
                                 "GENERATE needs first <= last and a positive increment");
        // Every member names a node or element of this file, each a line of its own: a range
        // of far more labels than that is a typing slip (found by fuzzing: 101 .. 4294967296
        // took minutes and then all the memory).
        const double count = std::floor((static_cast<double>(last) - static_cast<double>(first)) /
                                        static_cast<double>(step)) +
                             1.0;
        const double most = std::max(1e6, 8.0 * static_cast<double>(src_.size()));
        if (count > most)
          throw core::InputError(at(d.index), key,
                                 "GENERATE " + std::to_string(first) + " .. " +
                                     std::to_string(last) + " step " + std::to_string(step) +
                                     " lists " + core::readable_count(count) +
                                     " labels, more than this file of " +
                                     std::to_string(src_.size()) + " lines can define");
        const auto n = static_cast<std::int64_t>(count);
        for (std::int64_t i = 0; i < n; ++i) members.push_back({first + i * step, d.index});
        continue;
      }
      for (std::string_view field : f) {
        if (field.empty()) continue;
        if (std::isalpha(static_cast<unsigned char>(field.front()))) {
          const LabelSet* other = find_set(sets, std::string(field));
          if (other == nullptr)
            throw core::InputError(at(d.index), key,
                                   "set '" + std::string(field) + "' is not defined before");
          members.insert(members.end(), other->members.begin(), other->members.end());
        } else {
          members.push_back(
              {to_integer(field, at(d.index), key, "a label of set '" + name + "'"), d.index});
        }
      }
    }
    LabelSet& set = set_named(sets, name);
    set.members.insert(set.members.end(), members.begin(), members.end());
  }

  // For trusses the data line of *SOLID SECTION is the cross-section area.
  void read_section(const Keyword& k) {
    const std::string elset = required(k, "ELSET");
    if (k.data.empty()) return;
    const auto f = data_fields(k.data.front().text);
    if (f.front().empty()) return;
    sections_.push_back(
        {elset,
         to_real(f.front(), at(k.data.front().index), "*SOLID SECTION", "the cross-section area"),
         k.index});
  }

  void read_boundary(const Keyword& k) {
    const std::string key = "*BOUNDARY";
    for (const DataLine& d : k.data) {
      const auto f = data_fields(d.text);
      if (f.size() < 2 || f[0].empty() || f[1].empty())
        throw core::InputError(at(d.index), key,
                               "expected 'node or node set, first dof[, last dof[, value]]' or "
                               "'node or node set, ENCASTRE'");
      std::array<bool, 3> fixed{false, false, false};
      if (std::isalpha(static_cast<unsigned char>(f[1].front()))) {
        fixed = symbolic_boundary(upper(f[1]), at(d.index));
      } else {
        const auto first = to_integer(f[1], at(d.index), key, "the first dof");
        const auto last = f.size() > 2 && !f[2].empty()
                              ? to_integer(f[2], at(d.index), key, "the last dof")
                              : first;
        if (first < 1 || last < first)
          throw core::InputError(at(d.index), key,
                                 "dofs must satisfy 1 <= first <= last, found " +
                                     std::to_string(first) + ".." + std::to_string(last));
        if (f.size() > 3 && !f[3].empty() &&
            to_real(f[3], at(d.index), key, "the prescribed value") != 0.0)
          throw core::InputError(at(d.index), key,
                                 "nonzero prescribed values are not supported, only fixed dofs");
        // Rotations (4-6) and other dofs mean nothing for hexahedra and trusses.
        for (std::int64_t dof = first; dof <= std::min<std::int64_t>(last, 3); ++dof)
          fixed[static_cast<std::size_t>(dof - 1)] = true;
      }
      boundaries_.push_back({std::string(f[0]), fixed, d.index});
    }
  }

  std::array<bool, 3> symbolic_boundary(const std::string& type,
                                        const core::SourceLocation& where) const {
    static const std::map<std::string, std::array<bool, 3>> translations = {
        {"ENCASTRE", {true, true, true}}, {"PINNED", {true, true, true}},
        {"XSYMM", {true, false, false}},  {"YSYMM", {false, true, false}},
        {"ZSYMM", {false, false, true}},  {"XASYMM", {false, true, true}},
        {"YASYMM", {true, false, true}},  {"ZASYMM", {true, true, false}}};
    const auto it = translations.find(type);
    if (it == translations.end())
      throw core::InputError(where, "*BOUNDARY",
                             "unknown boundary type '" + type +
                                 "'; allowed: ENCASTRE, PINNED, XSYMM, YSYMM, ZSYMM, XASYMM, "
                                 "YASYMM, ZASYMM");
    return it->second;
  }

  void add_elements() {
    for (const RawElement& e : hexahedra_) {
      mesh_.hexahedra.push_back(numbering_.hexahedron(e));
      mesh_.hexahedron_part.push_back(e.part);
    }
    for (const RawElement& e : lines_) {
      mesh_.lines.push_back(numbering_.line(e));
      mesh_.line_part.push_back(e.part);
      mesh_.line_area.push_back(0.0);
    }
  }

  // The element set split into the hexahedra and the lines it holds (skipped types dropped).
  std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>> split(const LabelSet& s) const {
    std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>> out;
    for (const Member& m : s.members) {
      const auto it = element_of_label_.find(m.label);
      if (it == element_of_label_.end())
        throw core::InputError(at(m.index), "*ELSET",
                               "element set '" + s.name + "' lists element " +
                                   std::to_string(m.label) + ", which is not defined");
      const auto index = static_cast<std::int32_t>(it->second.second);
      if (it->second.first == Kind::hexahedron) out.first.push_back(index);
      if (it->second.first == Kind::line) out.second.push_back(index);
    }
    for (auto* v : {&out.first, &out.second}) {
      std::sort(v->begin(), v->end());
      v->erase(std::unique(v->begin(), v->end()), v->end());
    }
    return out;
  }

  void add_element_sets() {
    for (const LabelSet& s : elsets_) {
      auto [hexahedra, lines] = split(s);
      if (!hexahedra.empty()) mesh_.hexahedron_sets.push_back({s.name, std::move(hexahedra)});
      if (!lines.empty()) mesh_.line_sets.push_back({s.name, std::move(lines)});
    }
  }

  void add_sections() {
    for (const Section& section : sections_) {
      const LabelSet* s = find_set(elsets_, section.elset);
      if (s == nullptr)
        throw core::InputError(at(section.index), "*SOLID SECTION",
                               "element set '" + section.elset + "' is not defined");
      for (std::int32_t line : split(*s).second)
        mesh_.line_area[static_cast<std::size_t>(line)] = section.area;
    }
  }

  void add_node_sets() {
    for (const LabelSet& s : nsets_) {
      NamedSet set{s.name, {}};
      for (const Member& m : s.members)
        set.members.push_back(
            numbering_.index(m.label, at(m.index), "*NSET", "node set '" + s.name + "'"));
      std::sort(set.members.begin(), set.members.end());
      set.members.erase(std::unique(set.members.begin(), set.members.end()), set.members.end());
      mesh_.node_sets.push_back(std::move(set));
    }
  }

  // A single-node target gets the node set "node LABEL"; repeated targets add dofs.
  void add_boundaries() {
    for (const Boundary& b : boundaries_) {
      std::int32_t set = -1;
      if (std::isalpha(static_cast<unsigned char>(b.target.front()))) {
        set = find_node_set(b.target);
        if (set < 0)
          throw core::InputError(at(b.index), "*BOUNDARY",
                                 "node set '" + b.target + "' is not defined");
      } else {
        const auto label = to_integer(b.target, at(b.index), "*BOUNDARY", "the node label");
        set = single_node_set(mesh_, label,
                              numbering_.index(label, at(b.index), "*BOUNDARY", "*BOUNDARY"));
      }
      add_constraint(mesh_, set, b.fixed);
    }
  }

  std::int32_t find_node_set(const std::string& name) const {
    for (std::size_t i = 0; i < mesh_.node_sets.size(); ++i)
      if (upper(mesh_.node_sets[i].name) == upper(name)) return static_cast<std::int32_t>(i);
    return -1;
  }

  const SourceText& src_;
  MeshData mesh_;
  NodeNumbering numbering_;
  std::string part_;  // the *PART being read, if any
  std::vector<RawElement> hexahedra_, lines_;
  std::unordered_map<std::int64_t, std::pair<Kind, std::size_t>> element_of_label_;
  std::vector<LabelSet> nsets_, elsets_;
  std::vector<Section> sections_;
  std::vector<Boundary> boundaries_;
};

}  // namespace

MeshData parse_abaqus(const std::string& text, const std::string& path) {
  const SourceText src(text, path);
  return AbaqusReader(src).read();
}

}  // namespace afemp::fem
