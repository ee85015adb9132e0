// The allowed values of the scene's keys (docs/scene-format.md) and the rules that join them,
// each stated once: the scene-file parser (scene_parser.cpp) reads a key within its range and
// names its line, and the check of a scene built in code (scene_check.cpp) holds the same field
// to the same range and rule. A key's default is not here: it is the default-constructed
// struct member of include/afemp/scene.hpp, which the parser keeps when the file leaves the key
// out.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "afemp/model_parameters.hpp"
#include "afemp/scene.hpp"
#include "core/materials/material.hpp"

namespace afemp::core {

namespace scene_ranges {

// An allowed interval of whole numbers, both ends included.
struct Count {
  long lo = 0;
  long hi = std::numeric_limits<long>::max();
  bool contains(long v) const { return v >= lo && v <= hi; }
};

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr Range kPositive{0.0, kInfinity, true, false};
inline constexpr Range kNonNegative{0.0, kInfinity, false, false};
inline constexpr Range kFraction{0.0, 1.0, false, false};   // [0, 1]
inline constexpr Range kStepFactor{0.0, 1.0, true, false};  // (0, 1]
inline constexpr Range kBelowOne{0.0, 1.0, false, true};    // [0, 1): 0 switches it off

// [run] units: the systems the plausibility warnings know (core/plausibility.hpp).
inline constexpr std::array<std::string_view, 2> kUnitSystems{"mm-ms-g", "SI"};

namespace run {
inline constexpr Range end_time = kPositive;
inline constexpr Range time_step_factor = kStepFactor;
inline constexpr Range element_time_step_factor = kStepFactor;
inline constexpr Range time_step = kPositive;  // given; 0 in RunSettings: the stable step
inline constexpr Count max_steps{0};
inline constexpr Range output_every = kNonNegative;
inline constexpr Count history_every{1};
inline constexpr Range history_interval = kPositive;  // given; 0 in RunSettings: history_every
inline constexpr Range output_times = kPositive;
inline constexpr Range energy_error_limit = kNonNegative;
inline constexpr Range checkpoint_every = kNonNegative;
inline constexpr Range checkpoint_wall_every = kNonNegative;
inline constexpr Count checkpoint_keep{1, 1000};
inline constexpr Range terminate_travel = kPositive;
}  // namespace run

namespace phase {  // [[phases]] (core/phases.cpp)
inline constexpr Count load_steps{1, 100000};
inline constexpr Count max_iterations{1, 1000};
inline constexpr Range tolerance{0.0, 1e-2, true, false};            // (0, 0.01]
inline constexpr Range relaxation_tolerance{0.0, 0.1, true, false};  // DRTOL, (0, 0.1]
inline constexpr Range damping_factor{0.0, 1.0, true, true};         // DRFCTR, (0, 1)
inline constexpr Count check_every{1, 1000000};                      // NRCYCK
inline constexpr Range relaxation_step_factor = kStepFactor;         // TSSFDR, (0, 1]
inline constexpr Range implicit_time_step = kPositive;
inline constexpr Range hht_alpha{-1.0 / 3.0, 0.0, false, false};  // [-1/3, 0]
}  // namespace phase

namespace grid {
inline constexpr Range cell = kPositive;
inline constexpr Range far_field_pressure = kNonNegative;
}  // namespace grid

namespace mpm {
inline constexpr Range flip = kFraction;
inline constexpr Range split_alpha{0.5, 1.5, true, false};
inline constexpr Count split_max_particles{1, 2000000000};
}  // namespace mpm

namespace material {
inline constexpr Range density = kPositive;
inline constexpr Range youngs_modulus = kPositive;
inline constexpr Range shear_modulus = kPositive;
inline constexpr Range poisson_ratio{0.0, 0.5, false, true};
inline constexpr Range specific_heat = kNonNegative;
inline constexpr Range taylor_quinney = kFraction;
inline constexpr Range temperature = kNonNegative;
inline constexpr Range failure_strain = kNonNegative;
inline constexpr Range pressure_cutoff{-kInfinity, 0.0, true, false};
inline constexpr Range detonation_velocity = kPositive;
inline constexpr Range cj_pressure = kPositive;
}  // namespace material

namespace body {
inline constexpr Range temperature = kNonNegative;
inline constexpr Range internal_energy = kNonNegative;
inline constexpr Range pressure = kNonNegative;
inline constexpr Range geostatic_surface{};
inline constexpr Range earth_pressure_at_rest = kPositive;  // K0
inline constexpr Count particles_per_cell{1, 8};
inline constexpr Range bulk_linear = kFraction;
inline constexpr Range bulk_quadratic = Range{0.0, 10.0, false, false};
inline constexpr Range area = kPositive;
inline constexpr Range prestress{-kInfinity, kInfinity, true, true};  // finite
// Q_hg of the viscous and stiffness forms; the assumed-strain form's scale on its stiffness.
inline constexpr Range hourglass_coefficient = Range{0.0, 0.5, false, false};
inline constexpr Range hourglass_scale = kFraction;
constexpr Range hourglass_range(HourglassForm form) {
  return form == HourglassForm::assumed_strain ? hourglass_scale : hourglass_coefficient;
}
}  // namespace body

namespace mesh {
inline constexpr Range size = kPositive;
inline constexpr Count divisions{1, 100000};
inline constexpr Count graded_elements{1, 100000};
inline constexpr Count core{1, 10000};
inline constexpr Count ring{1, 10000};
inline constexpr Count axial{1, 100000};
inline constexpr Count sectors{1, 4};  // 1, 2 or 4 (a quarter, a half, the whole)
inline constexpr Count across{4, 10000};
inline constexpr Count segments{1, 1000000};
}  // namespace mesh

namespace erosion {
inline constexpr Range plastic_strain = kNonNegative;
inline constexpr Range volume_ratio = kBelowOne;
inline constexpr Range time_step = kNonNegative;
}  // namespace erosion

namespace conversion {
inline constexpr Range plastic_strain = kNonNegative;
inline constexpr Range volumetric_strain = kBelowOne;
inline constexpr Range jacobian_ratio = kBelowOne;
inline constexpr Range time_step_fraction = kBelowOne;
inline constexpr Range damage = kFraction;
inline constexpr Count points{1, 2};
}  // namespace conversion

namespace shape {
inline constexpr Range radius = kPositive;
inline constexpr Range length = kPositive;
inline constexpr Range nose_crh{0.5, kInfinity, false, false};
inline constexpr Range nose_meplat = kNonNegative;
inline constexpr Range cone_radius = kNonNegative;
inline constexpr Range cone_wall = kNonNegative;
inline constexpr Range mesh_scale = kPositive;
inline constexpr Range rebar_spacing = kPositive;
inline constexpr Range rebar_diameter = kPositive;
inline constexpr Range rebar_cover = kNonNegative;
}  // namespace shape

namespace contact {
inline constexpr Range friction = kNonNegative;
inline constexpr Range distance_factor = kNonNegative;
inline constexpr Range penalty = kStepFactor;
}  // namespace contact

inline constexpr Range selector_tolerance = kNonNegative;
inline constexpr Range wall_friction = kNonNegative;
inline constexpr Range detonation_time = kNonNegative;
inline constexpr Range probe_interval = kPositive;

namespace reference {
inline constexpr Range tolerance = kNonNegative;
inline constexpr Range energy_tolerance = kPositive;
inline constexpr Range taylor_length = kPositive;
}  // namespace reference

}  // namespace scene_ranges

// Conversion with every criterion off converts nothing (a table left empty by mistake).
inline std::optional<std::string> no_conversion_criterion(const ConversionSettings& c) {
  if (c.plastic_strain > 0.0 || c.volumetric_strain > 0.0 || c.jacobian_ratio > 0.0 ||
      c.negative_jacobian || c.time_step_fraction > 0.0 || c.damage > 0.0)
    return std::nullopt;
  return "every criterion is off; give at least one of plastic_strain, volumetric_strain, "
         "jacobian_ratio, negative_jacobian, time_step_fraction, damage";
}

// A contact's name prefixes its history columns (NAME.fx, ...).
inline std::optional<std::string> contact_name_refusal(const std::string& name) {
  if (!name.empty() && name.find_first_of(",\"\n") == std::string::npos) return std::nullopt;
  return "a contact name is a history column prefix: not empty, without commas, quotes or line "
         "breaks";
}

// A pressure cutoff (cavitation) cuts an EOS's pressure.
inline std::optional<std::string> pressure_cutoff_refusal(const Material& m) {
  if (m.pressure_cutoff == -std::numeric_limits<double>::infinity() ||
      (m.has_eos() && !has_own_pressure_law(m)))
    return std::nullopt;
  return "a pressure cutoff (cavitation) acts on an eos's pressure: give eos = { model = "
         "\"mie-gruneisen\" } or another, not a strength model's own pressure law "
         "(hjc-compaction), which has its own tension limit";
}

// A failure key that body's discretisation would not use, refused rather than ignored: the
// key (relative to the material's table when `of_material`, else to the body's) and why.
struct FailureKeyRefusal {
  bool of_material = false;
  std::string key;
  std::string message;
};
// Trusses run the uniaxial update, which has no failed state: their material fails only
// through erosion at its failure_strain (core/erosion_criteria.hpp), so they take that and no
// failure model. Erosion at the material's failure needs a material that fails.
inline std::optional<FailureKeyRefusal> failure_key_refusal(const BodySpec& b, const Material& m) {
  const bool failure_strain_only =
      !m.fails() ||
      (m.failure_strain > 0.0 && std::holds_alternative<PlasticStrainFailure>(m.failure) &&
       std::get<PlasticStrainFailure>(m.failure).strain == m.failure_strain);
  const bool erodes_at_failure = b.erosion && b.erosion->material_failure;
  if (b.discretisation == Discretisation::trusses && !failure_strain_only)
    return FailureKeyRefusal{
        true, "failure",
        "body \"" + b.name +
            "\" is made of trusses, which take failure_strain only (their erosion criterion, "
            "with erosion = { material_failure = true }); a failure model acts at the points "
            "of particles and hexahedra"};
  if (b.discretisation == Discretisation::trusses && m.failure_strain > 0.0 && !erodes_at_failure)
    return FailureKeyRefusal{false, "erosion",
                             "material \"" + m.name +
                                 "\"'s failure_strain acts on trusses only through erosion = { "
                                 "material_failure = true } (trusses have no failed state); add "
                                 "it, or remove failure_strain"};
  if (erodes_at_failure && !m.fails() && !(m.failure_strain > 0.0))
    return FailureKeyRefusal{false, "erosion.material_failure",
                             "material \"" + m.name +
                                 "\" has no failure_strain or failure model: no element erodes "
                                 "at its failure; give one, or remove material_failure"};
  return std::nullopt;
}

}  // namespace afemp::core
