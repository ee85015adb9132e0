// What the FE solver's generic stages ask of the hexahedra (hexahedron_set.hpp).
#include "fem/hexahedron_set.hpp"

#include <limits>

#include "core/materials/material.hpp"
#include "fem/hexahedron_one_point.hpp"

namespace afemp::fem {

std::span<const std::int32_t> HexahedronSet::connectivity() const {
  static_assert(sizeof(nodes[0]) == HexElements::corners * sizeof(std::int32_t),
                "an element's node indices are contiguous");
  return {nodes.empty() ? nullptr : nodes.front().data(), nodes.size() * HexElements::corners};
}

// The reference state's wave speed over the characteristic length; rigid bodies' elements
// carry no stress waves, so no step limit.
void HexahedronSet::initial_critical_steps(const core::Scene& scene,
                                           const std::vector<core::Vec3>& position) {
  for (const ElementBatch& b : batches) {
    const core::Material& mat = scene.materials[static_cast<std::size_t>(b.material)];
    for (std::size_t e = b.begin; e < b.end; ++e) {
      if (b.rigid) {
        critical_dt[e] = std::numeric_limits<double>::infinity();
        continue;
      }
      HexVectors x;
      for (std::size_t a = 0; a < 8; ++a) x[a] = position[static_cast<std::size_t>(nodes[e][a])];
      core::PointState st{{}, 0.0, 0.0, 0.0, mat.density};
      critical_dt[e] = characteristic_length(x, volume0[e]) / core::wave_speed(mat, st);
    }
  }
}

void HexahedronSet::eroded(std::span<const std::size_t> elements) {
  for (std::size_t e : elements) bulk_q[e] = 0.0;
}

std::size_t HexahedronSet::bytes() const {
  return ElementStore::bytes() + capacity_bytes(nodes) + capacity_bytes(bulk_q) +
         capacity_bytes(hourglass_force) + capacity_bytes(hourglass_power) +
         capacity_bytes(across) + capacity_bytes(shared_offsets) + capacity_bytes(shared_faces);
}

}  // namespace afemp::fem
