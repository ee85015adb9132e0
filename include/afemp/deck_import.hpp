// Input decks of other codes turned into afemp scenes (`afemp import`, docs/import.md):
// LS-DYNA keyword decks (Keyword User's Manual, Vol. I and II; fem/lsdyna_deck_import.cpp)
// and MPM3D / MPM3D-F90 decks (Ma 2005, appendix A; mpm/mpm3d_deck_import.cpp).
#pragma once

#include <string>
#include <vector>

#include "afemp/errors.hpp"

namespace afemp::core {

enum class DeckFormat { none, lsdyna, mpm3d };

/// The deck format of a file, by its extension (.k, .key, .dyn; .mpm) or else its first line
/// (`*KEYWORD`; `mpm3...`); none for anything else (a scene).
DeckFormat deck_format(const std::string& path);
const char* to_string(DeckFormat format);  // "LS-DYNA", "MPM3D"

/// Something of the deck the scene does not carry as the deck meant it: `approximated`
/// (translated, with a stated difference) or not (not translated; the run lacks it).
/// `changes_run`: not translated, and the run differs for it (contact, an initial condition, a
/// boundary motion, a load, erosion, elements): the import stops unless allow_untranslated.
struct DeckNote {
  SourceLocation at;
  std::string keyword;
  std::string what;
  bool approximated = false;
  bool changes_run = false;
};

/// A file the scene refers to (a point list), named relative to the scene's folder.
struct DeckFile {
  std::string name;
  std::string text;
};

/// The scene (TOML text that core::read_scene reads, the notes as comments at its top), the
/// notes, and the files to write beside it.
struct DeckImport {
  std::string scene;
  std::string units;  // the units the scene is in, and whether the deck's were converted
  std::vector<DeckNote> notes;
  std::vector<DeckFile> files;
};

struct DeckImportOptions {
  /// The deck's unit system: "mm-ms-g" (mm, ms, g, N, MPa: afemp's examples), "m-s-kg" (SI),
  /// "mm-s-t" (mm, s, tonne, N, MPa), "mm-ms-kg" (mm, ms, kg, kN, GPa), "cm-us-g" (cm, us, g,
  /// Mbar); the scene is then written in mm, ms, g, N, MPa. Empty: the numbers are kept as
  /// they are (any consistent set), and the scene says so.
  std::string units;
  /// Write the scene even when the deck holds something that changes the run and is not
  /// translated (DeckNote::changes_run); the scene then lists it in `[run] untranslated`,
  /// which `afemp check` and `afemp run` repeat as warnings. Off: such a deck is refused.
  bool allow_untranslated = false;
};

/// Reads the deck at `deck_path` for a scene to be written at `scene_path` (which names the
/// side files and the relative path to a mesh). A deck that cannot be read, or that holds a
/// material or generator with no counterpart, is an InputError naming the file, the line,
/// the keyword or field and what is allowed; so is one holding a keyword that changes the run
/// and is not translated, unless options.allow_untranslated.
DeckImport import_deck(const std::string& deck_path, const std::string& scene_path,
                       const DeckImportOptions& options = {});

/// Writes the scene and its side files.
void write_deck_import(const DeckImport& deck, const std::string& scene_path);

/// The notes as lines "FILE:LINE: KEYWORD: not translated: WHAT" (or "approximated: ...", or
/// "not translated, the run differs: ..." for one that changes the run).
std::string describe(const DeckNote& note);

}  // namespace afemp::core

namespace afemp {
using core::deck_format;
using core::DeckFile;
using core::DeckFormat;
using core::DeckImport;
using core::DeckImportOptions;
using core::DeckNote;
using core::describe;
using core::import_deck;
using core::to_string;
using core::write_deck_import;
}  // namespace afemp
