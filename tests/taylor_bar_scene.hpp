// The Taylor bar of examples/taylor_bar (OFHC copper at 190 m/s, Ma 2005 section 2.3.2) as scene
// text, coarse and short so that a comparison runs in a second: particles on a grid with
// symmetry and wall faces, or a quarter of hexahedra with symmetry constraints and a rigid wall
// (header only; not a test file itself).
#pragma once

#include <string>

namespace afemp::test {

inline constexpr const char* taylor_johnson_cook =
    R"(strength = { model = "johnson-cook", A = 157, B = 425, n = 1.0, C = 0.0 })";

// The bar with the given `strength = ...` line, of particles or of hexahedra of `element`
// ("one-point" or "full").
inline std::string taylor_bar_scene(bool hexahedra,
                                    const std::string& strength = taylor_johnson_cook,
                                    const std::string& element = "one-point") {
  const std::string bar = R"(
[run]
end_time = 0.01
[materials.copper]
density = 8.93e-3
E = 117e3
nu = 0.35
)" + strength + R"(
[[bodies]]
name = "bar"
material = "copper"
shape = { cylinder = { base = [0, 0, 0], axis = [0, 0, 1], radius = 3.8, length = 25.4 } }
velocity = [0, 0, -190]
)";
  if (!hexahedra)
    return bar + R"(particles_per_cell = 2
[grid]
cell = 1.0
min = [0, 0, 0]
max = [10, 10, 26]
boundary = { xmin = "symmetric", ymin = "symmetric", zmin = "wall" }
)";
  return bar + "discretisation = \"hexahedra\"\nelement = \"" + element + R"("
mesh = { size = 1.0, sectors = 1 }
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }
fixed = ["x"]
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 1, 0] } }
fixed = ["y"]
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
)";
}

}  // namespace afemp::test
