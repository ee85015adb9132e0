// How far outside a face of the grid a mesh node still counts as on it, in cells. Whether a node
// on the grid's wall face lies on it or 1e-20 below it is decided by the order of a sum (another
// thread or rank count), and what depends on it (an element's conversion into particles, a
// node's place on the grid) must not hang on that.
#pragma once

namespace afemp::core {

inline constexpr double kGridFaceMargin = 1e-9;

}  // namespace afemp::core
