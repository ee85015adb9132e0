// J2 plasticity with linear isotropic hardening, sigma_y = sigma_y0 + H eps_p: elastic
// predictor and radial return in closed form (Simo & Hughes 1998, box 3.2; Ma 2005, §2.2.1).
#include "afemp/strength_models.hpp"
#include "core/materials/model_parameters.hpp"

namespace afemp::core {

DeviatoricResult J2Plasticity::update(SymTensor& s, const SymTensor& de_dev,
                                      const StrengthContext& c) const {
  const double g = c.shear_modulus;
  const double sigma_y = yield_stress + hardening * c.plastic_strain;
  s += (2.0 * g) * de_dev;
  const double q_trial = von_mises(s);
  if (q_trial <= sigma_y) return {0.0, sigma_y};

  // Linear hardening makes the consistency condition q_tr - 3G dp = sigma_y + H dp linear
  // in dp, so the return is exact for any increment size.
  const double dp = (q_trial - sigma_y) / (3.0 * g + hardening);
  const double sigma_y_new = sigma_y + hardening * dp;
  s *= sigma_y_new / q_trial;
  return {dp, sigma_y_new};
}

void J2Plasticity::parameters(ParameterVisitor& v) {
  v.required("yield", yield_stress, Range::positive());
  v.require(!(v.reading() && v.has("hardening") && v.has("tangent_modulus")), "tangent_modulus",
            "give either hardening (plastic modulus H) or tangent_modulus (Et), not both");
  v.optional("hardening", hardening, 0.0, Range::non_negative());
  // Et is the slope of the uniaxial stress-strain curve after yield; the radial return wants
  // the plastic modulus, H = E Et / (E - Et).
  const double e = v.material().youngs_modulus;
  double et = 0.0;
  v.optional("tangent_modulus", et, 0.0, {0.0, e, false, true});
  if (v.reading() && v.has("tangent_modulus")) hardening = e * et / (e - et);
}

}  // namespace afemp::core
