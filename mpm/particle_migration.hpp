// Particles moving between ranks: the points that leave one rank's blocks packed into bytes
// through the point-state schema (for_each_particle_field: every array the run keeps, then the
// strength models' history store), and appended to the receiving rank's particles unchanged, bit
// for bit. A new per-point field travels with no change here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "mpm/particles.hpp"

namespace afemp::mpm {

// The points `which` (indices into p), in that order.
std::vector<std::byte> pack_particles(const Particles& p, std::span<const std::int32_t> which);

// Appends the points of `bytes` to p. They must keep the same fields and history width as p
// (every rank of a run keeps the same); std::invalid_argument otherwise, p unchanged.
void unpack_particles(Particles& p, std::span<const std::byte> bytes);

}  // namespace afemp::mpm
