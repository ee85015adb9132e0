// LS-DYNA keyword decks cut into keywords and cards (LS-DYNA Keyword User's Manual, Vol. I,
// "General card format" and *INCLUDE): the layer the mesh reader (fem/lsdyna_reader.cpp) and
// the deck importer (fem/lsdyna_deck_import.cpp) share. Cards are fixed-column, or free
// format with commas; '$' starts a comment line.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/source_text.hpp"

namespace afemp::fem {

struct LsDynaCard {
  const core::SourceText* source;  // the file the card is in (a deck or an included file)
  std::size_t index;               // its line in that file
  std::string_view text;
  core::SourceLocation at() const { return source->at(index); }
  bool blank() const { return core::trim(text).empty(); }
};

struct LsDynaKeyword {
  std::string name;  // upper case, without '*'
  const core::SourceText* source;
  std::size_t index;
  std::vector<LsDynaCard> cards;  // comment lines ('$') removed; blank cards kept
  core::SourceLocation at() const { return source->at(index); }
};

// Card layouts: field widths of the fixed-column form.
inline constexpr std::array<std::size_t, 6> kNodeColumns{8, 16, 16, 16, 8, 8};
inline constexpr std::array<std::size_t, 10> kElementColumns{8, 8, 8, 8, 8, 8, 8, 8, 8, 8};
inline constexpr std::array<std::size_t, 8> kStandardColumns{10, 10, 10, 10, 10, 10, 10, 10};

// A deck's keywords in file order, with the keywords of the files it includes (*INCLUDE, whose
// card names a file relative to the including file's folder) spliced in where the *INCLUDE
// stands. The deck owns the text of every file, so cards stay valid while it lives. The long
// (20-column) and i10 formats, an *INCLUDE option (_PATH, _TRANSFORM, ...), a missing included
// file and an include cycle are InputErrors at the line that asks for them.
class LsDynaDeck {
 public:
  static LsDynaDeck read(const std::string& path);
  // `path` names the text in messages; includes are looked up beside it.
  static LsDynaDeck parse(std::string text, const std::string& path);

  const std::vector<LsDynaKeyword>& keywords() const { return keywords_; }
  // Every file read: the deck first, then its includes in the order met.
  std::vector<std::string> files() const;

 private:
  void add_file(std::string text, const std::string& path, std::vector<std::string>& open);

  std::deque<std::string> texts_;
  std::deque<core::SourceText> sources_;
  std::vector<LsDynaKeyword> keywords_;
};

// The card's fields: split at commas when it has any (free format), else cut into columns.
template <std::size_t N>
std::vector<std::string_view> card_fields(const LsDynaCard& c,
                                          const std::array<std::size_t, N>& columns) {
  if (c.text.find(',') != std::string_view::npos) return core::split_fields(c.text, ',');
  std::vector<std::string_view> out;
  std::size_t begin = 0;
  for (std::size_t w : columns) {
    out.push_back(begin < c.text.size() ? core::trim(c.text.substr(begin, w)) : std::string_view{});
    begin += w;
  }
  return out;
}

// Field i of a card's fields as a number; a blank or missing field is 0, as in LS-DYNA. `key`
// and `what` name it in the message of a field that is not a number.
std::int64_t card_integer(const std::vector<std::string_view>& f, std::size_t i,
                          const LsDynaCard& c, const std::string& key, const std::string& what);
double card_real(const std::vector<std::string_view>& f, std::size_t i, const LsDynaCard& c,
                 const std::string& key, const std::string& what);

// *SET_NODE_LIST, *SET_PART_LIST (*SET_PART): "SID ..." (with _TITLE a title card first), then
// the members' ids, 8 to a card (blank and 0 fields skipped).
struct LsDynaIdList {
  std::string title;
  std::int64_t id = 0;
  const LsDynaCard* card = nullptr;                             // the "SID ..." card
  std::vector<std::pair<std::int64_t, const LsDynaCard*>> ids;  // (member id, its card)
};
LsDynaIdList lsdyna_id_list(const LsDynaKeyword& k);

// *PART: pairs of cards, the heading, then "PID SECID MID EOSID HGID GRAV ADPOPT TMID".
struct LsDynaPart {
  std::string title;
  std::int64_t id = 0, section = 0, material = 0, eos = 0, hourglass = 0;
  bool extra = false;  // GRAV, ADPOPT or TMID set
  LsDynaCard card;     // the "PID ..." card
  // *PART_CONTACT's card "FS FD DC VC OPTT SFT SSF": the part's friction, which a contact with
  // FS = -1 takes; contact_extra when VC, OPTT, SFT or SSF is set.
  bool has_contact = false, contact_extra = false;
  double fs = 0, fd = 0, dc = 0;
};
// *PART and *PART_CONTACT (a third card per part: its contact data).
std::vector<LsDynaPart> lsdyna_parts(const LsDynaKeyword& part);

}  // namespace afemp::fem
