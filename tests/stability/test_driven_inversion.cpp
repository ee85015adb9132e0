// Stability suite (ctest label `stability`), extreme case: elements driven to a negative
// Jacobian. A steel block (4 mm cube, B-bar hexahedra of 0.5 mm, J2, fixed at its base) is
// punched by a 1 x 1 mm patch of its top nodes driven down at 2000 m/s through the whole block
// and 0.5 mm past its fixed base: the elements under the punch must invert. They must erode
// (with an erosion table) or turn into particles (with conversion on negative_jacobian), never
// crash; without either, the run stops with the element and the field named.
// Units mm, ms, g, N, MPa (velocity m/s).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "afemp/errors.hpp"
#include "analysis/reference_checks.hpp"
#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "coupling/make_model.hpp"

namespace afemp::coupling {
namespace {

constexpr double element_mass = 7.85e-3 * 0.5 * 0.5 * 0.5;  // rho h^3

std::string punch_scene(const std::string& criterion, const std::string& grid_top = "3") {
  return R"(
[run]
end_time = 0.00225
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
strength = { model = "j2", yield = 500 }
[grid]
cell = 0.5
min = [-3, -3, -3]
max = [3, 3, )" +
         grid_top + R"(]
[[bodies]]
name = "block"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [-2, -2, -2], max = [2, 2, 2] } }
mesh = { size = 0.5 }
element = "full"
)" + criterion +
         R"(
[[constraints]]
nodes = { plane = { point = [0, 0, -2], normal = [0, 0, 1] } }
fixed = ["all"]
[[constraints]]
nodes = { box = { min = [-0.6, -0.6, 2], max = [0.6, 0.6, 2] } }
velocity = [0, 0, -2000]
)";
}

// Rows of the model's event log `file` (erosion.csv, conversion.csv) that contain `text`, left
// in the model by the run (a run without an output directory does not take them).
std::size_t event_rows(core::Model& model, const std::string& file, const std::string& text) {
  std::size_t n = 0;
  for (const core::EventLog& log : model.take_events())
    if (log.file == file)
      for (const std::string& row : log.rows) n += row.find(text) != std::string::npos;
  return n;
}

// Without erosion or conversion the first inverted element stops the run. Reference: a
// SimulationError naming the step, the hexahedron of body block and the field 'jacobian'.
TEST(Stability, DrivenInversionWithoutCriteriaStopsNamingTheElement) {
  const core::Scene scene = core::parse_scene(punch_scene(""), "punch.toml");
  const auto model = make_model(scene);
  try {
    analysis::run(*model, scene, core::RunOptions{});
    FAIL() << "the punch went through without inverting an element";
  } catch (const core::SimulationError& e) {
    const std::string what = e.what();
    std::printf("punch, no criterion: %s\n", what.c_str());
    EXPECT_GT(e.step(), 0);
    EXPECT_NE(what.find("of body block, field 'jacobian'"), std::string::npos) << what;
    EXPECT_NE(what.find("hexahedron "), std::string::npos) << what;
  }
}

// With an erosion table (its plastic-strain criterion out of reach) the inverted elements
// erode. References: the run reaches its end; the mass lost is exactly the eroded elements'
// (count x rho h^3, 1e-12); the energy balance, with the eroded energy booked, within 5 %
// (measured +2.5 %).
TEST(Stability, DrivenInversionErodesTheInvertedElements) {
  const core::Scene scene =
      core::parse_scene(punch_scene("erosion = { plastic_strain = 1000 }"), "punch.toml");
  const auto model = make_model(scene);
  const core::RunSummary s = analysis::run(*model, scene, core::RunOptions{});
  // erosion.csv also lists the nodes left without an element (kind "node").
  const std::size_t eroded = event_rows(*model, "erosion.csv", ",hexahedron,");
  const double m0 = s.initial.bodies[0].mass, m = s.final.bodies[0].mass;
  std::printf("punch, erosion: %ld steps, %zu elements eroded, energy %+.2f %% (largest %.2f %%)\n",
              s.steps, eroded, 100.0 * s.energy_error, 100.0 * s.max_energy_error);
  EXPECT_NEAR(s.time, 0.00225, 1e-12);
  EXPECT_GT(eroded, 0u);
  EXPECT_NEAR(m0 - m, static_cast<double>(eroded) * element_mass, 1e-12 * m0);
  EXPECT_LT(s.max_energy_error, 0.05);
}

// With conversion on negative_jacobian the inverted elements become particles (AFEMP).
// References: the run reaches its end; mass is conserved (the particles carry the elements'
// mass, 1e-12); the energy balance within 10 % (measured +6.1 %: the particles are crushed
// between the punch and the fixed base).
TEST(Stability, DrivenInversionConvertsTheInvertedElements) {
  const core::Scene scene =
      core::parse_scene(punch_scene("conversion = { negative_jacobian = true }"), "punch.toml");
  const auto model = make_model(scene);
  const core::RunSummary s = analysis::run(*model, scene, core::RunOptions{});
  const std::size_t converted = event_rows(*model, "conversion.csv", ",block,");
  const double m0 = s.initial.bodies[0].mass, m = s.final.bodies[0].mass;
  std::printf(
      "punch, conversion: %ld steps, %zu elements converted into %zu particles, energy "
      "%+.2f %% (largest %.2f %%)\n",
      s.steps, converted, s.final_particles, 100.0 * s.energy_error, 100.0 * s.max_energy_error);
  EXPECT_NEAR(s.time, 0.00225, 1e-12);
  EXPECT_GT(converted, 0u);
  EXPECT_EQ(s.final_particles, converted);  // one particle per element (points = 1)
  EXPECT_NEAR(m, m0, 1e-12 * m0);
  EXPECT_LT(s.max_energy_error, 0.10);
}

// Conversion needs the grid: with the grid ending at z = 0, the elements under the punch, which
// invert first, cannot convert. Reference: the run stops with a SimulationError that says so for
// the hexahedron it names (field 'jacobian').
TEST(Stability, DrivenInversionOutsideTheGridStopsAndSaysWhy) {
  const core::Scene scene = core::parse_scene(
      punch_scene("conversion = { negative_jacobian = true }", "0"), "punch.toml");
  const auto model = make_model(scene);
  try {
    analysis::run(*model, scene, core::RunOptions{});
    FAIL() << "no element inverted above the grid";
  } catch (const core::SimulationError& e) {
    const std::string what = e.what();
    std::printf("punch, grid below z = 0: %s\n", what.c_str());
    EXPECT_NE(what.find("(outside the background grid, where it cannot convert), field 'jacobian'"),
              std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace afemp::coupling
