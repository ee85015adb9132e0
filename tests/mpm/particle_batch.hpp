// Particles for the migration tests: every field a closed-form function of the point's id, and
// the optional fields an explosive with APIC keeps (affine, light time, burn) and two history
// values, so that a field left out of a pack shows.
#pragma once

#include <cstdint>

#include "mpm/particles.hpp"

namespace afemp::mpm::test {

inline Particles particle_batch(std::int32_t first_id, int count) {
  Particles p;
  p.history_count = 2;
  p.keep(&Particles::affine, core::Mat3{});
  p.keep(&Particles::light_time, 0.0);
  p.keep(&Particles::burn, 1.0);
  for (int k = 0; k < count; ++k) {
    const double id = first_id + k;
    p.push_back({id, 0.5 * id, -id}, {1.0 + id, 2.0, -0.25 * id}, 0.001 * (1.0 + id),
                0.1 / (1.0 + id), 293.0 + id, static_cast<std::int32_t>(first_id + k) % 3,
                static_cast<std::int32_t>(first_id + k) % 2);
    const std::size_t i = p.size() - 1;
    p.id[i] = first_id + k;
    p.stress[i] = core::SymTensor{id, -id, 2.0 * id, 0.1, 0.2, 0.3};
    p.plastic_strain[i] = 1e-3 * id;
    p.affine[i].m[0][1] = 3.0 * id;
    p.light_time[i] = 1e-4 * id;
    p.burn[i] = 1.0 / (2.0 + id);
    p.history[i * 2] = 7.0 * id;
    p.history[i * 2 + 1] = -id;
  }
  return p;
}

}  // namespace afemp::mpm::test
