// The jet-tip velocity a conical shaped charge should reach, estimated from its geometry alone
// (docs/explosives.md, "The PER estimate"): each liner element's Gurney collapse velocity, the
// Taylor deflection, and the steady collapse of Pugh, Eichelberger & Rostoker (1952).
// Units: those of the numbers given (mm, ms, g, MPa: velocities in m/s).
#pragma once

namespace afemp::analysis {

// Gurney's asymmetric sandwich with a tamper: a plate M driven by an explosive layer C with a
// tamper N on its far side, V / sqrt(2E) = ((1 + A^3) / (3 (1 + A)) + (N/C) A^2 + M/C)^(-1/2),
// A = (1 + 2 M/C) / (1 + 2 N/C) (Kennedy 1970; Cooper 1996). N = 0: the open-faced
// sandwich; N = M: the symmetric one, (2 M/C + 1/3)^(-1/2).
double gurney_tamped_sandwich(double m_over_c, double n_over_c);

// The steady collapse of a liner element (PER 1952; Walters & Zukas 1989, ch. 3): an element
// of a wall at half-angle alpha to the axis, swept by the detonation at `sweep_velocity` U
// along it, leaves at `collapse_velocity` V0, turned by Taylor's angle delta from the wall's
// normal, sin(delta) = V0 / (2 U). It meets the axis at the collapse angle beta = alpha + 2
// delta (steady: V0 the same along the wall), and splits there into the jet,
// Vj = V0 cos(alpha + delta - beta / 2) / sin(beta / 2), and the slug,
// Vs = V0 sin(alpha + delta - beta / 2) / cos(beta / 2).
struct PerCollapse {
  double delta = 0.0;  // rad
  double beta = 0.0;   // rad
  double jet_velocity = 0.0;
  double slug_velocity = 0.0;
};
PerCollapse per_steady_collapse(double collapse_velocity, double half_angle, double sweep_velocity);

// An axisymmetric charge: an explosive cylinder of `charge_radius` in a case `case_thickness`
// thick, a conical liner (outer surface's apex at `apex_z` on the axis, half-angle
// `half_angle`, `wall` thick normal to its surface, base at `base_z`), lit at a point on the
// axis at `detonation_z`.
struct ConicalCharge {
  double charge_radius = 0.0;
  double case_thickness = 0.0;
  double apex_z = 0.0;
  double half_angle = 0.0;  // rad
  double wall = 0.0;
  double base_z = 0.0;
  double detonation_z = 0.0;
  double explosive_density = 0.0;
  double liner_density = 0.0;
  double case_density = 0.0;
  double detonation_velocity = 0.0;  // D
  double cj_pressure = 0.0;          // p_CJ
  double gurney_velocity = 0.0;      // the explosive's sqrt(2E)
};

// One element of the liner: the slice of the charge normal to the axis at height z, its liner
// ring (outer radius r_o, inner r_i), the explosive ring from r_o to the charge's radius and
// the case ring, per unit length of the axis.
struct LinerElement {
  double z = 0.0;
  double outer_radius = 0.0;
  double inner_radius = 0.0;
  double c_over_m = 0.0;         // explosive over liner mass
  double n_over_c = 0.0;         // case over explosive mass
  double gurney_velocity = 0.0;  // the tamped sandwich's velocity with these ratios
  // The most the element can reach by the axis: driven at p_CJ over its way there, the
  // inner surface's distance to the axis along the wall's normal, r_i / cos(alpha):
  // sqrt(2 p_CJ (r_i / cos(alpha)) / (rho_liner wall)).
  double reach_velocity = 0.0;
  double collapse_velocity = 0.0;  // the lesser of the two
  // The detonation's sweep along the outer surface: D / cos(theta), theta the angle between
  // the ray from the detonation point and the wall.
  double sweep_velocity = 0.0;
  PerCollapse collapse{};
};

// The element at height z (a shell element: beyond the solid apex, where r_i > 0).
LinerElement per_liner_element(const ConicalCharge& charge, double z);

// The inner apex, where the liner first has a cavity: the outer apex plus the wall over
// sin(alpha). The estimates below sample the elements every `per_element_step` of z from it
// (the first one step beyond it) to the base.
double per_inner_apex(const ConicalCharge& charge);
inline constexpr double per_element_step = 0.01;

// The tip estimate: the element of the fastest steady jet.
LinerElement per_tip_element(const ConicalCharge& charge);

// The tip as the elements' inelastic merger: ahead of the fastest element the jets are slower
// (an inverse velocity gradient), so the elements behind overtake them and, mass and momentum
// kept, gather into one tip. Each element's jet is its liner ring's share sin^2(beta / 2) (PER
// 1952; Walters & Zukas 1989, ch. 3). Taken from the inner apex back, element by element:
// every element up to the fastest joins, and beyond it each element whose jet is
// still faster than the gathered tip; the first that is not ends the tip, as none behind it
// catches up (the jet velocity falls from there on). This is the tip's velocity once the
// merger is complete, with no break-up before it.
struct MergedTip {
  double last_z = 0.0;    // the last element that joins
  double jet_mass = 0.0;  // the tip's mass per radian of the charge (the full charge: 2 pi times)
  double velocity = 0.0;  // its mass-weighted jet velocity
};
MergedTip per_merged_tip(const ConicalCharge& charge);

}  // namespace afemp::analysis
