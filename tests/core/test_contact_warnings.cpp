// Warnings for bodies that meet without a contact (core/contact_warnings.cpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/contact_warnings.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

std::vector<std::string> warnings_of(const std::string& text) {
  const Scene scene = parse_scene(text, "welds.toml");
  const auto model = coupling::make_model(scene);
  return contact_warnings(scene, *model);
}

// A steel ball resting on an aluminium plate of particles (the trial: 562 m/s residual
// welded, 713 with contact), and two meshes of hexahedra.
const std::string kParticles =
    "[run]\nend_time = 1\n[grid]\ncell = 1\nmin = [-5, -5, -5]\nmax = [5, 5, 5]\n"
    "[materials.steel]\ndensity = 7.85e-3\nE = 2.1e5\nnu = 0.3\n"
    "[materials.aluminium]\ndensity = 2.7e-3\nE = 7e4\nnu = 0.33\n"
    "[[bodies]]\nname = \"ball\"\nmaterial = \"steel\"\n"
    "shape = { sphere = { centre = [0, 0, 1.6], radius = 1.5 } }\n"
    "[[bodies]]\nname = \"plate\"\nmaterial = \"aluminium\"\n"
    "shape = { box = { min = [-4, -4, -1], max = [4, 4, 0] } }\n";

// Reference: bodies of particles of different materials within one cell share the grid's
// velocity field and weld (Lian et al. 2013, §2.4: contact needs a field per body). Pass: the
// pair is named once with the word "weld" and both remedies; a grid contact or a declared weld
// silences it; a ball 3 cells away is not named.
TEST(ContactWarnings, ParticleBodiesThatWouldWeldAreNamed) {
  std::vector<std::string> w = warnings_of(kParticles);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("bodies \"ball\" and \"plate\""), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("materials steel and aluminium"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("weld where they meet"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("method = \"weld\""), std::string::npos) << w[0];
  EXPECT_TRUE(warnings_of(kParticles + "[[contact]]\nbodies = [\"ball\", \"plate\"]\n").empty());
  EXPECT_TRUE(
      warnings_of(kParticles + "[[contact]]\nbodies = [\"ball\", \"plate\"]\nmethod = \"weld\"\n")
          .empty());
  std::string far = kParticles;
  far.replace(far.find("centre = [0, 0, 1.6]"), 20, "centre = [0, 0, 3.4]");
  EXPECT_TRUE(warnings_of(far).empty());
}

// A rod of hexahedra standing on a plate of hexahedra.
const std::string kTouchingMeshes =
    "[run]\nend_time = 1\n[materials.steel]\ndensity = 7.85e-3\nE = 2.1e5\nnu = 0.3\n"
    "[[bodies]]\nname = \"rod\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
    "shape = { box = { min = [0, 0, 0], max = [1, 1, 5] } }\nmesh = { divisions = [1, 1, 5] }\n"
    "[[bodies]]\nname = \"plate\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
    "shape = { box = { min = [-3, -3, -1], max = [3, 3, 0] } }\nmesh = { divisions = [6, 6, 1] "
    "}\n";

// Reference: meshes meet only through a contact; without one they pass through each other.
// Pass: two touching bodies of hexahedra without a contact are named, with a contact not.
TEST(ContactWarnings, MeshesThatWouldPassThroughEachOtherAreNamed) {
  const std::string& meshes = kTouchingMeshes;
  const std::vector<std::string> w = warnings_of(meshes);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("two meshes pass through each other"), std::string::npos) << w[0];
  EXPECT_TRUE(warnings_of(meshes + "[[contact]]\nbodies = [\"rod\", \"plate\"]\n").empty());
  // A weld is for particles: on meshes it is an error naming the key.
  try {
    parse_scene(meshes + "[[contact]]\nbodies = [\"rod\", \"plate\"]\nmethod = \"weld\"\n",
                "w.toml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("contact[0].method"), std::string::npos) << e.what();
  }
}

// Reference: the scene format (docs/scene-format.md): overlap_allowed on either body says that
// the two are meant to meet, and the pair is not named; it names other bodies of the scene.
TEST(ContactWarnings, OverlapAllowedSilencesThePairAndNamesOtherBodies) {
  auto with = [](const std::string& line) {
    std::string text = kTouchingMeshes;
    return text.insert(text.find("discretisation"), line + "\n");
  };
  EXPECT_TRUE(warnings_of(with("overlap_allowed = [\"plate\"]")).empty());
  const std::string unknown = test::error_of(with("overlap_allowed = [\"plates\"]"));
  EXPECT_NE(
      unknown.find(
          "key 'bodies.rod.overlap_allowed': unknown body \"plates\"; bodies: \"rod\", \"plate\""),
      std::string::npos)
      << unknown;
  EXPECT_NE(test::error_of(with("overlap_allowed = [\"rod\"]")).find("bodies.rod.overlap_allowed"),
            std::string::npos);
  Scene scene = parse_scene(kTouchingMeshes, "touching.toml");
  scene.bodies[0].overlap_allowed = {2};
  try {
    check_scene(scene);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies.rod.overlap_allowed"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace afemp::core
