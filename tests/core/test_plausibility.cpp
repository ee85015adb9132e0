// Plausibility warnings (core/plausibility.hpp): the silent mistakes of the issue each warn,
// naming the file, line and key; correct scenes and silenced keys do not.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/plausibility.hpp"
#include "core/scene.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

std::vector<std::string> warnings_of(const std::string& text) {
  std::vector<std::string> out;
  for (const SceneWarning& w : plausibility_warnings(parse_scene(text, "s.toml")))
    out.push_back(w.text());
  return out;
}

// A copper sphere of particles in a mm-ms-g scene; `material` replaces its material table.
std::string particles(const std::string& material, const std::string& run_extra = "",
                      const std::string& grid_max = "[10, 10, 10]") {
  return "[run]\nend_time = 0.01\nunits = \"mm-ms-g\"\n" + run_extra +
         "[grid]\ncell = 0.5\nmin = [0, 0, 0]\nmax = " + grid_max + "\n" + material +
         "[[bodies]]\nname = \"ball\"\nmaterial = \"m\"\n"
         "shape = { sphere = { centre = [5, 5, 5], radius = 1 } }\n";
}

const std::string kCopper =
    "[materials.m]\ndensity = 8.93e-3\nE = 117e3\nnu = 0.35\n"
    "strength = { model = \"j2\", yield = 240 }\n";

// Reference: real copper in mm-ms-g units (rho 8.93e-3 g/mm^3, c_L 4.8 km/s, yield E / 490) on
// a grid of whole cells raises nothing.
TEST(Plausibility, ARealMaterialOnAWholeGridRaisesNothing) {
  EXPECT_TRUE(warnings_of(particles(kCopper)).empty());
}

// Reference: each mistake of the issue, one warning at its table's line with its key.
TEST(Plausibility, TheSilentMistakesEachWarnAtTheirKey) {
  auto expect_one = [](const std::string& text, const std::string& key) {
    const std::vector<std::string> w = warnings_of(text);
    ASSERT_EQ(w.size(), 1u) << (w.empty() ? "none" : w[0]);
    const std::string at = "s.toml:" + std::to_string(afemp::test::line_of(text, "[materials.m]")) +
                           ": key '" + key + "'";
    EXPECT_EQ(w[0].rfind(at, 0), 0u) << w[0];
  };
  // Steel's SI density in a millimetre scene (its wave speed is then 6 m/s too: two warnings).
  EXPECT_EQ(warnings_of(particles("[materials.m]\ndensity = 7830\nE = 2.1e5\nnu = 0.3\n")).size(),
            2u);
  // The SI concrete pasted in: density 2440 (its wave speed 3.8 km/s looks real).
  expect_one(particles("[materials.m]\ndensity = 2440\nE = 3.5e10\nnu = 0.2\n"),
             "materials.m.density");
  // Aluminium's E in GPa with its yield in MPa.
  {
    const std::vector<std::string> w = warnings_of(particles(
        "[materials.m]\ndensity = 2.7e-3\nE = 68.9\nnu = 0.33\nstrength = { model = \"j2\", "
        "yield = 324 }\n"));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("key 'materials.m.strength'"), std::string::npos) << w[0];
    EXPECT_NE(w[0].find("above E / 10 = 6.89"), std::string::npos) << w[0];
  }
  // A failure strain given as a percentage.
  expect_one(particles(kCopper + "failure_strain = 80\n"), "materials.m.failure_strain");
}

// Reference: a grid of 10.0 / 0.3 = 33.3 cells is extended to 34 (max 10.2): one warning per
// axis, at the line of max; silenced with quiet. Without declared units the material is
// checked against each unit system: steel's SI density with its E in MPa, one warning.
TEST(Plausibility, AGridOfPartCellsWarnsAndQuietSilencesIt) {
  std::string text = particles(kCopper, "", "[10, 10, 10.2]");
  text.replace(text.find("cell = 0.5"), 10, "cell = 0.3");
  const std::vector<std::string> w = warnings_of(text);
  ASSERT_EQ(w.size(), 2u);  // z is 34 cells exactly
  EXPECT_NE(w[0].find("s.toml:" + std::to_string(afemp::test::line_of(text, "max =")) +
                      ": key 'grid.max'"),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[0].find("extended to 34 cells (max x = 10.2)"), std::string::npos) << w[0];
  std::string quiet = particles(kCopper, "quiet = [\"grid.max\"]\n", "[10, 10, 10.2]");
  quiet.replace(quiet.find("cell = 0.5"), 10, "cell = 0.3");
  EXPECT_TRUE(warnings_of(quiet).empty());
  std::string no_units = particles("[materials.m]\ndensity = 7830\nE = 2.1e5\nnu = 0.3\n");
  no_units.erase(no_units.find("units = \"mm-ms-g\"\n"), 18);
  const std::vector<std::string> mixed = warnings_of(no_units);
  ASSERT_EQ(mixed.size(), 1u);
  EXPECT_NE(mixed[0].find("key 'materials.m.density'"), std::string::npos) << mixed[0];
}

// Reference: a quarter cylinder of hexahedra (sectors = 1) needs its two cut planes held along
// their normals; without constraints both warn, with them none.
TEST(Plausibility, AQuarterMeshWithoutItsSymmetryConstraintsWarns) {
  const std::string rod =
      "[run]\nend_time = 0.01\n[materials.m]\ndensity = 8.93e-3\nE = 117e3\nnu = 0.35\n"
      "[[bodies]]\nname = \"rod\"\ndiscretisation = \"hexahedra\"\nmaterial = \"m\"\n"
      "shape = { cylinder = { base = [0, 0, 0], axis = [0, 0, 1], radius = 2, length = 10 } }\n"
      "mesh = { size = 0.5, sectors = 1 }\n";
  const std::vector<std::string> w = warnings_of(rod);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NE(w[0].find("key 'bodies.rod.mesh.sectors': a quarter mesh"), std::string::npos) << w[0];
  const std::string held =
      rod +
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }\n"
      "fixed = [\"x\"]\n[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 1, "
      "0] } }\nfixed = [\"y\"]\n";
  EXPECT_TRUE(warnings_of(held).empty());
}

// A scene without [run] units: `material` for the ball, and for a second ball if `other`.
std::string without_units(const std::string& material, const std::string& other = "") {
  std::string text = particles(material) + other;
  text.erase(text.find("units = \"mm-ms-g\"\n"), 18);
  if (!other.empty())
    text +=
        "[[bodies]]\nname = \"ball2\"\nmaterial = \"n\"\n"
        "shape = { sphere = { centre = [2, 2, 2], radius = 1 } }\n";
  return text;
}

// Reference: without [run] units each material is checked against the unit systems a scene may
// be in (mm-ms-g, SI and the others of `afemp import --units`): steel's SI density 7850 with
// its modulus in MPa fits none (its wave speed would be 6 m/s) and warns with the likely
// systems and the density in the modulus's system (7.85e-3 g/mm^3 in mm-ms-g); an SI
// concrete among mm-ms-g materials warns with its values in mm-ms-g; consistent SI and
// mm-ms-g scenes raise nothing.
TEST(Plausibility, WithoutUnitsEachMaterialIsCheckedAgainstTheUnitSystems) {
  const std::vector<std::string> mixed =
      warnings_of(without_units("[materials.m]\ndensity = 7850\nE = 2.1e5\nnu = 0.3\n"));
  ASSERT_EQ(mixed.size(), 1u);
  EXPECT_NE(mixed[0].find("key 'materials.m.density': density 7850 looks like kg/m^3 (SI) and "
                          "E = 2.1e+05 like MPa (mm-ms-g)"),
            std::string::npos)
      << mixed[0];
  EXPECT_NE(mixed[0].find("in mm-ms-g the density is 0.00785 g/mm^3"), std::string::npos)
      << mixed[0];
  const std::vector<std::string> pasted =
      warnings_of(without_units(kCopper, "[materials.n]\ndensity = 2440\nE = 3.5e10\nnu = 0.2\n"));
  ASSERT_EQ(pasted.size(), 1u);
  EXPECT_NE(pasted[0].find("key 'materials.n.density': material n looks like SI"),
            std::string::npos)
      << pasted[0];
  EXPECT_NE(pasted[0].find("in mm-ms-g its density is 0.00244 g/mm^3 and E 3.5e+04 MPa"),
            std::string::npos)
      << pasted[0];
  EXPECT_TRUE(
      warnings_of(without_units("[materials.m]\ndensity = 7850\nE = 2.1e11\nnu = 0.3\n")).empty());
  EXPECT_TRUE(warnings_of(without_units(kCopper)).empty());
}

}  // namespace
}  // namespace afemp::core
