// MPM3D decks into afemp scenes: the free-format deck of MPM3D (Ma 2005, appendix A) and of its
// successor MPM3D-F90 (the public Fortran code's DataIn.f90 and Data/*.mpm): grid, time
// control, update scheme, materials with their EOS, particles (point lists and the block,
// sphere, block-with-hole and disc generators), initial velocities, gravity and contact.
#pragma once

#include <string>

#include "afemp/deck_import.hpp"

namespace afemp::mpm {

// `text` is the deck, `deck_path` its name in messages and notes; the particles of each body
// go to a point list beside the scene (DeckImport::files), named after `scene_path`.
core::DeckImport import_mpm3d_deck(const std::string& text, const std::string& deck_path,
                                   const std::string& scene_path,
                                   const core::DeckImportOptions& options);

}  // namespace afemp::mpm
