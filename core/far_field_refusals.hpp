// What a far field with the absolute stress ([grid] far_field.stress = "absolute";
// mpm/absorbing_faces.hpp) refuses: the condition and its wording, one for the parser (which
// names the line) and the scene check (scenes built in code) alike. Empty when allowed.
#pragma once

#include <optional>
#include <string>

#include "afemp/scene.hpp"

namespace afemp::core {

// A prestressed body at one particle per cell direction: the prestress in the internal force
// makes the lattice's zero-energy modes grow (measured: a still sphere of water at 10 MPa,
// kinetic energy x10 every 30 us); at two per direction it stays still.
inline std::optional<std::string> absolute_stress_lattice_refusal(const GridSettings& grid,
                                                                  const BodySpec& body) {
  if (!grid.far_field || !grid.far_field->absolute_stress || !body.pressure ||
      !(*body.pressure > 0.0) || body.particles_per_cell >= 2)
    return std::nullopt;
  return "under grid.far_field.stress = \"absolute\" a body that starts at a pressure needs "
         "two or more particles per cell direction (at one, its zero-energy modes grow under "
         "the prestress); allowed: 2 to 8, or stress = \"gauge\"";
}

// uGIMP: the static traction acts on the face plane's nodes, and the halo nodes beyond the
// face would take the held particles' push with nothing to balance it. The B-splines reach no
// node beyond a face, but the balance has been measured with the linear hat only.
inline std::optional<std::string> absolute_stress_shape_refusal(const GridSettings& grid,
                                                                ShapeFunction shape) {
  if (!grid.far_field || !grid.far_field->absolute_stress || shape == ShapeFunction::linear)
    return std::nullopt;
  return "grid.far_field.stress = \"absolute\" balances the ambient pressure on the face "
         "plane's nodes, which needs shape_function = \"linear\" (uGIMP's halo nodes beyond the "
         "face would take it unbalanced; the B-splines' balance is not verified); allowed "
         "with the others: stress = \"gauge\"";
}

}  // namespace afemp::core
