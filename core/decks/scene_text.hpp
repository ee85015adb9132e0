// Writing scene TOML from a deck importer: numbers, strings and vectors in TOML's syntax, and
// the comment block at the top of an imported scene (what was read, in which units, and every
// note: nothing of the deck is left out without a line here).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "afemp/deck_import.hpp"

namespace afemp::core {

std::string toml_number(double v);  // round-trips a double ("190", "8.93e-03" style)
std::string toml_string(std::string_view s);
std::string toml_vec3(double x, double y, double z);

// "# Imported by afemp import from DECK (FORMAT) ...", the units, and the notes.
std::string imported_scene_header(const std::string& deck_path, DeckFormat format,
                                  const std::string& units, const std::vector<DeckNote>& notes);

// What changes the run and is not translated (DeckNote::changes_run): without
// options.allow_untranslated an InputError at the first, naming the others; with it,
// `untranslated_run_key` is the `[run]` line listing them ("" when there are none).
void refuse_untranslated(const std::vector<DeckNote>& notes, const DeckImportOptions& options);
std::string untranslated_run_key(const std::vector<DeckNote>& notes);

}  // namespace afemp::core
