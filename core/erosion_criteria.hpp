// Erosion criteria of an element (or, later, of any point that fails): the first of its body's
// criteria the state meets, in the order of LS-DYNA's *MAT_ADD_EROSION checks that afemp has:
// equivalent plastic strain, the material's failure strain, volume ratio V / V0 and the
// element's critical time step. One function for every element kind, so that hexahedra,
// trusses and the failure models of other solvers erode by the same rule.
#pragma once

#include "afemp/material.hpp"
#include "afemp/scene.hpp"

namespace afemp::core {

// The criterion met, as erosion.csv names it, or nullptr. eps_p is the largest equivalent
// plastic strain of the element's points and damage their largest damage; volume and volume0
// its current and initial volume; critical_dt its stable step at the current state.
inline const char* erosion_reason(const ErosionSettings& erosion, const Material& material,
                                  double eps_p, double volume, double volume0, double critical_dt,
                                  double damage = 0.0) {
  if (erosion.plastic_strain > 0.0 && eps_p >= erosion.plastic_strain) return "plastic strain";
  if (erosion.material_failure && material.failure_strain > 0.0 && eps_p >= material.failure_strain)
    return "material failure strain";
  // A failure model's point has failed (afemp/failure_models.hpp).
  if (erosion.material_failure && material.fails() && damage >= 1.0) return "material failure";
  if (volume < erosion.volume_ratio * volume0) return "volume ratio";
  if (critical_dt < erosion.time_step) return "time step";
  return nullptr;
}

}  // namespace afemp::core
