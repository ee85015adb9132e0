// Scene files (docs/scene-format.md): a valid scene becomes the expected Scene with its
// documented defaults, and every kind of mistake is an InputError naming file, line, dotted
// key and what is allowed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>

#include "afemp/errors.hpp"
#include "core/scene.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

// The Taylor bar of docs/scene-format.md (OFHC copper at 190 m/s; mm, ms, g, N, MPa).
const std::string taylor_scene = R"(# Taylor bar
[run]
end_time = 0.08
output_every = 0.008

[grid]
cell = 0.5
min = [0, 0, 0]
max = [10, 10, 28]
boundary = { zmin = "fixed", xmin = "symmetric", ymin = "symmetric" }

[mpm]
scheme = "MUSL"

[materials.copper]
density = 8.93e-3
E = 117e3
nu = 0.35
strength = { model = "johnson-cook", A = 157, B = 425, n = 1.0, C = 0.0 }
eos = { model = "mie-gruneisen", c0 = 3940, s = 1.49, gamma0 = 1.96 }

[[bodies]]
name = "bar"
material = "copper"
shape = { cylinder = { base = [0, 0, 0], axis = [0, 0, 2], radius = 3.8, length = 25.4 } }
particles_per_cell = 2
velocity = [0, 0, -190]

[reference]
taylor = { L = 16.2, D = 13.5, W = 10.1, tolerance = 0.03 }
)";

// A small valid scene whose pieces the error tests replace or extend.
const std::string minimal_head = R"([run]
end_time = 1.0

[grid]
cell = 1.0
min = [0, 0, 0]
max = [10, 10, 10]
)";

const std::string minimal_tail = R"(
[materials.steel]
density = 7.8e-3
E = 200e3
nu = 0.3

[[bodies]]
name = "block"
material = "steel"
shape = { box = { min = [1, 1, 1], max = [3, 3, 3] } }
)";

using test::error_of;
using test::line_of;

TEST(SceneParser, TaylorBarSceneParsesIntoExpectedValuesIncludingDefaults) {
  const Scene s = parse_scene(taylor_scene, "taylor.toml");
  EXPECT_EQ(s.path, "taylor.toml");
  // [run]: given values and defaults.
  EXPECT_EQ(s.run.title, "");
  EXPECT_DOUBLE_EQ(s.run.end_time, 0.08);
  EXPECT_DOUBLE_EQ(s.run.output_every, 0.008);
  EXPECT_DOUBLE_EQ(s.run.time_step_factor, 0.3);
  EXPECT_DOUBLE_EQ(s.run.fixed_time_step, 0.0);
  EXPECT_EQ(s.run.max_steps, 0);
  EXPECT_EQ(s.run.history_every, 10);
  EXPECT_DOUBLE_EQ(norm(s.run.gravity), 0.0);
  // [grid] with integer arrays accepted as floats, unnamed faces free.
  const GridSettings& g = s.mpm.grid;
  EXPECT_DOUBLE_EQ(g.cell, 0.5);
  EXPECT_DOUBLE_EQ(g.min.x, 0.0);
  EXPECT_DOUBLE_EQ(g.max.z, 28.0);
  EXPECT_EQ(g.faces[static_cast<int>(Face::xmin)], FaceCondition::symmetric);
  EXPECT_EQ(g.faces[static_cast<int>(Face::ymin)], FaceCondition::symmetric);
  EXPECT_EQ(g.faces[static_cast<int>(Face::zmin)], FaceCondition::fixed);
  EXPECT_EQ(g.faces[static_cast<int>(Face::xmax)], FaceCondition::free);
  EXPECT_EQ(g.faces[static_cast<int>(Face::ymax)], FaceCondition::free);
  EXPECT_EQ(g.faces[static_cast<int>(Face::zmax)], FaceCondition::free);
  // [mpm]
  EXPECT_EQ(s.mpm.scheme, UpdateScheme::MUSL);
  EXPECT_DOUBLE_EQ(s.mpm.flip, 1.0);
  EXPECT_TRUE(s.mpm.jaumann);
  // [materials.copper]
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& cu = s.materials[0];
  EXPECT_EQ(cu.name, "copper");
  EXPECT_DOUBLE_EQ(cu.density, 8.93e-3);
  EXPECT_DOUBLE_EQ(cu.youngs_modulus, 117e3);
  EXPECT_DOUBLE_EQ(cu.poisson_ratio, 0.35);
  ASSERT_TRUE(std::holds_alternative<JohnsonCook>(cu.strength));
  const auto& jc = std::get<JohnsonCook>(cu.strength);
  EXPECT_DOUBLE_EQ(jc.A, 157.0);
  EXPECT_DOUBLE_EQ(jc.B, 425.0);
  EXPECT_DOUBLE_EQ(jc.n, 1.0);
  EXPECT_DOUBLE_EQ(jc.C, 0.0);
  EXPECT_DOUBLE_EQ(jc.m, 0.0);
  EXPECT_DOUBLE_EQ(jc.reference_strain_rate, 1.0);
  EXPECT_DOUBLE_EQ(jc.room_temperature, 293.0);
  EXPECT_DOUBLE_EQ(jc.melt_temperature, 0.0);
  ASSERT_TRUE(std::holds_alternative<MieGruneisen>(cu.eos));
  const auto& mg = std::get<MieGruneisen>(cu.eos);
  EXPECT_DOUBLE_EQ(mg.rho0, 8.93e-3);  // the EOS reference density is the material density
  EXPECT_DOUBLE_EQ(mg.c0, 3940.0);
  EXPECT_DOUBLE_EQ(mg.s, 1.49);
  EXPECT_DOUBLE_EQ(mg.gamma0, 1.96);
  EXPECT_DOUBLE_EQ(cu.thermal.specific_heat, 0.0);
  EXPECT_DOUBLE_EQ(cu.thermal.taylor_quinney, 0.9);
  EXPECT_DOUBLE_EQ(cu.thermal.initial_temperature, 293.0);
  // [[bodies]]
  ASSERT_EQ(s.bodies.size(), 1u);
  const BodySpec& bar = s.bodies[0];
  EXPECT_EQ(bar.name, "bar");
  EXPECT_EQ(bar.material, 0);
  ASSERT_TRUE(std::holds_alternative<CylinderShape>(bar.shape));
  const auto& cyl = std::get<CylinderShape>(bar.shape);
  EXPECT_DOUBLE_EQ(cyl.axis.z, 1.0);  // [0, 0, 2] normalised
  EXPECT_DOUBLE_EQ(cyl.radius, 3.8);
  EXPECT_DOUBLE_EQ(cyl.length, 25.4);
  EXPECT_EQ(bar.particles_per_cell, 2);
  EXPECT_DOUBLE_EQ(bar.velocity.z, -190.0);
  EXPECT_FALSE(bar.temperature.has_value());
  EXPECT_EQ(bar.where.file, "taylor.toml");
  EXPECT_EQ(bar.where.line, line_of(taylor_scene, "[[bodies]]"));
  // [reference]
  ASSERT_TRUE(s.taylor_reference.has_value());
  EXPECT_DOUBLE_EQ(s.taylor_reference->length, 16.2);
  EXPECT_DOUBLE_EQ(s.taylor_reference->impact_diameter, 13.5);
  EXPECT_DOUBLE_EQ(s.taylor_reference->bulge_diameter, 10.1);
  EXPECT_DOUBLE_EQ(s.taylor_reference->tolerance, 0.03);
}

TEST(SceneParser, EveryOptionalKeyIsReadAndMaterialsAreNumberedInFileOrder) {
  const std::string text = R"([run]
title = "all keys"
end_time = 2.5
time_step_factor = 0.5
time_step = 1e-4
max_steps = 100
output_every = 0.25
history_every = 3
gravity = [0, 0, -9.81e-3]

[grid]
cell = 1
min = [-5, -5, 0]
max = [5, 5, 10]
boundary = { xmin = "fixed", xmax = "symmetric", ymin = "free", ymax = "fixed", zmin = "symmetric", zmax = "free" }

[mpm]
scheme = "usl"
flip = 0.95
jaumann = false

[materials.zinc]
density = 7.1e-3
E = 100e3
nu = 0.25
strength = { model = "j2", yield = 200, hardening = 500 }
eos = { model = "linear" }
specific_heat = 390
taylor_quinney = 0.8
temperature = 300

[materials.aluminium]
density = 2.7e-3
E = 70e3
nu = 0.33
strength = { model = "johnson-cook", A = 265, B = 426, n = 0.34, C = 0.015, m = 1.0, reference_strain_rate = 1e-3, room_temperature = 294, melt_temperature = 775 }
eos = { model = "linear-polynomial", C1 = 70000, C4 = 2.0 }

[[bodies]]
name = "plate"
material = "aluminium"
shape = { box = { min = [-4, -4, 0], max = [4, 4, 2] } }
particles_per_cell = 3
temperature = 350

[[bodies]]
name = "ball"
material = "zinc"
shape = { sphere = { centre = [0, 0, 5], radius = 2 } }
velocity = [0, 0, -1]

[[bodies]]
name = "cloud"
material = "zinc"
shape = { points = { file = "data/cloud.txt" } }
)";
  const Scene s = parse_scene(text, "cases/all.toml");
  EXPECT_EQ(s.run.title, "all keys");
  EXPECT_DOUBLE_EQ(s.run.time_step_factor, 0.5);
  EXPECT_DOUBLE_EQ(s.run.fixed_time_step, 1e-4);
  EXPECT_EQ(s.run.max_steps, 100);
  EXPECT_DOUBLE_EQ(s.run.output_every, 0.25);
  EXPECT_EQ(s.run.history_every, 3);
  EXPECT_DOUBLE_EQ(s.run.gravity.z, -9.81e-3);
  const auto& f = s.mpm.grid.faces;
  EXPECT_EQ(f[0], FaceCondition::fixed);
  EXPECT_EQ(f[1], FaceCondition::symmetric);
  EXPECT_EQ(f[2], FaceCondition::free);
  EXPECT_EQ(f[3], FaceCondition::fixed);
  EXPECT_EQ(f[4], FaceCondition::symmetric);
  EXPECT_EQ(f[5], FaceCondition::free);
  EXPECT_EQ(s.mpm.scheme, UpdateScheme::USL);  // scheme names are case-insensitive
  EXPECT_DOUBLE_EQ(s.mpm.flip, 0.95);
  EXPECT_FALSE(s.mpm.jaumann);

  // File order, not alphabetical order.
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].name, "zinc");
  EXPECT_EQ(s.materials[1].name, "aluminium");
  const Material& zn = s.materials[0];
  const auto& j2 = std::get<J2Plasticity>(zn.strength);
  EXPECT_DOUBLE_EQ(j2.yield_stress, 200.0);
  EXPECT_DOUBLE_EQ(j2.hardening, 500.0);
  // The linear EOS defaults to the bulk modulus of E and nu.
  EXPECT_DOUBLE_EQ(std::get<LinearEos>(zn.eos).bulk_modulus, 100e3 / (3.0 * (1.0 - 0.5)));
  EXPECT_DOUBLE_EQ(zn.thermal.specific_heat, 390.0);
  EXPECT_DOUBLE_EQ(zn.thermal.taylor_quinney, 0.8);
  EXPECT_DOUBLE_EQ(zn.thermal.initial_temperature, 300.0);
  const Material& al = s.materials[1];
  const auto& jc = std::get<JohnsonCook>(al.strength);
  EXPECT_DOUBLE_EQ(jc.m, 1.0);
  EXPECT_DOUBLE_EQ(jc.reference_strain_rate, 1e-3);
  EXPECT_DOUBLE_EQ(jc.room_temperature, 294.0);
  EXPECT_DOUBLE_EQ(jc.melt_temperature, 775.0);
  const auto& lp = std::get<LinearPolynomialEos>(al.eos);
  EXPECT_DOUBLE_EQ(lp.rho0, 2.7e-3);
  EXPECT_DOUBLE_EQ(lp.c[0], 0.0);
  EXPECT_DOUBLE_EQ(lp.c[1], 70000.0);
  EXPECT_DOUBLE_EQ(lp.c[4], 2.0);
  EXPECT_DOUBLE_EQ(lp.c[6], 0.0);

  ASSERT_EQ(s.bodies.size(), 3u);
  EXPECT_EQ(s.bodies[0].material, 1);
  EXPECT_EQ(s.bodies[0].particles_per_cell, 3);
  ASSERT_TRUE(s.bodies[0].temperature.has_value());
  EXPECT_DOUBLE_EQ(*s.bodies[0].temperature, 350.0);
  EXPECT_TRUE(std::holds_alternative<BoxShape>(s.bodies[0].shape));
  EXPECT_EQ(s.bodies[1].material, 0);
  EXPECT_DOUBLE_EQ(std::get<SphereShape>(s.bodies[1].shape).radius, 2.0);
  EXPECT_DOUBLE_EQ(s.bodies[1].velocity.z, -1.0);
  // Point files are resolved relative to the scene file's directory.
  EXPECT_EQ(std::get<PointListShape>(s.bodies[2].shape).path, "cases/data/cloud.txt");
  EXPECT_FALSE(s.taylor_reference.has_value());
}

TEST(SceneParser, UnknownTopLevelKeyNamesFileLineKeyAndAllowedKeys) {
  const std::string text = minimal_head + "\n[rnu]\nend_time = 2\n" + minimal_tail;
  const std::string what = error_of(text);
  const std::string expected_prefix =
      "scene.toml:" + std::to_string(line_of(text, "[rnu]")) + ": key 'rnu': unknown key";
  EXPECT_EQ(what.rfind(expected_prefix, 0), 0u) << what;
  EXPECT_NE(
      what.find("run, grid, mpm, materials, bodies, constraints, absorbing, loads, walls, contact, "
                "reference"),
      std::string::npos)
      << what;
}

TEST(SceneParser, UnknownKeyInsideStrengthTableNamesDottedKeyLineAndAllowedKeys) {
  std::string tail = minimal_tail;
  tail.insert(tail.find("nu = 0.3") + 9, "strength = { model = \"j2\", yeild = 300 }\n");
  const std::string text = minimal_head + tail;
  const std::string what = error_of(text);
  const int line = line_of(text, "yeild");
  EXPECT_EQ(what.rfind("scene.toml:" + std::to_string(line) +
                           ": key 'materials.steel.strength.yeild': unknown key",
                       0),
            0u)
      << what;
  EXPECT_NE(what.find("model, yield, hardening, tangent_modulus"), std::string::npos) << what;
}

TEST(SceneParser, UnknownKeyInBodyAndMaterialTablesIsRejected) {
  std::string tail = minimal_tail + "colour = \"red\"\n";
  std::string what = error_of(minimal_head + tail);
  EXPECT_NE(what.find("key 'bodies.block.colour': unknown key"), std::string::npos) << what;
  tail = minimal_tail;
  tail.insert(tail.find("nu = 0.3"), "poisson = 0.3\n");
  what = error_of(minimal_head + tail);
  EXPECT_NE(what.find("key 'materials.steel.poisson': unknown key"), std::string::npos) << what;
}

TEST(SceneParser, WrongTypeNamesTheExpectedType) {
  std::string text = minimal_head + minimal_tail;
  text.replace(text.find("end_time = 1.0"), 14, "end_time = \"soon\"");
  const std::string what = error_of(text);
  EXPECT_EQ(what, "scene.toml:2: key 'run.end_time': expected a number, got a string");

  text = minimal_head + minimal_tail + "particles_per_cell = 2.5\n";
  EXPECT_NE(error_of(text).find(
                "key 'bodies.block.particles_per_cell': expected an integer, got a float"),
            std::string::npos);
  text = minimal_head + minimal_tail + "velocity = [1, 2]\n";
  EXPECT_NE(error_of(text).find("key 'bodies.block.velocity': expected an array of 3 numbers, "
                                "got an array of 2"),
            std::string::npos);
}

TEST(SceneParser, OutOfRangeValueNamesTheAllowedRange) {
  std::string text = minimal_head + minimal_tail;
  text.replace(text.find("nu = 0.3"), 8, "nu = 0.5");
  const std::string what = error_of(text);
  EXPECT_NE(what.find("key 'materials.steel.nu': value 0.5 is out of range; allowed: "
                      "0 <= value < 0.5"),
            std::string::npos)
      << what;
  text = minimal_head + minimal_tail + "particles_per_cell = 9\n";
  EXPECT_NE(error_of(text).find("allowed: 1 <= value <= 8"), std::string::npos);
}

TEST(SceneParser, EnumErrorListsAllowedValues) {
  const std::string text = minimal_head + "\n[mpm]\nscheme = \"APIC\"\n" + minimal_tail;
  const std::string what = error_of(text);
  EXPECT_NE(what.find("scene.toml:" + std::to_string(line_of(text, "APIC")) +
                      ": key 'mpm.scheme': unknown value \"APIC\"; allowed values: "
                      "\"USF\", \"USL\", \"MUSL\""),
            std::string::npos)
      << what;
  std::string head = minimal_head + "boundary = { zmin = \"sticky\" }\n";
  EXPECT_NE(error_of(head + minimal_tail)
                .find("key 'grid.boundary.zmin': unknown value \"sticky\"; allowed values: "
                      "\"free\", \"fixed\", \"symmetric\""),
            std::string::npos);
}

TEST(SceneParser, UnknownMaterialNameListsTheDefinedMaterials) {
  std::string tail = minimal_tail;
  tail.replace(tail.find("material = \"steel\""), 18, "material = \"stele\"");
  const std::string what = error_of(minimal_head + tail);
  EXPECT_NE(what.find("key 'bodies.block.material': unknown material \"stele\"; defined "
                      "materials: \"steel\""),
            std::string::npos)
      << what;
}

TEST(SceneParser, J2TangentModulusConvertsToPlasticModulus) {
  std::string tail = minimal_tail;
  tail.insert(tail.find("nu = 0.3") + 9,
              "strength = { model = \"j2\", yield = 250, tangent_modulus = 2000 }\n");
  const Scene s = parse_scene(minimal_head + tail, "scene.toml");
  const auto& j2 = std::get<J2Plasticity>(s.materials[0].strength);
  // H = E Et / (E - Et) = 200e3 * 2000 / 198e3
  EXPECT_NEAR(j2.hardening, 200e3 * 2000.0 / (200e3 - 2000.0), 1e-9);
  EXPECT_DOUBLE_EQ(j2.yield_stress, 250.0);

  tail = minimal_tail;
  tail.insert(
      tail.find("nu = 0.3") + 9,
      "strength = { model = \"j2\", yield = 250, hardening = 10, tangent_modulus = 2000 }\n");
  EXPECT_NE(error_of(minimal_head + tail).find("not both"), std::string::npos);
}

TEST(SceneParser, JohnsonCookThermalSofteningNeedsAMeltTemperature) {
  std::string tail = minimal_tail;
  tail.insert(tail.find("nu = 0.3") + 9,
              "strength = { model = \"johnson-cook\", A = 1, B = 1, n = 1, m = 1 }\n");
  EXPECT_NE(error_of(minimal_head + tail)
                .find("key 'materials.steel.strength.melt_temperature': required when m > 0"),
            std::string::npos);
}

TEST(SceneParser, StructuralMistakesAreReported) {
  // A body name used twice.
  std::string text =
      minimal_head + minimal_tail + minimal_tail.substr(minimal_tail.find("[[bodies]]"));
  EXPECT_NE(error_of(text).find("duplicate body name \"block\""), std::string::npos);
  // No body at all.
  text = minimal_head + minimal_tail.substr(0, minimal_tail.find("[[bodies]]"));
  EXPECT_NE(error_of(text).find("key 'bodies': at least one body is required"), std::string::npos);
  // Two shapes for one body.
  std::string tail = minimal_tail;
  tail.replace(tail.find("} }"), 3, "}, sphere = { centre = [5, 5, 5], radius = 1 } }");
  EXPECT_NE(
      error_of(minimal_head + tail).find("give exactly one of box, cylinder, cone, sphere, points"),
      std::string::npos);
  // Grid max not above min.
  std::string head = minimal_head;
  head.replace(head.find("max = [10, 10, 10]"), 18, "max = [10, 0, 10]");
  EXPECT_NE(error_of(head + minimal_tail).find("key 'grid.max': max must exceed min"),
            std::string::npos);
  // A missing required section.
  EXPECT_NE(error_of(minimal_tail).find("key 'run': required table is missing"), std::string::npos);
}

// The affine transfer is offered with uGIMP weights only (with the linear hat it blows up:
// mpm/stencil.hpp), and the FLIP blend means nothing with it; both are errors naming the key.
TEST(SceneParser, MpmShapeFunctionAndTransfer) {
  const Scene s = parse_scene(
      minimal_head + "\n[mpm]\nshape_function = \"gimp\"\ntransfer = \"apic\"\n" + minimal_tail,
      "scene.toml");
  EXPECT_EQ(s.mpm.shape, ShapeFunction::gimp);
  EXPECT_EQ(s.mpm.transfer, Transfer::apic);
  const Scene d = parse_scene(minimal_head + minimal_tail, "scene.toml");
  EXPECT_EQ(d.mpm.shape, ShapeFunction::linear);
  EXPECT_EQ(d.mpm.transfer, Transfer::flip);
  const std::string linear =
      error_of(minimal_head + "\n[mpm]\ntransfer = \"apic\"\n" + minimal_tail);
  EXPECT_NE(linear.find("key 'mpm.transfer': \"apic\" needs shape_function = \"gimp\""),
            std::string::npos)
      << linear;
  const std::string blend = error_of(
      minimal_head + "\n[mpm]\nshape_function = \"gimp\"\ntransfer = \"apic\"\nflip = 0.9\n" +
      minimal_tail);
  EXPECT_NE(blend.find("key 'mpm.flip'"), std::string::npos) << blend;
  const std::string shape =
      error_of(minimal_head + "\n[mpm]\nshape_function = \"cpdi\"\n" + minimal_tail);
  EXPECT_NE(shape.find("\"linear\", \"gimp\""), std::string::npos) << shape;
}

TEST(SceneParser, TomlSyntaxErrorReportsItsLine) {
  const std::string text = minimal_head + "\n[mpm]\nflip = [0.5\n" + minimal_tail;
  const std::string what = error_of(text);
  EXPECT_EQ(what.rfind("scene.toml:", 0), 0u) << what;
  EXPECT_NE(what.find("TOML syntax error"), std::string::npos) << what;
  const int line = std::stoi(what.substr(11));
  EXPECT_GE(line, line_of(text, "flip"));
}

TEST(SceneParser, MissingSceneFileIsAnInputErrorNamingThePath) {
  try {
    read_scene("/nonexistent/dir/scene.toml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/scene.toml"), std::string::npos);
  }
}

TEST(SceneParser, ReadSceneReadsAFileFromDisk) {
  const auto path = std::filesystem::temp_directory_path() / "afemp_test_scene_parser.toml";
  {
    std::ofstream out(path);
    out << taylor_scene;
  }
  const Scene s = read_scene(path.string());
  EXPECT_EQ(s.path, path.string());
  EXPECT_EQ(s.bodies.at(0).name, "bar");
  std::filesystem::remove(path);
}

TEST(SceneParser, EnumNamesRoundTripToTheirSceneSpelling) {
  EXPECT_STREQ(to_string(UpdateScheme::USF), "USF");
  EXPECT_STREQ(to_string(UpdateScheme::MUSL), "MUSL");
  EXPECT_STREQ(to_string(FaceCondition::symmetric), "symmetric");
  EXPECT_STREQ(to_string(Face::ymax), "ymax");
  EXPECT_STREQ(to_string(Face::zmin), "zmin");
}

}  // namespace
}  // namespace afemp::core

namespace afemp::core {
namespace {

const std::string mesh_scene = R"([run]
end_time = 1.0

[materials.steel]
density = 7.8e-3
E = 200e3
nu = 0.3
failure_strain = 0.4

[[bodies]]
name = "plate"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [4, 2, 1] } }
mesh = { divisions = [8, 4, 2] }
element = "full"
hourglass = { form = "stiffness", coefficient = 0.05 }
bulk_viscosity = { linear = 0.1, quadratic = 2.0 }
erosion = { plastic_strain = 0.8, material_failure = true, volume_ratio = 0.1, time_step = 1e-7 }
velocity = [0, 0, -10]

[[bodies]]
name = "bar"
discretisation = "trusses"
material = "steel"
shape = { line = { from = [0, 0, 0], to = [0, 0, 10] } }
mesh = { segments = 5 }
area = 0.5
erosion = { material_failure = true }

[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0], tolerance = 1e-9 } }
body = "plate"
fixed = ["x", "z"]

[[constraints]]
nodes = { set = "end" }
velocity = [0, 0, 1]

[[walls]]
point = [0, 0, -1]
normal = [0, 0, 2]
velocity = [0, 0, 1]
friction = 0.2
bodies = ["plate"]
)";

TEST(SceneParser, MeshBodiesConstraintsAndWallsNeedNoGrid) {
  const Scene s = parse_scene(mesh_scene, "mesh.toml");
  EXPECT_FALSE(s.has_grid);
  ASSERT_EQ(s.bodies.size(), 2u);
  const BodySpec& plate = s.bodies[0];
  EXPECT_EQ(plate.discretisation, Discretisation::hexahedra);
  EXPECT_EQ(plate.mesh.divisions, (std::array<int, 3>{8, 4, 2}));
  EXPECT_EQ(plate.element, HexFormulation::full);
  EXPECT_EQ(plate.hourglass.form, HourglassForm::stiffness);
  EXPECT_EQ(plate.hourglass.coefficient, 0.05);
  EXPECT_EQ(plate.bulk_viscosity->linear, 0.1);
  EXPECT_EQ(plate.bulk_viscosity->quadratic, 2.0);
  ASSERT_TRUE(plate.erosion.has_value());
  EXPECT_EQ(plate.erosion->plastic_strain, 0.8);
  EXPECT_TRUE(plate.erosion->material_failure);
  EXPECT_EQ(plate.erosion->volume_ratio, 0.1);
  EXPECT_EQ(plate.erosion->time_step, 1e-7);
  EXPECT_EQ(s.materials[0].failure_strain, 0.4);
  const BodySpec& bar = s.bodies[1];
  EXPECT_EQ(bar.discretisation, Discretisation::trusses);
  EXPECT_EQ(bar.mesh.segments, 5);
  EXPECT_EQ(bar.area, 0.5);
  ASSERT_EQ(s.constraints.size(), 2u);
  EXPECT_EQ(s.constraints[0].body, 0);
  EXPECT_EQ(s.constraints[0].components, (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(s.constraints[1].nodes.kind, NodeSelector::Kind::set);
  EXPECT_EQ(s.constraints[1].velocity.z, 1.0);
  ASSERT_EQ(s.walls.size(), 1u);
  EXPECT_EQ(s.walls[0].normal.z, 1.0);  // normalised
  EXPECT_EQ(s.walls[0].friction, 0.2);
  EXPECT_EQ(s.walls[0].bodies, std::vector<int>{0});
}

TEST(SceneParser, RebarTakesOnePlaneOrALayerPerPlane) {
  // `position` is a number (one mat) or an array (one mat per layer), each inside the box along
  // the mat's normal; a plane outside names the key and the value.
  auto with = [](const std::string& rebar) {
    std::string s = mesh_scene;
    const std::string from = "shape = { line = { from = [0, 0, 0], to = [0, 0, 10] } }";
    s.replace(s.find(from), from.size(), "shape = { rebar = " + rebar + " }");
    s.replace(s.find("mesh = { segments = 5 }"), 23, "mesh = { size = 0.5 }");
    s.replace(s.find("area = 0.5\n"), 11, "");
    return s;
  };
  const std::string box =
      "min = [0, 0, 0], max = [4, 2, 1], normal = \"z\", spacing = 0.5, "
      "diameter = 0.1, cover = 0.25";
  Scene s = parse_scene(with("{ " + box + ", position = 0.2 }"), "rebar.toml");
  const auto& one = std::get<RebarShape>(s.bodies[1].shape);
  EXPECT_EQ(one.positions, std::vector<double>{0.2});
  s = parse_scene(with("{ " + box + ", position = [0.2, 0.8] }"), "rebar.toml");
  EXPECT_EQ(std::get<RebarShape>(s.bodies[1].shape).positions, (std::vector<double>{0.2, 0.8}));
  std::string e = error_of(with("{ " + box + ", position = [0.2, 1.5] }"));
  EXPECT_NE(e.find("bodies.bar.shape.rebar.position"), std::string::npos) << e;
  EXPECT_NE(e.find("1.5 does not"), std::string::npos) << e;
  e = error_of(with("{ " + box + ", position = [] }"));
  EXPECT_NE(e.find("non-empty array"), std::string::npos) << e;
  e = error_of(with("{ " + box + " }"));
  EXPECT_NE(e.find("one mat per layer"), std::string::npos) << e;
}

TEST(SceneParser, CylinderNoseKeysNameTheKeyAndWhatIsAllowed) {
  // An ogive nose (core/ogive_nose.hpp): crh >= 0.5, a meplat below the diameter (7.6 here),
  // a nose shorter than the cylinder (CRH 12 on R = 3.8 is 26.1 long, the bar 25.4), and a flat
  // tip when hexahedra mesh it.
  auto with = [](const std::string& nose, bool hexahedra = false) {
    std::string s = taylor_scene;
    const std::string from = "length = 25.4 }";
    s.replace(s.find(from), from.size(), "length = 25.4, nose = " + nose + " }");
    if (hexahedra) {
      s.replace(s.find("particles_per_cell = 2\n"), 23,
                "discretisation = \"hexahedra\"\nmesh = { size = 1 }\n");
      s = s.substr(0, s.find("[reference]"));  // Taylor measures need a flat-ended bar
    }
    return s;
  };
  const Scene s = parse_scene(with("{ crh = 3, meplat = 1 }"), "nose.toml");
  const auto& bar = std::get<CylinderShape>(s.bodies[0].shape);
  EXPECT_EQ(bar.nose.crh, 3.0);
  EXPECT_EQ(bar.nose.meplat, 1.0);
  EXPECT_NO_THROW(parse_scene(with("{ crh = 3, meplat = 1 }", true), "nose.toml"));
  std::string e = error_of(with("{ crh = 0.3 }"));
  EXPECT_NE(e.find("bodies.bar.shape.cylinder.nose.crh"), std::string::npos) << e;
  EXPECT_NE(e.find("value >= 0.5"), std::string::npos) << e;
  e = error_of(with("{ crh = 12 }"));
  EXPECT_NE(e.find("must be shorter than the cylinder's length, 25.4"), std::string::npos) << e;
  e = error_of(with("{ crh = 3, meplat = 8 }"));
  EXPECT_NE(e.find("nose.meplat"), std::string::npos) << e;
  e = error_of(with("{ crh = 3 }", true));
  EXPECT_NE(e.find("nose.meplat"), std::string::npos) << e;
  EXPECT_NE(e.find("needs a flat tip"), std::string::npos) << e;
  e = error_of(with("{ crh = 3, tip = 1 }"));
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
}

TEST(SceneParser, MeshMistakesNameTheKeyAndWhatIsAllowed) {
  auto replaced = [](std::string from, const std::string& to) {
    std::string s = mesh_scene;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  std::string e = error_of(replaced("shape = { line = { from = [0, 0, 0], to = [0, 0, 10] } }",
                                    "shape = { sphere = { centre = [0, 0, 0], radius = 1 } }"));
  EXPECT_NE(e.find("a body of trusses takes one of line, rebar, mesh, not sphere"),
            std::string::npos)
      << e;
  e = error_of(replaced("element = \"full\"", "particles_per_cell = 2"));
  EXPECT_NE(e.find("bodies.plate.particles_per_cell"), std::string::npos) << e;
  EXPECT_NE(e.find("not to hexahedra"), std::string::npos) << e;
  e = error_of(replaced("fixed = [\"x\", \"z\"]", "fixed = [\"w\"]"));
  EXPECT_NE(e.find("allowed values: \"x\", \"y\", \"z\", \"all\""), std::string::npos) << e;
  e = error_of(replaced("bodies = [\"plate\"]", "bodies = [\"plat\"]"));
  EXPECT_NE(e.find("unknown body \"plat\""), std::string::npos) << e;
  e = error_of(replaced("area = 0.5\n", ""));
  EXPECT_NE(e.find("bodies.bar.area"), std::string::npos) << e;
  e = error_of(replaced("mesh = { segments = 5 }", "mesh = { core = 5 }"));
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
  e = error_of(replaced("hourglass = { form = \"stiffness\"", "hourglass = { form = \"stiff\""));
  EXPECT_NE(e.find("allowed values: \"viscous\", \"stiffness\", \"assumed_strain\""),
            std::string::npos)
      << e;
  // The assumed-strain form's coefficient is a scale on its stiffness: default 1, at most 1.
  const Scene asqbi =
      parse_scene(replaced("hourglass = { form = \"stiffness\", coefficient = 0.05 }",
                           "hourglass = { form = \"assumed_strain\" }"),
                  "mesh.toml");
  EXPECT_EQ(asqbi.bodies[0].hourglass.form, HourglassForm::assumed_strain);
  EXPECT_EQ(asqbi.bodies[0].hourglass.effective_coefficient(), 1.0);
  e = error_of(replaced("hourglass = { form = \"stiffness\", coefficient = 0.05 }",
                        "hourglass = { form = \"assumed_strain\", coefficient = 1.5 }"));
  EXPECT_NE(e.find("bodies.plate.hourglass.coefficient"), std::string::npos) << e;
  EXPECT_NE(e.find("1"), std::string::npos) << e;
}

TEST(SceneParser, GradedBoxAxesReadTheirSegmentsAndNameWhatIsWrong) {
  // The box runs from 0 to 4 along x: segments must rise to 4 with whole element counts.
  auto with = [](const std::string& mesh) {
    std::string s = mesh_scene;
    const std::string from = "mesh = { divisions = [8, 4, 2] }";
    s.replace(s.find(from), from.size(), mesh);
    return s;
  };
  const Scene s = parse_scene(with("mesh = { x = [[1, 4], [4, 3]], size = 0.5 }"), "mesh.toml");
  const core::MeshDensity& m = s.bodies[0].mesh;
  ASSERT_EQ(m.graded[0].size(), 2u);
  EXPECT_EQ(m.graded[0][1][0], 4.0);
  EXPECT_EQ(m.graded[0][1][1], 3.0);
  EXPECT_TRUE(m.graded[1].empty());
  EXPECT_EQ(m.size, 0.5);
  std::string e = error_of(with("mesh = { x = [[1, 4], [3, 3]], size = 0.5 }"));
  EXPECT_NE(e.find("scene.toml:15"), std::string::npos) << e;
  EXPECT_NE(e.find("bodies.plate.mesh.x"), std::string::npos) << e;
  EXPECT_NE(e.find("not at the box's max 4"), std::string::npos) << e;
  e = error_of(with("mesh = { x = [[2, 4], [1, 3]], size = 0.5 }"));
  EXPECT_NE(e.find("must lie beyond 2"), std::string::npos) << e;
  e = error_of(with("mesh = { x = [[4, 2.5]], size = 0.5 }"));
  EXPECT_NE(e.find("whole number"), std::string::npos) << e;
  e = error_of(with("mesh = { x = [[4, 8]], divisions = [8, 4, 2] }"));
  EXPECT_NE(e.find("not both"), std::string::npos) << e;
  e = error_of(with("mesh = { x = [[4, 8]] }"));
  EXPECT_NE(e.find("[end, elements]"), std::string::npos) << e;
}

// Artificial bulk viscosity: hexahedra have LS-DYNA's (0.06, 1.5) by default; particles have
// it by default only where the material has an EOS (shocks), and take the key too; trusses
// refuse it by name.
TEST(SceneParser, BulkViscosityDefaultsFollowTheDiscretisationAndTheEos) {
  const std::string text = R"(
[run]
end_time = 1.0
[grid]
cell = 1.0
min = [0, 0, 0]
max = [10, 10, 10]
[materials.solid]
density = 8.9e-3
E = 124e3
nu = 0.35
[materials.shocked]
density = 8.9e-3
E = 124e3
nu = 0.35
eos = { model = "mie-gruneisen", c0 = 3940, s = 1.49, gamma0 = 1.96 }
[[bodies]]
name = "plain"
material = "solid"
shape = { box = { min = [0, 0, 0], max = [2, 2, 2] } }
[[bodies]]
name = "with_eos"
material = "shocked"
shape = { box = { min = [3, 0, 0], max = [5, 2, 2] } }
[[bodies]]
name = "given"
material = "solid"
shape = { box = { min = [6, 0, 0], max = [8, 2, 2] } }
bulk_viscosity = { linear = 0.1 }
[[bodies]]
name = "elements"
discretisation = "hexahedra"
material = "solid"
shape = { box = { min = [0, 4, 0], max = [2, 6, 2] } }
mesh = { size = 1.0 }
)";
  const Scene s = parse_scene(text, "viscosity.toml");
  ASSERT_EQ(s.bodies.size(), 4u);
  EXPECT_EQ(bulk_viscosity_of(s, s.bodies[0]).linear, 0.0);
  EXPECT_EQ(bulk_viscosity_of(s, s.bodies[0]).quadratic, 0.0);
  EXPECT_EQ(bulk_viscosity_of(s, s.bodies[1]).linear, 0.06);
  EXPECT_EQ(bulk_viscosity_of(s, s.bodies[1]).quadratic, 1.5);
  EXPECT_EQ(bulk_viscosity_of(s, s.bodies[2]).linear, 0.1);
  EXPECT_EQ(bulk_viscosity_of(s, s.bodies[2]).quadratic, 1.5);  // the key's own default
  EXPECT_EQ(bulk_viscosity_of(s, s.bodies[3]).linear, 0.06);
  EXPECT_EQ(bulk_viscosity_of(s, s.bodies[3]).quadratic, 1.5);
  std::string bad = text;
  bad.replace(bad.find("bulk_viscosity = { linear = 0.1 }"), 33,
              "bulk_viscosity = { linear = 0.1, quadratic = 12 }");
  std::string e = error_of(bad);
  EXPECT_NE(e.find("bodies.given.bulk_viscosity.quadratic"), std::string::npos) << e;
  EXPECT_NE(e.find("10"), std::string::npos) << e;
  e = error_of(std::string(mesh_scene)
                   .replace(std::string(mesh_scene).find("area = 0.5"), 10,
                            "area = 0.5\nbulk_viscosity = { linear = 0.1 }"));
  EXPECT_NE(e.find("bodies.bar.bulk_viscosity"), std::string::npos) << e;
  EXPECT_NE(e.find("not to trusses"), std::string::npos) << e;
}

// [[contact]] names two particle bodies; its mistakes name the line and the key.
TEST(SceneParser, ContactReadsItsPairAndRejectsWhatItCannotDo) {
  const std::string second =
      "[[bodies]]\nname = \"plate\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [5, 1, 1], max = [7, 3, 3] } }\n";
  const std::string good = minimal_head + minimal_tail + second +
                           "[[contact]]\nbodies = [\"block\", \"plate\"]\nfriction = 0.2\n";
  const Scene s = parse_scene(good, "scene.toml");
  ASSERT_EQ(s.contacts.size(), 1u);
  EXPECT_EQ(s.contacts[0].bodies[0], 0);
  EXPECT_EQ(s.contacts[0].bodies[1], 1);
  EXPECT_EQ(s.contacts[0].friction, 0.2);
  EXPECT_EQ(s.contacts[0].distance_factor, 0.5);  // lambda of Lian et al. 2013, eq 42
  const int line = line_of(good, "[[contact]]");  // its bodies key is on the next line
  std::string e = error_of(minimal_head + minimal_tail + second +
                           "[[contact]]\nbodies = [\"block\", \"block\"]\n");
  EXPECT_NE(e.find("itself"), std::string::npos) << e;
  e = error_of(minimal_head + minimal_tail + second +
               "[[contact]]\nbodies = [\"block\", \"plat\"]\n");
  EXPECT_NE(e.find("scene.toml:" + std::to_string(line + 1)), std::string::npos) << e;
  EXPECT_NE(e.find("unknown body \"plat\""), std::string::npos) << e;
  e = error_of(good + "[[contact]]\nbodies = [\"plate\", \"block\"]\n");
  EXPECT_NE(e.find("already has a contact (line " + std::to_string(line)), std::string::npos) << e;
  e = error_of(minimal_head + "[mpm]\nscheme = \"USL\"\n" + minimal_tail + second +
               "[[contact]]\nbodies = [\"block\", \"plate\"]\n");
  EXPECT_NE(e.find("contact[0].bodies"), std::string::npos) << e;
  EXPECT_NE(e.find("\"MUSL\" (the default) or \"USF\""), std::string::npos) << e;
  e = error_of(minimal_head + minimal_tail + second +
               "[[contact]]\nbodies = [\"block\", \"plate\"]\nfriction = -0.1\n");
  EXPECT_NE(e.find("friction"), std::string::npos) << e;
}

// Particle and mesh bodies share a scene; the couplings (bonded_to, [[contact]] with a mesh
// body) are checked: each error names the key and what is allowed.
TEST(SceneParser, CouplingKeysNameTheKeyAndWhatIsAllowed) {
  std::string base = mesh_scene;
  base.insert(base.find("[materials.steel]"),
              "[grid]\ncell = 1.0\nmin = [-5, -5, -5]\nmax = [5, 5, 15]\n\n");
  base.insert(base.find("[[constraints]]"),
              "[[bodies]]\nname = \"ball\"\nmaterial = \"steel\"\n"
              "shape = { sphere = { centre = [0, 0, 5], radius = 1 } }\n\n");
  const Scene mixed = parse_scene(base, "mixed.toml");
  EXPECT_TRUE(has_particles(mixed) && has_mesh(mixed));
  EXPECT_FALSE(has_grid_coupling(mixed));
  // bar (trusses) bonded to the ball: resolved to the ball's index.
  auto with_bond = [&](const std::string& host) {
    std::string t = base;
    t.insert(t.find("area = 0.5") + 10, "\nbonded_to = \"" + host + "\"");
    return t;
  };
  const Scene bonded = parse_scene(with_bond("ball"), "bonded.toml");
  EXPECT_EQ(bonded.bodies[1].bonded_to, 2);
  EXPECT_TRUE(has_grid_coupling(bonded));
  std::string e = error_of(with_bond("slab"));
  EXPECT_NE(e.find("bodies.bar.bonded_to"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown body \"slab\""), std::string::npos) << e;
  // Trusses named into the plate's hexahedra are tied into them (rebar in solid elements).
  const Scene tied = parse_scene(with_bond("plate"), "tied.toml");
  EXPECT_TRUE(tied_into_hexahedra(tied, tied.bodies[1]));
  EXPECT_FALSE(bonded_to_particles(tied, tied.bodies[1]));
  std::string usl = with_bond("ball");
  usl.insert(usl.find("[materials.steel]"), "[mpm]\nscheme = \"USL\"\n");
  e = error_of(usl);
  EXPECT_NE(e.find("bonded coupling needs [mpm] scheme"), std::string::npos) << e;
  std::string on_particles = base;
  on_particles.insert(on_particles.find("radius = 1 } }") + 14, "\nbonded_to = \"plate\"");
  e = error_of(on_particles);
  EXPECT_NE(e.find("bodies.ball.bonded_to"), std::string::npos) << e;
  EXPECT_NE(e.find("applies to bodies of hexahedra or trusses"), std::string::npos) << e;
  // A bonded body moves with its host: no wall and no contact of its own.
  e = error_of(with_bond("ball") +
               "\n[[walls]]\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nbodies = [\"bar\"]\n");
  EXPECT_NE(e.find("walls[1].bodies"), std::string::npos) << e;  // mesh_scene has a wall
  EXPECT_NE(e.find("bonded to particles"), std::string::npos) << e;
  e = error_of(with_bond("ball") + "\n[[contact]]\nbodies = [\"bar\", \"plate\"]\n");
  EXPECT_NE(e.find("contact[0].bodies"), std::string::npos) << e;
  EXPECT_NE(e.find("is bonded to \"ball\""), std::string::npos) << e;
  // Grid contact needs a particle body on one side (two meshes meet by penalty contact, their
  // default); a mesh body with particles is coupled.
  e = error_of(base + "\n[[contact]]\nbodies = [\"bar\", \"plate\"]\nmethod = \"grid\"\n");
  EXPECT_NE(e.find("both bodies are meshes"), std::string::npos) << e;
  const Scene meshes =
      parse_scene(base + "\n[[contact]]\nbodies = [\"bar\", \"plate\"]\n", "m.toml");
  EXPECT_EQ(meshes.contacts.at(0).method, ContactMethod::penalty);
  EXPECT_FALSE(has_grid_coupling(meshes));
  const Scene cfemp =
      parse_scene(base + "\n[[contact]]\nbodies = [\"plate\", \"ball\"]\n", "c.toml");
  EXPECT_TRUE(has_grid_coupling(cfemp));
  // A contact read without its keys is the library's default ContactSpec, so that one built in
  // code is the same model (docs/scene-format.md: penalty 1, friction 0, distance_factor 0.5);
  // the library's penalty default was once 0.1.
  const ContactSpec defaults;
  EXPECT_EQ(defaults.penalty, 1.0);
  EXPECT_EQ(meshes.contacts.at(0).penalty, defaults.penalty);
  EXPECT_EQ(meshes.contacts.at(0).friction, defaults.friction);
  EXPECT_EQ(cfemp.contacts.at(0).distance_factor, defaults.distance_factor);
  EXPECT_EQ(defaults.distance_factor, 0.5);
  // A particle body without a grid is an error naming [grid].
  const std::string no_grid = minimal_tail;
  EXPECT_NE(error_of("[run]\nend_time = 1.0\n" + no_grid).find("key 'grid'"), std::string::npos);
}

// Conversion (AFEMP) keys: read into ConversionSettings; each misuse names bodies.NAME.conversion
// (or the sub-key) and what is allowed.
TEST(SceneParser, ConversionKeysNameTheKeyAndWhatIsAllowed) {
  std::string base = mesh_scene;
  base.insert(base.find("[materials.steel]"),
              "[grid]\ncell = 1.0\nmin = [-5, -5, -5]\nmax = [5, 5, 15]\n\n");
  auto with = [](std::string t, const std::string& conversion) {
    t.insert(t.find("velocity = [0, 0, -10]"), "conversion = " + conversion + "\n");
    return t;
  };
  const Scene s = parse_scene(
      with(base, "{ plastic_strain = 0.5, jacobian_ratio = 0.2, points = 2 }"), "c.toml");
  ASSERT_TRUE(s.bodies[0].conversion.has_value());
  const ConversionSettings& c = *s.bodies[0].conversion;
  EXPECT_EQ(c.plastic_strain, 0.5);
  EXPECT_EQ(c.jacobian_ratio, 0.2);
  EXPECT_TRUE(c.negative_jacobian);  // on by default
  EXPECT_EQ(c.points, 2);
  EXPECT_TRUE(has_grid_coupling(s));
  std::string e = error_of(with(base, "{ points = 3 }"));
  EXPECT_NE(e.find("bodies.plate.conversion.points"), std::string::npos) << e;
  e = error_of(with(base, "{ volumetric_strain = 1.5 }"));
  EXPECT_NE(e.find("bodies.plate.conversion.volumetric_strain"), std::string::npos) << e;
  e = error_of(with(base, "{ negative_jacobian = false }"));
  EXPECT_NE(e.find("every criterion is off"), std::string::npos) << e;
  e = error_of(with(base, "{ strain = 0.1 }"));
  EXPECT_NE(e.find("strain"), std::string::npos) << e;
  e = error_of(with(mesh_scene, "{ damage = 0.9 }"));
  EXPECT_NE(e.find("bodies.plate.conversion"), std::string::npos) << e;
  EXPECT_NE(e.find("add a [grid] section"), std::string::npos) << e;
  std::string usl = with(base, "{ damage = 0.9 }");
  usl.insert(usl.find("[materials.steel]"), "[mpm]\nscheme = \"USL\"\n");
  e = error_of(usl);
  EXPECT_NE(e.find("needs [mpm] scheme"), std::string::npos) << e;
  std::string trusses = base;
  trusses.insert(trusses.find("area = 0.5"), "conversion = { damage = 0.9 }\n");
  e = error_of(trusses);
  EXPECT_NE(e.find("bodies.bar.conversion"), std::string::npos) << e;
  EXPECT_NE(e.find("applies to bodies of hexahedra, not to trusses"), std::string::npos) << e;
}

// Reference: a failure key a discretisation does not use is an error naming the file, the
// line, the key and what that discretisation takes (issue 46). Trusses have no failed state:
// they take failure_strain, as the criterion of erosion = { material_failure = true }, and
// nothing else; an erosion at the material's failure needs a material that fails.
TEST(SceneParser, FailureKeysADiscretisationDoesNotUseAreErrors) {
  const std::string run = "[run]\nend_time = 1.0\n";
  const std::string steel = "[materials.steel]\ndensity = 7.85e-3\nE = 2.0e5\nnu = 0.3\n";
  const std::string jc_damage =
      "failure = { model = \"johnson-cook\", D1 = 0.05, D2 = 3.44, D3 = -2.12, D4 = 0.002, "
      "D5 = 0.61 }\n";
  const auto bar = [](const std::string& extra) {
    return "[[bodies]]\nname = \"bar\"\ndiscretisation = \"trusses\"\nmaterial = \"steel\"\n"
           "shape = { line = { from = [0, 0, 0], to = [10, 0, 0] } }\nmesh = { size = 1 }\n"
           "area = 1\n" +
           extra;
  };
  // Johnson-Cook damage on a truss material: refused at the material's failure key.
  const std::string jc = run + steel + jc_damage + bar("erosion = { material_failure = true }\n");
  std::string e = test::error_of(jc);
  EXPECT_EQ(e.rfind("scene.toml:" + std::to_string(test::line_of(jc, "failure = ")) +
                        ": key 'materials.steel.failure'",
                    0),
            0u)
      << e;
  EXPECT_NE(e.find("body \"bar\" is made of trusses, which take failure_strain only"),
            std::string::npos)
      << e;
  // So is the plastic-strain model written out (trusses would never erode at it).
  const std::string plastic = run + steel +
                              "failure = { model = \"plastic-strain\", strain = 0.2 }\n" +
                              bar("erosion = { material_failure = true }\n");
  e = test::error_of(plastic);
  EXPECT_NE(e.find("key 'materials.steel.failure'"), std::string::npos) << e;
  // A failure_strain that trusses would not erode at: without material_failure it does nothing.
  const std::string unused = run + steel + "failure_strain = 0.2\n" + bar("");
  e = test::error_of(unused);
  EXPECT_EQ(e.rfind("scene.toml:" + std::to_string(test::line_of(unused, "[[bodies]]")) +
                        ": key 'bodies.bar.erosion'",
                    0),
            0u)
      << e;
  EXPECT_NE(e.find("failure_strain acts on trusses only through erosion = { material_failure "
                   "= true }"),
            std::string::npos)
      << e;
  // Erosion at the material's failure, of a material that never fails.
  const std::string never = run + steel + bar("erosion = { material_failure = true }\n");
  e = test::error_of(never);
  EXPECT_EQ(
      e.rfind("scene.toml:" + std::to_string(test::line_of(never, "erosion = { material_failure")) +
                  ": key 'bodies.bar.erosion.material_failure'",
              0),
      0u)
      << e;
  // The truss's own criterion is accepted.
  EXPECT_NO_THROW(parse_scene(
      run + steel + "failure_strain = 0.2\n" + bar("erosion = { material_failure = true }\n"),
      "scene.toml"));
}

}  // namespace
}  // namespace afemp::core
