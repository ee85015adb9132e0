// The FE step plan: the stages one explicit FE step runs for a scene (central differences,
// Belytschko, Liu & Moran box 6.1), each with the line of the scene that asks for it, built once
// like the MPM plan (mpm/step_plan.hpp). FeSolver times exactly these stages; `afemp check`
// prints them.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace afemp::fem {

enum class FeStageKind {
  nodal_update,  // forces gathered per node -> v^{n+1/2}, imposed components (nodal_update.cpp)
  rigid_bodies,  // rigid bodies' momenta, rotation and node velocities (rigid_body.cpp)
  mesh_contact,  // contact corrections between meshes (mesh_contact.cpp)
  rigid_walls,   // rigid_wall.cpp
  hexahedra,     // strain rate, stress, bulk viscosity, hourglass, forces (hexahedron_update.cpp)
  trusses,       // truss_update.cpp
  erosion,       // eroded elements leave the mesh, node masses follow (erosion.cpp)
  conversion,    // retired hexahedra leave the mesh (element_retirement.cpp; particles: coupling/)
};

struct FeStage {
  FeStageKind kind;
  std::string name;  // as printed and as timed
  std::string why;   // one line: what the scene asked for that needs it
};

struct FeStepPlan {
  std::vector<FeStage> stages;

  // The position of the stage of this kind, or -1 when the scene does not need it.
  int index(FeStageKind kind) const;
  std::vector<std::string> stage_names() const;
  // One stage per line with its reason, numbered, as `afemp check` prints it.
  std::string describe() const;
};

// imposed_nodes: the nodes with an imposed velocity component, from the scene's constraints
// and from a mesh file's (which only the built mesh knows).
// imposed_nodes: nodes with an imposed velocity component; curved_components: node components
// whose imposed velocity follows a curve; absorbing_nodes: nodes of absorbing boundaries;
// loaded_nodes: nodes the faces of [[loads]] load (fem/surface_loads.cpp).
FeStepPlan build_fe_step_plan(const core::Scene& scene, std::size_t imposed_nodes,
                              std::size_t curved_components = 0, std::size_t absorbing_nodes = 0,
                              std::size_t loaded_nodes = 0);

}  // namespace afemp::fem
