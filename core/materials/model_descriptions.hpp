// How `afemp check` names a material's models in the step plans (mpm/step_plan.cpp,
// fem/fe_step_plan.cpp), one wording for particles and elements: the strength model, the
// equation of state and when a point fails (core/materials/failure.hpp).
#pragma once

#include <string>

#include "afemp/material.hpp"

namespace afemp::core {

// The scene file's model name ("j2"), or a user model's with its history and batch size.
std::string strength_description(const StrengthModel& strength);
// The scene file's model name, or "none" (the hypoelastic pressure of the bulk modulus).
std::string eos_description(const EquationOfState& eos);
// The failure model and its constants ("Johnson-Cook damage, D1 .. D5 = ..."), the
// failure_strain where it has none, a strength model's own damage (concrete, ceramics), or
// "none".
std::string failure_description(const Material& material);

}  // namespace afemp::core
