// The model a scene describes: particles on the grid (MPM), a mesh (FE), or both coupled on
// the grid (contact, bonded rebar, conversion). What `afemp run` and `afemp study` build.
#pragma once

#include <memory>

#include "core/scene.hpp"
#include "core/time_loop.hpp"

namespace afemp::coupling {

std::unique_ptr<core::Model> make_model(const core::Scene& scene);
// The model keeps a reference to the scene: a temporary one would dangle.
std::unique_ptr<core::Model> make_model(core::Scene&&) = delete;

}  // namespace afemp::coupling
