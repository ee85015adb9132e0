// What every element kind holds (ElementStore: per-element arrays, the integration points'
// state, the batches) and the schema of the integration points' arrays (for_each_point_field):
// each per-point array once, with its checkpoint name, output name, whether a scene may leave
// it empty and whether a particle made from the element takes it (coupling/element_conversion).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::fem {

// A contiguous range of elements of one body: one material, one formulation.
struct ElementBatch {
  int body = 0;
  int material = 0;
  std::size_t begin = 0, end = 0;  // elements
  std::size_t point_begin = 0;     // first integration point
  int points_per_element = 1;      // 1 (one-point hexahedron, truss) or 8 (B-bar)
  bool rigid = false;              // a rigid body's: no stress, no forces, no critical step
};

// When an optional per-point array is kept (empty otherwise): what in the scene needs it.
// FeSolver::setup_point_fields decides for each element kind which needs its scene has.
enum class PointNeed : std::uint8_t {
  always,
  // Elements may erode, or convert to particles that may leave the grid: their plastic and
  // viscous heat leave the totals with them (converted particles carry it).
  leaving,
  strain,     // some material's failure reads the strain tensor (principal-strain failure)
  explosive,  // some body is a high explosive (programmed burn)
};

// One per-point array of the schema.
struct PointField {
  const char* name;    // the checkpoint's item
  const char* output;  // the element mean's name in the field output (hexahedra), or nullptr
  PointNeed need;
  // A particle made from the element (coupling/element_conversion.cpp) takes the point's value
  // (or the points' mass-weighted mean) into its array of the same name (history: its store).
  bool convert;
  double rest;  // a new point's value of a scalar field (tensors start at zero)
};

// A new point's value in an array of T under `field`.
template <class T>
T rest_value(const PointField& field) {
  if constexpr (std::is_same_v<T, double>)
    return field.rest;
  else
    return T{};
}

// Bytes an array holds (its capacity).
template <class V>
std::size_t capacity_bytes(const V& x) {
  return x.capacity() * sizeof(x[0]);
}

// What every element kind holds: per element arrays, the integration points' state, and the
// batches. Each kind adds its connectivity and its own fields (HexElements, TrussElements).
struct ElementStore {
  std::vector<double> mass, volume0, volume;  // volume: current (trusses: A L)
  std::vector<double> critical_dt;            // element critical step of the last update
  std::vector<std::uint8_t> alive;
  // Integration points (trusses: the axial stress in the bar frame, sigma_xx).
  std::vector<core::SymTensor> stress;
  std::vector<double> point_mass, plastic_strain, temperature, energy, density;
  std::vector<double> damage;  // D in [0, 1]
  // The strain tensor (sum of D dt) of every point, kept only when some material's failure
  // reads it (principal-strain failure); empty otherwise.
  std::vector<core::SymTensor> strain;
  // The plastic work and the bulk-viscous heat each point has taken (per unit mass), kept only
  // where elements may erode (empty otherwise): an eroded element takes its share out of the
  // plastic and viscous totals, which then hold the live material's (the elastic column,
  // internal - plastic - viscous, stays the live elements' strain energy).
  std::vector<double> plastic_heat, viscous_heat;
  // High explosives (core/detonation_paths.hpp), per point, kept only when some body is one
  // (empty otherwise): the time the point lights, its burn fraction and the length it burns
  // over.
  std::vector<double> light_time, burn, burn_length;
  // The strength models' history variables (a user model's, or a built-in model's own;
  // core::Material::history_count): history_count per integration point, point-major;
  // history_count is the scene's (core::history_count).
  std::vector<double> history;
  std::size_t history_count = 0;
  std::vector<ElementBatch> batches;
  std::size_t size() const { return alive.size(); }
  bool empty() const { return alive.empty(); }
  std::size_t points() const { return point_mass.size(); }
  // Bytes held by these arrays (capacity).
  std::size_t bytes() const;
};

// The schema: calls f(field, array, width) for each per-point array of `el`, in the order the
// checkpoint stores them; width values per point (history: history_count, the others 1). An
// optional array the scene does not need is included (empty). The arrays every point keeps
// come first. A new per-point field is its array in ElementStore and its line here.
template <class Store, class F>
void for_each_point_field(Store& el, F&& f) {
  using N = PointNeed;
  f(PointField{"stress", "stress", N::always, true, 0.0}, el.stress, 1);
  f(PointField{"point_mass", nullptr, N::always, false, 0.0}, el.point_mass, 1);
  f(PointField{"plastic_strain", "plastic_strain", N::always, true, 0.0}, el.plastic_strain, 1);
  f(PointField{"temperature", "temperature", N::always, true, 0.0}, el.temperature, 1);
  f(PointField{"energy", nullptr, N::always, true, 0.0}, el.energy, 1);
  f(PointField{"density", nullptr, N::always, false, 0.0}, el.density, 1);
  f(PointField{"damage", "damage", N::always, true, 0.0}, el.damage, 1);
  f(PointField{"strain", nullptr, N::strain, true, 0.0}, el.strain, 1);
  f(PointField{"plastic_heat", nullptr, N::leaving, true, 0.0}, el.plastic_heat, 1);
  f(PointField{"viscous_heat", nullptr, N::leaving, true, 0.0}, el.viscous_heat, 1);
  f(PointField{"light_time", nullptr, N::explosive, false, 0.0}, el.light_time, 1);
  f(PointField{"burn", nullptr, N::explosive, false, 1.0}, el.burn, 1);
  f(PointField{"burn_length", nullptr, N::explosive, false, 0.0}, el.burn_length, 1);
  // Its variables are written one field each, under their names (core::history_field_names).
  f(PointField{"history", nullptr, N::always, true, 0.0}, el.history, el.history_count);
}

// The batch holding element e (the batches cover every element).
const ElementBatch& batch_of(const ElementStore& elements, std::size_t e);

}  // namespace afemp::fem
