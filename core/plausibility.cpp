// Plausibility warnings (core/plausibility.hpp).
#include "core/plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <variant>

#include "core/decks/deck_units.hpp"
#include "core/materials/initial_pressure.hpp"
#include "core/materials/material.hpp"
#include "core/nearly_incompressible.hpp"

namespace afemp::core {

namespace {

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

// Real materials' densities (aerogels and gases to osmium) and wave speeds in each unit system.
struct UnitRanges {
  const char* name;
  double density_low, density_high;
  const char* density_unit;
  const char* steel_density;
};
constexpr UnitRanges mm_ms_g{"mm-ms-g", 1e-7, 3e-2, "g/mm^3", "7.85e-3"};
constexpr UnitRanges si{"SI", 0.1, 3e4, "kg/m^3", "7850"};
constexpr double wave_low = 100.0, wave_high = 2e4;  // m/s (= mm/ms)

// Whether a constraint holds the normal component of the nodes on the plane through `point`
// with axis-aligned normal `axis` (a plane or box selector through it, or the body's named
// cut set).
bool holds_plane(const Scene& scene, int body, int axis, double coordinate, const char* set) {
  for (const ConstraintSpec& c : scene.constraints) {
    if (c.body >= 0 && c.body != body) continue;
    if (!c.components[static_cast<std::size_t>(axis)]) continue;
    const NodeSelector& s = c.nodes;
    switch (s.kind) {
      case NodeSelector::Kind::plane: {
        const double n = std::abs(s.normal[axis]);
        if (n > 1.0 - 1e-9 && std::abs(s.point[axis] - coordinate) <= s.tolerance + 1e-9)
          return true;
        break;
      }
      case NodeSelector::Kind::box:
        if (s.min[axis] <= coordinate && coordinate <= s.max[axis]) return true;
        break;
      case NodeSelector::Kind::set:
        if (s.set == set) return true;
        break;
    }
  }
  return false;
}

// Collects the warnings, leaving out those the scene's [run] quiet names.
class Warner {
 public:
  explicit Warner(const Scene& scene) : scene_(scene) {}
  void operator()(const SourceLocation& where, const std::string& key, const std::string& message) {
    const std::vector<std::string>& quiet = scene_.run.quiet;
    if (std::find(quiet.begin(), quiet.end(), key) != quiet.end()) return;
    out_.push_back({where, key, message + " (silence with [run] quiet = [\"" + key + "\"])"});
  }
  std::vector<SceneWarning> take() { return std::move(out_); }

 private:
  const Scene& scene_;
  std::vector<SceneWarning> out_;
};

// Materials, from the declared units: density, wave speed, yield stress and failure strain
// outside what real materials have.
void warn_material_units(const Scene& scene, Warner& warn) {
  const UnitRanges* u = scene.run.units == "mm-ms-g" ? &mm_ms_g
                        : scene.run.units == "SI"    ? &si
                                                     : nullptr;
  for (std::size_t m = 0; u && m < scene.materials.size(); ++m) {
    const Material& mat = scene.materials[m];
    const std::string key = "materials." + mat.name;
    const SourceLocation at =
        m < scene.material_where.size() ? scene.material_where[m] : SourceLocation{scene.path, 0};
    if (mat.density < u->density_low || mat.density > u->density_high)
      warn(at, key + ".density",
           "density " + num(mat.density) + " lies outside real materials' " + num(u->density_low) +
               " .. " + num(u->density_high) + " " + u->density_unit + " in " + u->name +
               " units (steel: " + u->steel_density + ")");
    const double c =
        std::sqrt((mat.bulk_modulus() + 4.0 / 3.0 * mat.shear_modulus()) / mat.density);
    // (A fluid given without E has no elastic wave speed of its own: its EOS sets it.)
    if (mat.youngs_modulus > 0.0 && std::isfinite(c) && (c < wave_low || c > wave_high))
      warn(at, key + ".E",
           "its elastic wave speed sqrt((K + 4G/3) / rho) is " + num(c) + " m/s, outside the " +
               num(wave_low) + " .. " + num(wave_high) + " m/s of real solids (" + u->name +
               " units: a modulus or the density in another unit?)");
    double yield = 0.0;
    if (const auto* j2 = std::get_if<J2Plasticity>(&mat.strength)) yield = j2->yield_stress;
    if (const auto* jc = std::get_if<JohnsonCook>(&mat.strength)) yield = jc->A;
    const double e_mod = 9.0 * mat.bulk_modulus() * mat.shear_modulus() /
                         (3.0 * mat.bulk_modulus() + mat.shear_modulus());
    if (yield > 0.1 * e_mod)
      warn(at, key + ".strength",
           "a yield stress of " + num(yield) + " is above E / 10 = " + num(0.1 * e_mod) +
               " (metals yield near E / 300 to E / 100: E and the yield stress in different "
               "units?)");
    double strain = mat.failure_strain;
    const char* which = "failure_strain";
    if (const auto* f = std::get_if<PlasticStrainFailure>(&mat.failure)) {
      strain = f->strain;
      which = "failure";
    }
    if (const auto* f = std::get_if<PrincipalStrainFailure>(&mat.failure)) {
      strain = f->strain;
      which = "failure";
    }
    if (mat.failure_strain > 0.0) {  // given as failure_strain (it acts as the model above)
      strain = mat.failure_strain;
      which = "failure_strain";
    }
    if (strain > 10.0)
      warn(at, key + "." + which,
           "a failure strain of " + num(strain) + " is above 10 (a strain, not a percentage)");
  }
}

// A material's numbers read in unit system s: density in g/mm^3, stress in MPa, speed in m/s
// (= mm/ms).
double density_in(const UnitSystem& s, double rho) {
  return rho * s.mass / (s.length * s.length * s.length);
}
double stress_in(const UnitSystem& s, double stress) {
  return stress * s.mass / (s.length * s.time * s.time);
}
// sqrt((K + 4G/3) / rho), the density read in system d and the moduli in system k.
double wave_speed_in(const Material& m, const UnitSystem& d, const UnitSystem& k) {
  return std::sqrt(stress_in(k, m.bulk_modulus() + 4.0 / 3.0 * m.shear_modulus()) /
                   density_in(d, m.density));
}
// Whether the material is a real one read in system s: its density, and its elastic wave speed
// where it gives E (a fluid's EOS sets its own).
bool real_in(const Material& m, const UnitSystem& s) {
  const double rho = density_in(s, m.density);
  if (rho < mm_ms_g.density_low || rho > mm_ms_g.density_high) return false;
  if (!(m.youngs_modulus > 0.0)) return true;
  const double c = wave_speed_in(m, s, s);
  return c >= wave_low && c <= wave_high;
}

// Without [run] units, the materials against the unit systems a scene may be in
// (core/decks/deck_units.hpp; mm-ms-g and SI give the same speeds, m/s = mm/ms, so a density
// and a modulus decide). A material real in no system whose density is real in one and whose
// modulus makes a real wave speed with it in another mixes the two (steel at 7850 kg/m^3 with
// E in MPa: 6 m/s); a material real only outside the system most materials are real in was
// pasted from another scene. Numbers real in no system and no pair are a scene's own units,
// which pass unwarned.
void warn_unstated_units(const Scene& scene, Warner& warn) {
  if (!scene.run.units.empty()) return;
  const std::span<const UnitSystem> systems = unit_systems();
  std::vector<std::size_t> count(systems.size(), 0);
  for (const Material& mat : scene.materials)
    for (std::size_t s = 0; s < systems.size(); ++s) count[s] += real_in(mat, systems[s]) ? 1 : 0;
  const std::size_t usual = static_cast<std::size_t>(std::max_element(count.begin(), count.end()) -
                                                     count.begin());  // the first on a tie
  const UnitSystem& u = systems[usual];
  for (std::size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& mat = scene.materials[m];
    if (real_in(mat, u)) continue;
    const std::string key = "materials." + mat.name + ".density";
    const SourceLocation at =
        m < scene.material_where.size() ? scene.material_where[m] : SourceLocation{scene.path, 0};
    const auto in_usual = [&](const UnitSystem& from) {
      std::string out = "density is " + num(density_in(from, mat.density) / density_in(u, 1.0)) +
                        " " + u.density_unit;
      if (mat.youngs_modulus > 0.0)
        out += " and E " + num(stress_in(from, mat.youngs_modulus) / stress_in(u, 1.0)) + " " +
               u.stress_unit;
      return out;
    };
    const auto other = std::find_if(systems.begin(), systems.end(),
                                    [&](const UnitSystem& s) { return real_in(mat, s); });
    if (other != systems.end()) {
      warn(at, key,
           "material " + mat.name + " looks like " + other->label + " (density " +
               num(mat.density) + " " + other->density_unit +
               (mat.youngs_modulus > 0.0
                    ? ", E " + num(mat.youngs_modulus) + " " + other->stress_unit
                    : std::string()) +
               ") while the scene's other materials look like " + u.label + "; in " + u.label +
               " its " + in_usual(*other) + " (or state [run] units)");
      continue;
    }
    if (!(mat.youngs_modulus > 0.0)) continue;
    // The density's system d and the modulus's k that make a real wave speed together, k the
    // usual one where it can be.
    for (std::size_t j = 0; j < systems.size(); ++j) {
      const UnitSystem& k = systems[j == 0 ? usual : j == usual ? 0 : j];
      const auto d = std::find_if(systems.begin(), systems.end(), [&](const UnitSystem& s) {
        const double rho = density_in(s, mat.density), c = wave_speed_in(mat, s, k);
        return rho >= mm_ms_g.density_low && rho <= mm_ms_g.density_high && c >= wave_low &&
               c <= wave_high;
      });
      if (d == systems.end()) continue;
      warn(at, key,
           "density " + num(mat.density) + " looks like " + d->density_unit + " (" + d->label +
               ") and E = " + num(mat.youngs_modulus) + " like " + k.stress_unit + " (" + k.label +
               "): its elastic wave speed sqrt((K + 4G/3) / rho) is " +
               num(wave_speed_in(mat, k, k)) + " m/s in " + k.label + "; in " + k.label +
               " the density is " + num(density_in(*d, mat.density) / density_in(k, 1.0)) + " " +
               k.density_unit + " (steel: " + num(7.85e-3 / density_in(k, 1.0)) + "), in " +
               d->label + " E is " + num(stress_in(k, mat.youngs_modulus) / stress_in(*d, 1.0)) +
               " " + d->stress_unit + " (or state [run] units)");
      break;
    }
  }
}

// Erosion plastic strains given as a percentage.
void warn_erosion_strain(const Scene& scene, Warner& warn) {
  for (const BodySpec& body : scene.bodies)
    if (body.erosion && body.erosion->plastic_strain > 10.0)
      warn(body.where, "bodies." + body.name + ".erosion.plastic_strain",
           "an erosion plastic strain of " + num(body.erosion->plastic_strain) +
               " is above 10 (a strain, not a percentage)");
}

// The grid: a whole number of cells along each axis (the grid is extended to the next one).
void warn_grid_cells(const Scene& scene, Warner& warn) {
  if (scene.has_grid) {
    const GridSettings& g = scene.mpm.grid;
    for (int a = 0; a < 3; ++a) {
      const double cells = (g.max[a] - g.min[a]) / g.cell;
      if (std::abs(cells - std::round(cells)) > 1e-9 * std::max(1.0, cells)) {
        const char* axis = a == 0 ? "x" : a == 1 ? "y" : "z";
        warn(scene.grid_where, "grid.max",
             std::string("the grid spans ") + num(g.max[a] - g.min[a]) + " along " + axis + ", " +
                 num(cells) + " cells of " + num(g.cell) + ": it is extended to " +
                 num(std::ceil(cells)) + " cells (max " + axis + " = " +
                 num(g.min[a] + std::ceil(cells) * g.cell) + ")");
      }
    }
  }
}

// Quarter and half meshes (generated cylinders along z, spheres) need their cut planes held.
void warn_unheld_cut_planes(const Scene& scene, Warner& warn) {
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& body = scene.bodies[b];
    if (body.discretisation != Discretisation::hexahedra || body.rigid) continue;
    const int sectors = body.mesh.sectors;
    if (sectors != 1 && sectors != 2) continue;
    Vec3 origin;
    if (const auto* c = std::get_if<CylinderShape>(&body.shape)) {
      if (std::abs(std::abs(c->axis.z) - 1.0) > 1e-9) continue;  // only along z is checked
      origin = c->base;
    } else if (const auto* s = std::get_if<SphereShape>(&body.shape)) {
      origin = s->centre;
    } else {
      continue;
    }
    // Cut planes: y = origin (sectors 1 and 2), x = origin (sectors 1).
    for (int axis : {1, 0}) {
      if (axis == 0 && sectors != 1) continue;
      const char* set = axis == 1 ? "cut_0" : "cut_1";
      if (holds_plane(scene, static_cast<int>(b), axis, origin[axis], set)) continue;
      const char* name = axis == 0 ? "x" : "y";
      warn(body.where, "bodies." + body.name + ".mesh.sectors",
           std::string("a ") + (sectors == 1 ? "quarter" : "half") +
               " mesh (sectors = " + std::to_string(sectors) +
               ") with no [[constraints]] holding its nodes on the cut "
               "plane " +
               name + " = " + num(origin[axis]) + " along " + name +
               ": it is free to drift off the symmetry plane; add nodes = { plane = { point = "
               "[...], normal = [...] } } with fixed = [\"" +
               name + "\"]");
    }
  }
}

// Under the gauge form an empty cell reads as the ambient pressure, so an explosion's
// products, expanding far below it, clump until they hold it and the bubble never slows
// (docs/explosives.md, "The bubble period").
void warn_gauge_far_field_explosive(const Scene& scene, Warner& warn) {
  if (scene.mpm.grid.far_field && !scene.mpm.grid.far_field->absolute_stress) {
    for (const BodySpec& body : scene.bodies) {
      if (body.material < 0 ||
          !scene.materials[static_cast<std::size_t>(body.material)].is_explosive())
        continue;
      warn(scene.grid_where, "grid.far_field.stress",
           "the far field's gauge stress holds the products of explosive body \"" + body.name +
               "\" at the ambient pressure once they expand below it, and the bubble does not "
               "slow down; for the bubble's period use stress = \"absolute\" (water at 2 "
               "particles per cell direction)");
      break;
    }
  }
}

// The far field's absolute stress holds a prestressed body under its pressure in the internal
// force, which destabilises its zero-energy modes unless its bulk modulus dwarfs the pressure:
// water at 10-20 MPa (K / p = 135-270) stays still at 2 particles per cell direction, a gas
// at 10 MPa (K = 1.4 p) was thrown between 3 and 30 MPa (mpm/absorbing_faces.hpp).
void warn_absolute_far_field_prestress(const Scene& scene, Warner& warn) {
  if (scene.mpm.grid.far_field && scene.mpm.grid.far_field->absolute_stress) {
    for (const BodySpec& body : scene.bodies) {
      if (!body.pressure || !(*body.pressure > 0.0) || body.material < 0) continue;
      const Material& mat = scene.materials[static_cast<std::size_t>(body.material)];
      const std::optional<double> mu =
          compression_at_pressure(mat, *body.pressure, body.internal_energy);
      if (!mu) continue;  // refused elsewhere, with its reason
      PointState start;
      start.density = mat.density * (1.0 + *mu);
      start.energy = body.internal_energy;
      const double c = wave_speed(mat, start);
      const double k = start.density * c * c;
      if (k < 10.0 * *body.pressure)
        warn(body.where, "bodies." + body.name + ".pressure",
             "under grid.far_field.stress = \"absolute\" the body starts at pressure " +
                 num(*body.pressure) + " with a bulk modulus of only " + num(k) +
                 " (below 10 times it): the prestress makes its particles' zero-energy modes "
                 "grow (a gas near the ambient); use stress = \"gauge\" for it");
    }
  }
}

}  // namespace

std::string SceneWarning::text() const {
  return where.file + ":" + std::to_string(where.line) + ": key '" + key + "': " + message;
}

// An imported scene whose deck held what changes the run and was not translated (written by
// `afemp import --allow-untranslated`): each such keyword, so that the scene does not pass
// for the deck.
void warn_untranslated(const Scene& scene, Warner& warn) {
  for (const std::string& line : scene.run.untranslated)
    warn(scene.run.untranslated_where, "run.untranslated",
         "this scene does not run as the deck it was imported from: " + line);
}

// The total-Lagrangian form keeps each particle's reference neighbours for the whole run: a
// material that fails or erodes cannot come apart in it (a penetration, a fragmenting plate),
// and the failed points keep pulling on their reference neighbours through the grid.
void warn_total_lagrangian_failure(const Scene& scene, Warner& warn) {
  if (scene.mpm.formulation != Formulation::total_lagrangian) return;
  for (const BodySpec& body : scene.bodies) {
    if (body.material < 0) continue;
    const Material& m = scene.materials[static_cast<std::size_t>(body.material)];
    if (!m.fails()) continue;
    warn(
        body.where, "mpm.formulation",
        "body \"" + body.name +
            "\" has a failure model, and the total-Lagrangian form keeps each "
            "particle's reference neighbours: failed material does not come apart (no perforation, "
            "no fragments); use formulation = \"updated-lagrangian\" where it must");
    break;
  }
}

// The mixed u-p pressure averages det F over two layers of nodes: for a compressible solid that
// smooths a volumetric strain that is really there. Measured on the cantilever of
// tests/mpm/test_mixed_pressure.cpp at nu = 0.3: first bending period +7.1 % (quadratic
// B-spline) of the B-bar hexahedra's, against +3.1 % point-wise; at nu = 0.499 it is what
// removes the locking.
void warn_mixed_pressure_compressible(const Scene& scene, Warner& warn) {
  if (scene.mpm.pressure != PressureField::mixed) return;
  for (const BodySpec& body : scene.bodies) {
    if (body.material < 0) continue;
    const Material& m = scene.materials[static_cast<std::size_t>(body.material)];
    if (m.poisson_ratio >= 0.45) continue;
    warn(body.where, "mpm.pressure",
         "body \"" + body.name + "\" is of material \"" + m.name +
             "\" with nu = " + num(m.poisson_ratio) +
             ": the mixed pressure averages the volume change over neighbouring nodes, which "
             "softens a compressible solid (a beam at nu = 0.3 bent 7 % slower than the B-bar "
             "hexahedra); it is meant for nearly incompressible ones (nu near 0.5); use pressure "
             "= \"standard\" here");
    break;
  }
}

// Hexahedra of a nearly incompressible solid at more than half LS-DYNA's step rule
// (core/nearly_incompressible.hpp).
void warn_nearly_incompressible_step(const Scene& scene, Warner& warn) {
  if (scene.run.element_time_step_factor <= nearly_incompressible::element_step_factor) return;
  for (const BodySpec& body : scene.bodies) {
    if (body.material < 0 || body.discretisation != Discretisation::hexahedra || body.rigid)
      continue;
    const Material& m = scene.materials[static_cast<std::size_t>(body.material)];
    if (m.poisson_ratio <= nearly_incompressible::poisson_ratio) continue;
    warn(body.where, "run.element_time_step_factor",
         "body \"" + body.name + "\" is of hexahedra of material \"" + m.name +
             "\" with nu = " + num(m.poisson_ratio) + ", and the element step factor is " +
             num(scene.run.element_time_step_factor) +
             ": hexahedra of a nearly incompressible solid ring above half the usual step (a "
             "twisting column at nu = 0.499 gained 128 % of its energy at 0.9); give [run] "
             "element_time_step_factor = " +
             num(nearly_incompressible::element_step_factor));
    break;
  }
}

std::vector<SceneWarning> plausibility_warnings(const Scene& scene) {
  Warner warn(scene);
  warn_untranslated(scene, warn);
  warn_material_units(scene, warn);
  warn_unstated_units(scene, warn);
  warn_erosion_strain(scene, warn);
  warn_grid_cells(scene, warn);
  warn_unheld_cut_planes(scene, warn);
  warn_gauge_far_field_explosive(scene, warn);
  warn_absolute_far_field_prestress(scene, warn);
  warn_total_lagrangian_failure(scene, warn);
  warn_mixed_pressure_compressible(scene, warn);
  warn_nearly_incompressible_step(scene, warn);
  return warn.take();
}

}  // namespace afemp::core
