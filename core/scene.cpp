// Scene entry points: enum names for messages and output, and reading a scene file.
// The checking itself lives in scene_parser.cpp; this file only turns file-system and TOML
// syntax failures into the same InputError form as every other input problem.
#include "core/scene.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/scene_parser.hpp"

namespace afemp::core {

const char* to_string(UpdateScheme s) {
  switch (s) {
    case UpdateScheme::USF:
      return "USF";
    case UpdateScheme::USL:
      return "USL";
    case UpdateScheme::MUSL:
      return "MUSL";
    case UpdateScheme::USAVG:
      return "USAVG";
  }
  return "?";
}

const char* to_string(ShapeFunction s) {
  switch (s) {
    case ShapeFunction::linear:
      return "linear";
    case ShapeFunction::gimp:
      return "gimp";
    case ShapeFunction::bspline2:
      return "bspline2";
    case ShapeFunction::bspline3:
      return "bspline3";
    case ShapeFunction::cpdi1:
      return "cpdi1";
    case ShapeFunction::cpdi2:
      return "cpdi2";
  }
  return "?";
}

const char* to_string(Formulation f) {
  return f == Formulation::total_lagrangian ? "total-lagrangian" : "updated-lagrangian";
}

const char* to_string(PressureField p) {
  return p == PressureField::mixed ? "mixed" : "standard";
}

const char* to_string(Transfer t) {
  return t == Transfer::apic ? "apic" : "flip";
}

const char* to_string(FaceCondition c) {
  switch (c) {
    case FaceCondition::free:
      return "free";
    case FaceCondition::fixed:
      return "fixed";
    case FaceCondition::symmetric:
      return "symmetric";
    case FaceCondition::wall:
      return "wall";
    case FaceCondition::outflow:
      return "outflow";
    case FaceCondition::absorbing:
      return "absorbing";
  }
  return "?";
}

const char* to_string(Face f) {
  switch (f) {
    case Face::xmin:
      return "xmin";
    case Face::xmax:
      return "xmax";
    case Face::ymin:
      return "ymin";
    case Face::ymax:
      return "ymax";
    case Face::zmin:
      return "zmin";
    case Face::zmax:
      return "zmax";
  }
  return "?";
}

const char* to_string(ContactMethod m) {
  switch (m) {
    case ContactMethod::grid:
      return "grid";
    case ContactMethod::penalty:
      return "penalty";
    case ContactMethod::weld:
      return "weld";
    case ContactMethod::surface:
      return "surface";
  }
  return "?";
}

std::string contact_name(const Scene& scene, const ContactSpec& contact) {
  if (!contact.name.empty()) return contact.name;
  const std::string& a = scene.bodies[static_cast<std::size_t>(contact.bodies[0])].name;
  if (contact.bodies[0] == contact.bodies[1]) return a + "-self";
  return a + "-" + scene.bodies[static_cast<std::size_t>(contact.bodies[1])].name;
}

bool has_grid_contact(const Scene& scene) {
  for (const ContactSpec& c : scene.contacts)
    if (c.method == ContactMethod::grid) return true;
  return false;
}

bool has_surface_contact(const Scene& scene) {
  for (const ContactSpec& c : scene.contacts)
    if (c.method == ContactMethod::surface) return true;
  return false;
}

bool has_particle_walls(const Scene& scene) {
  for (const WallSpec& w : scene.walls)
    for (int b : w.bodies)
      if (scene.bodies[static_cast<std::size_t>(b)].discretisation == Discretisation::particles)
        return true;
  return false;
}

bool has_rigid_body(const Scene& scene) {
  for (const BodySpec& b : scene.bodies)
    if (b.rigid) return true;
  return false;
}

const char* to_string(Discretisation d) {
  switch (d) {
    case Discretisation::particles:
      return "particles";
    case Discretisation::hexahedra:
      return "hexahedra";
    case Discretisation::trusses:
      return "trusses";
  }
  return "?";
}

const char* to_string(HexFormulation f) {
  return f == HexFormulation::one_point ? "one-point" : "full";
}

const char* to_string(HourglassForm f) {
  switch (f) {
    case HourglassForm::viscous:
      return "viscous";
    case HourglassForm::stiffness:
      return "stiffness";
    case HourglassForm::assumed_strain:
      return "assumed_strain";
  }
  return "?";
}

bool has_particles(const Scene& scene) {
  for (const BodySpec& b : scene.bodies)
    if (b.discretisation == Discretisation::particles) return true;
  return false;
}

bool has_mesh(const Scene& scene) {
  for (const BodySpec& b : scene.bodies)
    if (b.discretisation != Discretisation::particles) return true;
  return false;
}

bool bonded_to_particles(const Scene& scene, const BodySpec& body) {
  return body.bonded_to >= 0 &&
         scene.bodies[static_cast<std::size_t>(body.bonded_to)].discretisation ==
             Discretisation::particles;
}

bool tied_into_hexahedra(const Scene& scene, const BodySpec& body) {
  return body.bonded_to >= 0 &&
         scene.bodies[static_cast<std::size_t>(body.bonded_to)].discretisation ==
             Discretisation::hexahedra;
}

bool has_grid_coupling(const Scene& scene) {
  for (const BodySpec& b : scene.bodies)
    if (bonded_to_particles(scene, b) || b.conversion) return true;
  for (const ContactSpec& c : scene.contacts)
    if (c.method == ContactMethod::grid)
      for (int b : c.bodies)
        if (scene.bodies[static_cast<std::size_t>(b)].discretisation != Discretisation::particles)
          return true;
  return false;
}

std::size_t history_count(const Scene& scene) {
  std::size_t n = 0;
  for (const Material& m : scene.materials) n = std::max(n, m.history_count());
  return n;
}

std::vector<std::string> history_field_names(const Scene& scene) {
  std::vector<std::string> names(history_count(scene));
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::string name;
    bool shared = true;
    for (const Material& m : scene.materials) {
      if (k >= m.history_count()) continue;
      const std::string own = m.history_name(k);
      if (name.empty()) name = own;
      shared = shared && own == name;
    }
    names[k] =
        "history_" +
        (shared && !name.empty() && name.find('/') == std::string::npos ? name : std::to_string(k));
  }
  return names;
}

Scene read_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLocation{path, 0}, "", "cannot open scene file '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad())
    throw InputError(SourceLocation{path, 0}, "", "cannot read scene file '" + path + "'");
  return parse_scene(text.str(), path);
}

Scene parse_scene(const std::string& text, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(std::string_view(text), std::string_view(path));
  } catch (const toml::parse_error& e) {
    throw InputError(SourceLocation{path, static_cast<int>(e.source().begin.line)}, "",
                     "TOML syntax error: " + std::string(e.description()));
  }
  Scene scene = scene_detail::scene_from_toml(root, path);
  scene.source = text;
  return scene;
}

}  // namespace afemp::core
