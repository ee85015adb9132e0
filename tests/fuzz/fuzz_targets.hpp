// The inputs afemp reads from users, as fuzz targets: scene files, study files, Gmsh, Abaqus
// and LS-DYNA meshes, and the LS-DYNA and MPM3D deck importers. feed() gives a parser one input;
// a parser may accept it or refuse it with core::InputError (the file, line, key and what is
// allowed). Anything else that escapes, a crash, a hang or a sanitizer report is a finding.
// Used by the replay test of the default run (test_fuzz_replay.cpp) and by the libFuzzer
// targets (libfuzzer/fuzz_entry.cpp, label `fuzz`).
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "afemp/errors.hpp"
#include "analysis/study_file.hpp"
#include "core/scene.hpp"
#include "fem/lsdyna_deck_import.hpp"
#include "fem/mesh_import.hpp"
#include "mpm/mpm3d_deck_import.hpp"

namespace afemp::fuzz {

enum class Target { scene, study, gmsh, abaqus, lsdyna, mpm3d };
inline constexpr std::array<Target, 6> targets{Target::scene,  Target::study,  Target::gmsh,
                                               Target::abaqus, Target::lsdyna, Target::mpm3d};
// The corpus folder of each (tests/fuzz/corpus/NAME).
inline const char* name(Target t) {
  switch (t) {
    case Target::scene:
      return "scene";
    case Target::study:
      return "study";
    case Target::gmsh:
      return "gmsh";
    case Target::abaqus:
      return "abaqus";
    case Target::lsdyna:
      return "lsdyna";
    case Target::mpm3d:
      return "mpm3d";
  }
  return "?";
}

// The LS-DYNA target reads the text both as a mesh and as a deck to import; the paths only name
// the input in messages (an *INCLUDE is looked for beside a deck that is not there).
inline void feed(Target t, std::string_view data) {
  const std::string text(data);
  const std::string where = "/nonexistent/fuzz-input";
  try {
    switch (t) {
      case Target::scene:
        core::parse_scene(text, where + ".toml");
        break;
      case Target::study:
        analysis::parse_study(text, where + ".toml");
        break;
      case Target::gmsh:
        fem::parse_gmsh(text, where + ".msh");
        break;
      case Target::abaqus:
        fem::parse_abaqus(text, where + ".inp");
        break;
      case Target::lsdyna:
        try {
          fem::parse_lsdyna(text, where + ".k");
        } catch (const core::InputError&) {
        }
        fem::import_lsdyna_deck(text, where + ".k", where + "-scene.toml", {});
        break;
      case Target::mpm3d:
        mpm::import_mpm3d_deck(text, where + ".mpm", where + "-scene.toml", {});
        break;
    }
  } catch (const core::InputError&) {
    // A refusal with a message: what bad input must get.
  }
}

}  // namespace afemp::fuzz
