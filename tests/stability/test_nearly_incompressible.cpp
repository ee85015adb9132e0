// Stability suite (ctest label `stability`), stiff case: a nearly incompressible block
// (nu = 0.499, K / G = 833) dropped flat on a rigid wall, with the one-point hexahedron, the
// B-bar hexahedron and MPM. Each scheme must run to its end without NaN/Inf, keep the energy
// balance and give the uniaxial-strain stress of the closed form at the start of the impact;
// the volumetric-locking symptom, the pressure checkerboard, is measured and reported.
// Units mm, ms, g, N, MPa (velocity m/s).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/reference_checks.hpp"
#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "coupling/make_model.hpp"
#include "fem/fe_model.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::coupling {
namespace {

using core::Vec3;

constexpr double rho = 1.0e-3, E = 100.0, nu = 0.499, v0 = 20.0;  // rubber-like, 20 m/s
constexpr double half = 4.0, h = 0.5;                             // 8 mm cube, 0.5 mm cells

// Longitudinal (uniaxial-strain) wave speed and the stress behind the front of a flat impact on
// a rigid wall: sigma_zz = -rho c_L v0 (one-dimensional momentum jump).
double longitudinal_speed() {
  const double K = E / (3.0 * (1.0 - 2.0 * nu)), G = E / (2.0 * (1.0 + nu));
  return std::sqrt((K + 4.0 * G / 3.0) / rho);
}

std::string scene_text(const std::string& variant, double end_time, const std::string& extra = "") {
  std::string s = "[run]\nend_time = " + std::to_string(end_time) + "\n" + extra + R"(
[materials.rubber]
density = 1.0e-3
E = 100.0
nu = 0.499
)";
  if (variant == "mpm") {
    s += R"(
[grid]
cell = 0.5
min = [-6, -6, 0]
max = [6, 6, 10]
boundary = { zmin = "symmetric" }
[[bodies]]
name = "block"
material = "rubber"
shape = { box = { min = [-4, -4, 0], max = [4, 4, 8] } }
velocity = [0, 0, -20]
)";
  } else {
    s += R"(
[[bodies]]
name = "block"
discretisation = "hexahedra"
material = "rubber"
shape = { box = { min = [-4, -4, 0], max = [4, 4, 8] } }
mesh = { size = 0.5 }
velocity = [0, 0, -20]
element = ")" +
         std::string(variant == "full" ? "full" : "one-point") + R"("
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }
fixed = ["z"]
)";
  }
  return s;
}

// Pressure p = -tr(sigma) / 3 and stress sigma_zz of each point of the block, with the point's
// index (i, j, k) on the lattice the points formed at the start: the elements (spacing h) or
// the particles (h / 2, two per cell per direction).
struct Piece {
  int i, j, k;
  double p, szz;
  Vec3 x0;  // where the point was at the start
};

double lattice_spacing(const core::Model& model) {
  return dynamic_cast<const fem::FeModel*>(&model) ? h : 0.5 * h;
}

// Where each point was at the start: element centroids by element, particles by their id.
std::vector<Vec3> initial_points(const core::Model& model) {
  std::vector<Vec3> out;
  if (const auto* fe = dynamic_cast<const fem::FeModel*>(&model)) {
    for (const auto& nodes : fe->solver().hexahedra().nodes) {
      Vec3 c{};
      for (const std::int32_t a : nodes)
        c += 0.125 * fe->solver().nodes().position[static_cast<std::size_t>(a)];
      out.push_back(c);
    }
  } else {
    const mpm::Particles& p = dynamic_cast<const mpm::MpmModel&>(model).solver().particles();
    out.resize(p.size());
    for (std::size_t q = 0; q < p.size(); ++q)
      out[static_cast<std::size_t>(p.id[q])] = p.position[q];
  }
  return out;
}

std::vector<Piece> pieces(const core::Model& model, const std::vector<Vec3>& x0) {
  const double s = lattice_spacing(model);
  std::vector<Piece> out;
  auto add = [&](const Vec3& x, const core::SymTensor& sigma) {
    out.push_back({static_cast<int>(std::floor((x.x + half) / s)),
                   static_cast<int>(std::floor((x.y + half) / s)),
                   static_cast<int>(std::floor(x.z / s)), -(sigma.xx + sigma.yy + sigma.zz) / 3.0,
                   sigma.zz, x});
  };
  if (const auto* fe = dynamic_cast<const fem::FeModel*>(&model)) {
    const fem::HexElements& el = fe->solver().hexahedra();
    for (const fem::ElementBatch& b : el.batches)
      for (std::size_t e = b.begin; e < b.end; ++e) {
        core::SymTensor mean{};
        const auto n = static_cast<std::size_t>(b.points_per_element);
        for (std::size_t g = 0; g < n; ++g)
          mean += (1.0 / static_cast<double>(n)) * el.stress[b.point_begin + (e - b.begin) * n + g];
        add(x0[e], mean);
      }
  } else {
    const mpm::Particles& p = dynamic_cast<const mpm::MpmModel&>(model).solver().particles();
    for (std::size_t q = 0; q < p.size(); ++q)
      add(x0[static_cast<std::size_t>(p.id[q])], p.stress[q]);
  }
  return out;
}

// Checkerboard (pressure roughness) amplitude: each point's pressure against the mean of its six
// lattice neighbours, A = sqrt(sum (p - p_nb)^2 / sum p^2) over the points that have all six:
// 0 for a linear field, O((h / L)^2) for a smooth one and 2 for a pure checkerboard
// (-1)^(i+j+k), the volumetric-locking symptom.
double checkerboard(const std::vector<Piece>& points) {
  std::map<std::tuple<int, int, int>, double> p;
  for (const Piece& c : points) p[{c.i, c.j, c.k}] = c.p;
  double dev = 0.0, norm = 0.0;
  for (const Piece& c : points) {
    double sum = 0.0;
    int count = 0;
    for (const auto& [di, dj, dk] :
         {std::tuple{1, 0, 0}, std::tuple{-1, 0, 0}, std::tuple{0, 1, 0}, std::tuple{0, -1, 0},
          std::tuple{0, 0, 1}, std::tuple{0, 0, -1}}) {
      const auto it = p.find({c.i + di, c.j + dj, c.k + dk});
      if (it != p.end()) sum += it->second, ++count;
    }
    if (count < 6) continue;
    dev += (c.p - sum / 6.0) * (c.p - sum / 6.0);
    norm += c.p * c.p;
  }
  return std::sqrt(dev / norm);
}

struct Outcome {
  long steps = 0;
  double energy_error = 0.0, max_energy_error = 0.0, szz_early = 0.0, checker = 0.0,
         pressure_max = 0.0;
};

// The end of the long run: about five longitudinal transits of the block, while the sides
// bulge (shear wave speed sqrt(G / rho) = 183 m/s).
constexpr double end_time = 0.01;

Outcome run_variant(const std::string& variant, const std::string& run_keys = "") {
  const double c = longitudinal_speed();
  // Early: the front has run 2.4 mm up from the plane; the lateral release has reached 2.4 mm
  // in from the sides, so the central column |x|, |y| < 1.5 mm, 0.5 < z < 2 is still in
  // uniaxial strain.
  const double t_early = 2.4 / c;
  Outcome o{};
  {
    const core::Scene scene =
        core::parse_scene(scene_text(variant, t_early, run_keys), "incompressible.toml");
    const auto model = make_model(scene);
    const std::vector<Vec3> x0 = initial_points(*model);
    analysis::run(*model, scene, core::RunOptions{});
    double sum = 0.0;
    int count = 0;
    for (const Piece& p : pieces(*model, x0)) {
      if (std::abs(p.x0.x) < 1.5 && std::abs(p.x0.y) < 1.5 && p.x0.z > 0.5 && p.x0.z < 2.0)
        sum += p.szz, ++count;
    }
    o.szz_early = sum / count;
  }
  const core::Scene scene =
      core::parse_scene(scene_text(variant, end_time, run_keys), "incompressible.toml");
  const auto model = make_model(scene);
  const std::vector<Vec3> x0 = initial_points(*model);
  const core::RunSummary s = analysis::run(*model, scene, core::RunOptions{});
  const std::vector<Piece> cells = pieces(*model, x0);
  o.steps = s.steps;
  o.energy_error = s.energy_error;
  o.max_energy_error = s.max_energy_error;
  o.checker = checkerboard(cells);
  for (const Piece& p : cells) o.pressure_max = std::max(o.pressure_max, std::abs(p.p));
  std::printf(
      "nu = 0.499, %s %s: %ld steps, energy %+.2f %% (largest %.2f %%), early sigma_zz "
      "%.1f MPa (closed form %.1f), checkerboard %.4f, |p| max %.1f MPa\n",
      variant.c_str(), run_keys.empty() ? "" : "(factor 0.7)", o.steps, 100.0 * o.energy_error,
      100.0 * o.max_energy_error, o.szz_early, -rho * c * v0, o.checker, o.pressure_max);
  return o;
}

// The stress behind the front, -rho c_L v0 = -81.8 MPa.
double closed_form_stress() {
  return -rho * longitudinal_speed() * v0;
}

// One-point hexahedra with the default viscous hourglass control and the default element step
// factor 0.9 are past their stability limit at nu = 0.499: a mode grows (measured: energy
// error beyond 100 % by step 50, +3234 % at its largest over 0.04 ms without the guard; the
// same block is stable at nu = 0.49 and at the factor 0.8). Reference: the energy guard stops the
// run with a SimulationError naming the step, the body and the field 'energy balance' before the
// end time, instead of running on with the energy created.
TEST(Stability, NearlyIncompressibleOnePointHexahedraAtTheDefaultFactorAreStoppedByTheEnergyGuard) {
  const core::Scene scene =
      core::parse_scene(scene_text("one-point", end_time), "incompressible.toml");
  const auto model = make_model(scene);
  try {
    analysis::run(*model, scene, core::RunOptions{});
    FAIL() << "the unstable run reached its end time";
  } catch (const core::SimulationError& e) {
    const std::string what = e.what();
    std::printf("nu = 0.499, one-point, factor 0.9: %s\n", what.c_str());
    EXPECT_NE(what.find("body block, field 'energy balance'"), std::string::npos) << what;
    EXPECT_LT(model->time(), end_time);
    EXPECT_GT(e.step(), 0);
  }
}

// At the factor 0.7 the one-point block is stable. References: the energy balance within 5 %
// (measured 0.9 %), the uniaxial-strain stress behind the front within 10 % of the closed form
// (measured +1.1 %), and no locking: the checkerboard amplitude below 0.1 (measured 0.029; a
// pure checkerboard gives 2).
TEST(Stability, NearlyIncompressibleBlockOnePointHexahedraBelowTheirLimit) {
  const Outcome o = run_variant("one-point", "element_time_step_factor = 0.7\n");
  EXPECT_LT(o.max_energy_error, 0.05);
  EXPECT_NEAR(o.szz_early, closed_form_stress(), 0.1 * std::abs(closed_form_stress()));
  EXPECT_LT(o.checker, 0.1);
}

// B-bar hexahedra at the default factor 0.9: the same references (measured 1.6 %, +1.3 %,
// 0.034).
TEST(Stability, NearlyIncompressibleBlockBbarHexahedra) {
  const Outcome o = run_variant("full");
  EXPECT_LT(o.max_energy_error, 0.05);
  EXPECT_NEAR(o.szz_early, closed_form_stress(), 0.1 * std::abs(closed_form_stress()));
  EXPECT_LT(o.checker, 0.1);
}

// MPM (MUSL, 2 x 2 x 2 particles per cell) at the default factor 0.3: stable, energy within 5 %
// (measured 0.75 %), the stress behind the front within 15 % (measured +11 %: the front spreads
// over two cells). The particles' pressure is rough, the locking symptom of a stress evaluated
// at each particle from grid velocities that cannot follow an isochoric field: amplitude 0.33,
// ten times the hexahedra's; it must stay well below a pure checkerboard (2) and not grow into
// one, < 0.6.
TEST(Stability, NearlyIncompressibleBlockMpm) {
  const Outcome o = run_variant("mpm");
  EXPECT_LT(o.max_energy_error, 0.05);
  EXPECT_NEAR(o.szz_early, closed_form_stress(), 0.15 * std::abs(closed_form_stress()));
  EXPECT_LT(o.checker, 0.6);
}

}  // namespace
}  // namespace afemp::coupling
