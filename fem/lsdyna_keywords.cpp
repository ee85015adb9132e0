// LS-DYNA decks cut into keywords and cards, includes spliced in (fem/lsdyna_keywords.hpp).
#include "fem/lsdyna_keywords.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace afemp::fem {

namespace {

std::string read_text(const std::string& path, const core::SourceLocation& asked_at,
                      const std::string& key) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::InputError(asked_at, key, "cannot open '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

LsDynaDeck LsDynaDeck::read(const std::string& path) {
  return parse(read_text(path, {path, 0}, "deck"), path);
}

LsDynaDeck LsDynaDeck::parse(std::string text, const std::string& path) {
  LsDynaDeck deck;
  std::vector<std::string> open;
  deck.add_file(std::move(text), path, open);
  return deck;
}

std::vector<std::string> LsDynaDeck::files() const {
  std::vector<std::string> out;
  for (const core::SourceText& s : sources_) out.push_back(s.path());
  return out;
}

// `open` holds the files being read (the chain of includes), to refuse a cycle.
void LsDynaDeck::add_file(std::string text, const std::string& path,
                          std::vector<std::string>& open) {
  open.push_back(std::filesystem::path(path).lexically_normal().string());
  const core::SourceText& src = sources_.emplace_back(texts_.emplace_back(std::move(text)), path);
  bool in_include = false;
  for (std::size_t i = 0; i < src.size(); ++i) {
    const std::string_view line = src.line(i);
    if (line.starts_with('$')) continue;
    if (line.starts_with('*')) {
      in_include = false;
      const auto words = core::split_words(line.substr(1));
      const std::string name = words.empty() ? "" : core::upper(words.front());
      if (name.ends_with('+') || name.ends_with('%') ||
          (name == "KEYWORD" && core::upper(line).find("LONG=") != std::string::npos))
        throw core::InputError(src.at(i), "*" + name,
                               "long (20-column) and i10 formats are not supported; write the "
                               "deck in the standard format");
      if (name == "END") break;
      if (name == "INCLUDE") {
        in_include = true;
        continue;
      }
      if (name.starts_with("INCLUDE"))
        throw core::InputError(src.at(i), "*" + name,
                               "only the plain *INCLUDE (a file name relative to the deck) is "
                               "read; merge the file or name it with *INCLUDE");
      keywords_.push_back({name, &src, i, {}});
    } else if (in_include) {
      const std::string_view name = core::trim(line);
      if (name.empty()) continue;
      const std::string file = (std::filesystem::path(path).parent_path() / std::string(name))
                                   .lexically_normal()
                                   .string();
      if (std::find(open.begin(), open.end(), file) != open.end())
        throw core::InputError(src.at(i), "*INCLUDE", "'" + file + "' includes itself");
      add_file(read_text(file, src.at(i), "*INCLUDE"), file, open);
    } else if (!keywords_.empty() && keywords_.back().source == &src) {
      keywords_.back().cards.push_back({&src, i, line});
    }
  }
  open.pop_back();
}

std::int64_t card_integer(const std::vector<std::string_view>& f, std::size_t i,
                          const LsDynaCard& c, const std::string& key, const std::string& what) {
  return i < f.size() && !f[i].empty() ? core::to_integer(f[i], c.at(), key, what) : 0;
}

double card_real(const std::vector<std::string_view>& f, std::size_t i, const LsDynaCard& c,
                 const std::string& key, const std::string& what) {
  return i < f.size() && !f[i].empty() ? core::to_real(f[i], c.at(), key, what) : 0.0;
}

LsDynaIdList lsdyna_id_list(const LsDynaKeyword& k) {
  const std::string key = "*" + k.name;
  const bool titled = k.name.ends_with("_TITLE");
  std::size_t i = 0;
  if (k.cards.size() < (titled ? 2u : 1u))
    throw core::InputError(k.at(), key, "the card 'sid ...' is missing");
  LsDynaIdList list;
  if (titled) list.title = std::string(core::trim(k.cards[i++].text));
  list.card = &k.cards[i++];
  list.id =
      card_integer(card_fields(*list.card, kStandardColumns), 0, *list.card, key, "the set id");
  for (; i < k.cards.size(); ++i) {
    const LsDynaCard& c = k.cards[i];
    const auto f = card_fields(c, kStandardColumns);
    for (std::size_t a = 0; a < f.size(); ++a)
      if (const std::int64_t id = card_integer(f, a, c, key, "an id"); id != 0)
        list.ids.emplace_back(id, &c);
  }
  return list;
}

std::vector<LsDynaPart> lsdyna_parts(const LsDynaKeyword& k) {
  const std::string key = "*" + k.name;
  const bool contact = k.name == "PART_CONTACT";
  const std::size_t per_part = contact ? 3 : 2;
  std::vector<LsDynaPart> parts;
  for (std::size_t i = 0; i < k.cards.size(); i += per_part) {
    if (i + 1 == k.cards.size())
      throw core::InputError(k.cards[i].at(), key,
                             "the card 'pid secid mid ...' after the heading is missing");
    const LsDynaCard& c = k.cards[i + 1];
    const auto f = card_fields(c, kStandardColumns);
    LsDynaPart p{std::string(core::trim(k.cards[i].text)),
                 card_integer(f, 0, c, key, "the part id"),
                 card_integer(f, 1, c, key, "the section id"),
                 card_integer(f, 2, c, key, "the material id"),
                 card_integer(f, 3, c, key, "the EOS id"),
                 card_integer(f, 4, c, key, "the hourglass id"),
                 false,
                 c};
    for (std::size_t a = 5; a < 8; ++a)
      p.extra = p.extra || card_real(f, a, c, key, "GRAV, ADPOPT or TMID") != 0.0;
    if (contact) {
      if (i + 2 == k.cards.size())
        throw core::InputError(c.at(), key,
                               "the card 'FS FD DC VC OPTT SFT SSF' after the part's is missing");
      const LsDynaCard& cc = k.cards[i + 2];
      const auto g = card_fields(cc, kStandardColumns);
      p.has_contact = true;
      p.fs = card_real(g, 0, cc, key, "FS");
      p.fd = card_real(g, 1, cc, key, "FD");
      p.dc = card_real(g, 2, cc, key, "DC");
      for (std::size_t a = 3; a < 7; ++a)
        p.contact_extra =
            p.contact_extra || card_real(g, a, cc, key, "VC, OPTT, SFT or SSF") != 0.0;
    }
    parts.push_back(std::move(p));
  }
  return parts;
}

}  // namespace afemp::fem
