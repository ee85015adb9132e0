// The failure models' scene-file keys, ranges and rules (afemp/failure_models.hpp; their damage
// is failure.hpp's): Johnson & Cook (1985) with Borvik et al.'s (2001) threshold and coupling,
// plastic and principal strain, and spall (Tuler & Butcher 1968 for the cumulative form).
#include "afemp/failure_models.hpp"

#include <limits>

#include "core/materials/model_parameters.hpp"

namespace afemp::core {

void JohnsonCookFailure::parameters(ParameterVisitor& v) {
  // eps_f must stay positive at every triaxiality: D1 + D2 > 0 at sigma* = 0 and D1 >= 0
  // where exp(D3 sigma*) vanishes (D3 < 0), D2 >= 0. It falls as the triaxiality rises
  // (D3 <= 0) and rises with the temperature (D5 >= 0), as in every published set; a D5 < 0
  // would bring it to zero below the melt. D4 takes either sign: steels that lose ductility
  // with the rate have D4 < 0 (Weldox 460 E, -0.0123: Borvik et al. 2001), whose rate factor
  // would reach zero only at epsdot* = exp(-1/D4), e^81 there; a point that got there would
  // fail at once.
  v.required("D1", D1, Range::any());
  v.required("D2", D2, Range::non_negative());
  v.required("D3", D3, {-std::numeric_limits<double>::infinity(), 0.0, false, false});
  v.optional("D4", D4, 0.0, Range::any());
  v.optional("D5", D5, 0.0, Range::non_negative());
  v.require(D1 + D2 > 0.0, "D2", out_of_range(D1 + D2, "D1 + D2 > 0 (a positive fracture strain)"));
  v.optional("reference_strain_rate", reference_strain_rate, 1.0, Range::positive());
  v.optional("room_temperature", room_temperature, 293.0, Range::non_negative());
  v.optional("melt_temperature", melt_temperature, 0.0, Range::non_negative());
  v.optional("damage_threshold", damage_threshold, 0.0, Range::non_negative());
  // D_C = 1 would soften the deviator to zero, from which the effective one is lost.
  v.optional("critical_damage", critical_damage, 0.0, {0.0, 1.0, false, true});
}

void PlasticStrainFailure::parameters(ParameterVisitor& v) {
  v.required("strain", strain, Range::positive());
}

void PrincipalStrainFailure::parameters(ParameterVisitor& v) {
  v.required("strain", strain, Range::positive());
}

void SpallFailure::parameters(ParameterVisitor& v) {
  // The scene names the criterion by the key it gives the strength under.
  if (v.reading()) {
    double pressure = 0.0, principal = 0.0;
    v.optional("pressure", pressure, 0.0, Range::positive());
    v.optional("principal_stress", principal, 0.0, Range::positive());
    const bool by_pressure = v.has("pressure");
    v.require(by_pressure != v.has("principal_stress"),
              by_pressure ? "principal_stress" : "pressure",
              "a spall model takes exactly one strength: pressure (fails when -p exceeds it) or "
              "principal_stress (when the largest principal stress does)");
    criterion = by_pressure ? Criterion::pressure : Criterion::principal_stress;
    strength = by_pressure ? pressure : principal;
  } else {
    v.required("strength", strength, Range::positive());
  }
  v.optional("impulse", impulse, 0.0, Range::non_negative());
  v.optional("exponent", exponent, 2.0, Range::at_least(1.0));
  v.require(!(v.reading() && v.has("exponent")) || impulse > 0.0, "exponent",
            "the exponent is the cumulative (Tuler-Butcher) form's: give impulse > 0 with it");
}

}  // namespace afemp::core
