// LS-DYNA keyword decks into afemp scenes: the mesh stays in the deck (the scene's bodies read
// it by part), and the keywords around it become the scene's materials, bodies, walls and run
// settings (LS-DYNA Keyword User's Manual, Vol. I (*PART, *SECTION, *HOURGLASS, *INITIAL,
// *RIGIDWALL, *CONTROL, *DATABASE) and Vol. II (*MAT, *EOS)). docs/import.md has the table.
#pragma once

#include <string>

#include "afemp/deck_import.hpp"

namespace afemp::fem {

// `text` is the deck at `deck_path` (its includes are read beside it); the scene's mesh files
// are written relative to `scene_path`.
core::DeckImport import_lsdyna_deck(const std::string& text, const std::string& deck_path,
                                    const std::string& scene_path,
                                    const core::DeckImportOptions& options);

}  // namespace afemp::fem
