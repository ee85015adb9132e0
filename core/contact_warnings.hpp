// Bodies that meet without a contact that covers them: on the background grid two bodies of
// particles share one velocity field and weld where they meet (no slip, no separation);
// meshes, and particles and meshes, pass through each other unless a [[contact]], a bond or a
// conversion couples them. `afemp check` and `afemp run` print these warnings before the run.
#pragma once

#include <string>
#include <vector>

#include "core/model.hpp"
#include "core/scene.hpp"

namespace afemp::core {

// One line per pair of bodies whose boxes (their points with their half sizes, at the start)
// overlap or come within one grid cell (meshes without a grid: touch) with nothing between
// them: no [[contact]] naming both (a weld included), no bond, no conversion, no
// overlap_allowed.
std::vector<std::string> contact_warnings(const Scene& scene, const Model& model);

}  // namespace afemp::core
