// What a mixed displacement-pressure MPM scene (`[mpm] pressure = "mixed"`) is refused for,
// shared by the parser (file, line and key) and check_scene (scenes built in code). The mixed
// scheme (Zhang et al. 2022, the mixed u-p TLMPM paper, eqs 17-24) replaces the volumetric
// part K (J - 1) of a split strain energy W_dev + K / 2 (J - 1)^2 by a pressure projected over
// the reference grid: it needs the total-Lagrangian form, whose grid stands for the reference
// configuration, and a material whose energy splits that way.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "core/scene.hpp"

namespace afemp::core {

// The [mpm] key and the message, or nothing.
inline std::optional<std::pair<std::string, std::string>> mixed_pressure_mpm_refusal(
    const MpmSettings& mpm) {
  if (mpm.pressure != PressureField::mixed) return std::nullopt;
  if (mpm.formulation != Formulation::total_lagrangian)
    return std::pair{std::string("pressure"),
                     std::string("\"mixed\" with formulation = \"") + to_string(mpm.formulation) +
                         "\": the mixed displacement-pressure scheme projects the volume ratio "
                         "over the reference grid and is built for formulation = "
                         "\"total-lagrangian\"; with the updated-Lagrangian form allowed: "
                         "\"standard\""};
  return std::nullopt;
}

// The material of a particle body whose strength has no split volumetric energy: the key and
// the message, or nothing.
inline std::optional<std::pair<std::string, std::string>> mixed_pressure_scene_refusal(
    const Scene& scene) {
  if (scene.mpm.pressure != PressureField::mixed) return std::nullopt;
  for (const BodySpec& b : scene.bodies) {
    if (b.discretisation != Discretisation::particles) continue;
    const Material& m = scene.materials[static_cast<std::size_t>(b.material)];
    if (!m.splits_volumetric_energy())
      return std::pair{"materials." + m.name + ".strength",
                       "material \"" + m.name + "\" of body \"" + b.name +
                           "\" has no volumetric energy K / 2 (J - 1)^2 of its own for [mpm] "
                           "pressure = \"mixed\" to replace (the neo-Hookean solid's log form has "
                           "lambda / 2 (ln J)^2 - mu ln J); allowed: strength model "
                           "\"neo-hookean\" with form = \"split\" or \"mooney-rivlin\" (without "
                           "an eos), or pressure = \"standard\""};
  }
  return std::nullopt;
}

}  // namespace afemp::core
