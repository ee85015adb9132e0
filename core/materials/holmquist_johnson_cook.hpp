// The Holmquist-Johnson-Cook concrete model's own history: the largest compaction mu_max
// reached, which the compaction law's unloading reads (Holmquist, Johnson & Cook 1993;
// holmquist_johnson_cook.cpp, hjc_compaction.cpp).
#pragma once

#include <cstddef>

#include "core/materials/material.hpp"

namespace afemp::core {

// PointState::history slot of the largest volumetric strain mu = rho / rho0 - 1 reached.
inline constexpr std::size_t kMaxCompaction = 0;

}  // namespace afemp::core
