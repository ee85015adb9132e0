#include "mpm/step_plan.hpp"

#include <cstdio>
#include <set>
#include <sstream>

#include "core/materials/model_descriptions.hpp"
#include "core/scene.hpp"

namespace afemp::mpm {

namespace {

Stage stage(StageKind kind, std::string name, std::string why) {
  return {kind, std::move(name), std::move(why)};
}

// The plan's switches and the materials its bodies use.
void set_options(StepPlan& plan, const core::Scene& scene) {
  plan.scheme = scene.mpm.scheme;
  plan.shape = scene.mpm.shape;
  plan.transfer = scene.mpm.transfer;
  plan.flip = scene.mpm.flip;
  plan.strain = scene.run.output_strain;
  // Principal-strain failure reads the strain tensor of its particles, and of the particles
  // hexahedra convert into (coupling/element_conversion.cpp).
  for (const core::BodySpec& b : scene.bodies)
    if ((b.discretisation == core::Discretisation::particles || b.conversion) &&
        scene.materials[static_cast<std::size_t>(b.material)].needs_strain())
      plan.strain = true;
  plan.splitting = scene.mpm.splitting.has_value();
  plan.total_lagrangian = scene.mpm.formulation == core::Formulation::total_lagrangian;
  plan.mixed_pressure = scene.mpm.pressure == core::PressureField::mixed;
  plan.jaumann = scene.mpm.jaumann;
  const core::Vec3& g = scene.run.gravity;
  plan.gravity = g.x != 0.0 || g.y != 0.0 || g.z != 0.0;
  for (const core::LoadSpec& l : scene.loads)
    if (scene.bodies[static_cast<std::size_t>(l.body)].discretisation ==
        core::Discretisation::particles)
      ++plan.particle_loads;

  // The materials of particles: the particle bodies' and those of hexahedra that convert.
  std::set<int> used;
  for (const auto& b : scene.bodies)
    if (b.discretisation == core::Discretisation::particles || b.conversion)
      used.insert(b.material);
  plan.deformation_gradient = plan.total_lagrangian;
  for (int m : used)
    if (scene.materials[static_cast<std::size_t>(m)].reads_deformation_gradient())
      plan.deformation_gradient = true;
  for (int m : used) {
    const core::Material& mat = scene.materials[static_cast<std::size_t>(m)];
    plan.materials.push_back({mat.name, core::strength_description(mat.strength),
                              core::eos_description(mat.eos), mat.has_thermal_term(),
                              core::failure_description(mat), mat.reads_deformation_gradient()});
  }
}

// Velocity fields: one for each body in a contact, one shared by all the others; and the grid
// contacts' lines for describe().
void assign_velocity_fields(StepPlan& plan, const core::Scene& scene) {
  plan.field_of_body.assign(scene.bodies.size(), 0);
  std::vector<bool> in_contact(scene.bodies.size(), false);
  for (const auto& c : scene.contacts)
    if (c.method == core::ContactMethod::grid)
      for (int b : c.bodies) in_contact[static_cast<std::size_t>(b)] = true;
  bool shared = false;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    shared = shared || (!in_contact[b] &&
                        (scene.bodies[b].discretisation == core::Discretisation::particles ||
                         scene.bodies[b].conversion));
  int next = shared ? 1 : 0;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (in_contact[b]) plan.field_of_body[b] = next++;
  // Bonded mesh bodies (HFEMP) move in their host's field.
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (scene.bodies[b].bonded_to >= 0)
      plan.field_of_body[b] =
          plan.field_of_body[static_cast<std::size_t>(scene.bodies[b].bonded_to)];
  const bool contact = core::has_grid_contact(scene);
  plan.velocity_fields = contact ? next : 1;
  for (const auto& c : scene.contacts) {
    if (c.method != core::ContactMethod::grid) continue;
    std::ostringstream o;
    o << scene.bodies[static_cast<std::size_t>(c.bodies[0])].name << " - "
      << scene.bodies[static_cast<std::size_t>(c.bodies[1])].name << ": friction " << c.friction
      << ", contact once the gap is below " << c.distance_factor << " cell";
    plan.contacts.push_back(o.str());
  }
}

// The one stage every scheme runs the same way.
Stage grid_update_stage(const core::Scene& scene) {
  return stage(
      StageKind::grid_momentum_update, "grid momentum update",
      scene.mpm.grid.far_field
          ? std::string("explicit momentum update and boundary conditions; the far field's "
                        "ambient pressure is ") +
                (scene.mpm.grid.far_field->absolute_stress ? "a static traction on the faces"
                                                           : "taken off the internal force") +
                ", and absorbing faces answer as the unbounded fluid beyond (Geers 1978, DAA1)"
      : scene.mpm.grid.has_face(core::FaceCondition::absorbing)
          ? "explicit momentum update and boundary conditions; absorbing faces damp their "
            "nodes (Lysmer & Kuhlemeyer 1969)"
          : "explicit momentum update and boundary conditions");
}

// Rigid walls ([[walls]] naming particle bodies) act on the updated grid velocity, after grid
// contact, at the particles' boundary.
Stage walls_stage(const core::Scene& scene) {
  return stage(
      StageKind::particle_walls, "surface contact",
      std::string(core::has_particle_walls(scene) ? "rigid walls ([[walls]])" : "") +
          (core::has_particle_walls(scene) && core::has_surface_contact(scene) ? " and " : "") +
          (core::has_surface_contact(scene) ? "mesh faces ([[contact]] method \"surface\")" : "") +
          " met where the particles' boundary reaches them: the impulse that keeps each "
          "particle's predicted domain off them, through its nodes, Coulomb friction");
}

// The stages before the transfers: splitting, outflow, binning.
void append_particle_stages(StepPlan& plan, const core::Scene& scene) {
  auto& s = plan.stages;
  std::string outflow_faces;
  for (int f = 0; f < 6; ++f)
    if (scene.mpm.grid.faces[static_cast<std::size_t>(f)] == core::FaceCondition::outflow)
      outflow_faces += std::string(outflow_faces.empty() ? "" : ", ") +
                       core::to_string(static_cast<core::Face>(f));
  // Splitting before outflow: a child placed beyond an outflow face leaves with it.
  if (plan.splitting) {
    const core::SplittingSettings& split = *scene.mpm.splitting;
    std::string axes;
    for (int a = 0; a < 3; ++a)
      if (split.axes[static_cast<std::size_t>(a)]) axes += static_cast<char>('x' + a);
    char why[240];
    std::snprintf(why, sizeof why,
                  "a particle whose length along an axis (%s) reached %g x its initial length "
                  "splits in two along each such axis (at most %zu particles)",
                  axes.c_str(), 2.0 * split.alpha, split.max_particles);
    s.push_back(stage(StageKind::split_particles, "split particles", why));
  }
  if (!outflow_faces.empty())
    s.push_back(stage(StageKind::outflow, "outflow",
                      "particles beyond the outflow faces (" + outflow_faces +
                          ") leave the run; their mass, momentum and energy are booked"));
  s.push_back(stage(StageKind::bin_particles, "bin particles",
                    "cells of the points, active grid blocks, colour layers for the P2G sweep"));
}

// The scheme's transfers, forces, grid update and stress update, in its order.
void append_scheme_stages(StepPlan& plan, const core::Scene& scene) {
  using core::UpdateScheme;
  const bool contact = core::has_grid_contact(scene);
  const Stage surfaces =
      stage(StageKind::contact_surfaces, "contact surfaces",
            "grid contact: each contact body's normal from its mass "
            "gradient and its reach toward the other (Lian et al. 2013, eqs 37, 42)");
  const Stage grid_contact =
      stage(StageKind::grid_contact, "grid contact",
            "grid contact on the updated velocity: normal stop, Coulomb friction, separation "
            "(Lian et al. 2013, eqs 38-42)");

  std::string force_why = plan.gravity ? "internal force -V sigma.grad N and gravity m N g"
                                       : "internal force -V sigma.grad N (no body force)";
  if (plan.particle_loads > 0)
    force_why += "; the [[loads]] on particles, N f_p (" + std::to_string(plan.particle_loads) +
                 (plan.particle_loads == 1 ? " load" : " loads") + " shared by mass)";
  const Stage grid_update = grid_update_stage(scene);
  const bool particle_walls = core::has_particle_walls(scene) || core::has_surface_contact(scene);
  const Stage walls = walls_stage(scene);
  auto& s = plan.stages;
  const std::string velocity = plan.transfer == core::Transfer::apic
                                   ? "particle velocity and affine velocity (APIC)"
                                   : "particle velocity (PIC/FLIP blend)";
  // The parts the schemes share: the start of a step that updates the stress before the forces
  // (USF; USAVG's first half), what follows the forces, and MUSL's remap (MUSL; USAVG's second
  // half).
  auto stress_first_start = [&](const std::string& scheme, const std::string& velocity_why) {
    s.push_back(stage(StageKind::p2g_mass_momentum, "p2g mass momentum",
                      scheme + ": nodal mass and momentum first"));
    if (contact) s.push_back(surfaces);
    s.push_back(stage(StageKind::grid_velocity, "grid velocity", scheme + ": " + velocity_why));
    if (contact)
      s.push_back(stage(StageKind::contact_start, "contact start velocity",
                        "grid contact on the start velocity the strain rate is taken from"));
  };
  auto after_forces = [&] {
    s.push_back(grid_update);
    if (contact) s.push_back(grid_contact);
    if (particle_walls) s.push_back(walls);
  };
  auto remap = [&](const std::string& scheme, const std::string& strain_why) {
    s.push_back(stage(StageKind::g2p_velocity, "g2p velocity",
                      velocity + "; positions move with the strain"));
    s.push_back(stage(StageKind::p2g_remap, "p2g remap",
                      scheme + ": updated particle momentum mapped back to the grid"));
    if (contact)
      s.push_back(stage(StageKind::contact_remap, "contact remap",
                        "grid contact on the remapped velocity the strain rate is taken from"));
    s.push_back(
        stage(StageKind::strain_stress_update, "strain stress update", scheme + ": " + strain_why));
  };
  switch (plan.scheme) {
    case UpdateScheme::USF:
      stress_first_start("USF", "stress is updated from the velocity at the start of the step");
      s.push_back(stage(StageKind::strain_stress_update, "strain stress update",
                        "USF: strain rate from the grid velocity before the momentum update"));
      s.push_back(stage(StageKind::p2g_force, "p2g force", force_why));
      after_forces();
      s.push_back(stage(StageKind::g2p_velocity_position, "g2p velocity position",
                        velocity + " and position"));
      break;
    case UpdateScheme::USAVG:
      stress_first_start("USAVG", "the start velocity the first half of the strain is taken from");
      s.push_back(stage(StageKind::strain_stress_start, "strain stress start",
                        "USAVG: half the strain increment from the start velocity, so the "
                        "forces come from the mid-step stress"));
      s.push_back(stage(StageKind::p2g_force, "p2g force", force_why));
      after_forces();
      remap("USAVG",
            "the other half of the strain increment from the remapped grid velocity; "
            "positions move");
      break;
    case UpdateScheme::USL:
    case UpdateScheme::MUSL:
      s.push_back(stage(StageKind::p2g_mass_momentum_force, "p2g mass momentum force",
                        "nodal mass, momentum and " + force_why));
      if (contact) s.push_back(surfaces);
      after_forces();
      if (plan.scheme == UpdateScheme::USL) {
        s.push_back(stage(StageKind::g2p_velocity_strain_stress, "g2p velocity strain stress",
                          "USL: " + velocity +
                              ", strain rate from the updated grid velocity and position, in "
                              "one sweep"));
        break;
      }
      remap("MUSL", "strain rate from the remapped grid velocity; positions move");
      break;
  }
}

}  // namespace

StepPlan build_step_plan(const core::Scene& scene) {
  StepPlan plan;
  set_options(plan, scene);
  assign_velocity_fields(plan, scene);
  append_particle_stages(plan, scene);
  append_scheme_stages(plan, scene);
  // The mixed u-p pressure is projected inside each stress stage, between the kinematics (F)
  // and the constitutive update that reads it (mpm/mixed_pressure.cpp).
  if (plan.mixed_pressure)
    for (Stage& st : plan.stages)
      if (st.kind == StageKind::strain_stress_start || st.kind == StageKind::strain_stress_update ||
          st.kind == StageKind::g2p_velocity_strain_stress)
        st.why +=
            "; then the mixed u-p pressure, projected over the grid from det F before the "
            "stress reads it";
  return plan;
}

std::vector<std::string> StepPlan::stage_names() const {
  std::vector<std::string> names;
  for (const auto& st : stages) names.push_back(st.name);
  return names;
}

std::string StepPlan::describe() const {
  std::ostringstream o;
  o << "step plan (" << core::to_string(scheme) << ", " << velocity_fields << " velocity field"
    << (velocity_fields == 1 ? ": bodies share it, no contact stage" : "s") << "):\n";
  int i = 1;
  for (const auto& st : stages) o << "  " << i++ << ". " << st.name << "  -- " << st.why << "\n";
  for (const auto& c : contacts) o << "grid contact " << c << "\n";
  o << "constitutive update per material batch" << (jaumann ? " (Jaumann rate)" : "") << ":\n";
  for (const auto& m : materials) {
    o << "  " << m.material << ": strength " << m.strength << ", EOS " << m.eos
      << (m.eos != "none"  ? ""
          : m.hyperelastic ? (mixed_pressure ? " (pressure: the mixed u-p projection)"
                                             : " (pressure from its strain energy)")
                           : " (pressure from the bulk modulus)")
      << ", thermal " << (m.thermal ? "on (plastic work heats)" : "off") << ", failure "
      << m.failure << "\n";
  }
  o << "shape functions: ";
  switch (shape) {
    case core::ShapeFunction::linear:
      o << "linear hat (8 nodes)\n";
      break;
    case core::ShapeFunction::gimp:
      o << "uGIMP (27 nodes per particle)\n";
      break;
    case core::ShapeFunction::bspline2:
      o << "quadratic B-spline, modified at the grid faces (27 nodes per particle)\n";
      break;
    case core::ShapeFunction::bspline3:
      o << "cubic B-spline, modified at the grid faces (64 nodes per particle)\n";
      break;
    case core::ShapeFunction::cpdi1:
      o << "CPDI1, parallelepiped domains following the deformation gradient (8 corners, up to "
           "64 nodes per particle; a domain reaching past its cell's neighbours stops the run)\n";
      break;
    case core::ShapeFunction::cpdi2:
      o << "CPDI2, hexahedral domains with tracked corners (8 corners, up to 64 nodes per "
           "particle; a domain reaching past its cell's neighbours stops the run)\n";
      break;
  }
  if (total_lagrangian)
    o << "formulation: total-Lagrangian (weights at the particles' reference positions, taken "
         "from those alone; gradients mapped by each particle's deformation gradient F, updated "
         "F <- (I + dt L) F; the grid stands for the reference configuration)\n";
  else
    o << "formulation: updated-Lagrangian (weights at the particles' current positions)\n";
  if (mixed_pressure)
    o << "pressure: mixed displacement-pressure (Zhang et al. 2022): det F averaged to the nodes "
         "and back, K (J - 1) projected to the nodes and back, with "
      << (shape == core::ShapeFunction::linear ? "a constant per cell (under the linear hat)"
                                               : "the linear hat at the reference positions")
      << "; it replaces each point's K (J - 1)\n";
  if (transfer == core::Transfer::apic)
    o << "particle velocity: APIC (affine velocity carried by each particle)\n";
  else
    o << "particle velocity: PIC/FLIP blend, flip = " << flip << "\n";
  o << "strain tensor: " << (strain ? "integrated and written (output_strain)" : "not integrated")
    << "\n";
  o << "body force: " << (gravity ? "gravity" : "none") << "\n";
  return o.str();
}

}  // namespace afemp::mpm
