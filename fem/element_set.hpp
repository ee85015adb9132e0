// One kind of element (hexahedra, trusses) behind the interface through which FeSolver's
// generic stages reach every kind: the force slots and node-to-slot incidence, the node masses,
// the critical and stable steps, energies, bytes, live counts, erosion, the update stage, and
// the surfaces that mesh contact and absorbing boundaries gather (boundary faces or, for a kind
// without faces, its elements' nodes). Each kind implements it in its own files and is its
// container (hexahedron_set.hpp, truss_set.hpp); FeSolver keeps the list. A stage makes one virtual
// call per set, never one per element or point: the loops run over the set's store or inside the
// kind's own code.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/scene.hpp"
#include "fem/element_store.hpp"
#include "fem/fe_step_plan.hpp"

namespace afemp::fem {

class FeSolver;

// Boundary faces of elements: 4 nodes each, in the order of their element's face, the element
// each bounds and its set (its index in FeSolver's list of sets).
struct SurfaceFaces {
  std::vector<std::array<std::int32_t, 4>> nodes;
  std::vector<std::int32_t> element;  // in its set
  std::vector<std::int32_t> set;
};

// The mean of the positions x of `nodes` (an element's centroid).
inline core::Vec3 mean_position(std::span<const std::int32_t> nodes,
                                const std::vector<core::Vec3>& x) {
  const double w = 1.0 / static_cast<double>(nodes.size());
  core::Vec3 mean;
  for (std::int32_t k : nodes) mean += w * x[static_cast<std::size_t>(k)];
  return mean;
}

class ElementSet {
 public:
  virtual ~ElementSet() = default;
  // The kind's name in erosion records and messages ("hexahedron", "truss").
  virtual const char* kind() const = 0;
  virtual int corners() const = 0;  // nodes per element
  virtual ElementStore& store() = 0;
  virtual const ElementStore& store() const = 0;
  // The node indices, corners() per element, element after element.
  virtual std::span<const std::int32_t> connectivity() const = 0;
  // The critical step of every element in its initial state (nodes at `position`); rigid
  // bodies' elements set none (+inf).
  virtual void initial_critical_steps(const core::Scene& scene,
                                      const std::vector<core::Vec3>& position) = 0;
  // The stage of the step plan that updates the set, and the update: the points' state, the
  // element forces into its force slots, the critical steps, erosion.
  virtual FeStageKind stage() const = 0;
  virtual void update(FeSolver& fe, double dt) = 0;
  // What the kind's own arrays do when these elements erode (their flags are already down).
  virtual void eroded(std::span<const std::size_t> elements) = 0;
  // Bytes held by its arrays (capacity).
  virtual std::size_t bytes() const = 0;
  // Surfaces (mesh contact, absorbing boundaries; gathered at set-up and after erosion, never
  // per step). A kind with faces appends the boundary faces of its live elements of the bodies
  // with selected[body] != 0 (faces no other such element shares), named as of set `set`, and
  // is a master in contact; a kind without faces appends none, and contact takes its live
  // elements' nodes as slaves.
  virtual bool has_faces() const = 0;
  virtual void boundary_faces(const std::vector<char>& selected, std::int32_t set,
                              SurfaceFaces& faces) const = 0;

  std::size_t live() const {
    const std::vector<std::uint8_t>& alive = store().alive;
    return static_cast<std::size_t>(std::count(alive.begin(), alive.end(), 1));
  }
  // The centroid of element e at node positions x (a face's outward side).
  core::Vec3 element_centroid(std::size_t e, const std::vector<core::Vec3>& x) const {
    const auto n = static_cast<std::size_t>(corners());
    return mean_position(connectivity().subspan(n * e, n), x);
  }
  // Its first slot in FeSolver's element forces: corner a of element e at
  // first_slot + corners() e + a (set with the incidence, FeSolver::build_incidence).
  std::size_t first_slot = 0;
};

}  // namespace afemp::fem
