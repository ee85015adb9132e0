// Plausibility warnings: mistakes that run silently (a steel density of 7830 in a millimetre
// scene, an SI concrete pasted into one, E given in GPa where MPa is meant, a failure strain of
// 80, a quarter mesh without its symmetry constraints, a grid that is not a whole number of
// cells). The material checks use the scene's declared unit system ([run] units = "mm-ms-g"
// or "SI"); without one, each material is tried against the unit systems a scene may be in
// and a mix of two, or a material of another system than the others', is warned. The others
// always run, as does the list of what an imported scene's deck held untranslated ([run]
// untranslated, docs/import.md). `[run] quiet = ["KEY", ...]` silences the warnings of those
// keys (as the warning names them). `afemp check` and `afemp run` print them.
#pragma once

#include <string>
#include <vector>

#include "core/scene.hpp"

namespace afemp::core {

struct SceneWarning {
  SourceLocation where;
  std::string key;  // dotted, as `quiet` names it
  std::string message;
  std::string text() const;  // "FILE:LINE: key 'KEY': MESSAGE"
};

std::vector<SceneWarning> plausibility_warnings(const Scene& scene);

}  // namespace afemp::core
