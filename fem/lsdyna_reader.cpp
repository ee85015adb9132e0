// LS-DYNA keyword decks (.k, .key, .dyn; LS-DYNA Keyword User's Manual, Vol. I), the subset a
// hexahedron-and-truss mesh needs: *NODE, *ELEMENT_SOLID, *ELEMENT_BEAM, *PART, *SECTION_BEAM,
// *SET_NODE_LIST, *BOUNDARY_SPC_SET/NODE, in the deck and the files it includes
// (fem/lsdyna_keywords.hpp). Other keywords are the deck importer's (fem/lsdyna_deck_import.cpp).
#include <algorithm>
#include <array>
#include <iterator>
#include <map>
#include <unordered_set>
#include <utility>

#include "fem/lsdyna_keywords.hpp"
#include "fem/mesh_import.hpp"

namespace afemp::fem {

namespace {

using namespace import_detail;

using Card = LsDynaCard;
using Keyword = LsDynaKeyword;

// Keywords read here, and the options of theirs that are not: a deck using one of those would
// otherwise lose elements or constraints without a word.
const std::vector<std::string> kSupported = {"NODE",
                                             "ELEMENT_SOLID",
                                             "ELEMENT_BEAM",
                                             "PART",
                                             "PART_CONTACT",
                                             "SECTION_BEAM",
                                             "SECTION_BEAM_TITLE",
                                             "SET_NODE_LIST",
                                             "SET_NODE_LIST_TITLE",
                                             "BOUNDARY_SPC_SET",
                                             "BOUNDARY_SPC_NODE"};

struct PartCard {
  std::string title;
  std::int64_t section;
};

struct Spc {
  std::int64_t target;  // node set id, or node id when on_node
  bool on_node;
  std::array<bool, 3> fixed;
  const Card* card;
};

struct NodeList {
  std::string name;
  std::vector<std::pair<std::int64_t, const Card*>> nodes;  // (node id, its card)
};

class LsDynaReader {
 public:
  explicit LsDynaReader(const LsDynaDeck& deck) : deck_(deck) {}

  MeshData read() {
    for (const Keyword& k : deck_.keywords()) {
      key_ = "*" + k.name;
      if (k.name == "NODE")
        read_nodes(k);
      else if (k.name == "ELEMENT_SOLID")
        read_solids(k);
      else if (k.name == "ELEMENT_BEAM")
        read_beams(k);
      else if (k.name == "PART" || k.name == "PART_CONTACT")
        read_parts(k);
      else if (k.name.starts_with("SECTION_BEAM") && supported(k))
        read_beam_sections(k);
      else if (k.name.starts_with("SET_NODE_LIST") && supported(k))
        read_node_list(k);
      else if (k.name.starts_with("BOUNDARY_SPC_") && supported(k))
        read_spc(k);
      else
        for (const std::string& s : kSupported)
          if (k.name.starts_with(s + "_"))
            throw core::InputError(k.at(), key_,
                                   "this option of *" + s +
                                       " is not supported; supported "
                                       "keywords: " +
                                       supported_list());
    }
    add_elements();
    add_node_sets();
    add_constraints();
    validate(mesh_, deck_.files().front());
    return std::move(mesh_);
  }

 private:
  static bool supported(const Keyword& k) {
    return std::find(kSupported.begin(), kSupported.end(), k.name) != kSupported.end();
  }

  static std::string supported_list() {
    std::string s;
    for (const std::string& k : kSupported) s += (s.empty() ? "*" : ", *") + k;
    return s;
  }

  static core::SourceLocation at(const Card& c) { return c.at(); }

  std::int64_t integer(const std::vector<std::string_view>& f, std::size_t i, const Card& c,
                       const std::string& what) const {
    return card_integer(f, i, c, key_, what);
  }
  double real(const std::vector<std::string_view>& f, std::size_t i, const Card& c,
              const std::string& what) const {
    return card_real(f, i, c, key_, what);
  }

  void read_nodes(const Keyword& k) {
    for (const Card& c : k.cards) {
      if (c.blank()) continue;
      const auto f = card_fields(c, kNodeColumns);
      const std::int64_t nid = integer(f, 0, c, "the node id");
      if (nid <= 0) throw core::InputError(at(c), key_, "node ids must be positive");
      const std::string what = "a coordinate of node " + std::to_string(nid);
      numbering_.add(mesh_, nid, {real(f, 1, c, what), real(f, 2, c, what), real(f, 3, c, what)},
                     at(c), key_);
    }
  }

  // "eid pid n1 ... n8" on one card, or the legacy form "eid pid" with n1 ... n10 on the next.
  void read_solids(const Keyword& k) {
    for (std::size_t i = 0; i < k.cards.size(); ++i) {
      const Card& c = k.cards[i];
      if (c.blank()) continue;
      auto f = card_fields(c, kElementColumns);
      const std::int64_t eid = integer(f, 0, c, "the element id");
      const std::int64_t pid = integer(f, 1, c, "the part id of element " + std::to_string(eid));
      const std::string who = "element " + std::to_string(eid);
      f.erase(f.begin(), f.begin() + std::min<std::ptrdiff_t>(2, std::ssize(f)));
      const Card* node_card = &c;
      if (std::all_of(f.begin(), f.end(), [](std::string_view s) { return s.empty(); })) {
        if (i + 1 == k.cards.size())
          throw core::InputError(at(c), key_, who + ": the card with its nodes is missing");
        node_card = &k.cards[++i];
        f = card_fields(*node_card, kElementColumns);
        if (integer(f, 8, *node_card, "node 9 of " + who) != 0 ||
            integer(f, 9, *node_card, "node 10 of " + who) != 0)
          throw core::InputError(at(*node_card), key_,
                                 who + " has more than 8 nodes; only 8-node hexahedra are read");
      }
      RawElement raw{eid, {}, at(*node_card), key_, 0};
      for (std::size_t a = 0; a < 8; ++a)
        raw.nodes.push_back(integer(f, a, *node_card, "a node of " + who));
      add_raw(raw, pid, solid_ids_, hexahedra_, hex_pid_);
    }
  }

  void read_beams(const Keyword& k) {
    for (const Card& c : k.cards) {
      if (c.blank()) continue;
      const auto f = card_fields(c, kElementColumns);
      const std::int64_t eid = integer(f, 0, c, "the element id");
      const std::string who = "element " + std::to_string(eid);
      RawElement raw{eid,
                     {integer(f, 2, c, "node 1 of " + who), integer(f, 3, c, "node 2 of " + who)},
                     at(c),
                     key_,
                     0};
      add_raw(raw, integer(f, 1, c, "the part id of " + who), beam_ids_, lines_, line_pid_);
    }
  }

  void add_raw(const RawElement& raw, std::int64_t pid, std::unordered_set<std::int64_t>& ids,
               std::vector<RawElement>& list, std::vector<std::int64_t>& pids) {
    if (!ids.insert(raw.label).second)
      throw core::InputError(raw.at, key_,
                             "element " + std::to_string(raw.label) + " is already defined");
    list.push_back(raw);
    pids.push_back(pid);
  }

  void read_parts(const Keyword& k) {
    for (const LsDynaPart& p : lsdyna_parts(k))
      if (!parts_.emplace(p.id, PartCard{p.title, p.section}).second)
        throw core::InputError(p.card.at(), key_,
                               "part " + std::to_string(p.id) + " is already defined");
  }

  // "secid elform ..." then, for resultant beams (ELFORM 2) and trusses (3), "A ..." (with
  // _TITLE a title card first). Other formulations give their dimensions, not an area.
  void read_beam_sections(const Keyword& k) {
    const std::size_t per_section = k.name.ends_with("_TITLE") ? 3 : 2;
    for (std::size_t i = 0; i < k.cards.size(); i += per_section) {
      if (i + per_section > k.cards.size())
        throw core::InputError(at(k.cards[i]), key_,
                               "a section needs " + std::to_string(per_section) + " cards");
      const Card& c1 = k.cards[i + per_section - 2];
      const Card& c2 = k.cards[i + per_section - 1];
      const auto f1 = card_fields(c1, kStandardColumns);
      const std::int64_t secid = integer(f1, 0, c1, "the section id");
      const std::int64_t elform = integer(f1, 1, c1, "ELFORM");
      const double area = elform == 2 || elform == 3 ? real(card_fields(c2, kStandardColumns), 0,
                                                            c2, "the cross-section area A")
                                                     : 0.0;
      if (!beam_area_.emplace(secid, area).second)
        throw core::InputError(at(c1), key_,
                               "section " + std::to_string(secid) + " is already defined");
    }
  }

  void read_node_list(const Keyword& k) {
    LsDynaIdList list = lsdyna_id_list(k);
    const std::int64_t sid = list.id;
    NodeList nodes{list.title.empty() ? "set " + std::to_string(sid) : list.title,
                   std::move(list.ids)};
    if (!node_lists_.emplace(sid, std::move(nodes)).second)
      throw core::InputError(at(*list.card), key_,
                             "node set " + std::to_string(sid) + " is already defined");
  }

  // "nsid (or nid) cid dofx dofy dofz dofrx dofry dofrz", one constraint to a card.
  void read_spc(const Keyword& k) {
    const bool on_node = k.name == "BOUNDARY_SPC_NODE";
    for (const Card& c : k.cards) {
      if (c.blank()) continue;
      const auto f = card_fields(c, kStandardColumns);
      if (integer(f, 1, c, "CID") != 0)
        throw core::InputError(at(c), key_,
                               "constraints in a local coordinate system (CID) are not "
                               "supported; use CID = 0");
      Spc spc{integer(f, 0, c, on_node ? "the node id" : "the node set id"), on_node, {}, &c};
      for (std::size_t d = 0; d < 6; ++d) {
        const std::int64_t dof = integer(f, 2 + d, c, "a dof flag");
        if (dof != 0 && dof != 1)
          throw core::InputError(
              at(c), key_, "dof flags are 0 (free) or 1 (fixed), found " + std::to_string(dof));
        // Rotations mean nothing for hexahedra and trusses.
        if (d < 3) spc.fixed[d] = dof == 1;
      }
      spcs_.push_back(spc);
    }
  }

  // Parts in the order elements first use them; a heading shared by two parts gets the id.
  std::int32_t part_of(std::int64_t pid) {
    if (const auto it = part_index_.find(pid); it != part_index_.end()) return it->second;
    const auto card = parts_.find(pid);
    std::string name = card != parts_.end() && !card->second.title.empty()
                           ? card->second.title
                           : "part " + std::to_string(pid);
    if (std::find(mesh_.part_names.begin(), mesh_.part_names.end(), name) != mesh_.part_names.end())
      name += " (part " + std::to_string(pid) + ")";
    mesh_.part_names.push_back(name);
    mesh_.part_labels.push_back(pid);
    const auto index = static_cast<std::int32_t>(mesh_.part_names.size() - 1);
    part_index_.emplace(pid, index);
    return index;
  }

  double area_of(std::int64_t pid) const {
    const auto part = parts_.find(pid);
    if (part == parts_.end()) return 0.0;
    const auto section = beam_area_.find(part->second.section);
    return section == beam_area_.end() ? 0.0 : section->second;
  }

  void add_elements() {
    for (std::size_t e = 0; e < hexahedra_.size(); ++e) {
      mesh_.hexahedra.push_back(numbering_.hexahedron(hexahedra_[e]));
      mesh_.hexahedron_part.push_back(part_of(hex_pid_[e]));
    }
    for (std::size_t e = 0; e < lines_.size(); ++e) {
      mesh_.lines.push_back(numbering_.line(lines_[e]));
      mesh_.line_part.push_back(part_of(line_pid_[e]));
      mesh_.line_area.push_back(area_of(line_pid_[e]));
    }
  }

  void add_node_sets() {
    for (const auto& [sid, list] : node_lists_) {
      NamedSet set{list.name, {}};
      for (const auto& [nid, card] : list.nodes)
        set.members.push_back(
            numbering_.index(nid, card->at(), "*SET_NODE_LIST", "node set " + std::to_string(sid)));
      std::sort(set.members.begin(), set.members.end());
      set.members.erase(std::unique(set.members.begin(), set.members.end()), set.members.end());
      set_index_.emplace(sid, static_cast<std::int32_t>(mesh_.node_sets.size()));
      mesh_.node_sets.push_back(std::move(set));
    }
  }

  void add_constraints() {
    for (const Spc& spc : spcs_) {
      const core::SourceLocation where = spc.card->at();
      std::int32_t set = -1;
      if (spc.on_node) {
        set = single_node_set(
            mesh_, spc.target,
            numbering_.index(spc.target, where, "*BOUNDARY_SPC_NODE", "*BOUNDARY_SPC_NODE"));
      } else {
        const auto it = set_index_.find(spc.target);
        if (it == set_index_.end())
          throw core::InputError(where, "*BOUNDARY_SPC_SET",
                                 "node set " + std::to_string(spc.target) + " is not defined");
        set = it->second;
      }
      add_constraint(mesh_, set, spc.fixed);
    }
  }

  const LsDynaDeck& deck_;
  std::string key_;  // the keyword being read, for messages
  MeshData mesh_;
  NodeNumbering numbering_;
  std::vector<RawElement> hexahedra_, lines_;
  std::vector<std::int64_t> hex_pid_, line_pid_;
  std::unordered_set<std::int64_t> solid_ids_, beam_ids_;
  std::map<std::int64_t, PartCard> parts_;
  std::map<std::int64_t, double> beam_area_;  // section id -> A
  std::map<std::int64_t, NodeList> node_lists_;
  std::map<std::int64_t, std::int32_t> set_index_;  // node set id -> index in mesh.node_sets
  std::map<std::int64_t, std::int32_t> part_index_;
  std::vector<Spc> spcs_;
};

}  // namespace

MeshData lsdyna_mesh(const LsDynaDeck& deck) {
  return LsDynaReader(deck).read();
}

MeshData parse_lsdyna(const std::string& text, const std::string& path) {
  return lsdyna_mesh(LsDynaDeck::parse(text, path));
}

}  // namespace afemp::fem
