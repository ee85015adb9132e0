// `afemp import` in the library (include/afemp/deck_import.hpp): the deck's format picks the
// importer, LS-DYNA's in fem/ and MPM3D's in mpm/.
#include "afemp/deck_import.hpp"

#include <fstream>
#include <sstream>

#include "fem/lsdyna_deck_import.hpp"
#include "mpm/mpm3d_deck_import.hpp"

namespace afemp::core {

DeckImport import_deck(const std::string& deck_path, const std::string& scene_path,
                       const DeckImportOptions& options) {
  const DeckFormat format = deck_format(deck_path);
  if (format == DeckFormat::none)
    throw InputError({deck_path, 0}, "import",
                     "not a deck afemp imports: LS-DYNA keyword decks (.k, .key, .dyn, or "
                     "starting with *KEYWORD) and MPM3D decks (.mpm, or starting with mpm3d)");
  std::ifstream in(deck_path, std::ios::binary);
  if (!in) throw InputError({deck_path, 0}, "import", "cannot open the deck");
  std::ostringstream text;
  text << in.rdbuf();
  return format == DeckFormat::lsdyna
             ? fem::import_lsdyna_deck(text.str(), deck_path, scene_path, options)
             : mpm::import_mpm3d_deck(text.str(), deck_path, scene_path, options);
}

}  // namespace afemp::core
