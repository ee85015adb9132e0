// The step plans' names of a material's models (core/materials/model_descriptions.hpp).
#include "core/materials/model_descriptions.hpp"

#include <type_traits>
#include <variant>

#include "core/appendf.hpp"
#include "core/materials/material.hpp"
#include "core/materials/model_parameters.hpp"
#include "core/materials/user_strength_chunk.hpp"

namespace afemp::core {

std::string strength_description(const StrengthModel& strength) {
  if (const auto* u = std::get_if<UserStrength>(&strength))
    return "user model " + (u->definition ? u->definition->name : std::string("?")) + " (" +
           std::to_string(u->history_count()) + " history variables, batches of " +
           std::to_string(kUserChunk) + ")";
  return std::string(model_name(strength));
}

std::string eos_description(const EquationOfState& eos) {
  const std::string_view name = model_name(eos);
  return name.empty() ? "none" : std::string(name);
}

std::string failure_description(const Material& material) {
  std::string out;
  std::visit(
      [&](const auto& f) {
        using F = std::decay_t<decltype(f)>;
        if constexpr (std::is_same_v<F, JohnsonCookFailure>) {
          appendf(out, "Johnson-Cook damage, D1 .. D5 = %g, %g, %g, %g, %g", f.D1, f.D2, f.D3, f.D4,
                  f.D5);
          if (f.damage_threshold > 0.0)
            appendf(out, ", from plastic strain %g", f.damage_threshold);
          if (f.critical_damage > 0.0)
            appendf(out, ", softening the deviator to %g at failure", 1.0 - f.critical_damage);
        } else if constexpr (std::is_same_v<F, PlasticStrainFailure>) {
          appendf(out, "plastic strain %g", f.strain);
        } else if constexpr (std::is_same_v<F, SpallFailure>) {
          appendf(out, "spall, %s %g%s",
                  f.criterion == SpallFailure::Criterion::pressure ? "tension -p"
                                                                   : "largest principal stress",
                  f.strength, f.impulse > 0.0 ? ", cumulative (Tuler-Butcher)" : "");
        } else if constexpr (std::is_same_v<F, PrincipalStrainFailure>) {
          appendf(out, "principal strain %g", f.strain);
        } else if constexpr (std::is_same_v<F, NoFailure>) {
          if (material.failure_strain > 0.0)
            appendf(out, "plastic strain %g", material.failure_strain);
          else if (has_own_pressure_law(material))
            out = "the strength model's own damage";
          else
            out = "none";
        } else {
          static_assert(sizeof(F) == 0, "a failure model the step plans do not describe");
        }
      },
      material.failure);
  return out;
}

}  // namespace afemp::core
