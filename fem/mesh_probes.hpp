// The probes a mesh answers (core/probes.hpp): node and element probes, resolved once to the
// node or element index, and the live elements' part of the field extremes (at each
// centroid, with the point-averaged stress and the mean nodal velocity, as the field output
// averages them); and a body's points for the Taylor, crater and hole metrics. Used by FeModel
// and by the coupled model.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "afemp/probes.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {

class MeshProbes {
 public:
  // Finds the node or element of each node and element probe (by index within its body, or
  // nearest to a point at the start). Throws core::InputError naming the probe's line and key,
  // and the body's range, when the index is beyond the body's nodes or elements.
  void resolve(std::span<const core::ProbeSpec> probes, const FeSolver& fe,
               const core::Scene& scene);
  // Node and element probes and the elements' part of each extreme into out (probe_stride per
  // probe). An element that is gone (eroded, converted) leaves its NaN.
  void sample(const FeSolver& fe, std::span<double> out) const;
  // Whether a probe reads the elements' state (an element probe, or an extreme).
  bool reads_elements() const;

 private:
  std::vector<core::ProbeSpec> specs_;
  std::vector<std::size_t> target_;  // the node, or the element within its kind
};

// The positions of the nodes of body `body`'s live elements.
std::vector<core::Vec3> live_node_positions(const FeSolver& fe, int body);

}  // namespace afemp::fem
