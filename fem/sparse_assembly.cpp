// The sparsity pattern from the node-element incidence and the scatter of element matrices
// (fem/sparse_assembly.hpp).
#include "fem/sparse_assembly.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace afemp::fem {

SparseAssembly::SparseAssembly(std::span<const Hexahedron> hexahedra, std::span<const Line> lines,
                               std::vector<int> equation, int equations,
                               std::span<const std::vector<std::int32_t>> coupled)
    : equation_(std::move(equation)) {
  const std::size_t nodes = equation_.size() / 3;
  std::vector<std::vector<int>> neighbours(nodes);  // nodes sharing an element, itself included
  for (const Hexahedron& h : hexahedra)
    for (std::int32_t a : h) neighbours[a].insert(neighbours[a].end(), h.begin(), h.end());
  for (const Line& l : lines)
    for (std::int32_t a : l) neighbours[a].insert(neighbours[a].end(), l.begin(), l.end());
  for (const std::vector<std::int32_t>& g : coupled)
    for (std::int32_t a : g) neighbours[a].insert(neighbours[a].end(), g.begin(), g.end());
  std::vector<std::vector<int>> rows(equations);
  for (std::size_t n = 0; n < nodes; ++n) {
    std::vector<int>& near = neighbours[n];
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    for (int i = 0; i < 3; ++i) {
      const int column = equation_[3 * n + i];
      if (column < 0) continue;
      for (int m : near)
        for (int j = 0; j < 3; ++j) {
          const int row = equation_[3 * m + j];
          if (row >= 0 && row <= column) rows[column].push_back(row);
        }
    }
  }
  matrix_.size = equations;
  matrix_.column_start.assign(1, 0);
  for (std::vector<int>& r : rows) {
    std::sort(r.begin(), r.end());
    matrix_.row.insert(matrix_.row.end(), r.begin(), r.end());
    matrix_.column_start.push_back(static_cast<int>(matrix_.row.size()));
  }
  matrix_.value.assign(matrix_.row.size(), 0.0);
}

void SparseAssembly::clear() {
  std::fill(matrix_.value.begin(), matrix_.value.end(), 0.0);
}

void SparseAssembly::add(const Hexahedron& nodes, const HexMatrix& k) {
  add(nodes.data(), 24, k.data());
}

void SparseAssembly::add(const Line& nodes, const LineMatrix& k) {
  add(nodes.data(), 6, k.data());
}

void SparseAssembly::add_group(std::span<const std::int32_t> nodes, const double* k) {
  add(nodes.data(), 3 * static_cast<int>(nodes.size()), k);
}

void SparseAssembly::add(const std::int32_t* nodes, int n, const double* k) {
  std::array<int, 3 * 24> eq;  // a group: up to 24 nodes
  if (n > static_cast<int>(eq.size()))
    throw std::invalid_argument("sparse assembly: a group of more than 24 nodes");
  for (int a = 0; a < n / 3; ++a)
    for (int i = 0; i < 3; ++i) eq[3 * a + i] = equation_[3 * nodes[a] + i];
  for (int q = 0; q < n; ++q) {
    const int column = eq[q];
    if (column < 0) continue;
    const auto first = matrix_.row.begin() + matrix_.column_start[column],
               last = matrix_.row.begin() + matrix_.column_start[column + 1];
    for (int p = 0; p < n; ++p) {
      const int row = eq[p];
      if (row < 0 || row > column) continue;
      matrix_.value[std::lower_bound(first, last, row) - matrix_.row.begin()] += k[n * p + q];
    }
  }
}

}  // namespace afemp::fem
