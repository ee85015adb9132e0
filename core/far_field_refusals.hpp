// What a far field with the absolute stress ([grid] far_field.stress = "absolute";
// mpm/absorbing_faces.hpp) refuses, in one wording for the parser and the scene check.
#pragma once

#include <string>

namespace afemp::core {

// A prestressed body at one particle per cell direction: the prestress in the internal force
// makes the lattice's zero-energy modes grow (measured: a still sphere of water at 10 MPa,
// kinetic energy x10 every 30 us); at two per direction it stays still.
inline std::string absolute_stress_lattice_refusal() {
  return "under grid.far_field.stress = \"absolute\" a body that starts at a pressure needs "
         "two or more particles per cell direction (at one, its zero-energy modes grow under "
         "the prestress); allowed: 2 to 8, or stress = \"gauge\"";
}

// uGIMP: the static traction acts on the face plane's nodes, and the halo nodes beyond the
// face would take the held particles' push with nothing to balance it.
inline std::string absolute_stress_shape_refusal() {
  return "grid.far_field.stress = \"absolute\" balances the ambient pressure on the face "
         "plane's nodes, which needs shape_function = \"linear\" (uGIMP's halo nodes beyond the "
         "face would take it unbalanced); allowed with \"gimp\": stress = \"gauge\"";
}

}  // namespace afemp::core
