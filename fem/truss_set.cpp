// What the FE solver's generic stages ask of the trusses (truss_set.hpp).
#include "fem/truss_set.hpp"

#include "core/materials/uniaxial_update.hpp"
#include "fem/truss.hpp"

namespace afemp::fem {

std::span<const std::int32_t> TrussSet::connectivity() const {
  static_assert(sizeof(nodes[0]) == TrussElements::corners * sizeof(std::int32_t),
                "an element's node indices are contiguous");
  return {nodes.empty() ? nullptr : nodes.front().data(), nodes.size() * TrussElements::corners};
}

// The bar speed of the reference state over the initial length.
void TrussSet::initial_critical_steps(const core::Scene& scene, const std::vector<core::Vec3>&) {
  for (const ElementBatch& b : batches) {
    const core::Material& mat = scene.materials[static_cast<std::size_t>(b.material)];
    core::PointState st{{}, 0.0, 0.0, 0.0, mat.density};
    const double modulus = core::uniaxial_modulus(mat, st);
    for (std::size_t e = b.begin; e < b.end; ++e)
      critical_dt[e] = truss_time_step(length0[e], modulus, mat.density);
  }
}

std::size_t TrussSet::bytes() const {
  return ElementStore::bytes() + capacity_bytes(nodes) + capacity_bytes(length0) +
         capacity_bytes(area0);
}

}  // namespace afemp::fem
