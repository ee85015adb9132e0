// The PER estimate of a conical shaped charge's jet-tip velocity (shaped_charge_per.hpp).
#include "analysis/shaped_charge_per.hpp"

#include <algorithm>
#include <cmath>

namespace afemp::analysis {

double gurney_tamped_sandwich(double m_over_c, double n_over_c) {
  const double a = (1.0 + 2.0 * m_over_c) / (1.0 + 2.0 * n_over_c);
  return 1.0 / std::sqrt((1.0 + a * a * a) / (3.0 * (1.0 + a)) + n_over_c * a * a + m_over_c);
}

PerCollapse per_steady_collapse(double collapse_velocity, double half_angle,
                                double sweep_velocity) {
  PerCollapse c;
  c.delta = std::asin(collapse_velocity / (2.0 * sweep_velocity));
  c.beta = half_angle + 2.0 * c.delta;
  const double turn = half_angle + c.delta - 0.5 * c.beta;
  c.jet_velocity = collapse_velocity * std::cos(turn) / std::sin(0.5 * c.beta);
  c.slug_velocity = collapse_velocity * std::sin(turn) / std::cos(0.5 * c.beta);
  return c;
}

LinerElement per_liner_element(const ConicalCharge& q, double z) {
  LinerElement e;
  e.z = z;
  const double cos_a = std::cos(q.half_angle), sin_a = std::sin(q.half_angle);
  e.outer_radius = (z - q.apex_z) * std::tan(q.half_angle);
  e.inner_radius = std::max(0.0, e.outer_radius - q.wall / cos_a);  // the wall, radially
  const double ro2 = e.outer_radius * e.outer_radius, ri2 = e.inner_radius * e.inner_radius;
  const double rc = q.charge_radius + q.case_thickness;
  const double liner = q.liner_density * (ro2 - ri2);  // each per pi per unit length
  const double explosive = q.explosive_density * (q.charge_radius * q.charge_radius - ro2);
  const double casing = q.case_density * (rc * rc - q.charge_radius * q.charge_radius);
  e.c_over_m = explosive / liner;
  e.n_over_c = casing / explosive;
  e.gurney_velocity = q.gurney_velocity * gurney_tamped_sandwich(1.0 / e.c_over_m, e.n_over_c);
  e.reach_velocity =
      std::sqrt(2.0 * q.cj_pressure * (e.inner_radius / cos_a) / (q.liner_density * q.wall));
  e.collapse_velocity = std::min(e.gurney_velocity, e.reach_velocity);
  // The ray from the detonation point to the outer surface against the wall's direction.
  const double ray = std::hypot(e.outer_radius, z - q.detonation_z);
  const double cos_theta = (e.outer_radius * sin_a + (z - q.detonation_z) * cos_a) / ray;
  e.sweep_velocity = q.detonation_velocity / cos_theta;
  e.collapse = per_steady_collapse(e.collapse_velocity, q.half_angle, e.sweep_velocity);
  return e;
}

double per_inner_apex(const ConicalCharge& q) {
  return q.apex_z + q.wall / std::sin(q.half_angle);
}

LinerElement per_tip_element(const ConicalCharge& q) {
  const double inner_apex = per_inner_apex(q);
  LinerElement best;
  for (int k = 1; inner_apex + k * per_element_step < q.base_z; ++k) {
    const LinerElement e = per_liner_element(q, inner_apex + k * per_element_step);
    if (e.collapse.jet_velocity > best.collapse.jet_velocity) best = e;
  }
  return best;
}

MergedTip per_merged_tip(const ConicalCharge& q) {
  const double inner_apex = per_inner_apex(q);
  const double step = per_element_step;
  const double fastest = per_tip_element(q).z;
  MergedTip tip;
  double momentum = 0.0;
  for (int k = 1; inner_apex + k * step < q.base_z; ++k) {
    const LinerElement e = per_liner_element(q, inner_apex + k * step);
    if (e.z > fastest && e.collapse.jet_velocity < tip.velocity) break;
    // The ring's liner mass per radian over the step, and its jet's share.
    const double ring = 0.5 * q.liner_density *
                        (e.outer_radius * e.outer_radius - e.inner_radius * e.inner_radius) * step;
    const double s = std::sin(0.5 * e.collapse.beta);
    tip.jet_mass += ring * s * s;
    momentum += ring * s * s * e.collapse.jet_velocity;
    tip.velocity = momentum / tip.jet_mass;
    tip.last_z = e.z;
  }
  return tip;
}

}  // namespace afemp::analysis
