// Crater and hole measures of a target (docs/study-format.md, metrics "crater" and "hole"),
// read from the positions of the points that carry its material (particles, the nodes of live
// elements: Model::body_points). Both work about an impact axis: the line through `point`
// along the unit `normal` of the struck face (pointing out of the target, at the projectile).
// For a point x, h = (x - point).normal is its height above `point` and r its distance from the
// axis. Quarter and half models measure the same as whole ones.
#pragma once

#include <span>

#include "afemp/tensor.hpp"

namespace afemp::analysis {

struct CraterMeasures {
  double depth = 0.0;  // NaN: no material left within `ring` of the axis (perforated)
  double diameter = 0.0;
};

// The highest h over the points: the struck face's level (at the start: the initial surface,
// measured on the same points so that a particle's half spacing below the surface cancels).
double surface_level(std::span<const Vec3> points, const Vec3& point, const Vec3& normal);

// The points are binned by r into rings of width `ring` (ring k: k ring <= r < (k + 1) ring).
// The surface of ring k is the top of its material column: its heights sorted, walked up from
// the lowest while successive heights are at most `ring` apart (ejecta flying above the
// surface are not the surface). The drop of ring k is initial_level - its surface (an empty
// ring: infinite). depth = the drop of ring 0. The crater's radius R is where the drop falls to
// `threshold`: between the centres of the last ring dropped by more and the first ring not,
// linearly interpolated (0 when ring 0 is not dropped by more than threshold; the outer edge of
// the outermost ring when every ring is); diameter = 2 R.
CraterMeasures measure_crater(std::span<const Vec3> points, const Vec3& point, const Vec3& normal,
                              double initial_level, double ring, double threshold);

// The hole's diameter: twice the smallest r among the points with |h| <= band (the material
// in a slab about the plate's mid-plane through `point`), i.e. the largest circle about the
// axis free of that material. NaN when no point lies in the slab. Points sit inside the
// material (a particle's material reaches half a spacing beyond it), so with particles the
// hole reads up to one particle spacing wide; nodes lie on the surface.
double measure_hole(std::span<const Vec3> points, const Vec3& point, const Vec3& normal,
                    double band);

}  // namespace afemp::analysis
