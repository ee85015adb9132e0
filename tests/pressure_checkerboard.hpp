// The pressure checkerboard V8 marks (VALIDATION.md: a cell's jump from its neighbours' mean
// below 5 % of the range), as V8's harnesses measure it on particles (tests/cooks_membrane.hpp,
// tests/mixed_beam.hpp, tests/twisting_column.hpp): the particles binned into cells of `cell` by
// their reference position along `axes`, less `origin`; each cell's mean pressure; the largest
// |p_c - mean of its face neighbours| over the range of the cells' means, among the cells
// `counted` accepts whose 2 D face neighbours all hold particles and are `whole`.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <utility>

#include "mpm/particles.hpp"

namespace afemp::test {

template <std::size_t D, class Counted, class Whole>
double pressure_checkerboard(const mpm::Particles& q, double cell, const std::array<int, D>& axes,
                             const core::Vec3& origin, Counted counted, Whole whole) {
  using Cell = std::array<int, D>;
  std::map<Cell, std::pair<double, int>> cells;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const core::Vec3 x0 = q.reference_position[i] - origin;
    Cell c;
    for (std::size_t a = 0; a < D; ++a) c[a] = static_cast<int>(std::floor(x0[axes[a]] / cell));
    auto& [sum, count] = cells[c];
    sum -= q.stress[i].trace() / 3.0;
    ++count;
  }
  double lo = 1e300, hi = -1e300, jump = 0.0;
  for (const auto& [c, v] : cells) {
    lo = std::min(lo, v.first / v.second);
    hi = std::max(hi, v.first / v.second);
  }
  for (const auto& [c, v] : cells) {
    if (!counted(c)) continue;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t a = 0; a < D; ++a)
      for (const int d : {-1, 1}) {
        Cell n = c;
        n[a] += d;
        const auto it = cells.find(n);
        if (it == cells.end() || !whole(n)) continue;
        sum += it->second.first / it->second.second;
        ++count;
      }
    if (count == 2 * D)
      jump = std::max(jump, std::abs(v.first / v.second - sum / static_cast<double>(count)));
  }
  return jump / (hi - lo);
}

}  // namespace afemp::test
