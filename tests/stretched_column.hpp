// The splitting tests' jet (tests/mpm/test_particle_splitting.cpp and tests/mpi/
// test_mpm_stage_ranks.cpp; header only, not a test file itself).
#pragma once

#include <string>

#include "mpm/particles.hpp"

namespace afemp::test {

// A nearly strengthless aluminium bar 1 x 1 x 10 mm (yield 5 MPa, free sides; cell 0.5 mm,
// 2 particles per cell per direction, uGIMP, 5 % PIC) stretched by its own inertia, like a
// jet: v_z = 1000 (z - 5) / 5 m/s, so its ends fly apart at 1000 m/s, until it spans 4x its
// length (about 18 us). rho v^2 = 2700 MPa dwarfs the yield, so the stretch stays close to
// uniform; plastic flow keeps the volume, so the section narrows to about half its width.
// Measured as well (not asserted): with pure FLIP 3 layers open even with splitting (the
// particles leave their lattice and the strain-tracked length lags their spacing), and with
// a yield of 50 MPa 5 open (the perfectly plastic bar necks and separates: fragments, which
// splitting must not fill).
inline std::string column(const std::string& splitting, const std::string& more_bodies = "") {
  return R"(
[run]
end_time = 1.0
[grid]
cell = 0.5
min = [-1, -1, -20]
max = [2, 2, 30]
[mpm]
shape_function = "gimp"
flip = 0.95
)" + splitting +
         R"(
[materials.aluminium]
density = 2.7e-3
E = 7.0e4
nu = 0.33
strength = { model = "j2", yield = 5 }
[[bodies]]
name = "column"
material = "aluminium"
shape = { box = { min = [0, 0, 0], max = [1, 1, 10] } }
)" + more_bodies;
}

// The column's particles (body 0) given the stretching velocity v_z = 200 (z - 5) m/s.
inline void stretch_column(mpm::Particles& p) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body[i] == 0) p.velocity[i] = {0.0, 0.0, 200.0 * (p.position[i].z - 5.0)};
}

}  // namespace afemp::test
