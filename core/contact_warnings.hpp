// Bodies that meet without a contact that covers them: on the background grid two bodies of
// particles share one velocity field and weld where they meet (no slip, no separation);
// meshes, and particles and meshes, pass through each other unless a [[contact]], a bond or a
// conversion couples them. `afemp check` and `afemp run` print these warnings before the run.
// During the run, OverlapCheck finds the pairs that have come to overlap.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "core/scene.hpp"

namespace afemp::core {

class StateArchive;

// One line per pair of bodies whose boxes (their points with their half sizes, at the start)
// overlap or come within one grid cell (meshes without a grid: touch) with nothing between
// them: no [[contact]] naming both (a weld included), no bond, no conversion, no
// overlap_allowed.
std::vector<std::string> contact_warnings(const Scene& scene, const Model& model);

// The run's check for bodies that come to overlap with nothing between them (as above), at
// each history row. Per such pair, once their boxes meet: the points of one (mesh nodes,
// particles) inside the other's hexahedra, deeper than its surface (Model::points_inside); and,
// for two bodies of particles of different materials, the particles of the first in cells next
// to the second's, with which they share grid nodes and weld. A pair is warned of on stderr the
// first time it overlaps, with the time and the count; summary() repeats it with the largest
// count and when. A run with no overlap pays one pass over the pairs' points per row.
class OverlapCheck {
 public:
  explicit OverlapCheck(const Scene& scene);
  // No pair to check: the time loop keeps no check.
  bool empty() const { return pairs_.empty(); }
  // A history row.
  void check(const Model& model);
  // One line per pair that overlapped, for RunSummary::warnings.
  std::vector<std::string> summary() const;
  // A checkpoint: what was seen so far.
  void state(StateArchive& a);

 private:
  struct Pair {
    std::size_t a = 0, b = 0;  // indices into Scene::bodies, a < b
    double first_time = -1.0, most_time = 0.0;
    std::size_t most_count = 0;
    std::string first_what, most_what;  // what overlapped, with the counts
  };
  // What to add to the pair's names: a contact, or overlap_allowed.
  std::string remedy(const Pair& p) const;

  const Scene& scene_;
  std::vector<Pair> pairs_;
};

}  // namespace afemp::core
