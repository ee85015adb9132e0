// Taylor-bar measures (Ma 2005, §2.3.2): final length L, impact-face diameter D and the
// diameter W at 0.2 L0 from the wall, and the mean relative error of eq 2-42,
// (|dL|/L + |dD|/D + |dW|/W) / 3, against reference values. Solvers pass the points of the
// bar: particle centres with their half size, or mesh nodes (half size 0).
#pragma once

#include <span>

#include "afemp/run.hpp"
#include "core/scene.hpp"

namespace afemp::core {

// Measures a cylinder bar whose base faces the wall. Each point stands for material reaching
// half[i] beyond it (half may be empty: points on the surface, as mesh nodes are); D and W are
// twice the largest radius about the cylinder axis (a quarter bar gives the same radius).
// Points count for D within half a spacing of the wall end (the larger of the largest 2 half
// and `face_band`), for W within that band of 0.2 L0 from the wall end.
TaylorMeasures measure_taylor(std::span<const Vec3> points, std::span<const double> half,
                              const CylinderShape& bar, double face_band);

// The cylinder of scene body `body`; throws std::invalid_argument naming the body when it is
// not a cylinder.
const CylinderShape& taylor_bar(const Scene& scene, int body);

// Eq 2-42.
double taylor_mean_error(const TaylorMeasures& m, const TaylorReference& ref);

}  // namespace afemp::core
