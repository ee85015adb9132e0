// The hexahedra: their container (8-node, one-point with hourglass control or 2 x 2 x 2 B-bar)
// and the element set over it (element_set.hpp). Their stage is hexahedron_update.cpp with the
// passes of hexahedron_passes.hpp; hexahedron_set.cpp has what the generic stages ask of them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fem/element_set.hpp"

namespace afemp::fem {

// 8-node hexahedra: one-point (hourglass-controlled) or 2 x 2 x 2 B-bar.
struct HexElements : ElementStore {
  static constexpr int corners = 8;
  std::vector<std::array<std::int32_t, 8>> nodes;
  std::vector<double> bulk_q;  // bulk-viscous pressure acting this step
  // The stiffness form's generalised hourglass forces (global axes), the viscous form's
  // a_h q of the last update (global axes), or the assumed strain form's generalised
  // stresses (the element's corotational frame).
  std::vector<std::array<core::Vec3, 4>> hourglass_force;
  // The viscous form: the power of the forces above at the velocities they were found from
  // (their work is booked once the next step has moved the nodes, hexahedron_update.cpp).
  std::vector<double> hourglass_power;
  // The mesh's face links (fem/surface_faces.cpp, link_faces; set once, as the node lists never
  // change): per element and face, the element across it (-1: none), or -2 - g when three or
  // more elements share the face (an invalid mesh), g a group of shared_faces (CSR, entries
  // 6 e + face). The boundary faces then follow from the live flags in one sweep.
  std::vector<std::array<std::int32_t, 6>> across;
  std::vector<std::int32_t> shared_offsets, shared_faces;
};

// The hexahedra as an element set. FeSolver lists them first: their force slots start at 0
// (hexahedron_passes.hpp writes corner a of element e at 8 e + a).
class HexahedronSet final : public HexElements, public ElementSet {
 public:
  const char* kind() const override { return "hexahedron"; }
  int corners() const override { return HexElements::corners; }
  ElementStore& store() override { return *this; }
  const ElementStore& store() const override { return *this; }
  std::span<const std::int32_t> connectivity() const override;
  // Characteristic length over the wave speed of the reference state.
  void initial_critical_steps(const core::Scene& scene,
                              const std::vector<core::Vec3>& position) override;
  FeStageKind stage() const override { return FeStageKind::hexahedra; }
  void update(FeSolver& fe, double dt) override;  // hexahedron_update.cpp
  // An eroded element's bulk-viscous pressure acts no more.
  void eroded(std::span<const std::size_t> elements) override;
  std::size_t bytes() const override;
  // Its boundary faces (surface_faces.cpp, one sweep of the live flags over the face links).
  bool has_faces() const override { return true; }
  void boundary_faces(const std::vector<char>& selected, std::int32_t set,
                      SurfaceFaces& faces) const override;
};

}  // namespace afemp::fem
