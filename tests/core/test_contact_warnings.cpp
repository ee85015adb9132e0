// Warnings for bodies that meet without a contact (core/contact_warnings.cpp): before the run,
// and during it for bodies that come to overlap.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "analysis/reference_checks.hpp"
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

// A steel ball resting on an aluminium plate of particles (the issue's trial: 562 m/s residual
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

// The overlap warnings of a run's summary (OverlapCheck, at history rows).
std::vector<std::string> overlaps_of(const std::string& text) {
  const Scene scene = parse_scene(text, "overlap.toml");
  const auto model = coupling::make_model(scene);
  const RunSummary s = analysis::run(*model, scene, RunOptions{});
  std::vector<std::string> out;
  for (const std::string& w : s.warnings)
    if (w.find("overlap") != std::string::npos) out.push_back(w);
  return out;
}

// The time of "from t = T" in a warning.
double first_time(const std::string& w) {
  const std::string key = "from t = ";
  const std::size_t at = w.find(key);
  EXPECT_NE(at, std::string::npos) << w;
  return at == std::string::npos ? -1.0 : std::strtod(w.c_str() + at + key.size(), nullptr);
}

// A steel rod 1 x 1 x 5 mm (0.25 mm hexahedra) 0.1 mm above a steel plate 1 mm thick (0.5 mm
// hexahedra), flying at it at 500 m/s with no [[contact]] between them, for 4 us.
const std::string kRodAndPlate = R"(
[run]
end_time = 0.004
history_every = 1
[materials.steel]
density = 7.85e-3
E = 2.1e5
nu = 0.3
[[bodies]]
name = "rod"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [-0.5, -0.5, 0.1], max = [0.5, 0.5, 5.1] } }
mesh = { size = 0.25 }
velocity = [0, 0, -500]
[[bodies]]
name = "plate"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [-3, -3, -1], max = [3, 3, 0] } }
mesh = { size = 0.5 }
)";

// Reference: nothing acts on the rod, which flies through the plate unchanged: its node layers
// (0.25 mm apart, 25 nodes each) sit at z = 0.1 + 0.25 k - 500 t. The first enters the plate
// once t > 0.1 / 500 = 2e-4 ms; from the first history row after, the run warns of the pair
// (both bodies, the time); at most 4 layers lie within the plate's 1 mm (100 nodes; its nodes
// on the rod's mesh planes x = y = 0, at z = -1, -0.5, 0, are inside the rod: 3), the nodes on
// the plate's mesh planes included and none on its outer faces. With overlap_allowed, or with
// a [[contact]] between them, there is no such warning.
TEST(OverlapCheck, ARodDrivenThroughAPlateWithNoContactIsWarnedOf) {
  const std::vector<std::string> w = overlaps_of(kRodAndPlate);
  ASSERT_EQ(w.size(), 1u);
  std::printf("[ overlap ] %s\n", w[0].c_str());
  EXPECT_EQ(w[0].rfind("bodies \"rod\" and \"plate\" overlap with no [[contact]] between them", 0),
            0u)
      << w[0];
  const double dt = 0.9 * 0.25 / std::sqrt(2.1e5 * 0.7 / (1.3 * 0.4 * 7.85e-3));
  EXPECT_GT(first_time(w[0]), 2e-4);
  EXPECT_LT(first_time(w[0]), 2e-4 + 1.5 * dt);
  EXPECT_NE(w[0].find("the most at t = "), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("100 nodes of \"rod\" lie inside the elements of \"plate\", and 3 nodes of "
                      "\"plate\" lie inside the elements of \"rod\""),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[0].find("overlap_allowed = [\"plate\"] in body \"rod\""), std::string::npos) << w[0];

  std::string allowed = kRodAndPlate;
  allowed.insert(allowed.find("velocity = [0, 0, -500]"), "overlap_allowed = [\"plate\"]\n");
  EXPECT_TRUE(overlaps_of(allowed).empty());
  EXPECT_TRUE(overlaps_of(kRodAndPlate + "[[contact]]\nbodies = [\"rod\", \"plate\"]\n").empty());
}

// Reference: a block of particles (on the grid's lattice, 0.25 mm apart from z = 0.125, 8 x 8
// a layer) flying at 500 m/s through a plate of hexahedra 1 mm thick with no contact: nothing
// couples them, so it passes unchanged, and 4 of its layers lie within the plate once it is
// through the plate's top: 256 particles, from the first history row after its lowest layer
// crosses z = 0 (t = 2.5e-4 ms; a step is 0.3 h / (c + 500) = 2.3e-5 ms).
TEST(OverlapCheck, ParticlesFlyingThroughAMeshWithNoContactAreWarnedOf) {
  const std::vector<std::string> w = overlaps_of(R"(
[run]
end_time = 0.003
history_every = 1
[grid]
cell = 0.5
min = [-2, -2, -2]
max = [2, 2, 3]
[materials.steel]
density = 7.85e-3
E = 2.1e5
nu = 0.3
[[bodies]]
name = "block"
material = "steel"
shape = { box = { min = [-1, -1, 0.1], max = [1, 1, 2.1] } }
velocity = [0, 0, -500]
[[bodies]]
name = "plate"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [-1.5, -1.5, -1], max = [1.5, 1.5, 0] } }
mesh = { size = 0.5 }
)");
  ASSERT_EQ(w.size(), 1u);
  std::printf("[ overlap ] %s\n", w[0].c_str());
  EXPECT_NE(w[0].find("256 particles of \"block\" lie inside the elements of \"plate\""),
            std::string::npos)
      << w[0];
  EXPECT_GT(first_time(w[0]), 2.5e-4);
  EXPECT_LT(first_time(w[0]), 2.5e-4 + 2.3e-5);
  EXPECT_NE(w[0].find("(method \"surface\")"), std::string::npos) << w[0];
}

// A steel block of particles falling at 200 m/s onto an aluminium plate of particles 1.5 mm
// below it, on one grid (cell 0.5 mm) with no contact between them.
const std::string kBlockOnPlate = R"(
[run]
end_time = 0.007
history_every = 1
[grid]
cell = 0.5
min = [-3, -3, -2]
max = [3, 3, 3]
[materials.steel]
density = 7.85e-3
E = 2.1e5
nu = 0.3
[materials.aluminium]
density = 2.7e-3
E = 7e4
nu = 0.33
[[bodies]]
name = "block"
material = "steel"
shape = { box = { min = [-1, -1, 1.5], max = [1, 1, 2.5] } }
velocity = [0, 0, -200]
[[bodies]]
name = "plate"
material = "aluminium"
shape = { box = { min = [-2, -2, -1], max = [2, 2, 0] } }
)";

// Reference: particles reach the nodes of their cell, so two particles share grid nodes once
// their cells are neighbours. The block's lowest particles (z = 1.625) and the plate's highest
// (z = -0.125, cell 3 of the grid from z = -2) come to neighbouring cells when the block's
// reach cell 4, below z = 0.5: after 1.125 mm of free flight, t = 5.625e-3 ms. From then on
// the two materials share one velocity field and weld; the run warns of it, and not with a
// grid contact between them.
TEST(OverlapCheck, ParticleBodiesThatComeToShareGridNodesAreWarnedOf) {
  const std::vector<std::string> w = overlaps_of(kBlockOnPlate);
  ASSERT_EQ(w.size(), 1u);
  std::printf("[ overlap ] %s\n", w[0].c_str());
  EXPECT_NE(w[0].find("particles of \"block\" lie in cells next to those of \"plate\" (materials "
                      "steel and aluminium): they share grid nodes and weld there"),
            std::string::npos)
      << w[0];
  EXPECT_GT(first_time(w[0]), 5.625e-3);
  EXPECT_LT(first_time(w[0]), 5.8e-3);
  EXPECT_TRUE(
      overlaps_of(kBlockOnPlate + "[[contact]]\nbodies = [\"block\", \"plate\"]\n").empty());
}

}  // namespace
}  // namespace afemp::core
