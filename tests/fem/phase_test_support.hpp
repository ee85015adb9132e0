// The steel column the phase tests share (header only; not a test file itself): 10 x 10 x 100 mm
// of 2 x 2 x 20 hexahedra, its base held, under g = 100 mm/ms^2 along -z, with what its closed
// forms need and the measures the tests read.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>

#include "afemp/simulation.hpp"

namespace afemp::test {

constexpr double kColumnDensity = 7.85e-3, kColumnModulus = 2.0e5, kColumnGravity = 100.0,
                 kColumnHeight = 100.0, kColumnArea = 100.0;

// The column's scene: `element` the body's element (and hourglass) lines, `run_extra` more
// [run] keys, `phases` the [[phases]] text; the end time written to round-trip exactly.
inline std::string column_scene(const std::string& element, const std::string& phases,
                                double end_time, const std::string& run_extra = "") {
  char head[96];
  std::snprintf(head, sizeof head, "[run]\nend_time = %.17g\ngravity = [0, 0, -100]\n", end_time);
  return head + run_extra +
         "history_every = 1\n"
         "[materials.steel]\ndensity = 7.85e-3\nE = 2.0e5\nnu = 0.3\n"
         "[[bodies]]\nname = \"column\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n" +
         element +
         "\nshape = { box = { min = [0, 0, 0], max = [10, 10, 100] } }\n"
         "mesh = { divisions = [2, 2, 20] }\n"
         "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
         "fixed = [\"x\", \"y\", \"z\"]\n" +
         phases;
}

// Mean z displacement of the nodes at the top (z = H): the highest ones, since the column's
// nodes start on a 5 x 5 x 21 lattice and move less than 1 mm.
inline double top_displacement(Simulation& sim) {
  const NodeFields n = sim.nodes();
  double sum = 0.0, highest = -1e300;
  int count = 0;
  for (std::size_t i = 0; i < n.size(); ++i) highest = std::max(highest, n.position[i].z);
  for (std::size_t i = 0; i < n.size(); ++i)
    if (n.position[i].z > highest - 1.0) sum += n.position[i].z - kColumnHeight, ++count;
  return sum / count;
}

// The mean axial stress of the trusses whose middle lies between z0 and z1 (a tendon's middle,
// away from the anchored ends that pass its force to the concrete over an element or two).
inline double mean_truss_stress(Simulation& sim, double z0, double z1) {
  const ElementFields t = sim.trusses();
  const NodeFields n = sim.nodes();
  double sum = 0.0;
  int count = 0;
  for (std::size_t e = 0; e < t.size(); ++e) {
    const double z = 0.5 * (n.position[static_cast<std::size_t>(t.connectivity[2 * e])].z +
                            n.position[static_cast<std::size_t>(t.connectivity[2 * e + 1])].z);
    if (z > z0 && z < z1) sum += t.stress[t.first_point[e]].xx, ++count;
  }
  return sum / count;
}

inline double max_speed(Simulation& sim) {
  const NodeFields n = sim.nodes();
  double v = 0.0;
  for (std::size_t i = 0; i < n.size(); ++i) v = std::max(v, norm(n.velocity[i]));
  return v;
}

}  // namespace afemp::test
