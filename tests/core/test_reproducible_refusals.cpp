// The reproducible mode's scope ([run] reproducible = true; core/reproducible_refusals.hpp): a
// scene that asks for it with a stage whose sums it does not make independent of their order
// is refused at the key's line, naming the stage; a scene built in code the same way through
// the scene check. Reference: the rule itself (what mpm/reproducible_sums.cpp covers).
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "copper_bar_on_wall.hpp"
#include "core/reproducible_refusals.hpp"
#include "core/scene.hpp"
#include "scene_errors.hpp"
#include "striker_on_plate.hpp"

namespace afemp::core {
namespace {

std::string bar(const std::string& mpm) {
  return test::copper_bar_on_wall("end_time = 0.01\nreproducible = true\n", mpm);
}

TEST(ReproducibleMode, ParticleAndMeshScenesAreTaken) {
  const Scene s = parse_scene(bar("scheme = \"USL\"\nshape_function = \"bspline3\"\n"), "s.toml");
  EXPECT_TRUE(s.run.reproducible);
  EXPECT_NO_THROW(check_scene(s));
  const Scene mesh = parse_scene(test::block_and_rod_on_wall("reproducible = true\n"), "m.toml");
  EXPECT_TRUE(mesh.run.reproducible);
  EXPECT_NO_THROW(check_scene(mesh));
  EXPECT_FALSE(
      parse_scene(test::copper_bar_on_wall("end_time = 0.01\n", ""), "s.toml").run.reproducible);
  // Meshes coupled to particles: the mesh nodes' terms join the fixed-point sums.
  const Scene coupled =
      parse_scene(test::striker_on_plate(true, "end_time = 1.0\nreproducible = true\n"), "c.toml");
  EXPECT_TRUE(coupled.run.reproducible);
  EXPECT_NO_THROW(check_scene(coupled));
}

// Hexahedra that convert into particles bring the particles' stages, and their refusals.
TEST(ReproducibleMode, HexahedraThatConvertMeetTheParticlesRefusals) {
  Scene s = parse_scene(test::block_and_rod_on_wall("reproducible = true\n"), "m.toml");
  s.mpm.shape = ShapeFunction::cpdi1;
  EXPECT_FALSE(reproducible_refusal(s)) << "CPDI has no particles to act on";
  s.bodies.front().conversion = ConversionSettings{};
  const std::optional<std::string> why = reproducible_refusal(s);
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("CPDI"), std::string::npos) << *why;
}

TEST(ReproducibleMode, RefusesWhatItsSumsDoNotCoverAtTheKeysLine) {
  const std::string cpdi = bar("shape_function = \"cpdi1\"\n");
  const std::string e = test::error_of(cpdi);
  EXPECT_NE(e.find("scene.toml:" + std::to_string(test::line_of(cpdi, "reproducible")) +
                   ": key 'run.reproducible'"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("CPDI"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: reproducible = false"), std::string::npos) << e;
}

TEST(ReproducibleMode, TheSceneCheckRefusesAsTheParserDoes) {
  Scene s = parse_scene(bar(""), "s.toml");
  s.mpm.shape = ShapeFunction::cpdi1;
  try {
    check_scene(s);
    ADD_FAILURE() << "CPDI taken in the reproducible mode";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("CPDI"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("run.reproducible"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace afemp::core
