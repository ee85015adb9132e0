// The scene: everything a run needs, as read from a scene file (docs/scene-format.md).
// Plain data with defaults a newcomer would pick; the parser (scene_parser.cpp) fills it and
// checks every value, the solvers read it. Units are the scene's own consistent set.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/error.hpp"
#include "core/materials/material.hpp"
#include "core/tensor.hpp"

namespace afemp::core {

enum class UpdateScheme { USF, USL, MUSL };  // seed 000 eqs 25-27
// free: nothing; fixed: all velocity components zero (the material sticks);
// symmetric: normal component zero (a symmetry plane; tension is carried across it);
// wall: a rigid frictionless wall the material may not cross but may leave (the normal
// component is zeroed only at nodes whose updated velocity points into the wall).
enum class FaceCondition { free, fixed, symmetric, wall };
enum class Face { xmin = 0, xmax, ymin, ymax, zmin, zmax };

const char* to_string(UpdateScheme s);
const char* to_string(FaceCondition c);
const char* to_string(Face f);

struct RunSettings {
  std::string title;
  double end_time = 0.0;           // required
  double time_step_factor = 0.3;   // Courant safety factor on the stable step
  double fixed_time_step = 0.0;    // > 0: use this step instead of the stable one
  long max_steps = 0;              // > 0: stop after this many steps
  double output_every = 0.0;       // simulated time between field outputs; 0: final state only
  long history_every = 10;         // steps between history rows
  bool output_strain = false;      // integrate and write each particle's strain tensor
  Vec3 gravity;                    // body force per unit mass
};

struct GridSettings {
  double cell = 0.0;  // cell edge length h (cubic cells)
  Vec3 min, max;      // the domain; grid nodes sit at min + i h
  std::array<FaceCondition, 6> faces{FaceCondition::free, FaceCondition::free,
                                     FaceCondition::free, FaceCondition::free,
                                     FaceCondition::free, FaceCondition::free};
};

struct MpmSettings {
  UpdateScheme scheme = UpdateScheme::MUSL;
  double flip = 1.0;     // velocity update blend: 1 pure FLIP, 0 pure PIC
  bool jaumann = true;   // objective (Jaumann) stress rate
  GridSettings grid;
};

struct BoxShape {
  Vec3 min, max;
};
struct CylinderShape {
  Vec3 base;               // centre of the base disc
  Vec3 axis{0, 0, 1};      // direction, normalised by the parser
  double radius = 0.0;
  double length = 0.0;
};
struct SphereShape {
  Vec3 centre;
  double radius = 0.0;
};
// Plain-text points: one "x y z [volume]" per line, '#' comments; the path is resolved
// relative to the scene file.
struct PointListShape {
  std::string path;
};
using Shape = std::variant<BoxShape, CylinderShape, SphereShape, PointListShape>;

struct BodySpec {
  std::string name;
  int material = -1;            // index into Scene::materials
  Shape shape;
  int particles_per_cell = 2;   // per direction
  Vec3 velocity;                // initial velocity
  std::optional<double> temperature;  // initial temperature; default the material's
  SourceLocation where;         // the [[bodies]] table, for messages
};

// Reference values a run compares its result with at the end (seed 001 eq 2-42).
struct TaylorReference {
  double length = 0.0, impact_diameter = 0.0, bulge_diameter = 0.0;  // L, D, W
  double tolerance = 0.0;       // allowed mean error; 0: report only
};

struct Scene {
  std::string path;             // the scene file, as given
  RunSettings run;
  MpmSettings mpm;
  std::vector<Material> materials;
  std::vector<BodySpec> bodies;
  std::optional<TaylorReference> taylor_reference;
};

// Reads and validates a scene file. Throws InputError naming file, line, key and what is
// allowed for unknown keys, wrong types and out-of-range values.
Scene read_scene(const std::string& path);
// Same, from text (the path is used in messages and to resolve relative paths).
Scene parse_scene(const std::string& text, const std::string& path);

}  // namespace afemp::core
