// Verification of the explicit FE solver against closed forms (VALIDATION.md W1-W3): the 1-D
// stress wave in a bar (front at c = sqrt(E / rho), tension reflected at a free end), the
// axial frequency c / (4 L) of a fixed-free bar of hexahedra and of trusses, and the
// Euler-Bernoulli cantilever frequency (1.8751^2 / 2 pi) sqrt(E I / (rho A L^4)).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {
namespace {

constexpr double young = 200e3, density = 7.85e-3;  // steel; units mm, ms, g, N, MPa
const double bar_speed = std::sqrt(young / density);

std::string steel(double nu) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = %g\n", nu);
  return buf;
}

// A mesh body named "bar" with its shape and mesh lines, clamped (all components) at z = 0.
std::string clamped_body(double nu, const std::string& body_lines) {
  return "[run]\nend_time = 1.0\n" + steel(nu) +
         "[[bodies]]\nname = \"bar\"\nmaterial = \"steel\"\n" + body_lines +
         "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
         "fixed = [\"all\"]\n";
}

std::string element_name(const ::testing::TestParamInfo<const char*>& info) {
  return std::string(info.param) == "full" ? "FullBbar" : "OnePoint";
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Mean displacement component `axis` of the nodes that start on the plane z = at.
double mean_displacement(const FeNodes& n, double at, int axis) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < n.size(); ++i)
    if (std::abs(n.initial_position[i].z - at) < 1e-9) {
      sum += n.position[i][axis] - n.initial_position[i][axis];
      ++count;
    }
  return sum / count;
}

struct Vibration {
  double period = 0.0;  // 0: fewer than two crossings
  double max_displacement = 0.0;
  double max_internal = 0.0, max_hourglass = 0.0;  // over the run
  double max_stabilisation = 0.0;  // assumed-strain stabilisation (part of internal)
  // core::energy_balance_error, largest over the run. The kinetic energy is that of the
  // half-step velocities, so kinetic + internal swings by up to omega dt / 2 of the total in a
  // vibration without drifting.
  double max_balance_error = 0.0;
};

// Starts a body clamped at z = 0 at rest in its undeformed shape with the velocity component
// `axis` = v(z) (a mode shape), runs it to t = duration and measures the period of the
// displacement of the plane z = tip from its zero crossings (linear interpolation between
// steps), counting t = 0, where it starts, as the first crossing.
template <class Shape>
Vibration vibrate(FeSolver& solver, int axis, Shape v, double tip, double duration) {
  FeNodes& nodes = solver.mutable_nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    nodes.velocity[i][axis] = v(nodes.initial_position[i].z);
  Vibration out;
  const core::Energies initial = solver.energies();
  double max_kinetic = initial.kinetic;
  std::vector<double> crossings{0.0};
  double t_prev = 0.0, u_prev = 0.0;
  while (solver.time() < duration) {
    solver.step(solver.stable_time_step());
    const double u = mean_displacement(solver.nodes(), tip, axis);
    if (solver.step_count() > 1 && (u < 0.0) != (u_prev < 0.0))
      crossings.push_back(t_prev + (solver.time() - t_prev) * u_prev / (u_prev - u));
    t_prev = solver.time();
    u_prev = u;
    out.max_displacement = std::max(out.max_displacement, std::abs(u));
    const core::Energies e = solver.energies();
    out.max_internal = std::max(out.max_internal, e.internal);
    out.max_hourglass = std::max(out.max_hourglass, e.hourglass);
    out.max_stabilisation = std::max(out.max_stabilisation, e.stabilisation);
    max_kinetic = std::max(max_kinetic, e.kinetic);
    out.max_balance_error = std::max(out.max_balance_error,
                                     std::abs(core::energy_balance_error(e, initial, max_kinetic)));
  }
  if (crossings.size() > 1)
    out.period = 2.0 * crossings.back() / static_cast<double>(crossings.size() - 1);
  return out;
}

// ---------------------------------------------------------------------------------------------
// W1: a velocity step at one end of a free bar.

// Means over the slab |z - at| < half: axial stress of the hexahedra whose centroid lies in it,
// axial velocity of its nodes.
struct Slab {
  double stress = 0.0, velocity = 0.0;
};
Slab slab(const FeSolver& solver, double at, double half) {
  const FeNodes& n = solver.nodes();
  const HexElements& h = solver.hexahedra();
  const std::size_t points = h.stress.size() / h.size();
  Slab s;
  int elements = 0, nodes = 0;
  for (std::size_t e = 0; e < h.size(); ++e) {
    double z = 0.0;
    for (std::int32_t a : h.nodes[e])
      z += 0.125 * n.initial_position[static_cast<std::size_t>(a)].z;
    if (std::abs(z - at) >= half) continue;
    for (std::size_t g = 0; g < points; ++g)
      s.stress += h.stress[points * e + g].zz / static_cast<double>(points);
    ++elements;
  }
  for (std::size_t i = 0; i < n.size(); ++i)
    if (std::abs(n.initial_position[i].z - at) < half) {
      s.velocity += n.velocity[i].z;
      ++nodes;
    }
  if (elements > 0) s.stress /= elements;
  if (nodes > 0) s.velocity /= nodes;
  return s;
}

class FeWaveInBar : public ::testing::TestWithParam<const char*> {};

TEST_P(FeWaveInBar, FrontRunsAtBarSpeedAndReflectsAsTensionAtTheFreeEnd) {
  // A steel bar 2 x 2 x 100 mm (1 x 1 x 0.5 mm elements) at rest, nu = 0.3, lateral faces free
  // (uniaxial stress); the end z = 0 is driven at v0 along +z from t = 0 (its lateral velocity
  // held at 0). Theory: a compressive front at the bar speed c = sqrt(E / rho) (the 3-D
  // dilatational speed is 16 % higher) with sigma = -rho c v0 and velocity v0 behind it; at the
  // free end it reflects as tension, leaving sigma = 0 and velocity 2 v0.
  const double length = 100.0, v0 = 1.0;
  const std::string text = "[run]\nend_time = 1.0\n" + steel(0.3) + R"(
[[bodies]]
name = "bar"
material = "steel"
discretisation = "hexahedra"
element = ")" + std::string(GetParam()) +
                           R"("
shape = { box = { min = [0, 0, 0], max = [2, 2, 100] } }
mesh = { divisions = [2, 2, 200] }
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }
velocity = [0, 0, 1]
)";
  const core::Scene scene = core::parse_scene(text, "w1.toml");
  const auto t0 = std::chrono::steady_clock::now();
  FeSolver solver(scene);
  const double plateau = -density * bar_speed * v0;
  // Arrival at a station: the first crossing of half the plateau by the stress of the one
  // element layer centred there, interpolated in time.
  const double stations[2] = {20.25, 70.25};
  double arrival[2] = {-1.0, -1.0}, previous[2] = {0.0, 0.0}, t_prev = 0.0;
  // The incident state 30 mm behind the front when it reaches the free end, and the reflected
  // state 50 mm behind the reflected front at t = 1.8 L / c; both over z = 70 +- 2 mm.
  Slab incident, reflected;
  bool incident_taken = false;
  const core::Energies initial = solver.energies();
  double max_kinetic = 0.0;
  while (solver.time() < 1.8 * length / bar_speed) {
    solver.step(solver.stable_time_step());
    max_kinetic = std::max(max_kinetic, solver.energies().kinetic);
    for (int k = 0; k < 2; ++k) {
      const double s = slab(solver, stations[k], 0.25).stress;
      if (arrival[k] < 0.0 && s <= 0.5 * plateau)
        arrival[k] =
            t_prev + (solver.time() - t_prev) * (0.5 * plateau - previous[k]) / (s - previous[k]);
      previous[k] = s;
    }
    t_prev = solver.time();
    if (!incident_taken && solver.time() >= length / bar_speed) {
      incident = slab(solver, 70.0, 2.0);
      incident_taken = true;
    }
  }
  reflected = slab(solver, 70.0, 2.0);
  // The driver's work (the reaction at the driven end times v0) against kinetic + internal +
  // hourglass energy, at the end: the work is booked a step after the strain it causes, which
  // matters only in the first few steps.
  const double balance = core::energy_balance_error(solver.energies(), initial, max_kinetic);
  const double c = (stations[1] - stations[0]) / (arrival[1] - arrival[0]);
  std::printf(
      "[W1 %s, 2x2x200 hexahedra, nu 0.3, %ld steps, %.2f s] front speed %.6g, reference "
      "sqrt(E/rho) %.6g: error %+.3f %% (tolerance 2 %%)\n"
      "  incident at z = 70: stress %.4g MPa (reference %.4g), velocity %.4g (reference "
      "%.4g); reflected: stress %.4g (reference 0), velocity %.4g (reference %.4g); "
      "tolerance 5 %% of the plateau; energy balance error %.3g\n",
      GetParam(), solver.step_count(), seconds_since(t0), c, bar_speed,
      100.0 * (c / bar_speed - 1.0), incident.stress, plateau, incident.velocity, v0,
      reflected.stress, reflected.velocity, 2.0 * v0, balance);
  EXPECT_NEAR(c, bar_speed, 0.02 * bar_speed);
  EXPECT_NEAR(incident.stress, plateau, 0.05 * std::abs(plateau));
  EXPECT_NEAR(incident.velocity, v0, 0.05 * v0);
  // The reflected wave is tensile: it lifts the stress by rho c v0, back to zero.
  EXPECT_NEAR(reflected.stress - incident.stress, -plateau, 0.05 * std::abs(plateau));
  EXPECT_NEAR(reflected.stress, 0.0, 0.05 * std::abs(plateau));
  EXPECT_NEAR(reflected.velocity, 2.0 * v0, 0.05 * v0);
  EXPECT_LT(std::abs(balance), 0.01);
}

INSTANTIATE_TEST_SUITE_P(BothHexahedra, FeWaveInBar, ::testing::Values("one-point", "full"),
                         element_name);

// ---------------------------------------------------------------------------------------------
// W2: axial vibration of a fixed-free bar, f1 = c / (4 L), started in its first mode
// v_z = v0 sin(pi z / (2 L)).

auto first_axial_mode(double length) {
  return [length](double z) { return 0.1 * std::sin(0.5 * std::numbers::pi * z / length); };
}

class FeFixedFreeBar : public ::testing::TestWithParam<const char*> {};

TEST_P(FeFixedFreeBar, FirstAxialFrequencyIsBarSpeedOverFourLengths) {
  // 2 x 2 x 100 mm in 1 x 1 x 2.5 mm elements, nu = 0.3 with the lateral faces free (uniaxial
  // stress; the Rayleigh-Love lateral-inertia correction nu^2 k^2 r^2 / 2 is 7e-6 here).
  const double length = 100.0;
  const core::Scene scene = core::parse_scene(
      clamped_body(0.3, "discretisation = \"hexahedra\"\nelement = \"" + std::string(GetParam()) +
                            "\"\nshape = { box = { min = [0, 0, 0], max = [2, 2, 100] } }\n"
                            "mesh = { divisions = [2, 2, 40] }\n"),
      "w2.toml");
  const auto t0 = std::chrono::steady_clock::now();
  FeSolver solver(scene);
  const double f_ref = bar_speed / (4.0 * length);
  const Vibration v = vibrate(solver, 2, first_axial_mode(length), length, 2.1 / f_ref);
  const double error = 1.0 / (v.period * f_ref) - 1.0;
  std::printf(
      "[W2 fixed-free bar, %s, 2x2x40 hexahedra, nu 0.3, %ld steps, %.2f s] f1 = %.6g "
      "/ms, reference c/(4L) = %.6g: error %+.3f %% (tolerance 1 %%); energy balance "
      "error %.3g\n",
      GetParam(), solver.step_count(), seconds_since(t0), 1.0 / v.period, f_ref, 100.0 * error,
      v.max_balance_error);
  EXPECT_LT(std::abs(error), 0.01);
  EXPECT_LT(v.max_balance_error, 0.02);
}

INSTANTIATE_TEST_SUITE_P(BothHexahedra, FeFixedFreeBar, ::testing::Values("one-point", "full"),
                         element_name);

TEST(FeFixedFreeTruss, FirstAxialFrequencyIsBarSpeedOverFourLengths) {
  const double length = 100.0;
  const core::Scene scene =
      core::parse_scene(clamped_body(0.3,
                                     "discretisation = \"trusses\"\n"
                                     "shape = { line = { from = [0, 0, 0], to = [0, 0, 100] } }\n"
                                     "area = 4.0\nmesh = { segments = 50 }\n"),
                        "truss.toml");
  const auto t0 = std::chrono::steady_clock::now();
  FeSolver solver(scene);
  const double f_ref = bar_speed / (4.0 * length);
  const Vibration v = vibrate(solver, 2, first_axial_mode(length), length, 2.1 / f_ref);
  const double error = 1.0 / (v.period * f_ref) - 1.0;
  std::printf(
      "[truss fixed-free bar, 50 trusses, %ld steps, %.2f s] f1 = %.6g /ms, reference "
      "c/(4L) = %.6g: error %+.3f %% (tolerance 1 %%); energy balance error %.3g\n",
      solver.step_count(), seconds_since(t0), 1.0 / v.period, f_ref, 100.0 * error,
      v.max_balance_error);
  EXPECT_LT(std::abs(error), 0.01);
  EXPECT_LT(v.max_balance_error, 0.02);
}

// ---------------------------------------------------------------------------------------------
// W3: bending of a cantilever, started with a small velocity in the first Euler-Bernoulli mode.

constexpr double beta_l = 1.8751040687119611;  // first root of 1 + cos(b) cosh(b) = 0

// The first clamped-free mode at xi = z / L (tip value 2).
double cantilever_mode(double xi) {
  const double sigma =
      (std::cosh(beta_l) + std::cos(beta_l)) / (std::sinh(beta_l) + std::sin(beta_l));
  return std::cosh(beta_l * xi) - std::cos(beta_l * xi) -
         sigma * (std::sinh(beta_l * xi) - std::sin(beta_l * xi));
}

struct BeamRun {
  double frequency = 0.0, reference = 0.0;
  Vibration vibration;
  long steps = 0;
  double seconds = 0.0;
};

// A steel cantilever of square section 2 x 2 mm and length 40 (L / h = 20, so shear and
// rotary inertia change f1 by about 0.1 %), nu = 0 so that beam theory with E holds whatever
// the mesh does across the width, clamped at z = 0, bending in y; `element_lines` give the
// element, its hourglass control and the mesh. Tip amplitude 1e-3 L.
BeamRun cantilever(const std::string& element_lines, double periods, double nu = 0.0,
                   double time_step_factor = 0.9) {
  const double h = 2.0, length = 40.0;
  core::Scene scene =
      core::parse_scene(clamped_body(nu,
                                     "discretisation = \"hexahedra\"\n"
                                     "shape = { box = { min = [0, 0, 0], max = [2, 2, 40] } }\n" +
                                         element_lines),
                        "w3.toml");
  scene.run.element_time_step_factor = time_step_factor;
  const auto t0 = std::chrono::steady_clock::now();
  FeSolver solver(scene);
  BeamRun r;
  // sqrt(E I / (rho A L^4)) = c h / (sqrt(12) L^2) for a square section.
  r.reference = beta_l * beta_l / (2.0 * std::numbers::pi) * bar_speed * h /
                (std::sqrt(12.0) * length * length);
  const double tip_velocity = 1e-3 * length * 2.0 * std::numbers::pi * r.reference;
  r.vibration = vibrate(
      solver, 1, [&](double z) { return 0.5 * tip_velocity * cantilever_mode(z / length); }, length,
      periods / r.reference);
  r.frequency = r.vibration.period > 0.0 ? 1.0 / r.vibration.period : 0.0;
  r.steps = solver.step_count();
  r.seconds = seconds_since(t0);
  return r;
}

// The element lines of a one-point cantilever with hourglass form `form` on the mesh
// `divisions` ("[nx, ny, nz]").
std::string one_point(const std::string& form, const std::string& divisions) {
  return "element = \"one-point\"\nhourglass = { form = \"" + form +
         "\" }\nmesh = { divisions = " + divisions + " }\n";
}

void print(const char* what, const BeamRun& r, const char* tolerance) {
  std::printf(
      "[W3 cantilever, %s, %ld steps, %.2f s] f1 = %.6g /ms, reference Euler-Bernoulli "
      "%.6g: error %+.3f %% (%s); max hourglass / max internal energy %.3g; max "
      "assumed-strain stabilisation / max internal %.3g; energy balance error %.3g\n",
      what, r.steps, r.seconds, r.frequency, r.reference, 100.0 * (r.frequency / r.reference - 1.0),
      tolerance, r.vibration.max_hourglass / r.vibration.max_internal,
      r.vibration.max_stabilisation / r.vibration.max_internal, r.vibration.max_balance_error);
}

// One-point elements with four elements through the depth carry the bending as piecewise
// constant axial strain (the midpoint rule through the depth: -1/16 of the stiffness, -3.1 %
// of f1); the viscous hourglass form adds no stiffness (measured -3.3 %), the stiffness form
// restores part of the intra-element bending.
TEST(FeCantilever, OnePointStiffnessFormWithFourElementsThroughDepthMatchesEulerBernoulli) {
  const BeamRun r = cantilever(one_point("stiffness", "[1, 4, 80]"), 1.1);
  print("one-point, stiffness hourglass Q 0.05, 1x4x80 (2 x 0.5 x 0.5 mm)", r, "tolerance 3 %");
  EXPECT_NEAR(r.frequency, r.reference, 0.03 * r.reference);
  EXPECT_LT(r.vibration.max_balance_error, 0.02);
}

// The 2x2x2 B-bar element shear-locks in bending (parasitic shear energy (G/E)(l_e/h)^2 of the
// bending energy for elements l_e long on a beam h deep: +1.6 % of f1 here) while the averaged
// dilatation softens it (-1.0 %): with cubic 0.5 mm elements the two nearly cancel.
TEST(FeCantilever, FullBbarWithFourElementsThroughDepthMatchesEulerBernoulli) {
  const BeamRun r = cantilever("element = \"full\"\nmesh = { divisions = [1, 4, 80] }\n", 1.1);
  print("full B-bar, 1x4x80 (2 x 0.5 x 0.5 mm)", r, "tolerance 3 %");
  EXPECT_NEAR(r.frequency, r.reference, 0.03 * r.reference);
  EXPECT_LT(r.vibration.max_balance_error, 0.02);
}

// With one element through the depth the one-point element's centre sees no bending strain:
// all of the bending stiffness is hourglass stiffness, so the hourglass energy dwarfs the
// internal energy, far over the 10 % at which FeModel warns. The frequency is printed only
// (sanity: the beam does vibrate, within a factor 2 of the reference).
TEST(FeCantilever, OnePointWithOneElementThroughDepthBendsOnHourglassForcesAlone) {
  const BeamRun r = cantilever(one_point("stiffness", "[1, 1, 20]"), 1.1);
  print("one-point, stiffness hourglass Q 0.05, 1x1x20 (2 mm cubes)", r, "reported only");
  EXPECT_GT(r.vibration.max_hourglass, 10.0 * r.vibration.max_internal);
  EXPECT_GT(r.frequency, 0.5 * r.reference);
  EXPECT_LT(r.frequency, 2.0 * r.reference);
  EXPECT_LT(r.vibration.max_balance_error, 0.02);
}

// The assumed-strain form (Belytschko & Bindeman's ASQBI) resists the hourglass modes with the
// strain energy of a linear strain field under Hooke's law, exact for a rectangular element in
// pure bending: one element through the depth bends like the beam. There is no artificial
// hourglass energy (0, against the 10 % mark); the bending energy is the stabilisation's
// strain energy, counted as internal energy and printed on its own.
// With 4 elements through the depth as well: the stabilisation then carries only the bending
// within each layer (a few % of the internal energy).
TEST(FeCantilever, OnePointAssumedStrainWithOneOrFourElementsThroughDepthMatchesEulerBernoulli) {
  const struct {
    const char* divisions;
    const char* label;
    double min_stabilisation_share;
  } meshes[] = {{"[1, 1, 20]", "1x1x20 (2 mm cubes)", 0.5},
                {"[1, 4, 80]", "1x4x80 (2 x 0.5 x 0.5 mm)", 0.0}};
  for (const auto& m : meshes) {
    const BeamRun r = cantilever(one_point("assumed_strain", m.divisions), 1.1);
    print((std::string("one-point, assumed-strain stabilisation, ") + m.label).c_str(), r,
          "tolerance 3 %");
    EXPECT_NEAR(r.frequency, r.reference, 0.03 * r.reference) << m.label;
    EXPECT_LT(r.vibration.max_hourglass, 0.1 * r.vibration.max_internal) << m.label;
    EXPECT_GE(r.vibration.max_stabilisation, m.min_stabilisation_share * r.vibration.max_internal)
        << m.label;
    EXPECT_LT(r.vibration.max_balance_error, 0.02) << m.label;
  }
}

// With nu = 0.3, ASQBI's bending modes of one plane are coupled through nu / (1 - nu) to the
// transverse bending of the other: the beam's axial bending mode alone would bend with the
// plane-strain modulus E / (1 - nu^2), but the free width lets the element curve anticlastically
// (the transverse mode takes -nu times the axial curvature), which brings the energy back to
// E kappa^2 I / 2: f1 matches Euler-Bernoulli with E. Reference: f1(E), 1 % (a plate strip's
// 1 / sqrt(1 - nu^2) = +4.8 % would fail).
// One element across the section makes every node a corner node, where the element's
// dilatation mode rings at 2 sqrt(3 K / rho) / h: stable only below the factor
// sqrt((1 - nu) / (1 + nu)) = 0.73 on the usual V / A_max length (docs/scene-format.md), so
// this mesh runs at 0.6 (at 0.9 it blows up with every hourglass form).
TEST(FeCantilever, OnePointAssumedStrainWithPoissonRatioBendsWithYoungsModulus) {
  const double nu = 0.3;
  const BeamRun r = cantilever(one_point("assumed_strain", "[1, 1, 20]"), 1.1, nu, 0.6);
  print("one-point, assumed-strain stabilisation, nu 0.3, 1x1x20, factor 0.6", r, "tolerance 1 %");
  EXPECT_NEAR(r.frequency, r.reference, 0.01 * r.reference);
  EXPECT_LT(r.vibration.max_hourglass, 0.1 * r.vibration.max_internal);
  EXPECT_LT(r.vibration.max_balance_error, 0.02);
}

// The viscous hourglass form only damps: with one element through the depth the beam has no
// bending stiffness at all, so the tip drifts off at its initial velocity instead of turning
// back within the reference period at the elastic amplitude 1e-3 L.
TEST(FeCantilever, OnePointViscousFormWithOneElementThroughDepthIsAMechanism) {
  const BeamRun r = cantilever(one_point("viscous", "[1, 1, 20]"), 1.1);
  std::printf(
      "[W3 cantilever, one-point, viscous hourglass Q 0.1, 1x1x20, %ld steps, %.2f s] "
      "zero crossings after t = 0: %s; largest tip deflection %.4g mm (elastic amplitude "
      "%.4g)\n",
      r.steps, r.seconds, r.frequency > 0.0 ? "some" : "none", r.vibration.max_displacement,
      1e-3 * 40.0);
  EXPECT_EQ(r.frequency, 0.0);
  EXPECT_GT(r.vibration.max_displacement, 5.0 * 1e-3 * 40.0);
}

}  // namespace
}  // namespace afemp::fem
