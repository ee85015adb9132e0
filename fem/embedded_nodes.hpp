// Trusses tied into hexahedra: rebar in solid elements (LS-DYNA's *CONSTRAINED_BEAM_IN_SOLID,
// Abaqus's *EMBEDDED ELEMENT). Each node s of a tied body moves with the host element that
// holds it, u_s = sum_a N_a(xi_s) u_a, with xi_s its natural coordinates in the undeformed
// host: the embedded-reinforcement constraint (Elwi & Hrudey, J. Eng. Mech. 115(4), 1989,
// 740-754; perfect bond, no slip). The explicit step eliminates the node: it lends its lumped
// mass to the host's nodes (m_a += N_a m_s) and hands them its force (f_a += N_a f_s), the host's
// nodes take the update with both, and the node follows, v_s = sum N_a v_a, x_s = sum N_a x_a.
// The momentum is exact (sum_a N_a = 1), and the kinetic energy the run books is that of the
// masses the update moves, sum_a m_a v_a^2 / 2 with the lent masses. A node whose host erodes or
// converts is released: it takes back its own mass and moves with its trusses alone.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "afemp/energies.hpp"
#include "afemp/scene.hpp"
#include "afemp/tensor.hpp"
#include "fem/hexahedron_set.hpp"

namespace afemp::fem {

struct FeNodes;

struct EmbeddedNodes {
  std::vector<std::int32_t> node;  // the tied node
  std::vector<std::int32_t> host;  // the hexahedron that holds it
  std::vector<std::array<std::int32_t, 8>> host_nodes;
  std::vector<std::array<double, 8>> weight;  // N_a(xi_s)
  std::vector<double> own_mass;               // the node's lumped mass, from its live trusses
  // Per FE node, the ties whose node hands its force to it: ties[offsets[i] .. offsets[i+1])
  // as (tie, corner of the host). Empty when nothing is tied.
  std::vector<std::int64_t> offsets;
  std::vector<std::pair<std::int32_t, std::int32_t>> ties;

  bool empty() const { return node.empty(); }
  std::size_t size() const { return node.size(); }
  bool bound(std::size_t k, const HexElements& hexes) const {
    return hexes.alive[static_cast<std::size_t>(host[k])] != 0;
  }
};

// The ties of every truss body whose bonded_to names a body of hexahedra, from the nodes'
// positions now. A tied node that no live element of its host holds, or that a constraint holds,
// is an InputError naming the body, the node and where it lies.
EmbeddedNodes tie_embedded_nodes(const core::Scene& scene, const FeNodes& nodes,
                                 const HexElements& hexes);

// After the lumped masses are made from the live elements: each bound node's mass moves to its
// host's nodes (own_mass keeps it); a released node keeps its own.
void lend_embedded_masses(EmbeddedNodes& ties, FeNodes& nodes, const HexElements& hexes);

// The bound nodes take their hosts' motion: v_s = sum N_a v_a, x_s = sum N_a x_a.
void follow_hosts(const EmbeddedNodes& ties, FeNodes& nodes, const HexElements& hexes);

// The body sums with each bound node's lent mass, momentum and kinetic energy counted in its
// own body rather than in its host's (the totals are unchanged).
void book_embedded_bodies(const EmbeddedNodes& ties, const FeNodes& nodes, const HexElements& hexes,
                          std::vector<core::BodySums>& bodies);

}  // namespace afemp::fem
