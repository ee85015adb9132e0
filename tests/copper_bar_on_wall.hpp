// A quarter of a copper bar (Johnson-Cook, the Taylor bar's OFHC copper) at 200 m/s onto a wall
// at z = 0, symmetric faces at x = 0 and y = 0, cells of 1 mm and 2 particles per direction:
// about 2,300 particles that cross the grid's blocks within 100 steps, the divided-run tests'
// scene (header only; not a test file itself). Also a bar of hexahedra that erodes at a wall.
#pragma once

#include <string>

#include "core/material_fixtures.hpp"

namespace afemp::test {

// `run`: the [run] table's lines (end_time at least); `mpm`: the [mpm] table's.
inline std::string copper_bar_on_wall(const std::string& run, const std::string& mpm) {
  return "[run]\n" + run + R"(
[materials.copper]
density = 8.93e-3
E = 117e3
nu = 0.35
strength = { model = "johnson-cook", A = 157, B = 425, n = 1.0, C = 0.0 }
[grid]
cell = 1.0
min = [0, 0, 0]
max = [10, 10, 28]
boundary = { xmin = "symmetric", ymin = "symmetric", zmin = "wall" }
[mpm]
)" + mpm +
         R"(
[[bodies]]
name = "bar"
material = "copper"
shape = { cylinder = { base = [0, 0, 0], axis = [0, 0, 1], radius = 3.8, length = 25.4 } }
velocity = [0, 0, -200]
particles_per_cell = 2
)";
}

// A copper bar of one-point hexahedra (a quarter, 0.5 mm elements) onto a rigid wall at 400 m/s
// with Johnson-Cook, Mie-Grueneisen, gravity and erosion at a plastic strain of 0.5: every stage
// of the FE step; its foot erodes within 100 steps.
inline std::string eroding_copper_bar_of_hexahedra() {
  return std::string("[run]\n") + core::fixtures::kDeterminismCopperToml + R"(
[[bodies]]
name = "bar"
discretisation = "hexahedra"
material = "copper"
shape = { cylinder = { base = [0, 0, 0.01], radius = 4, length = 20 } }
mesh = { size = 0.5, sectors = 1 }
velocity = [0, 0, -400]
erosion = { plastic_strain = 0.5 }
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

// Two bodies onto a wall: a block of fully integrated (8-point) hexahedra of steel at 300 m/s
// that yields and erodes, and a rod of 160 trusses (three runs of 64, dealt round the ranks).
// `run`: lines added to the [run] table (end_time = 1.0 given).
inline std::string block_and_rod_on_wall(const std::string& run = "") {
  return "[run]\nend_time = 1.0\n" + run + R"([materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
strength = { model = "johnson-cook", A = 350, B = 275, n = 0.36 }
[[bodies]]
name = "block"
discretisation = "hexahedra"
material = "steel"
element = "full"
shape = { box = { min = [0, 0, 0.05], max = [4, 4, 6] } }
mesh = { size = 0.5 }
velocity = [0, 0, -300]
erosion = { plastic_strain = 0.2 }
[[bodies]]
name = "rod"
discretisation = "trusses"
material = "steel"
shape = { line = { from = [6, 0, 0.05], to = [6, 0, 16] } }
mesh = { size = 0.1 }
area = 0.1
velocity = [0, 0, -300]
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
)";
}

}  // namespace afemp::test
