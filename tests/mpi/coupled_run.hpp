// What the coupled divided runs' tests record of a run of coupling::CoupledModel after each
// step (header only; test_coupled_ranks.cpp, test_reproducible_ranks.cpp).
#pragma once

#include <vector>

#include "core/scene.hpp"
#include "coupling/coupled_model.hpp"

namespace afemp::test {

struct CoupledRun {
  std::vector<core::Energies> energies;        // after each step
  std::vector<std::vector<double>> forces;     // the history's force columns after each step
  std::vector<std::vector<core::Vec3>> nodes;  // the FE nodes after each step
  mpm::Particles particles;                    // this rank's at the end
};

// `steps` steps at the stable step, recorded into `r`; the particles at the end.
inline void advance(coupling::CoupledModel& model, CoupledRun& r, int steps) {
  for (int k = 0; k < steps; ++k) {
    model.step(model.stable_time_step());
    r.energies.push_back(model.energies());
    r.forces.emplace_back();
    model.force_values(r.forces.back());
    r.nodes.push_back(model.fe().nodes().position);
  }
  r.particles = model.mpm().particles();
}

}  // namespace afemp::test
