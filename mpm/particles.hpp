// Material points as a structure of arrays (Ma 2005, §2.1: each point carries mass, volume,
// velocity, stress and history). Points of one material are kept contiguous so that the
// constitutive update runs per material batch.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
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

// The schema of the per-point state: for each array of Particles, its name and what it does
// when points are split (particle_splitting.cpp) or added from elsewhere (elements converted
// into particles, MpmSolver::add_particles), besides what every array does alike (reordering,
// filtering, growing, the checkpoint under its name, mpm_state.cpp). A new per-point field is
// one array and one line of Particles::for_each_field; the places above follow from it.
enum class SplitRule : std::uint8_t {
  copy,   // intensive: each piece takes the parent's value (velocity, stress, temperature, ...)
  share,  // extensive (a scalar): each piece takes its share (mass, volume)
  own,    // the splitter sets it (position, id, lengths, half width, CPDI domain)
};
enum class AddRule : std::uint8_t {
  carry,  // an added point takes its source's value, or the rest value where the source has none
  own,    // the solver sets it from the others (id, half width, lengths, CPDI domain)
};
struct ParticleField {
  const char* name;    // the checkpoint's item
  const char* output;  // its name in the field output (fields.h5), or nullptr if not written
  int slot;            // an optional field's bit in Particles::optional_fields; -1: always kept
  SplitRule split;
  AddRule add;
  double rest;  // a new point's value of a scalar field (vectors and tensors start at zero)
};

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
  // Optional (kept only when the run asks for them: optional_fields below):
  std::vector<double> half_width;  // not linear: half the particle's initial edge, in cells
  std::vector<core::Mat3> affine;  // APIC: the affine velocity C_p (a velocity gradient)
  // CPDI1: the domain's half edge vectors r_k (columns), corners x_p + sum +-r_k
  // (core/grid/cpdi.hpp).
  std::vector<core::Mat3> domain;
  // CPDI2: the domain's eight tracked corners, corner c = a + 2 b + 4 k at natural coordinates
  // (2a - 1, 2b - 1, 2k - 1).
  std::vector<std::array<Vec3, 8>> corners;
  // Total-Lagrangian MPM: each particle's reference position X_p, where its weights are taken,
  // and its deformation gradient F_p = dx/dX, which maps their gradients to the current
  // configuration (mpm/stencil.hpp, ReferenceStencil).
  std::vector<Vec3> reference_position;
  std::vector<core::Mat3> deformation_gradient;
  // [[loads]] on particles: 1 + the index of the scene's load the particle shares, 0 for none;
  // kept only when a load acts on particles (particle_loads.cpp).
  std::vector<std::int32_t> load;
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
  // The optional fields this run keeps (bit ParticleField::slot). Once kept, an optional array
  // holds a value for every point, those made later included, even while there are none (a
  // scene whose particles all come from converted elements starts with none).
  std::uint32_t optional_fields = 0;
  // Whether the points keep `field`.
  bool has(const ParticleField& field) const {
    return field.slot < 0 || ((optional_fields >> field.slot) & 1u) != 0;
  }
  // Keeps the optional array `member` from now on; fills it with `value` unless it already
  // holds one per point (given by the caller).
  template <class T>
  void keep(std::vector<T> Particles::*member, const T& value);
  // Calls f(field, array) for each per-point array in the schema's order
  // (for_each_particle_field), those this run does not keep included (empty); the history
  // store is not among them (its width is history_count).
  template <class F>
  void for_each_field(F&& f);
  template <class F>
  void for_each_field(F&& f) const;
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

// The schema: each per-point array of Particles (a pointer to the member) with its rules, in
// the order the checkpoint stores them.
template <class F>
void for_each_particle_field(F&& f) {
  using R = ParticleField;
  using S = SplitRule;
  using A = AddRule;
  f(R{"position", nullptr, -1, S::own, A::carry, 0.0}, &Particles::position);
  f(R{"velocity", "velocity", -1, S::copy, A::carry, 0.0}, &Particles::velocity);
  f(R{"mass", "mass", -1, S::share, A::carry, 0.0}, &Particles::mass);
  f(R{"volume", nullptr, -1, S::share, A::carry, 0.0}, &Particles::volume);
  f(R{"stress", "stress", -1, S::copy, A::carry, 0.0}, &Particles::stress);
  f(R{"strain", "strain", 0, S::copy, A::carry, 0.0}, &Particles::strain);
  f(R{"plastic_strain", "plastic_strain", -1, S::copy, A::carry, 0.0}, &Particles::plastic_strain);
  f(R{"temperature", "temperature", -1, S::copy, A::carry, 0.0}, &Particles::temperature);
  f(R{"energy", "internal_energy", -1, S::copy, A::carry, 0.0}, &Particles::energy);
  f(R{"damage", "damage", -1, S::copy, A::carry, 0.0}, &Particles::damage);
  f(R{"bulk_q", nullptr, -1, S::copy, A::carry, 0.0}, &Particles::bulk_q);
  f(R{"body", "body", -1, S::copy, A::carry, 0.0}, &Particles::body);
  f(R{"material", nullptr, -1, S::copy, A::carry, 0.0}, &Particles::material);
  f(R{"id", "id", -1, S::own, A::own, 0.0}, &Particles::id);
  f(R{"half_width", nullptr, 1, S::own, A::own, 0.0}, &Particles::half_width);
  f(R{"affine", nullptr, 2, S::copy, A::carry, 0.0}, &Particles::affine);
  f(R{"length", nullptr, 3, S::own, A::own, 0.0}, &Particles::length);
  f(R{"length0", nullptr, 4, S::copy, A::own, 0.0}, &Particles::length0);
  f(R{"plastic_heat", nullptr, 5, S::copy, A::carry, 0.0}, &Particles::plastic_heat);
  f(R{"viscous_heat", nullptr, 6, S::copy, A::carry, 0.0}, &Particles::viscous_heat);
  f(R{"light_time", nullptr, 7, S::copy, A::carry, 0.0}, &Particles::light_time);
  f(R{"burn", nullptr, 8, S::copy, A::carry, 1.0}, &Particles::burn);
  f(R{"domain", nullptr, 9, S::own, A::own, 0.0}, &Particles::domain);
  f(R{"corners", nullptr, 10, S::own, A::own, 0.0}, &Particles::corners);
  f(R{"reference_position", nullptr, 11, S::own, A::own, 0.0}, &Particles::reference_position);
  f(R{"deformation_gradient", nullptr, 12, S::copy, A::own, 0.0}, &Particles::deformation_gradient);
  f(R{"load", nullptr, 13, S::copy, A::carry, 0.0}, &Particles::load);
}

template <class T>
void Particles::keep(std::vector<T> Particles::*member, const T& value) {
  for_each_particle_field([&](const ParticleField& field, auto m) {
    if constexpr (std::is_same_v<decltype(m), std::vector<T> Particles::*>) {
      if (m != member || field.slot < 0) return;
      optional_fields |= 1u << field.slot;
      if ((this->*member).size() != size()) (this->*member).assign(size(), value);
    }
  });
}

template <class F>
void Particles::for_each_field(F&& f) {
  for_each_particle_field(
      [&](const ParticleField& field, auto member) { f(field, this->*member); });
}

template <class F>
void Particles::for_each_field(F&& f) const {
  for_each_particle_field(
      [&](const ParticleField& field, auto member) { f(field, this->*member); });
}

}  // namespace afemp::mpm
