// Lighting times of explosive points when the detonation travels through explosive only:
// Huygens' construction, the first arrival along the shortest path that stays in the
// explosive and bends around inert bodies and voids in its way (the "indirect path" lighting
// of hydrocodes; a wave shaper in a shaped charge). Each point lights at
// min over detonations of (time + path length / D); a detonation without `shadow` uses the
// straight line (core/programmed_burn.hpp).
//
// The path is found on voxels of the explosive (edge s, the points' spacing) by Lazy Theta*
// (A. Nash, S. Koenig & C. Tovey, "Lazy Theta*: any-angle path planning and path length
// analysis in 3D", AAAI 2010): a voxel's path runs straight from the last corner it could see,
// so points that see the detonation light at their exact straight-line time, and a path that
// bends does so at corners of the obstacle, within about a voxel of them.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "afemp/scene.hpp"

namespace afemp::core {

// Lighting times of explosive points x (detonation velocities D, one per point; the points
// stand about `spacing` apart and fill the explosive). +inf where no detonation reaches the
// point (a shadowed detonation cannot reach explosive cut off from it). Throws InputError
// naming a shadowed detonation that lies farther than two spacings from every explosive point.
std::vector<double> lighting_times(std::span<const Vec3> x, std::span<const double> D,
                                   double spacing, std::span<const DetonationSpec> detonations);

// lighting_times for a solver's explosive points of the scene's bodies (`body`: each point's
// index into scene.bodies). Throws InputError at the first shadowed detonation, naming the
// body and how many of its points no detonation reaches.
std::vector<double> explosive_lighting_times(std::span<const Vec3> x, std::span<const double> D,
                                             std::span<const std::int32_t> body, double spacing,
                                             const Scene& scene);

}  // namespace afemp::core
