// Probes ([[probes]] in a scene, docs/scene-format.md): the history of one particle, mesh node
// or element, of a body's mean velocity, or of the extreme of a field over the points inside a
// box. The scene names what each probe watches; the model resolves it once at the start
// (Model::resolve_probes: index lookups) and fills probe_stride values per probe whenever the
// time loop samples (Model::sample_probes), so that sampling costs a few loads per probe and
// one pass over the points for a field extreme.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

/// What a probe watches, and the columns it records.
enum class ProbeKind {
  particle,       ///< x, y, z, vx, vy, vz, pressure, von_mises, plastic_strain
  node,           ///< x, y, z, vx, vy, vz
  element,        ///< centroid, mean nodal velocity, and the point-averaged stress measures
  mean_velocity,  ///< vx, vy, vz: the body's momentum / mass
  extreme,        ///< value, x, y, z: the largest (or smallest) field value in a box, and where
  /// The interface force of a penalty contact or a wall (fx, fy, fz, normal, tangential) or a
  /// rigid body (fx, fy, fz, mx, my, mz, and rfx .. rmz of a body with fixed components): the
  /// model's history columns NAME.*.
  force,
};

/// Fields an extreme probe reads at each point (particles; element centroids with their
/// point-averaged stress and mean nodal velocity); x, y, z: the point's position (the
/// furthest point along an axis: a jet's tip).
enum class ProbeField { pressure, von_mises, plastic_strain, speed, vx, vy, vz, x, y, z };

/// The scene file's name of a probe kind or field.
const char* to_string(ProbeKind k);
const char* to_string(ProbeField f);

/// One [[probes]] entry of a scene.
struct ProbeSpec {
  std::string name{};  ///< unique in the scene; the file probes/NAME.csv
  ProbeKind kind = ProbeKind::particle;
  int body = -1;  ///< the body watched; extreme: -1 for every body
  /// particle, node, element: the 0-based index within the body (particles in the order they
  /// were made, nodes and elements in mesh order), or -1 and `near`: the one nearest to it at
  /// the start (element: by centroid).
  long index = -1;
  Vec3 near{};
  ProbeField field = ProbeField::pressure;  ///< extreme
  std::string target{};                     ///< force: the contact's, wall's or body's name
  bool maximum = true;                      ///< extreme: max, or min
  Vec3 box_min{}, box_max{};                ///< extreme
  double interval = 0.0;   ///< > 0: simulated time between samples; 0: every history row
  SourceLocation where{};  ///< the [[probes]] table
  std::string key{};       ///< "probes[k]", for messages
};

/// Values per probe in the buffer Model::sample_probes fills (the longest column list).
inline constexpr std::size_t probe_stride = 9;

/// The columns after "time" of a probe of kind k (at most probe_stride).
std::vector<std::string> probe_columns(ProbeKind k);

/// A probe's recorded history: one row per sample.
struct ProbeSeries {
  std::string name{};
  ProbeKind kind = ProbeKind::particle;
  std::vector<std::string> columns{};  ///< probe_columns(kind)
  std::vector<double> time{};
  std::vector<double>
      values{};  ///< row-major: columns.size() values per row; NaN: the entity is gone
  std::size_t rows() const { return time.size(); }
  double at(std::size_t row, std::size_t column) const {
    return values[row * columns.size() + column];
  }
  /// The index of a column, or -1.
  int column(const std::string& name) const;
  /// One column over the rows.
  std::vector<double> series(std::size_t column) const;
};

/// Folds a candidate (value at x) of an extreme probe into out[0..3] (value, x, y, z): it
/// replaces what is there when out[0] is NaN or the candidate is more extreme.
inline void merge_extreme(const ProbeSpec& p, double value, const Vec3& x, double* out) {
  if (!std::isnan(out[0]) && (p.maximum ? !(value > out[0]) : !(value < out[0]))) return;
  out[0] = value;
  out[1] = x.x;
  out[2] = x.y;
  out[3] = x.z;
}

/// Whether x lies in the box of an extreme probe (faces included).
inline bool in_probe_box(const ProbeSpec& p, const Vec3& x) {
  return x.x >= p.box_min.x && x.x <= p.box_max.x && x.y >= p.box_min.y && x.y <= p.box_max.y &&
         x.z >= p.box_min.z && x.z <= p.box_max.z;
}

/// The field an extreme probe reads, at a point at `position` with stress s, plastic strain ep,
/// velocity v.
double probe_field_value(ProbeField f, const SymTensor& s, double plastic_strain, const Vec3& v,
                         const Vec3& position);

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::ProbeField;
using core::ProbeKind;
using core::ProbeSeries;
using core::ProbeSpec;
}  // namespace afemp
