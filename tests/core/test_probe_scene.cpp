// [[probes]] in a scene (core/scene_parser.cpp): what each kind reads into core::ProbeSpec, and
// every mistake names the file, the line, the key and what is allowed.
#include <gtest/gtest.h>

#include <string>

#include "core/scene.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

using test::error_of;
using test::line_of;

const std::string head = R"(
[run]
end_time = 0.01
[grid]
cell = 1.0
min = [0, 0, 0]
max = [10, 10, 10]
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
[[bodies]]
name = "cube"
material = "steel"
shape = { box = { min = [1, 1, 1], max = [3, 3, 3] } }
[[bodies]]
name = "brick"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [5, 5, 5], max = [7, 7, 7] } }
mesh = { divisions = [2, 2, 2] }
)";

TEST(ProbeScene, EachKindReadsWhatItNames) {
  const Scene s = parse_scene(head + R"(
[[probes]]
name = "p"
particle = { body = "cube", index = 3 }
[[probes]]
name = "n"
node = { body = "brick", near = [7, 7, 7] }
interval = 0.001
[[probes]]
name = "e"
element = { body = "brick", index = 0 }
[[probes]]
name = "v"
mean_velocity = "brick"
[[probes]]
name = "x-1"
extreme = { field = "von_mises", of = "min", box = { min = [0, 0, 0], max = [4, 4, 4] }, body = "cube" }
)",
                              "scene.toml");
  ASSERT_EQ(s.probes.size(), 5u);
  EXPECT_EQ(s.probes[0].kind, ProbeKind::particle);
  EXPECT_EQ(s.probes[0].body, 0);
  EXPECT_EQ(s.probes[0].index, 3);
  EXPECT_EQ(s.probes[0].interval, 0.0);
  EXPECT_EQ(s.probes[1].kind, ProbeKind::node);
  EXPECT_EQ(s.probes[1].body, 1);
  EXPECT_EQ(s.probes[1].index, -1);
  EXPECT_EQ(s.probes[1].near.z, 7.0);
  EXPECT_EQ(s.probes[1].interval, 0.001);
  EXPECT_EQ(s.probes[2].kind, ProbeKind::element);
  EXPECT_EQ(s.probes[3].kind, ProbeKind::mean_velocity);
  EXPECT_EQ(s.probes[3].body, 1);
  EXPECT_EQ(s.probes[4].kind, ProbeKind::extreme);
  EXPECT_EQ(s.probes[4].field, ProbeField::von_mises);
  EXPECT_FALSE(s.probes[4].maximum);
  EXPECT_EQ(s.probes[4].body, 0);
  EXPECT_EQ(s.probes[4].box_max.x, 4.0);
  EXPECT_EQ(s.probes[4].key, "probes[4]");
  EXPECT_EQ(probe_columns(ProbeKind::extreme), (std::vector<std::string>{"value", "x", "y", "z"}));
}

// The error of `head` plus one probe table `probe` ("[[probes]]\n..."), and the line of `at`.
std::string probe_error(const std::string& probe) {
  return error_of(head + probe);
}
std::string at(const std::string& probe, const std::string& needle) {
  return "scene.toml:" + std::to_string(line_of(head + probe, needle)) + ": ";
}

TEST(ProbeScene, MistakesNameTheFileLineKeyAndWhatIsAllowed) {
  std::string p = "[[probes]]\nname = \"a\"\nnode = { body = \"cube\", index = 0 }\n";
  EXPECT_EQ(probe_error(p), at(p, "node =") +
                                "key 'probes[0].node.body': body \"cube\" is made of "
                                "particles; this applies to mesh bodies");
  p = "[[probes]]\nname = \"a\"\nparticle = { body = \"brick\", index = 0 }\n";
  EXPECT_NE(
      probe_error(p).find(at(p, "particle =") + "key 'probes[0].particle.body': body \"brick\" "
                                                "is a mesh"),
      std::string::npos);
  p = "[[probes]]\nname = \"a\"\nmean_velocity = \"rod\"\n";
  EXPECT_EQ(probe_error(p), at(p, "mean_velocity") +
                                "key 'probes[0].mean_velocity': unknown body "
                                "\"rod\"; bodies: \"cube\", \"brick\"");
  p = "[[probes]]\nname = \"a\"\nmean_velocity = \"cube\"\nnode = { body = \"brick\", index = 0 "
      "}\n";
  EXPECT_EQ(
      probe_error(p).find(at(p, "[[probes]]") + "key 'probes[0]': give exactly one of particle"),
      0u);
  p = "[[probes]]\nname = \"a b\"\nmean_velocity = \"cube\"\n";
  EXPECT_NE(probe_error(p).find(at(p, "name = \"a b\"") + "key 'probes[0].name': a probe name"),
            std::string::npos);
  p = "[[probes]]\nname = \"a\"\nmean_velocity = \"cube\"\n[[probes]]\nname = \"a\"\nmean_velocity "
      "= \"cube\"\n";
  EXPECT_NE(probe_error(p).find(
                "key 'probes[1].name': duplicate probe name \"a\" (first defined at line " +
                std::to_string(line_of(head + p, "[[probes]]")) + ")"),
            std::string::npos);
  p = "[[probes]]\nname = \"a\"\nelement = { body = \"brick\", index = 0, near = [0, 0, 0] }\n";
  EXPECT_NE(probe_error(p).find("key 'probes[0].element.index': give either index = I"),
            std::string::npos);
  p = "[[probes]]\nname = \"a\"\nelement = { body = \"brick\", index = -1 }\n";
  EXPECT_NE(probe_error(p).find("key 'probes[0].element.index'"), std::string::npos);
  p = "[[probes]]\nname = \"a\"\nextreme = { field = \"temperature\", box = { min = [0, 0, 0], max "
      "= [1, 1, 1] } }\n";
  EXPECT_NE(
      probe_error(p).find("key 'probes[0].extreme.field': unknown value \"temperature\"; allowed "
                          "values: \"pressure\", \"von_mises\", \"plastic_strain\", \"speed\", "
                          "\"vx\", \"vy\", \"vz\""),
      std::string::npos);
  p = "[[probes]]\nname = \"a\"\nextreme = { field = \"vx\", box = { min = [0, 0, 2], max = [1, 1, "
      "1] } }\n";
  EXPECT_NE(probe_error(p).find("key 'probes[0].extreme.box.max': max must not be below min"),
            std::string::npos);
  p = "[[probes]]\nname = \"a\"\nmean_velocity = \"cube\"\ninterval = 0\n";
  EXPECT_NE(probe_error(p).find(at(p, "interval") + "key 'probes[0].interval'"), std::string::npos);
  p = "[[probes]]\nname = \"a\"\nmean_velocity = \"cube\"\nevery = 2\n";
  EXPECT_NE(probe_error(p).find(at(p, "every") + "key 'probes[0].every': unknown key"),
            std::string::npos);
  p = "[probes]\nname = \"a\"\n";
  EXPECT_NE(probe_error(p).find("key 'probes': expected an array of tables ([[probes]])"),
            std::string::npos);
}

}  // namespace
}  // namespace afemp::core
