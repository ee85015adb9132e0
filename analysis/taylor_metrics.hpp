// Taylor-bar measures (Ma 2005, §2.3.2): final length L, impact-face diameter D and the
// diameter W at 0.2 L0 from the wall, and the mean relative error of eq 2-42,
// (|dL|/L + |dD|/D + |dW|/W) / 3, against reference values. Measured from the points that
// carry the bar's material (core::Model::body_points): particles with their half size, mesh
// nodes with 0.
#pragma once

#include <span>

#include "afemp/run.hpp"
#include "core/scene.hpp"

namespace afemp::analysis {

// Measures scene body `body`, a flat-ended cylinder whose base faces the wall, from its points
// at `position`, each standing for material reaching half_size[i] beyond it. D and W are twice
// the largest radius about the cylinder axis (a quarter bar gives the same radius). Points
// count for D within half a spacing of the wall end, for W within that band of 0.2 L0 from
// the wall end; a mesh body's band is at least half an initial element length, as its nodes
// lie on the surface. Throws std::invalid_argument naming the body when it is not a
// flat-ended cylinder or has no points.
TaylorMeasures measure_taylor(const Scene& scene, int body, std::span<const Vec3> position,
                              std::span<const double> half_size);

// Eq 2-42.
double taylor_mean_error(const TaylorMeasures& m, const TaylorReference& ref);

}  // namespace afemp::analysis
