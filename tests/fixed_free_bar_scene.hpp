// A 1 x 1 x 50 mm steel bar of 50 hexahedra (nu = 0, so c = sqrt(E / rho) = 5047.5 m/s) held
// at z = 0 and moving at -10 m/s, run to 79.2 us with a history row every step: the probe and
// study-metric tests put their [[probes]] after it (header only; not a test file itself).
#pragma once

#include <string>

namespace afemp::test {

// `body_extra`: more keys of the bar's [[bodies]] table (an erosion criterion, ...).
inline std::string fixed_free_bar_scene(const std::string& body_extra = "") {
  return R"(
[run]
end_time = 0.0792
history_every = 1
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0
[[bodies]]
name = "bar"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [1, 1, 50] } }
mesh = { divisions = [1, 1, 50] }
velocity = [0, 0, -10]
)" + body_extra +
         R"(
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }
fixed = ["all"]
)";
}

}  // namespace afemp::test
