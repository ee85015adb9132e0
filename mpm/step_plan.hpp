// The step plan: the list of stages one explicit MPM step runs, assembled once from the scene
// (NairnMPM's task chain, Lian et al. 2013, eqs 25-27 for the three orders). The time loop
// executes exactly this list, so a scene pays only for the stages it needs.
#pragma once

#include <string>
#include <vector>

#include "core/scene.hpp"

namespace afemp::mpm {

enum class StageKind {
  outflow,                     // particles beyond an outflow face leave (outflow.cpp; eq 13 there)
  split_particles,             // long particles split (particle_splitting.cpp; eqs 14-17 there)
  bin_particles,               // cells of the points; active grid blocks; colouring layers
  p2g_mass_momentum,           // eqs 2-29, 2-30 (USF: before the stress update)
  p2g_force,                   // eqs 2-10, 2-11 (USF: after the stress update)
  p2g_mass_momentum_force,     // eqs 2-29..2-31 in one sweep (USL, MUSL)
  grid_velocity,               // v = p / m with boundary conditions (USF)
  grid_momentum_update,        // eq 2-32 and boundary conditions
  g2p_velocity_position,       // eqs 2-33..2-36, PIC/FLIP blend (USF)
  g2p_velocity,                // eq 2-36 only (USL, MUSL); positions move in the strain pass
  p2g_remap,                   // MUSL: eq 2-37
  strain_stress_start,         // USAVG: eqs 2-38..2-41 over half the step from the start velocity
  strain_stress_update,        // eqs 2-38..2-41 from the velocity the scheme names
  g2p_velocity_strain_stress,  // USL: eqs 2-33..2-41 in one sweep (same weights, same field)
  contact_surfaces,            // grid contact: normals (Lian et al. 2013, eq 37) and reach (eq 42)
  contact_start,               // grid contact on the start velocity (USF: the strain reads it)
  grid_contact,    // Lian et al. 2013, eqs 38-42 on the updated velocity, Coulomb friction
  contact_remap,   // MUSL: the same on the remapped velocity
  particle_walls,  // rigid walls met at the particles' boundary (particle_wall_contact.cpp)
};

// Which nodal velocity a grid-contact stage corrects.
enum class ContactPass { start, update, remap };

struct Stage {
  StageKind kind;
  std::string name;  // short, as printed and as counted
  std::string why;   // one line: what the scene asked for that needs it
};

// What the constitutive stage does for one material: the composition it instantiates.
struct MaterialPlan {
  std::string material;
  std::string strength;       // the scene file's model name ("j2"), or the user model's
  std::string eos;            // "none" (hypoelastic pressure) | "linear" | "mie-gruneisen" | ...
  bool thermal = false;       // temperature integrated from plastic work
  std::string failure;        // when a point fails (core::failure_description)
  bool hyperelastic = false;  // its pressure comes from its strain energy, not a bulk law
};

struct StepPlan {
  core::UpdateScheme scheme = core::UpdateScheme::MUSL;
  core::ShapeFunction shape = core::ShapeFunction::linear;
  core::Transfer transfer = core::Transfer::flip;
  double flip = 1.0;       // PIC/FLIP blend of the particle velocity update (transfer flip)
  bool strain = false;     // the strain tensor is integrated (run.output_strain)
  bool splitting = false;  // particle lengths are tracked and long particles split
  // Weights at the reference positions, gradients mapped by F (mpm/stencil.hpp,
  // ReferenceStencil).
  bool total_lagrangian = false;
  // Particles carry F (total-Lagrangian, or a hyperelastic material among the particles').
  bool deformation_gradient = false;
  // The mixed u-p pressure (mpm/mixed_pressure.cpp) replaces the points' own K (J - 1).
  bool mixed_pressure = false;
  std::vector<Stage> stages;
  std::vector<MaterialPlan> materials;  // the materials of particles (bodies and conversions)
  bool gravity = false;                 // body force added in p2g_force
  std::size_t particle_loads = 0;       // [[loads]] on particles, added in p2g_force
  bool jaumann = true;
  int velocity_fields = 1;  // one shared field: bodies stick (no contact stage)
  // Grid contact: the velocity field of each body (all 0 with one field), and one line per
  // contact pair for describe().
  std::vector<int> field_of_body;
  std::vector<std::string> contacts;

  // The plan as `afemp check` prints it, one stage per line with its reason.
  std::string describe() const;
  std::vector<std::string> stage_names() const;
};

StepPlan build_step_plan(const core::Scene& scene);

}  // namespace afemp::mpm
