// An LS-DYNA deck that runs as it means (issue 47): a blunt steel projectile of hexahedra
// through an aluminium plate of hexahedra (quarter model, 0.5 mm elements, 400 m/s), written
// as a keyword deck with *CONTACT_ERODING_SURFACE_TO_SURFACE, a node-set *INITIAL_VELOCITY,
// *MAT_PLASTIC_KINEMATIC and *MAT_ADD_EROSION (EFFEPS 0.8), symmetry and the plate's held
// edges by *BOUNDARY_SPC_SET, imported with afemp::import_deck and run beside the same
// problem written by hand as a scene (examples/fe_contact/perforation.toml's materials, a
// smaller projectile and plate). Reference: the hand scene's residual velocity; tolerance 1 %.
// Measured (2-core Intel Xeon VM): -289.082 m/s both, 856 steps, 0.6 s each; the projectile's
// lowest point at z = -9.02 mm, through the plate (z = -2). The deck's mesh is the hand scene's
// box meshes written out, so the runs agree to the last digit: the translation is exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "afemp/deck_import.hpp"
#include "analysis/reference_checks.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"
#include "fem/mesh_generation.hpp"
#include "scratch_dir.hpp"

namespace afemp::fem {
namespace {

const core::BoxShape kProjectile{{0, 0, 0.05}, {2.5, 2.5, 7.55}};
const std::array<int, 3> kProjectileDivisions{5, 5, 15};
const core::BoxShape kPlate{{0, 0, -2}, {8, 8, 0}};
const std::array<int, 3> kPlateDivisions{16, 16, 4};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// The mesh's nodes (labels first + 1 ...) and elements of part `part`.
std::string mesh_cards(const MeshData& m, int part, int first) {
  std::string s = "*NODE\n";
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    s += std::to_string(first + 1 + static_cast<int>(i)) + "," + number(m.nodes[i].x) + "," +
         number(m.nodes[i].y) + "," + number(m.nodes[i].z) + "\n";
  s += "*ELEMENT_SOLID\n";
  for (std::size_t e = 0; e < m.hexahedra.size(); ++e) {
    s += std::to_string(first + 1 + static_cast<int>(e)) + "," + std::to_string(part);
    for (const std::int32_t n : m.hexahedra[e]) {
      s += ',';  // appended apart: "," + std::string trips GCC 12's -Wrestrict
      s += std::to_string(first + 1 + n);
    }
    s += "\n";
  }
  return s;
}

// A *SET_NODE_LIST of the mesh's node set `name` (every node when empty).
std::string node_set(const MeshData& m, int first, int sid, const std::string& name) {
  std::vector<std::int32_t> members;
  for (const NamedSet& set : m.node_sets)
    if (set.name == name) members = set.members;
  if (name.empty())
    for (std::size_t i = 0; i < m.nodes.size(); ++i)
      members.push_back(static_cast<std::int32_t>(i));
  std::string s = "*SET_NODE_LIST\n" + std::to_string(sid) + "\n";
  for (std::size_t i = 0; i < members.size(); ++i)
    s += std::to_string(first + 1 + members[i]) +
         (i % 8 == 7 || i + 1 == members.size() ? "\n" : ",");
  return s;
}

std::string perforation_deck() {
  const MeshData projectile = box_mesh(kProjectile, kProjectileDivisions);
  const MeshData plate = box_mesh(kPlate, kPlateDivisions);
  const int plate_first = 100000;
  return "*KEYWORD\n*TITLE\nblunt projectile through a plate\n*CONTROL_TERMINATION\n0.03\n"
         "*PART\nprojectile\n1,1,1\n*PART\nplate\n2,1,2\n*SECTION_SOLID\n1,1\n"
         "*MAT_PLASTIC_KINEMATIC\n1,7.85e-3,2.1e5,0.3,1900.0,1000.0,1.0\n"
         "*MAT_PLASTIC_KINEMATIC\n2,2.7e-3,7.0e4,0.33,300.0,500.0,1.0\n"
         "*MAT_ADD_EROSION\n2,,,,0.8\n"
         "*CONTACT_ERODING_SURFACE_TO_SURFACE\n1,2,3,3\n0.0,0.0\n\n0,1,0\n" +
         node_set(projectile, 0, 1, "") + "*INITIAL_VELOCITY\n1\n0.0,0.0,-400.0\n" +
         node_set(projectile, 0, 11, "xmin") + node_set(projectile, 0, 12, "ymin") +
         node_set(plate, plate_first, 21, "xmin") + node_set(plate, plate_first, 22, "ymin") +
         node_set(plate, plate_first, 23, "xmax") + node_set(plate, plate_first, 24, "ymax") +
         "*BOUNDARY_SPC_SET\n11,0,1,0,0\n12,0,0,1,0\n21,0,1,0,0\n22,0,0,1,0\n23,0,1,1,1\n"
         "24,0,1,1,1\n" +
         mesh_cards(projectile, 1, 0) + mesh_cards(plate, 2, plate_first) + "*END\n";
}

const char* const kHandScene = R"([run]
end_time = 0.03
[materials.steel]
density = 7.85e-3
E = 2.1e5
nu = 0.3
strength = { model = "j2", yield = 1900, tangent_modulus = 1000 }
[materials.aluminium]
density = 2.7e-3
E = 7.0e4
nu = 0.33
strength = { model = "j2", yield = 300, tangent_modulus = 500 }
[[bodies]]
name = "projectile"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0.05], max = [2.5, 2.5, 7.55] } }
mesh = { divisions = [5, 5, 15] }
velocity = [0, 0, -400]
[[bodies]]
name = "plate"
discretisation = "hexahedra"
material = "aluminium"
shape = { box = { min = [0, 0, -2], max = [8, 8, 0] } }
mesh = { divisions = [16, 16, 4] }
erosion = { plastic_strain = 0.8 }
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }
fixed = ["x"]
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 1, 0] } }
fixed = ["y"]
[[constraints]]
nodes = { box = { min = [7.9, -1, -3], max = [9, 9, 1] } }
fixed = ["x", "y", "z"]
[[constraints]]
nodes = { box = { min = [-1, 7.9, -3], max = [9, 9, 1] } }
fixed = ["x", "y", "z"]
[[contact]]
bodies = ["projectile", "plate"]
)";

struct Perforation {
  double residual_velocity;  // the projectile's mean velocity along z at the end
  double lowest_z;           // its lowest point then
};

Perforation run_projectile(core::Scene scene, const char* label) {
  core::VelocityReference v;
  v.body = 0;
  v.component = 2;
  v.value = -400.0;
  scene.velocity_references.push_back(v);
  const std::unique_ptr<core::Model> model = coupling::make_model(scene);
  const core::RunSummary s = analysis::run(*model, scene, {});
  Perforation p{0.0, 0.0};
  for (const core::ReferenceCheck& c : s.checks)
    if (c.name.find("velocity") != std::string::npos) p.residual_velocity = c.value;
  const core::BodyPoints points = model->body_points(0);
  p.lowest_z = points.position.front().z;
  for (const core::Vec3& x : points.position) p.lowest_z = std::min(p.lowest_z, x.z);
  std::printf("%s: residual velocity %.3f m/s, lowest point z = %.3f mm, %ld steps, %.1f s\n",
              label, p.residual_velocity, p.lowest_z, s.steps, s.wall_seconds);
  return p;
}

// Reference: the hand-written scene's residual velocity, within 1 %; both perforate (the
// projectile's lowest point below the plate's lower face z = -2, still moving down).
TEST(LsDynaDeckPerforation, ImportedDeckGivesTheHandSceneResidualVelocity) {
  test::ScratchDir dir;
  const std::string deck_path = dir.write("perforation.k", perforation_deck());
  const std::string scene_path = dir.file("perforation.toml");
  const core::DeckImport deck = core::import_deck(deck_path, scene_path);
  core::write_deck_import(deck, scene_path);
  const core::Scene imported = core::read_scene(scene_path);
  ASSERT_EQ(imported.contacts.size(), 1u) << deck.scene;
  ASSERT_TRUE(imported.bodies[1].erosion.has_value()) << deck.scene;
  EXPECT_DOUBLE_EQ(imported.bodies[0].velocity.z, -400.0);

  const Perforation a = run_projectile(imported, "imported deck");
  const Perforation b =
      run_projectile(core::read_scene(dir.write("hand.toml", kHandScene)), "hand scene");
  EXPECT_LT(b.lowest_z, -2.0);
  EXPECT_LT(b.residual_velocity, -100.0);
  EXPECT_LT(a.lowest_z, -2.0);
  EXPECT_NEAR(a.residual_velocity, b.residual_velocity, 0.01 * std::abs(b.residual_velocity));
}

}  // namespace
}  // namespace afemp::fem
