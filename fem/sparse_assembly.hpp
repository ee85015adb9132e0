// Assembly of element stiffness matrices (hexahedra and 2-node lines) into the sparse symmetric
// matrix of a mesh's free degrees of freedom (3 per node). The pattern comes once from the
// node-element incidence (two dofs couple when their nodes share an element); Dirichlet dofs
// are eliminated: their rows and columns are dropped (the prescribed values enter the residual
// through the internal forces of the current displacement, so no right-hand side needs
// lifting).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "fem/mesh.hpp"
#include "fem/sparse_cholesky.hpp"

namespace afemp::fem {

// A 24 x 24 element matrix, row-major, dof 3 a + i for component i of node a.
using HexMatrix = std::array<double, 24 * 24>;
// A 6 x 6 matrix of a 2-node line (truss), row-major, dof 3 a + i likewise.
using LineMatrix = std::array<double, 6 * 6>;

// A node tied into a hexahedron (rebar in solid elements, fem/embedded_nodes.hpp): it moves
// with the host's nodes, u = sum_a weight[a] u[host[a]], and has no equations of its own.
struct TiedNode {
  std::int32_t node = 0;
  std::array<std::int32_t, 8> host{};
  std::array<double, 8> weight{};
};

class SparseAssembly {
 public:
  // equation[3 n + i]: the equation (0 .. equations - 1) of component i of node n, or -1 for a
  // fixed dof (or a node of no element). `coupled`: more groups of nodes whose dofs couple (a
  // truss with tied nodes couples the nodes of their hosts), each added with add_group.
  SparseAssembly(std::span<const Hexahedron> hexahedra, std::span<const Line> lines,
                 std::vector<int> equation, int equations,
                 std::span<const std::vector<std::int32_t>> coupled = {});

  const std::vector<int>& equation() const { return equation_; }
  // All values to zero (the pattern stays).
  void clear();
  // Adds the upper triangle of the symmetric element matrix k of element `nodes`.
  void add(const Hexahedron& nodes, const HexMatrix& k);
  void add(const Line& nodes, const LineMatrix& k);
  // k: 3 nodes.size() dofs, row-major, for a group given to the constructor.
  void add_group(std::span<const std::int32_t> nodes, const double* k);
  const SymmetricCsc& matrix() const { return matrix_; }

 private:
  // k: n dofs (3 per node of `nodes`), row-major.
  void add(const std::int32_t* nodes, int n, const double* k);

  std::vector<int> equation_;
  SymmetricCsc matrix_;
};

}  // namespace afemp::fem
