// Elastic strength model: hypoelastic deviatoric update s += 2 G de_dev (Ma 2005, eq 2-41,
// deviatoric part of the Jaumann-rate Hooke law; the rotation is applied by the caller).
#include "afemp/strength_models.hpp"

namespace afemp::core {

DeviatoricResult Elastic::update(SymTensor& s, const SymTensor& de_dev,
                                 const StrengthContext& c) const {
  s += (2.0 * c.shear_modulus) * de_dev;
  // No yield surface: report zero flow stress so plastic work (flow_stress * dp) stays zero.
  return {0.0, 0.0};
}

// Fluid: no shear strength; the EOS carries the pressure.
DeviatoricResult Fluid::update(SymTensor& s, const SymTensor&, const StrengthContext&) const {
  s = SymTensor{};
  return {0.0, 0.0};
}

}  // namespace afemp::core
