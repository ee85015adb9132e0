// A steel striker at 600 m/s onto an aluminium plate of particles (12 x 12 x 4 mm, 2 particles
// per cell direction on 1 mm cells: 4,608), 0.2 mm above it, quarter model (symmetric faces
// x = 0 and y = 0): the divided runs' scene for grid contact and the couplings (header only; not
// a test file itself). Units: mm, ms, g, N, MPa.
#pragma once

#include <string>

namespace afemp::test {

// `meshes` false: the striker of particles, in grid contact with the plate with friction 0.2.
// True: the striker of one-point hexahedra (1 mm) in grid contact (CFEMP), and a rod of 12
// trusses across the plate bonded into it (HFEMP). `end`: the [run] table's lines.
inline std::string striker_on_plate(bool meshes, const std::string& end = "end_time = 1.0\n") {
  std::string text = "[run]\n" + end + R"(
[grid]
cell = 1.0
min = [0, 0, -8]
max = [16, 16, 14]
boundary = { xmin = "symmetric", ymin = "symmetric" }
[mpm]
scheme = "MUSL"
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.29
strength = { model = "johnson-cook", A = 792, B = 510, n = 0.26, C = 0.0 }
[materials.aluminium]
density = 2.70e-3
E = 69e3
nu = 0.33
strength = { model = "johnson-cook", A = 324, B = 114, n = 0.42, C = 0.0 }
[[bodies]]
name = "plate"
material = "aluminium"
shape = { box = { min = [0, 0, 0], max = [12, 12, 4] } }
[[bodies]]
name = "striker"
material = "steel"
shape = { cylinder = { base = [0, 0, 4.2], axis = [0, 0, 1], radius = 3, length = 8 } }
velocity = [0, 0, -600]
)";
  if (!meshes)
    return text + R"(
[[contact]]
bodies = ["striker", "plate"]
friction = 0.2
)";
  return text + R"(discretisation = "hexahedra"
mesh = { size = 1.0, sectors = 1 }
[[bodies]]
name = "rod"
discretisation = "trusses"
material = "steel"
shape = { line = { from = [0.5, 2.5, 2.0], to = [12.5, 2.5, 2.0] } }
mesh = { size = 1.0 }
area = 0.2
bonded_to = "plate"
[[contact]]
bodies = ["striker", "plate"]
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }
body = "striker"
fixed = ["x"]
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 1, 0] } }
body = "striker"
fixed = ["y"]
)";
}

}  // namespace afemp::test
