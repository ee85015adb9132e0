// A column of elastic copper hexahedra in uniaxial strain, its top face driven by a velocity
// history: the plane-wave scene of the spall and absorbing-boundary tests (header only; not a
// test file itself). Units mm, ms, g, N, MPa.
#pragma once

#include <cstdio>
#include <string>

namespace afemp::test {

// Copper (rho 8.93e-3, E 1.24e5, nu 0.34: c_L = 4623 m/s) plus `failure` (a `failure = ...`
// line or ""), a box [0, width]^2 x [z_min, z_max] of divisions [n_across, n_across, n_along],
// every node held in x and y, the face z = z_max moving along -z at `speed` times the factor of
// `curve` (a TOML array of [time, factor] pairs).
inline std::string driven_copper_column(const std::string& failure, double width, double z_min,
                                        double z_max, int n_across, int n_along, double speed,
                                        const std::string& curve) {
  char geometry[512];
  std::snprintf(geometry, sizeof geometry,
                "shape = { box = { min = [0, 0, %.17g], max = [%.17g, %.17g, %.17g] } }\n"
                "mesh = { divisions = [%d, %d, %d] }\n"
                "[[constraints]]\n"
                "nodes = { box = { min = [-1, -1, %.17g], max = [%.17g, %.17g, %.17g] } }\n"
                "fixed = [\"x\", \"y\"]\n"
                "[[constraints]]\n"
                "nodes = { plane = { point = [0, 0, %.17g], normal = [0, 0, 1] } }\n"
                "velocity = [0, 0, %.17g]\n",
                z_min, width, width, z_max, n_across, n_across, n_along, z_min - 1.0, width + 1.0,
                width + 1.0, z_max + 1.0, z_max, -speed);
  return "[run]\nend_time = 1.0\n[materials.copper]\ndensity = 8.93e-3\nE = 1.24e5\nnu = 0.34\n" +
         failure +
         "\n[[bodies]]\nname = \"column\"\ndiscretisation = \"hexahedra\"\n"
         "material = \"copper\"\n" +
         geometry + "components = [\"z\"]\ncurve = " + curve + "\n";
}

}  // namespace afemp::test
