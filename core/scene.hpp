// The scene's functions inside the library: what a scene holds, and the scene-file reader.
// The scene's data types are public (afemp/scene.hpp).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "afemp/scene.hpp"
#include "core/materials/material.hpp"

namespace afemp::core {

// Whether some body is made of particles / of a mesh (hexahedra or trusses).
bool has_particles(const Scene& scene);
bool has_mesh(const Scene& scene);
// A mesh body's bond (`bonded_to`): to a body of particles (HFEMP: its nodes join that body's
// velocity field on the grid), or trusses tied into a body of hexahedra (rebar in solid
// elements: its nodes follow the host's elements, fem/embedded_nodes.hpp). False when unbonded.
bool bonded_to_particles(const Scene& scene, const BodySpec& body);
bool tied_into_hexahedra(const Scene& scene, const BodySpec& body);

// Whether mesh nodes take part in the grid step: a mesh body bonded to particles, named in a
// grid contact, or converting its elements into particles (coupling/).
bool has_grid_coupling(const Scene& scene);

// Whether the scene has a grid contact / a rigid body.
bool has_grid_contact(const Scene& scene);
bool has_rigid_body(const Scene& scene);
// Whether a [[walls]] entry names a body of particles (mpm/particle_wall_contact.cpp).
bool has_particle_walls(const Scene& scene);
// Whether a [[contact]] has method "surface" (particles at a mesh's faces).
bool has_surface_contact(const Scene& scene);

// History variables per point the solvers store: the most any of the scene's materials has
// (user strength models, afemp/user_material.hpp); 0 when none has any.
std::size_t history_count(const Scene& scene);
// The output field of each history column: "history_NAME" when every material with that
// column names it NAME, else "history_K".
std::vector<std::string> history_field_names(const Scene& scene);

// The name of a contact's history columns (NAME.fx, ...): its own, or "BODY1-BODY2"
// ("BODY-self" for a self-contact), the default of the scene file and of a program alike.
std::string contact_name(const Scene& scene, const ContactSpec& contact);

// The bulk viscosity of a body: its own, or the default (on for hexahedra and for particles
// whose material has an equation of state).
BulkViscositySettings bulk_viscosity_of(const Scene& scene, const BodySpec& body);

// What a [[loads]] entry may not do on its body (a truss or bonded body, a traction or a
// non-box region on particles): the key and why, or nothing. The parser and check_scene ask.
struct LoadRefusal {
  std::string key, message;
};
std::optional<LoadRefusal> load_refusal(const Scene& scene, const LoadSpec& load);

// Checks a scene built in code as the parser checks a file (core/scene_check.cpp): throws
// InputError naming the object and field by their dotted scene-file key and what is allowed.
void check_scene(const Scene& scene);

// Reads and validates a scene file. Throws InputError naming file, line, key and what is
// allowed for unknown keys, wrong types and out-of-range values.
Scene read_scene(const std::string& path);
// Same, from text (the path is used in messages and to resolve relative paths).
Scene parse_scene(const std::string& text, const std::string& path);

}  // namespace afemp::core
