// Taylor-bar measures (seed 001 §2.3.2): final length L, impact-face diameter D and the
// diameter W at 0.2 L0 from the wall, and the mean relative error of eq 2-42,
// (|dL|/L + |dD|/D + |dW|/W) / 3, against reference values.
#pragma once

#include "core/scene.hpp"
#include "mpm/particles.hpp"

namespace afemp::mpm {

struct TaylorMeasures {
  double length = 0.0, impact_diameter = 0.0, bulge_diameter = 0.0;
};

// Measures the particles of body number `body`, a cylinder whose base faces the wall. Material
// extends half a particle spacing (cube root of its volume) beyond each particle centre;
// D and W are twice the largest radius about the cylinder axis (symmetry planes through the
// axis are fine: a quarter bar gives the same radius).
TaylorMeasures measure_taylor(const Particles& particles, const core::Scene& scene, int body);

// Eq 2-42.
double taylor_mean_error(const TaylorMeasures& m, const core::TaylorReference& ref);

}  // namespace afemp::mpm
