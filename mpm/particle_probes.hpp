// The probes a body of particles answers (core/probes.hpp): particle probes, resolved once to
// the particle's stable id, and the particles' part of the field extremes. Used by MpmModel and
// by the coupled model.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "afemp/probes.hpp"
#include "core/scene.hpp"
#include "mpm/particles.hpp"

namespace afemp::mpm {

class ParticleProbes {
 public:
  // Finds the particle of each particle probe among `p` (the particles at the start). Throws
  // core::InputError naming the probe's line and key when its index is beyond the body's
  // particles.
  void resolve(std::span<const core::ProbeSpec> probes, const Particles& p,
               const core::Scene& scene);
  // Particle probes and the particles' part of each extreme into out (probe_stride per probe).
  void sample(const Particles& p, std::span<double> out) const;
  // A run divided among ranks: every rank's samples (`all`, one out array per rank in rank order,
  // each filled by sample() on its rank's particles) merged into out: a particle probe's row from
  // the rank that holds the particle, each extreme over every rank's (ties to the lower rank).
  void merge_ranks(std::span<const double> all, std::span<double> out) const;

 private:
  std::vector<core::ProbeSpec> specs_;
  std::vector<std::int32_t> id_;           // particle probes: the particle's id
  mutable std::vector<std::size_t> slot_;  // where it sat at the last sample (reordering moves it)
};

}  // namespace afemp::mpm
