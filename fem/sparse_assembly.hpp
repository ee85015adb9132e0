// Assembly of element stiffness matrices into the sparse symmetric matrix of a mesh's free
// degrees of freedom (3 per node). The pattern comes once from the node-element incidence (two
// dofs couple when their nodes share an element); Dirichlet dofs are eliminated: their rows and
// columns are dropped (the prescribed values enter the residual through the internal forces of
// the current displacement, so no right-hand side needs lifting).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "fem/mesh.hpp"
#include "fem/sparse_cholesky.hpp"

namespace afemp::fem {

// A 24 x 24 element matrix, row-major, dof 3 a + i for component i of node a.
using HexMatrix = std::array<double, 24 * 24>;

class SparseAssembly {
 public:
  // equation[3 n + i]: the equation (0 .. equations - 1) of component i of node n, or -1 for a
  // fixed dof (or a node of no element).
  SparseAssembly(std::span<const Hexahedron> hexahedra, std::vector<int> equation, int equations);

  const std::vector<int>& equation() const { return equation_; }
  // All values to zero (the pattern stays).
  void clear();
  // Adds the upper triangle of the symmetric element matrix k of element `nodes`.
  void add(const Hexahedron& nodes, const HexMatrix& k);
  const SymmetricCsc& matrix() const { return matrix_; }

 private:
  std::vector<int> equation_;
  SymmetricCsc matrix_;
};

}  // namespace afemp::fem
