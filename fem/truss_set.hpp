// The trusses: their container (2-node bars, one point, uniaxial stress) and the element set
// over it (element_set.hpp). Their stage is truss_update.cpp; truss_set.cpp has what the
// generic stages ask of them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fem/element_set.hpp"

namespace afemp::fem {

// 2-node trusses (bars): one point, uniaxial stress.
struct TrussElements : ElementStore {
  static constexpr int corners = 2;
  std::vector<std::array<std::int32_t, 2>> nodes;
  std::vector<double> length0, area0;  // initial length and cross-section

  // The axial force of bar e in batch b at the node positions x (tension positive):
  // N = sigma A with the area from the volume the update keeps, A = V / l.
  double axial_force(const ElementBatch& b, std::size_t e, const std::vector<core::Vec3>& x) const {
    const double length = core::norm(x[static_cast<std::size_t>(nodes[e][1])] -
                                     x[static_cast<std::size_t>(nodes[e][0])]);
    return stress[b.point_begin + (e - b.begin)].xx * volume[e] / length;
  }
};

// The trusses as an element set; they have no faces: contact takes their live nodes as slaves.
class TrussSet final : public TrussElements, public ElementSet {
 public:
  const char* kind() const override { return "truss"; }
  int corners() const override { return TrussElements::corners; }
  ElementStore& store() override { return *this; }
  const ElementStore& store() const override { return *this; }
  std::span<const std::int32_t> connectivity() const override;
  // Length over the bar speed of the reference state.
  void initial_critical_steps(const core::Scene& scene,
                              const std::vector<core::Vec3>& position) override;
  FeStageKind stage() const override { return FeStageKind::trusses; }
  void update(FeSolver& fe, double dt) override;  // truss_update.cpp
  void eroded(std::span<const std::size_t>) override {}
  std::size_t bytes() const override;
  bool has_faces() const override { return false; }
  void boundary_faces(const std::vector<char>&, std::int32_t, SurfaceFaces&) const override {}
};

}  // namespace afemp::fem
