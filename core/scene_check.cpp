// Checks of a scene built in code (afemp::Simulation): the same ranges and rules the scene-file
// parser (scene_parser.cpp) applies as it reads, on the plain data, with messages that name the
// object and the field by the scene file's dotted key and say what is allowed.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <variant>

#include "core/axisymmetric_refusals.hpp"
#include "core/far_field_refusals.hpp"
#include "core/materials/initial_pressure.hpp"
#include "core/mixed_pressure_refusals.hpp"
#include "core/phases.hpp"
#include "core/reproducible_refusals.hpp"
#include "core/scene.hpp"
#include "core/scene_parser.hpp"
#include "core/scene_ranges.hpp"
#include "core/shape_function_refusals.hpp"
#include "core/total_lagrangian_refusals.hpp"

namespace afemp::core {

namespace {

class Checker {
 public:
  explicit Checker(const Scene& scene) : scene_(scene) {}

  [[noreturn]] void fail(const SourceLocation& where, const std::string& key,
                         const std::string& message) const {
    SourceLocation at = where;
    if (at.file.empty()) at.file = scene_.path.empty() ? "scene built in code" : scene_.path;
    throw InputError(at, key, message);
  }
  // The parser's Range and message (scene_parser.cpp), on a value built in code.
  void range(const SourceLocation& where, const std::string& key, double v,
             const scene_detail::Range& allowed) const {
    if (!allowed.contains(v))
      fail(where, key,
           "value " + scene_detail::format_number(v) +
               " is out of range; allowed: " + allowed.describe());
  }
  // A whole number within its Count, with the parser's message.
  void count(const SourceLocation& where, const std::string& key, long v,
             const scene_ranges::Count& allowed) const {
    if (!allowed.contains(v))
      fail(where, key,
           "value " + std::to_string(v) + " is out of range; allowed: " +
               (allowed.hi == std::numeric_limits<long>::max()
                    ? "value >= " + std::to_string(allowed.lo)
                    : std::to_string(allowed.lo) + " <= value <= " + std::to_string(allowed.hi)));
  }
  void finite(const SourceLocation& w, const std::string& key, const Vec3& v) const {
    if (!std::isfinite(v.x + v.y + v.z)) fail(w, key, "every component must be a finite number");
  }
  int body(const SourceLocation& w, const std::string& key, int index, bool mesh_only) const {
    if (index < 0 || static_cast<std::size_t>(index) >= scene_.bodies.size())
      fail(w, key,
           "body index " + std::to_string(index) + " is not defined; the scene has " +
               std::to_string(scene_.bodies.size()) + " bodies");
    if (mesh_only &&
        scene_.bodies[static_cast<std::size_t>(index)].discretisation == Discretisation::particles)
      fail(w, key,
           "body \"" + scene_.bodies[static_cast<std::size_t>(index)].name +
               "\" is made of particles; this applies to mesh bodies");
    return index;
  }

 private:
  const Scene& scene_;
};

void check_run(const Checker& c, const RunSettings& run) {
  namespace range = scene_ranges::run;
  const SourceLocation w;
  c.range(w, "run.end_time", run.end_time, range::end_time);
  c.range(w, "run.time_step_factor", run.time_step_factor, range::time_step_factor);
  c.range(w, "run.element_time_step_factor", run.element_time_step_factor,
          range::element_time_step_factor);
  // 0: not given (the stable step; history_every's rows).
  if (run.fixed_time_step != 0.0)
    c.range(w, "run.time_step", run.fixed_time_step, range::time_step);
  c.count(w, "run.max_steps", run.max_steps, range::max_steps);
  c.range(w, "run.output_every", run.output_every, range::output_every);
  c.count(w, "run.history_every", run.history_every, range::history_every);
  if (run.history_interval != 0.0)
    c.range(w, "run.history_interval", run.history_interval, range::history_interval);
  for (std::size_t k = 0; k < run.output_times.size(); ++k)
    if (!range::output_times.contains(run.output_times[k]) ||
        !(run.output_times[k] > (k > 0 ? run.output_times[k - 1] : 0.0)) ||
        run.output_times[k] > run.end_time)
      c.fail(w, "run.output_times", "times must be positive, increasing and at most end_time");
  c.range(w, "run.energy_error_limit", run.energy_error_limit, range::energy_error_limit);
  c.finite(w, "run.gravity", run.gravity);
  if (!run.units.empty() &&
      std::find(scene_ranges::kUnitSystems.begin(), scene_ranges::kUnitSystems.end(), run.units) ==
          scene_ranges::kUnitSystems.end())
    c.fail(w, "run.units",
           "unknown unit system \"" + run.units + "\"; allowed: \"mm-ms-g\", \"SI\"");
  c.range(w, "run.checkpoint_every", run.checkpoint_every, range::checkpoint_every);
  c.range(w, "run.checkpoint_wall_every", run.checkpoint_wall_every, range::checkpoint_wall_every);
  c.count(w, "run.checkpoint_keep", run.checkpoint_keep, range::checkpoint_keep);
}

void check_grid(const Checker& c, const Scene& scene) {
  const SourceLocation w;
  const GridSettings& g = scene.mpm.grid;
  if (has_particles(scene) && !scene.has_grid)
    c.fail(w, "grid", "bodies of particles need a grid (has_grid, cell, min, max)");
  if (!scene.has_grid) return;
  c.range(w, "grid.cell", g.cell, scene_ranges::grid::cell);
  c.finite(w, "grid.min", g.min);
  c.finite(w, "grid.max", g.max);
  for (int a = 0; a < 3; ++a)
    if (!(g.max[a] > g.min[a]))
      c.fail(w, "grid.max",
             "max must exceed min in every component; component " + std::to_string(a));
  c.range(w, "mpm.flip", scene.mpm.flip, scene_ranges::mpm::flip);
  if (const std::optional<SplittingSettings>& split = scene.mpm.splitting) {
    c.range(w, "mpm.splitting.alpha", split->alpha, scene_ranges::mpm::split_alpha);
    c.count(w, "mpm.splitting.max_particles", static_cast<long>(split->max_particles),
            scene_ranges::mpm::split_max_particles);
    if (!split->axes[0] && !split->axes[1] && !split->axes[2])
      c.fail(w, "mpm.splitting.axes", "name at least one axis (x, y, z)");
    for (int b : split->bodies)
      if (c.body(w, "mpm.splitting.bodies", b, false) >= 0 &&
          scene.bodies[static_cast<std::size_t>(b)].discretisation != Discretisation::particles)
        c.fail(w, "mpm.splitting.bodies", "only bodies of particles split");
  }
  if (const std::optional<std::string> why =
          apic_shape_refusal(scene.mpm.shape, scene.mpm.transfer))
    c.fail(w, "mpm.transfer", *why);
  if (scene.mpm.splitting)
    if (const std::optional<std::string> why = cpdi_splitting_refusal(scene.mpm.shape))
      c.fail(w, "mpm.splitting", *why);
  if (const auto why = total_lagrangian_mpm_refusal(scene.mpm))
    c.fail(w, "mpm." + why->first, why->second);
  if (const auto why = total_lagrangian_scene_refusal(scene)) c.fail(w, why->first, why->second);
  if (const auto why = mixed_pressure_mpm_refusal(scene.mpm))
    c.fail(w, "mpm." + why->first, why->second);
  if (const auto why = mixed_pressure_scene_refusal(scene)) c.fail(w, why->first, why->second);
  if (const std::optional<std::string> why = spline_grid_refusal(g, scene.mpm.shape))
    c.fail(w, "mpm.shape_function", *why);
  if (const std::optional<std::string> why = absorbing_face_shape_refusal(g, scene.mpm.shape))
    c.fail(w, "mpm.shape_function", *why);
  bool converts = false;
  for (const BodySpec& b : scene.bodies) converts = converts || b.conversion.has_value();
  for (int f = 0; f < 6; ++f)
    if ((g.faces[static_cast<std::size_t>(f)] == FaceCondition::outflow ||
         g.faces[static_cast<std::size_t>(f)] == FaceCondition::absorbing) &&
        !has_particles(scene) && !converts)
      c.fail(w, std::string("grid.boundary.") + to_string(static_cast<Face>(f)),
             std::string("\"") + to_string(g.faces[static_cast<std::size_t>(f)]) +
                 "\" acts on particles, and the scene has none (no particle body, no "
                 "conversion); allowed here: \"free\", \"fixed\", \"symmetric\", \"wall\"");
  if (g.far_field) {
    c.finite(w, "grid.far_field.centre", g.far_field->centre);
    c.range(w, "grid.far_field.pressure", g.far_field->pressure,
            scene_ranges::grid::far_field_pressure);
    if (!g.has_face(FaceCondition::absorbing))
      c.fail(w, "grid.far_field",
             "the far field acts through absorbing faces, and no face of "
             "grid.boundary is \"absorbing\"");
    for (const BodySpec& b : scene.bodies)
      if (b.discretisation != Discretisation::particles)
        c.fail(w, "grid.far_field",
               "the far field's ambient pressure acts on bodies of particles, and body \"" +
                   b.name + "\" is of " + to_string(b.discretisation) +
                   "; model the fluid and what it surrounds as particles");
    for (const BodySpec& b : scene.bodies)
      if (const std::optional<std::string> why = absolute_stress_lattice_refusal(g, b))
        c.fail(b.where, "bodies." + b.name + ".particles_per_cell", *why);
    if (const std::optional<std::string> why = absolute_stress_shape_refusal(g, scene.mpm.shape))
      c.fail(w, "mpm.shape_function", *why);
  }
}

void check_material(const Checker& c, const Material& m) {
  const SourceLocation w;
  const std::string key = "materials." + (m.name.empty() ? std::string("(unnamed)") : m.name);
  namespace range = scene_ranges::material;
  if (m.name.empty()) c.fail(w, key + ".name", "a material name must not be empty");
  c.range(w, key + ".density", m.density, range::density);
  // A fluid may leave out E and nu (0), as the parser allows: it has no shear.
  if (!(std::holds_alternative<Fluid>(m.strength) && m.youngs_modulus == 0.0))
    c.range(w, key + ".E", m.youngs_modulus, range::youngs_modulus);
  c.range(w, key + ".nu", m.poisson_ratio, range::poisson_ratio);
  c.range(w, key + ".specific_heat", m.thermal.specific_heat, range::specific_heat);
  c.range(w, key + ".taylor_quinney", m.thermal.taylor_quinney, range::taylor_quinney);
  c.range(w, key + ".temperature", m.thermal.initial_temperature, range::temperature);
  c.range(w, key + ".failure_strain", m.failure_strain, range::failure_strain);
  // The scene file's failure_strain is short for the plastic-strain failure model, which the
  // solvers' points fail by; a program gives the model with it.
  if (m.failure_strain > 0.0 &&
      !(std::holds_alternative<PlasticStrainFailure>(m.failure) &&
        std::get<PlasticStrainFailure>(m.failure).strain == m.failure_strain))
    c.fail(w, key + ".failure_strain",
           "a failure_strain is the failure model PlasticStrainFailure{failure_strain} (the scene "
           "file's short form of failure = { model = \"plastic-strain\" }); set failure to it, "
           "or give the failure model alone");
  if (m.pressure_cutoff != -std::numeric_limits<double>::infinity())
    c.range(w, key + ".pressure_cutoff", m.pressure_cutoff, range::pressure_cutoff);
  if (const std::optional<std::string> why = pressure_cutoff_refusal(m))
    c.fail(w, key + ".pressure_cutoff", *why);
  try {
    m.validate();
  } catch (const std::invalid_argument& e) {
    c.fail(w, key, e.what());
  }
}

void check_shape(const Checker& c, const BodySpec& b, const std::string& key) {
  using D = Discretisation;
  const bool particles = b.discretisation == D::particles;
  const bool hexes = b.discretisation == D::hexahedra;
  const std::string shape = key + ".shape";
  if (const auto* box = std::get_if<BoxShape>(&b.shape)) {
    if (b.discretisation == D::trusses)
      c.fail(b.where, shape, "a box makes particles or hexahedra");
    for (int a = 0; a < 3; ++a)
      if (!(box->max[a] > box->min[a]))
        c.fail(b.where, shape + ".box.max", "max must exceed min in every component");
  } else if (const auto* cyl = std::get_if<CylinderShape>(&b.shape)) {
    if (b.discretisation == D::trusses)
      c.fail(b.where, shape, "a cylinder makes particles or hexahedra");
    if (cyl->top_radius >= 0.0 && !particles)
      c.fail(b.where, shape + ".cone", "a cone makes particles only");
    namespace range = scene_ranges::shape;
    const bool cone = cyl->top_radius >= 0.0;
    const std::string at = shape + (cone ? ".cone" : ".cylinder");
    if (cone) {
      c.range(b.where, at + ".radius", cyl->radius, range::cone_radius);
      c.range(b.where, at + ".top_radius", cyl->top_radius, range::cone_radius);
      c.range(b.where, at + ".wall", cyl->wall, range::cone_wall);
    } else {
      c.range(b.where, at + ".radius", cyl->radius, range::radius);
    }
    c.range(b.where, at + ".length", cyl->length, range::length);
    if (!(norm(cyl->axis) > 0.0))
      c.fail(b.where, at + ".axis", "the axis must be a non-zero vector");
    if (cyl->nose.crh != 0.0) {
      c.range(b.where, at + ".nose.crh", cyl->nose.crh, range::nose_crh);
      c.range(b.where, at + ".nose.meplat", cyl->nose.meplat, range::nose_meplat);
      if (!(cyl->nose.meplat < 2.0 * cyl->radius))
        c.fail(b.where, at + ".nose.meplat",
               "the flat tip's diameter must be less than the cylinder's");
      if (hexes && !(cyl->nose.meplat > 0.0))
        c.fail(b.where, at + ".nose.meplat",
               "a nose meshed with hexahedra needs a flat tip (meplat > 0)");
    }
  } else if (const auto* s = std::get_if<SphereShape>(&b.shape)) {
    if (b.discretisation == D::trusses)
      c.fail(b.where, shape, "a sphere makes particles or hexahedra");
    c.range(b.where, shape + ".sphere.radius", s->radius, scene_ranges::shape::radius);
  } else if (const auto* p = std::get_if<PointListShape>(&b.shape)) {
    if (!particles) c.fail(b.where, shape, "points make particles only");
    if (p->path.empty() && p->points.empty())
      c.fail(b.where, shape + ".points", "give a points file or the points themselves");
    if (!p->volumes.empty() && p->volumes.size() != p->points.size())
      c.fail(b.where, shape + ".points.volumes",
             "one volume per point (" + std::to_string(p->points.size()) + "), or none");
    for (double v : p->volumes)
      if (!(v > 0.0)) c.fail(b.where, shape + ".points.volumes", "every volume must be > 0");
  } else if (const auto* m = std::get_if<MeshFileShape>(&b.shape)) {
    if (particles) c.fail(b.where, shape, "a mesh makes hexahedra or trusses, not particles");
    if (m->path.empty()) {
      const MeshArrays& a = m->arrays;
      if (hexes ? a.hexahedra.empty() : a.trusses.empty())
        c.fail(b.where, shape + ".mesh",
               std::string("the arrays hold no ") + (hexes ? "hexahedra" : "trusses"));
      if (!a.truss_areas.empty() && a.truss_areas.size() != a.trusses.size())
        c.fail(b.where, shape + ".mesh.truss_areas",
               "one area per truss (" + std::to_string(a.trusses.size()) + "), or none");
    }
    c.range(b.where, shape + ".mesh.scale", m->scale, scene_ranges::shape::mesh_scale);
  } else if (std::holds_alternative<LineShape>(b.shape) ||
             std::holds_alternative<RebarShape>(b.shape)) {
    if (b.discretisation != D::trusses) c.fail(b.where, shape, "lines and rebar make trusses only");
    if (const auto* r = std::get_if<RebarShape>(&b.shape)) {
      namespace range = scene_ranges::shape;
      c.range(b.where, shape + ".rebar.spacing", r->spacing, range::rebar_spacing);
      c.range(b.where, shape + ".rebar.diameter", r->diameter, range::rebar_diameter);
      c.range(b.where, shape + ".rebar.cover", r->cover, range::rebar_cover);
    }
  }
}

// A generated mesh's density (the parser's read_mesh_density): 0 is "not given".
void check_mesh_density(const Checker& c, const BodySpec& b, const std::string& key) {
  namespace range = scene_ranges::mesh;
  const MeshDensity& m = b.mesh;
  if (m.size != 0.0) c.range(b.where, key + ".size", m.size, range::size);
  const auto given = [&](const char* name, int v, const scene_ranges::Count& allowed) {
    if (v != 0) c.count(b.where, key + "." + name, v, allowed);
  };
  const bool sphere = std::holds_alternative<SphereShape>(b.shape);
  given(sphere ? "across" : "divisions", m.divisions[0], sphere ? range::across : range::divisions);
  given("divisions", m.divisions[1], range::divisions);
  given("divisions", m.divisions[2], range::divisions);
  given("core", m.core, range::core);
  given("ring", m.ring, range::ring);
  given("axial", m.axial, range::axial);
  given("segments", m.segments, range::segments);
  c.count(b.where, key + ".sectors", m.sectors, range::sectors);
  if (m.sectors == 3) c.fail(b.where, key + ".sectors", "allowed: 1 (quarter), 2 (half), 4 (full)");
  if (sphere && m.divisions[0] % 4 != 0)
    c.fail(b.where, key + ".across", "must be a multiple of 4");
}

void check_body(const Checker& c, const Scene& scene, const BodySpec& b) {
  using D = Discretisation;
  const std::string key = "bodies." + (b.name.empty() ? std::string("(unnamed)") : b.name);
  if (b.name.empty()) c.fail(b.where, key + ".name", "a body name must not be empty");
  if (b.material < 0 || static_cast<std::size_t>(b.material) >= scene.materials.size())
    c.fail(b.where, key + ".material",
           "material index " + std::to_string(b.material) + " is not defined; the scene has " +
               std::to_string(scene.materials.size()) + " materials");
  namespace range = scene_ranges::body;
  // A hyperelastic model reads the deformation gradient: particles carry it, hexahedra take it
  // from their nodes; trusses have none, and a particle made from a hexahedron would start
  // from an unstrained F.
  if (const Material& m = scene.materials[static_cast<std::size_t>(b.material)];
      m.reads_deformation_gradient()) {
    if (b.discretisation == D::trusses)
      c.fail(b.where, key + ".material",
             "the strength model of material \"" + m.name +
                 "\" is hyperelastic and reads the deformation gradient, and body \"" + b.name +
                 "\" is of trusses, which have none; give it to bodies of particles or "
                 "hexahedra, or use a hypoelastic model (elastic, j2, johnson-cook) for trusses");
    if (b.discretisation == D::hexahedra && b.conversion)
      c.fail(b.where, key + ".conversion",
             "body \"" + b.name + "\" has a hyperelastic material (\"" + m.name +
                 "\"), whose hexahedra would convert into particles without their deformation "
                 "gradient; leave conversion out, or use a hypoelastic model");
  }
  check_shape(c, b, key);
  for (int o : b.overlap_allowed) {
    c.body(b.where, key + ".overlap_allowed", o, false);
    if (scene.bodies[static_cast<std::size_t>(o)].name == b.name)
      c.fail(b.where, key + ".overlap_allowed",
             "a body is not checked against itself; name other bodies");
  }
  c.finite(b.where, key + ".velocity", b.velocity);
  if (b.temperature) c.range(b.where, key + ".temperature", *b.temperature, range::temperature);
  c.range(b.where, key + ".internal_energy", b.internal_energy, range::internal_energy);
  if (b.pressure) {
    c.range(b.where, key + ".pressure", *b.pressure, range::pressure);
    if (b.discretisation != D::particles)
      c.fail(b.where, key + ".pressure", "an initial pressure applies to bodies of particles");
    if (b.material >= 0 && static_cast<std::size_t>(b.material) < scene.materials.size())
      if (const std::optional<std::string> why =
              initial_pressure_refusal(scene.materials[static_cast<std::size_t>(b.material)],
                                       *b.pressure, b.internal_energy))
        c.fail(b.where, key + ".pressure", *why);
  }
  if (b.prestress != 0.0) {
    c.range(b.where, key + ".prestress", b.prestress, range::prestress);
    if (b.discretisation != D::trusses)
      c.fail(b.where, key + ".prestress", "a prestress applies to bodies of trusses");
  }
  if (b.initial_stress) {
    if (!std::isfinite(b.initial_stress->surface))
      c.fail(b.where, key + ".initial_stress.surface", "must be a finite number");
    c.range(b.where, key + ".initial_stress.K0", b.initial_stress->k0,
            range::earth_pressure_at_rest);
    if (b.discretisation == D::trusses)
      c.fail(b.where, key + ".initial_stress",
             "a geostatic initial stress applies to bodies of particles or hexahedra");
    if (b.material >= 0 && static_cast<std::size_t>(b.material) < scene.materials.size())
      if (const std::optional<std::string> why =
              geostatic_stress_refusal(scene.materials[static_cast<std::size_t>(b.material)],
                                       scene.run.gravity, b.pressure.has_value()))
        c.fail(b.where, key + ".initial_stress", *why);
  }
  c.count(b.where, key + ".particles_per_cell", b.particles_per_cell, range::particles_per_cell);
  if (b.layout == BodySpec::Layout::shells && !std::holds_alternative<SphereShape>(b.shape))
    c.fail(b.where, key + ".layout",
           "layout shells places particles in shells that follow a sphere; the body's shape is "
           "not a sphere");
  if (b.bulk_viscosity) {
    if (b.discretisation == D::trusses)
      c.fail(b.where, key + ".bulk_viscosity", "applies to bodies of hexahedra or particles");
    c.range(b.where, key + ".bulk_viscosity.linear", b.bulk_viscosity->linear, range::bulk_linear);
    c.range(b.where, key + ".bulk_viscosity.quadratic", b.bulk_viscosity->quadratic,
            range::bulk_quadratic);
  }
  if (b.material >= 0 && static_cast<std::size_t>(b.material) < scene.materials.size()) {
    const Material& m = scene.materials[static_cast<std::size_t>(b.material)];
    if (const std::optional<FailureKeyRefusal> refusal = failure_key_refusal(b, m))
      c.fail(b.where, (refusal->of_material ? "materials." + m.name : key) + "." + refusal->key,
             refusal->message);
  }
  if (b.rigid && b.discretisation != D::hexahedra)
    c.fail(b.where, key + ".rigid", "a rigid body is made of hexahedra");
  if (b.rigid && (b.erosion || b.conversion || b.bonded_to >= 0))
    c.fail(b.where, key + ".rigid",
           "a rigid body's elements carry no stress; it cannot erode, "
           "convert or bond");
  if (b.discretisation == D::particles) {
    if (b.erosion || b.conversion || b.bonded_to >= 0)
      c.fail(b.where,
             key + (b.erosion      ? ".erosion"
                    : b.conversion ? ".conversion"
                                   : ".bonded_to"),
             "applies to mesh bodies, not to particles");
    return;
  }
  if (b.discretisation == D::hexahedra && b.hourglass.coefficient)
    c.range(b.where, key + ".hourglass.coefficient", *b.hourglass.coefficient,
            range::hourglass_range(b.hourglass.form));
  check_mesh_density(c, b, key + ".mesh");
  const bool generated = !std::holds_alternative<MeshFileShape>(b.shape);
  const bool all_graded =
      !b.mesh.graded[0].empty() && !b.mesh.graded[1].empty() && !b.mesh.graded[2].empty();
  if (generated && !(b.mesh.size > 0.0) && b.mesh.divisions[0] == 0 && !all_graded &&
      (b.mesh.core == 0 || b.mesh.ring == 0 || b.mesh.axial == 0) && b.mesh.segments == 0)
    c.fail(b.where, key + ".mesh", "a generated mesh needs its density: a size or divisions");
  if (b.erosion) {
    namespace erosion = scene_ranges::erosion;
    c.range(b.where, key + ".erosion.plastic_strain", b.erosion->plastic_strain,
            erosion::plastic_strain);
    c.range(b.where, key + ".erosion.volume_ratio", b.erosion->volume_ratio, erosion::volume_ratio);
    c.range(b.where, key + ".erosion.time_step", b.erosion->time_step, erosion::time_step);
  }
  if (b.conversion) {
    if (b.discretisation != D::hexahedra)
      c.fail(b.where, key + ".conversion", "applies to bodies of hexahedra");
    if (!scene.has_grid)
      c.fail(b.where, key + ".conversion",
             "converted elements become particles on the "
             "background grid; the scene needs a grid");
    if (b.bonded_to >= 0)
      c.fail(b.where, key + ".conversion", "a body bonded to particles cannot also convert");
    if (scene.mpm.scheme == UpdateScheme::USL || scene.mpm.scheme == UpdateScheme::USAVG)
      c.fail(b.where, key + ".conversion", "conversion needs [mpm] scheme MUSL or USF");
    namespace conversion = scene_ranges::conversion;
    const ConversionSettings& v = *b.conversion;
    const std::string at = key + ".conversion";
    c.range(b.where, at + ".plastic_strain", v.plastic_strain, conversion::plastic_strain);
    c.range(b.where, at + ".volumetric_strain", v.volumetric_strain, conversion::volumetric_strain);
    c.range(b.where, at + ".jacobian_ratio", v.jacobian_ratio, conversion::jacobian_ratio);
    c.range(b.where, at + ".time_step_fraction", v.time_step_fraction,
            conversion::time_step_fraction);
    c.range(b.where, at + ".damage", v.damage, conversion::damage);
    c.count(b.where, at + ".points", v.points, conversion::points);
    if (const std::optional<std::string> why = no_conversion_criterion(v))
      c.fail(b.where, at, *why);
  }
  if (b.area != 0.0) c.range(b.where, key + ".area", b.area, range::area);
  if (b.discretisation == D::trusses && std::holds_alternative<LineShape>(b.shape) &&
      !(b.area > 0.0))
    c.fail(b.where, key + ".area", "a truss line needs its cross-section area (> 0)");
  if (b.bonded_to >= 0) {
    if (static_cast<std::size_t>(b.bonded_to) >= scene.bodies.size() ||
        &scene.bodies[static_cast<std::size_t>(b.bonded_to)] == &b)
      c.fail(b.where, key + ".bonded_to", "names no other body of the scene");
    const BodySpec& host = scene.bodies[static_cast<std::size_t>(b.bonded_to)];
    if (host.discretisation == D::hexahedra) {
      if (b.discretisation != D::trusses)
        c.fail(b.where, key + ".bonded_to",
               "only trusses are tied into hexahedra; a mesh body bonds to a body of particles");
      if (host.rigid || host.bonded_to >= 0)
        c.fail(b.where, key + ".bonded_to",
               "trusses are tied into a deformable body of hexahedra that is bonded to nothing");
      if (b.velocity.x != 0.0 || b.velocity.y != 0.0 || b.velocity.z != 0.0)
        c.fail(b.where, key + ".velocity",
               "a body tied into hexahedra moves with its host from the start; give the "
               "velocity to \"" +
                   host.name + "\"");
    } else if (host.discretisation != D::particles) {
      c.fail(b.where, key + ".bonded_to",
             "a mesh body bonds to a body of particles, or trusses are tied into hexahedra");
    } else if (scene.mpm.scheme == UpdateScheme::USL || scene.mpm.scheme == UpdateScheme::USAVG) {
      c.fail(b.where, key + ".bonded_to", "bonded coupling needs [mpm] scheme MUSL or USF");
    }
  }
}

}  // namespace

BulkViscositySettings bulk_viscosity_of(const Scene& scene, const BodySpec& body) {
  if (body.bulk_viscosity) return *body.bulk_viscosity;
  const bool with_eos = body.material >= 0 &&
                        static_cast<std::size_t>(body.material) < scene.materials.size() &&
                        scene.materials[static_cast<std::size_t>(body.material)].has_eos();
  if (body.discretisation == Discretisation::hexahedra || with_eos) return BulkViscositySettings{};
  return BulkViscositySettings{0.0, 0.0};
}

std::optional<LoadRefusal> load_refusal(const Scene& scene, const LoadSpec& load) {
  if (load.body < 0 || static_cast<std::size_t>(load.body) >= scene.bodies.size()) return {};
  const BodySpec& b = scene.bodies[static_cast<std::size_t>(load.body)];
  const std::string name = "body \"" + b.name + "\"";
  if (b.discretisation == Discretisation::trusses)
    return LoadRefusal{"body", name +
                                   " is a body of trusses, which has no faces to load; loads "
                                   "act on hexahedra (a traction on their faces) and on "
                                   "particles (a force they share)"};
  if (b.bonded_to >= 0)
    return LoadRefusal{"body", name +
                                   " is bonded to particles and moves with the grid; load "
                                   "the particle body instead"};
  if (b.conversion)
    return LoadRefusal{"body", name +
                                   " converts elements into particles, whose nodes then move "
                                   "with the grid and would drop the load on their faces; "
                                   "load a body without `conversion`"};
  if (b.discretisation == Discretisation::particles) {
    if (load.region.kind != NodeSelector::Kind::box)
      return LoadRefusal{"particles", "particles are selected by a box = { min, max }"};
    if (load.traction)
      return LoadRefusal{"traction", name +
                                         " is made of particles, which carry no surface "
                                         "area: give the total force = [fx, fy, fz] that "
                                         "the particles in the box share by mass"};
  }
  return {};
}

void check_scene(const Scene& scene) {
  const Checker c(scene);
  check_run(c, scene.run);
  if (scene.bodies.empty()) c.fail({}, "bodies", "the scene has no body");
  std::set<std::string> names;
  for (const Material& m : scene.materials) {
    check_material(c, m);
    if (!names.insert(m.name).second)
      c.fail({}, "materials." + m.name, "duplicate material name \"" + m.name + "\"");
  }
  check_grid(c, scene);
  names.clear();
  for (const BodySpec& b : scene.bodies) {
    check_body(c, scene, b);
    if (!names.insert(b.name).second)
      c.fail(b.where, "bodies." + b.name, "duplicate body name \"" + b.name + "\"");
  }
  for (std::size_t k = 0; k < scene.constraints.size(); ++k) {
    const ConstraintSpec& s = scene.constraints[k];
    const std::string key = "constraints[" + std::to_string(k) + "]";
    if (s.body >= 0) c.body(s.where, key + ".body", s.body, true);
    if (!s.components[0] && !s.components[1] && !s.components[2])
      c.fail(s.where, key + ".fixed", "name at least one component");
    if (s.nodes.kind == NodeSelector::Kind::plane && !(norm(s.nodes.normal) > 0.0))
      c.fail(s.where, key + ".plane.normal", "the normal must be a non-zero vector");
    if (s.nodes.kind == NodeSelector::Kind::plane)
      c.range(s.where, key + ".plane.tolerance", s.nodes.tolerance,
              scene_ranges::selector_tolerance);
  }
  for (std::size_t k = 0; k < scene.loads.size(); ++k) {
    const LoadSpec& l = scene.loads[k];
    const std::string key = "loads[" + std::to_string(k) + "]";
    c.body(l.where, key + ".body", l.body, false);
    if (const std::optional<LoadRefusal> why = load_refusal(scene, l))
      c.fail(l.where, key + "." + why->key, why->message);
    for (std::size_t i = 1; i < l.curve.size(); ++i)
      if (!(l.curve[i][0] > l.curve[i - 1][0]))
        c.fail(l.where, key + ".curve", "the times must increase");
  }
  for (std::size_t k = 0; k < scene.walls.size(); ++k) {
    const WallSpec& wl = scene.walls[k];
    const std::string key = "walls[" + std::to_string(k) + "]";
    if (!(norm(wl.normal) > 0.0))
      c.fail(wl.where, key + ".normal", "the normal must be a non-zero vector");
    c.range(wl.where, key + ".friction", wl.friction, scene_ranges::wall_friction);
    for (int b : wl.bodies) {
      c.body(wl.where, key + ".bodies", b, false);
      if (scene.bodies[static_cast<std::size_t>(b)].rigid)
        c.fail(wl.where, key + ".bodies", "walls act on deformable mesh bodies, not rigid ones");
    }
  }
  for (std::size_t k = 0; k < scene.contacts.size(); ++k) {
    const ContactSpec& ct = scene.contacts[k];
    const std::string key = "contact[" + std::to_string(k) + "]";
    const int a = c.body(ct.where, key + ".bodies", ct.bodies[0], false);
    const int b = c.body(ct.where, key + ".bodies", ct.bodies[1], false);
    const BodySpec& ba = scene.bodies[static_cast<std::size_t>(a)];
    const BodySpec& bb = scene.bodies[static_cast<std::size_t>(b)];
    const bool meshes = ba.discretisation != Discretisation::particles &&
                        bb.discretisation != Discretisation::particles;
    c.range(ct.where, key + ".friction", ct.friction, scene_ranges::contact::friction);
    if (!ct.name.empty())
      if (const std::optional<std::string> why = contact_name_refusal(ct.name))
        c.fail(ct.where, key + ".name", *why);
    if (ct.method == ContactMethod::weld) {
      if (a == b || ba.discretisation != Discretisation::particles ||
          bb.discretisation != Discretisation::particles)
        c.fail(ct.where, key + ".method", "a weld names two different bodies of particles");
      continue;
    }
    if (ct.method == ContactMethod::penalty) {
      if (!meshes) c.fail(ct.where, key + ".method", "penalty contact acts between meshes");
      if (ba.discretisation == Discretisation::trusses &&
          bb.discretisation == Discretisation::trusses)
        c.fail(ct.where, key + ".bodies", "penalty contact needs a body of hexahedra on one side");
      if (a == b && (ba.discretisation != Discretisation::hexahedra || ba.rigid))
        c.fail(ct.where, key + ".bodies", "self-contact needs a deformable body of hexahedra");
      c.range(ct.where, key + ".penalty", ct.penalty, scene_ranges::contact::penalty);
      continue;
    }
    if (ct.method == ContactMethod::surface) {
      const bool one_each = (ba.discretisation == Discretisation::particles) !=
                            (bb.discretisation == Discretisation::particles);
      const BodySpec& m = ba.discretisation == Discretisation::particles ? bb : ba;
      if (a == b || !one_each || m.discretisation != Discretisation::hexahedra)
        c.fail(ct.where, key + ".method",
               "surface contact is between a body of particles and a body of hexahedra");
      c.range(ct.where, key + ".penalty", ct.penalty, scene_ranges::contact::penalty);
      continue;
    }
    if (a == b) c.fail(ct.where, key + ".bodies", "a body cannot be in grid contact with itself");
    if (ba.rigid || bb.rigid)
      c.fail(ct.where, key + ".bodies", "grid contact with particles does not take rigid bodies");
    if (meshes)
      c.fail(ct.where, key + ".bodies",
             "both bodies are meshes; grid contact needs a particle "
             "body on one side (meshes meet by method penalty)");
    if (!scene.has_grid) c.fail(ct.where, key + ".bodies", "grid contact needs a grid");
    if (scene.mpm.scheme == UpdateScheme::USL)
      c.fail(ct.where, key + ".bodies", "grid contact needs [mpm] scheme MUSL or USF");
    if (scene.mpm.scheme == UpdateScheme::USAVG &&
        (ba.discretisation != Discretisation::particles ||
         bb.discretisation != Discretisation::particles))
      c.fail(ct.where, key + ".bodies",
             "grid contact of a mesh with particles needs [mpm] scheme MUSL or USF");
    c.range(ct.where, key + ".distance_factor", ct.distance_factor,
            scene_ranges::contact::distance_factor);
  }
  for (std::size_t k = 0; k < scene.detonations.size(); ++k)
    c.range(scene.detonations[k].where, "detonations[" + std::to_string(k) + "].time",
            scene.detonations[k].time, scene_ranges::detonation_time);
  scene_detail::check_explosives(scene);
  if (const std::optional<std::string> why = reproducible_refusal(scene))
    c.fail(scene.run.reproducible_where, "run.reproducible", *why);
  if (const std::optional<AxisymmetricRefusal> no = axisymmetric_refusal(scene))
    c.fail(no->where, no->key, no->why);
  for (const VelocityReference& v : scene.velocity_references) {
    c.body(v.where, "reference.velocity.body", v.body, false);
    if (v.value == 0.0) c.fail(v.where, "reference.velocity.value", "must not be 0");
    c.range(v.where, "reference.velocity.tolerance", v.tolerance,
            scene_ranges::reference::tolerance);
  }
  if (const std::optional<TaylorReference>& t = scene.taylor_reference) {
    namespace range = scene_ranges::reference;
    c.range({}, "reference.taylor.L", t->length, range::taylor_length);
    c.range({}, "reference.taylor.D", t->impact_diameter, range::taylor_length);
    c.range({}, "reference.taylor.W", t->bulge_diameter, range::taylor_length);
    c.range({}, "reference.taylor.tolerance", t->tolerance, range::tolerance);
  }
  if (scene.energy_tolerance != 0.0)
    c.range({}, "reference.energy.tolerance", scene.energy_tolerance,
            scene_ranges::reference::energy_tolerance);
  if (scene.run.terminate) {
    c.body({}, "run.terminate.body", scene.run.terminate->body, false);
    c.range({}, "run.terminate.travel", scene.run.terminate->travel,
            scene_ranges::run::terminate_travel);
  }
  check_phases(scene, [&](const SourceLocation& where, const std::string& key,
                          const std::string& message) { c.fail(where, key, message); });
}

}  // namespace afemp::core
