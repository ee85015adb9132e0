// Material points as a structure of arrays (Ma 2005, §2.1: each point carries mass, volume,
// velocity, stress and history). Points of one material are kept contiguous so that the
// constitutive update runs per material batch.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::mpm {

using core::Mat3;
using core::SymTensor;
using core::Vec3;

// The half width of a particle's domain, the half edge of the cube of its volume: where its
// boundary lies for contact at the surface (particle_wall_contact.cpp,
// coupling/particle_surface_contact.cpp).
inline double particle_half_width(double volume) {
  return 0.5 * std::cbrt(volume);
}

struct Particles {
  std::vector<Vec3> position;
  std::vector<Vec3> velocity;
  std::vector<double> mass;
  std::vector<double> volume;          // current volume; density = mass / volume
  std::vector<SymTensor> stress;       // Cauchy stress
  std::vector<SymTensor> strain;       // accumulated strain (sum of D dt); empty unless asked for
  std::vector<double> plastic_strain;  // equivalent plastic strain
  std::vector<double> temperature;
  std::vector<double> energy;  // specific internal energy (per unit mass)
  std::vector<double> damage;  // scalar damage D in [0, 1]
  std::vector<double> bulk_q;  // artificial bulk-viscous pressure acting this step
  std::vector<std::int32_t> body;
  std::vector<std::int32_t> material;
  std::vector<std::int32_t> id;  // stable id, unchanged by reordering
  // Empty unless the scene asks for them:
  std::vector<double> half_width;  // uGIMP: half the particle's initial edge, in cells
  std::vector<core::Mat3> affine;  // APIC: the affine velocity C_p (a velocity gradient)
  // Splitting: the particle's current length along x, y, z, and the length the particle it
  // came from started with (particle_splitting.cpp).
  std::vector<Vec3> length;
  std::vector<Vec3> length0;
  // The plastic work and bulk-viscous heat each particle has taken (per unit mass), kept only
  // where particles may leave through outflow faces (empty otherwise): a particle that leaves
  // takes its share out of the plastic and viscous totals, as its m e leaves the internal
  // energy, so the elastic column (internal - plastic - viscous) stays the particles' own.
  std::vector<double> plastic_heat, viscous_heat;
  // High explosives (programmed burn): the time each particle lights and its burn fraction;
  // kept only when some material is an explosive (empty otherwise; other particles hold 0
  // and 1, unread).
  std::vector<double> light_time, burn;
  // The strength models' history variables (a user model's, or a built-in model's own, such as
  // the largest compaction of HJC concrete; core::Material::history_count): history_count
  // values per point, point-major (point i's at history[i * history_count]); history_count is
  // the largest count of the scene's materials, 0 (and history empty) when none has any.
  std::vector<double> history;
  std::size_t history_count = 0;

  std::size_t size() const { return position.size(); }
  void resize(std::size_t n);
  void reserve(std::size_t n);
  // Appends one point at rest-state (zero stress, strain, plastic strain, energy, damage,
  // history).
  void push_back(const Vec3& x, const Vec3& v, double m, double vol, double temp,
                 std::int32_t body_id, std::int32_t material_id);
  // Reorders every array by perm: new[i] = old[perm[i]].
  void permute(const std::vector<std::int32_t>& perm);
  // Keeps the points `kept` (increasing indices) in their order and drops the others.
  void select(const std::vector<std::int32_t>& kept);
  // Bytes held by the arrays (capacity), for memory estimates.
  std::size_t bytes() const;
};

}  // namespace afemp::mpm
