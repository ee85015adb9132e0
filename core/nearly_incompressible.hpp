// Hexahedra of a nearly incompressible solid ring above half LS-DYNA's step rule: a twisting
// column of neo-Hookean gel at nu = 0.499 (B-bar hexahedra 4 across) gained 128 % of its energy
// at the default factor 0.9 and kept it to 2e-3 at 0.5 (tests/fem/test_hyperelastic_hexahedra.cpp);
// a block at nu = 0.495 stayed stable at 0.9 (docs/studies/README.md). `afemp check` warns
// (core/plausibility.cpp) and the LS-DYNA import holds TSSFAC (fem/lsdyna_deck_import.cpp) by
// these two figures.
#pragma once

namespace afemp::core::nearly_incompressible {

// A Poisson's ratio above this counts as nearly incompressible for the hexahedra's step.
inline constexpr double poisson_ratio = 0.495;
// The element step factor such hexahedra need.
inline constexpr double element_step_factor = 0.5;

}  // namespace afemp::core::nearly_incompressible
