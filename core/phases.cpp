// The phases of a scene (core/phases.hpp). Static and implicit phases may come anywhere in
// the sequence: the solves (fem/static_solve.hpp) start from the state the phase before leaves
// (fem/static_phase.hpp). A relaxation phase comes first only: after another phase it would damp
// away the motion that phase computed. The time loop runs a static, implicit or relaxation
// phase as one step when its clock reaches the phase's start (phase_due), and stops the
// explicit steps there (next_phase_start).
#include "core/phases.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "afemp/errors.hpp"
#include "core/materials/small_strain_tangent.hpp"
#include "core/model.hpp"
#include "core/scene.hpp"
#include "core/scene_ranges.hpp"

namespace afemp::core {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string vector_text(const Vec3& v) {
  // Appended in turn: GCC 12's -Wrestrict warns, falsely, on "(" + std::string&& inlined here.
  std::string text = "(";
  text += number(v.x);
  text += ", ";
  text += number(v.y);
  text += ", ";
  text += number(v.z);
  text += ")";
  return text;
}

bool solvable_default(const BodySpec& b) {
  return b.discretisation != Discretisation::particles && !b.rigid && b.bonded_to < 0;
}

bool listed(const std::vector<int>& bodies, int b) {
  return std::find(bodies.begin(), bodies.end(), b) != bodies.end();
}

}  // namespace

const char* to_string(PhaseKind k) {
  switch (k) {
    case PhaseKind::static_load:
      return "static";
    case PhaseKind::implicit_dynamics:
      return "implicit";
    case PhaseKind::relaxation:
      return "relaxation";
    case PhaseKind::explicit_dynamics:
      return "explicit";
  }
  return "?";
}

double phase_start(const Scene& scene, std::size_t k) {
  return k == 0 ? 0.0 : phase_end(scene, k - 1);
}

const PhaseSpec* phase_due(const Scene& scene, double t) {
  for (std::size_t k = 0; k < scene.phases.size(); ++k) {
    if (scene.phases[k].kind == PhaseKind::explicit_dynamics) continue;
    const double start = phase_start(scene, k), end = phase_end(scene, k);
    if (std::abs(t - start) <= 1e-12 * end && t < end) return &scene.phases[k];
  }
  return nullptr;
}

int implicit_steps(const PhaseSpec& phase, double span) {
  return static_cast<int>(std::ceil(span / phase.time_step * (1.0 - 1e-12)));
}

double next_phase_start(const Scene& scene, double t) {
  for (std::size_t k = 0; k < scene.phases.size(); ++k) {
    const double start = phase_start(scene, k);
    if (scene.phases[k].kind != PhaseKind::explicit_dynamics && start > t * (1.0 + 1e-12))
      return start;
  }
  return std::numeric_limits<double>::infinity();
}

double explicit_span(const Scene& scene) {
  if (scene.phases.empty()) return scene.run.end_time;
  double span = 0.0;
  for (std::size_t k = 0; k < scene.phases.size(); ++k)
    if (scene.phases[k].kind == PhaseKind::explicit_dynamics)
      span += phase_end(scene, k) - phase_start(scene, k);
  return span;
}

bool books_damped_energy(const Scene& scene) {
  for (std::size_t k = 0; k < scene.phases.size(); ++k) {
    const PhaseKind kind = scene.phases[k].kind;
    if (kind == PhaseKind::relaxation || kind == PhaseKind::implicit_dynamics ||
        (kind == PhaseKind::static_load && k > 0))
      return true;
  }
  return false;
}

double phase_end(const Scene& scene, std::size_t k) {
  const double end = scene.phases[k].end_time;
  return end == 0.0 && k + 1 == scene.phases.size() ? scene.run.end_time : end;
}

double phase_tolerance(const PhaseSpec& phase) {
  if (phase.tolerance > 0.0) return phase.tolerance;
  return phase.kind == PhaseKind::relaxation ? 1e-3 : 1e-8;
}

std::vector<int> moving_bodies(const Scene& scene) {
  std::vector<int> out;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (norm(scene.bodies[b].velocity) > 0.0) out.push_back(static_cast<int>(b));
  return out;
}

std::vector<int> static_phase_bodies(const Scene& scene, const PhaseSpec& phase) {
  std::vector<int> out = phase.bodies;
  if (out.empty())
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      if (solvable_default(scene.bodies[b])) out.push_back(static_cast<int>(b));
  // Trusses tied into a body of hexahedra the phase solves are solved with it.
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (tied_into_hexahedra(scene, scene.bodies[b]) && listed(out, scene.bodies[b].bonded_to) &&
        !listed(out, static_cast<int>(b)))
      out.push_back(static_cast<int>(b));
  return out;
}

void check_phases(const Scene& scene, const PhaseFailure& fail) {
  const std::size_t n = scene.phases.size();
  double previous = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const PhaseSpec& p = scene.phases[k];
    const std::string key = "phases[" + std::to_string(k) + "]";
    const double end = phase_end(scene, k);
    if (!(end > previous) || !std::isfinite(end))
      fail(p.where, key + ".end_time",
           "value " + number(end) + " must be after the previous phase's end (" + number(previous) +
               ")");
    previous = end;
    if (k + 1 == n && std::abs(end - scene.run.end_time) > 1e-12 * scene.run.end_time)
      fail(p.where, key + ".end_time",
           "the last phase ends at [run] end_time (" + number(scene.run.end_time) + "), not " +
               number(end));
  }
  if (n == 0) return;
  auto check_solved = [&](const PhaseSpec* s, const std::string& key, std::size_t k) {
    namespace r = scene_ranges::phase;
    if (s->kind == PhaseKind::relaxation) {
      if (s->tolerance != 0.0 && !r::relaxation_tolerance.contains(s->tolerance))
        fail(s->where, key + ".tolerance", "allowed: " + r::relaxation_tolerance.describe());
      if (!r::damping_factor.contains(s->damping_factor))
        fail(s->where, key + ".damping_factor", "allowed: " + r::damping_factor.describe());
      if (!r::check_every.contains(s->check_every))
        fail(s->where, key + ".check_every",
             "allowed: " + std::to_string(r::check_every.lo) +
                 " <= value <= " + std::to_string(r::check_every.hi));
      if (!r::relaxation_step_factor.contains(s->relaxation_step_factor))
        fail(s->where, key + ".time_step_factor",
             "allowed: " + r::relaxation_step_factor.describe());
      return;
    }
    const bool implicit = s->kind == PhaseKind::implicit_dynamics;
    const std::string a_phase = implicit ? "an implicit phase" : "a static phase";
    if (!implicit && !r::load_steps.contains(s->load_steps))
      fail(s->where, key + ".load_steps",
           "allowed: " + std::to_string(r::load_steps.lo) +
               " <= value <= " + std::to_string(r::load_steps.hi));
    if (implicit && !r::implicit_time_step.contains(s->time_step))
      fail(s->where, key + ".time_step", "allowed: " + r::implicit_time_step.describe());
    if (implicit && !r::hht_alpha.contains(s->alpha))
      fail(s->where, key + ".alpha", "allowed: " + r::hht_alpha.describe());
    if (!r::max_iterations.contains(s->max_iterations))
      fail(s->where, key + ".max_iterations",
           "allowed: " + std::to_string(r::max_iterations.lo) +
               " <= value <= " + std::to_string(r::max_iterations.hi));
    if (s->tolerance != 0.0 && !r::tolerance.contains(s->tolerance))
      fail(s->where, key + ".tolerance", "allowed: " + r::tolerance.describe());
    if (s->gravity && !std::isfinite(s->gravity->x + s->gravity->y + s->gravity->z))
      fail(s->where, key + ".gravity", "every component must be a finite number");
    const std::vector<int> bodies = static_phase_bodies(scene, *s);
    if (bodies.empty())
      fail(s->where, key + ".bodies",
           "no body to solve: " + a_phase +
               " solves deformable mesh bodies (hexahedra, trusses) that are not bonded to "
               "particles, and the scene has none");
    for (int b : bodies) {
      if (b < 0 || static_cast<std::size_t>(b) >= scene.bodies.size())
        fail(s->where, key + ".bodies", "body index " + std::to_string(b) + " is not defined");
      const BodySpec& body = scene.bodies[static_cast<std::size_t>(b)];
      const std::string name = "body \"" + body.name + "\"";
      if (body.discretisation == Discretisation::particles)
        fail(s->where, key + ".bodies",
             name + " is made of particles; " + a_phase +
                 " solves meshes (particles are held where they are: use it for the meshes "
                 "alone), a relaxation phase any body");
      if (body.rigid)
        fail(s->where, key + ".bodies", name + " is rigid; " + a_phase + " holds rigid bodies");
      if (bonded_to_particles(scene, body))
        fail(s->where, key + ".bodies",
             name + " is bonded to particles, which " + a_phase +
                 " holds: its nodes cannot move without them");
      if (tied_into_hexahedra(scene, body) && !listed(bodies, body.bonded_to))
        fail(s->where, key + ".bodies",
             name + " is tied into \"" +
                 scene.bodies[static_cast<std::size_t>(body.bonded_to)].name + "\", which " +
                 a_phase + " does not solve: list that body (its tied trusses come with it)");
      if (body.discretisation == Discretisation::hexahedra &&
          body.element == HexFormulation::one_point &&
          body.hourglass.form == HourglassForm::viscous)
        fail(s->where, key + ".bodies",
             name +
                 " has one-point hexahedra with the viscous hourglass form, which resists "
                 "rates only and has no stiffness; give it hourglass form \"stiffness\" or "
                 "\"assumed_strain\", or element = \"full\", or preload the scene with "
                 "kind = \"relaxation\", which takes any body");
      // A first static phase is a slow loading from the unstressed state, whose loads' work
      // is the stress work; a prestress released on that path would be booked as negative
      // work of the loads.
      if (k == 0 && !implicit && body.prestress != 0.0)
        fail(s->where, key + ".bodies",
             name +
                 " is prestressed; a first static phase loads the meshes slowly from the "
                 "unstressed state: bring the prestress into equilibrium with kind = "
                 "\"relaxation\" or \"implicit\", or leave the body out of bodies");
      // The solve starts from the state the phase before leaves, but not from the hourglass
      // forms' forces a one-point element carries.
      if (k > 0 && body.discretisation == Discretisation::hexahedra &&
          body.element == HexFormulation::one_point)
        fail(s->where, key + ".bodies",
             name + " has one-point hexahedra, whose hourglass forms' forces the " +
                 to_string(s->kind) +
                 " solve does not take from the phase before (it would start them unloaded); "
                 "give the body element = \"full\" (B-bar), or run this phase first");
      try {
        check_small_strain_tangent(scene.materials[static_cast<std::size_t>(body.material)]);
      } catch (const std::invalid_argument& e) {
        fail(s->where, key + ".bodies",
             name + ": " + e.what() +
                 "; list the bodies the phase solves without it (it is then held), or preload "
                 "the scene with kind = \"relaxation\", which takes any material");
      }
    }
    for (std::size_t w = 0; w < scene.walls.size(); ++w) {
      const WallSpec& wall = scene.walls[w];
      if (wall.friction == 0.0 && norm(wall.velocity) == 0.0) continue;
      for (int b : bodies) {
        const std::vector<int>& on = wall.bodies;
        if (on.empty() || std::find(on.begin(), on.end(), b) != on.end())
          fail(wall.where, "walls[" + std::to_string(w) + "]",
               "the wall acts on body \"" + scene.bodies[static_cast<std::size_t>(b)].name +
                   "\", which the " + to_string(s->kind) + " phase solves, and " +
                   (wall.friction != 0.0 ? "has friction" : "moves") + "; the " +
                   to_string(s->kind) +
                   " solve takes frictionless walls at rest (an exact contact constraint): give "
                   "the wall friction 0 and no velocity, or hold the body by [[constraints]] in "
                   "that phase");
      }
    }
  };
  for (std::size_t k = 0; k < n; ++k) {
    const PhaseSpec& p = scene.phases[k];
    if (p.kind == PhaseKind::explicit_dynamics) continue;
    const std::string key = "phases[" + std::to_string(k) + "]";
    if (p.kind == PhaseKind::relaxation && k > 0)
      fail(p.where, key + ".kind",
           "a relaxation phase comes first: after another phase it would damp away the motion "
           "that phase computed (a static phase after an explicit one finds the equilibrium and "
           "puts the bodies it solves at rest)");
    check_solved(&p, key, k);
  }
}

std::string describe_phases(const Scene& scene) {
  if (scene.phases.empty()) return {};
  std::string out = "Phases (on one clock):\n";
  double from = 0.0;
  for (std::size_t k = 0; k < scene.phases.size(); ++k) {
    const PhaseSpec& p = scene.phases[k];
    out += "  " + std::to_string(k + 1) + ". " + to_string(p.kind) + ", t " + number(from) +
           " -> " + number(phase_end(scene, k)) + ": ";
    from = phase_end(scene, k);
    if (p.kind == PhaseKind::explicit_dynamics) {
      const PhaseKind before = k > 0 ? scene.phases[k - 1].kind : PhaseKind::explicit_dynamics;
      out += "explicit dynamics of every body, with the stages below; it starts from ";
      if (k == 0)
        out += "the bodies' initial state and velocities";
      else if (before == PhaseKind::implicit_dynamics)
        out +=
            "the state the implicit phase leaves (positions, stresses, plastic strains and the "
            "velocities of the bodies it solved; the others keep theirs)";
      else if (before == PhaseKind::static_load && k > 1)
        out +=
            "the state the static phase leaves (positions, stresses, plastic strains; the "
            "bodies it solved at rest, the others with the velocities they had)";
      else
        out +=
            "the state the phase before leaves (positions, stresses, plastic strains) and the "
            "bodies' initial velocities";
      out += ", and the constraints' velocities\n";
      continue;
    }
    if (p.kind == PhaseKind::relaxation) {
      std::string held;
      for (int b : moving_bodies(scene))
        held += (held.empty() ? "" : ", ") + scene.bodies[static_cast<std::size_t>(b)].name;
      out +=
          "dynamic relaxation (LS-DYNA's *CONTROL_DYNAMIC_RELAXATION): the explicit model, "
          "with the stages below, under [run] gravity " +
          vector_text(scene.run.gravity) + " and the constraints, every velocity multiplied by " +
          number(p.damping_factor) + " after every step, at " + number(p.relaxation_step_factor) +
          " x the stable step; converged when the largest kinetic energy since the last "
          "check (every " +
          std::to_string(p.check_every) + " steps) is below " + number(phase_tolerance(p)) +
          " of its peak, then put at rest; not converged by the phase's end: the run stops";
      if (!held.empty())
        out += "; held at rest, their initial velocity given at the phase's end: " + held;
      out += "\n";
      continue;
    }
    const std::vector<int> bodies = static_phase_bodies(scene, p);
    std::string solved, held;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      const bool in = std::find(bodies.begin(), bodies.end(), static_cast<int>(b)) != bodies.end();
      (in ? solved : held) += (in ? solved : held).empty() ? "" : ", ";
      (in ? solved : held) += scene.bodies[b].name;
    }
    if (p.kind == PhaseKind::implicit_dynamics) {
      const double span = phase_end(scene, k) - phase_start(scene, k);
      const int steps = implicit_steps(p, span);
      out += "the implicit dynamics of " + solved + " (" +
             (p.alpha == 0.0 ? std::string("Newmark's trapezoidal rule, no numerical damping")
                             : "HHT-alpha, alpha " + number(p.alpha)) +
             ", " + std::to_string(steps) + " steps of " + number(span / steps) +
             ", the consistent mass; each step Newton with the consistent tangent, |r| <= " +
             number(phase_tolerance(p)) + " x the force scale in at most " +
             std::to_string(p.max_iterations) + " iterations, CHOLMOD), " +
             (k == 0 ? std::string("from the bodies' initial velocities")
                     : "from the state the phase before leaves (positions, stresses, plastic "
                       "strains, velocities)") +
             "; loads, constant from the phase's start: gravity " +
             vector_text(p.gravity ? *p.gravity : scene.run.gravity) +
             ", the constraints' fixed components held and their velocities followed; the "
             "velocities at its end go on into the explicit phase, and what the scheme "
             "dissipated is booked as damped energy";
    } else {
      out += "the equilibrium of " + solved + " (Newton with the consistent tangent, " +
             std::to_string(p.load_steps) + " load steps, |r| <= " + number(phase_tolerance(p)) +
             " x the force scale in at most " + std::to_string(p.max_iterations) +
             " iterations each, CHOLMOD); loads: gravity " +
             vector_text(p.gravity ? *p.gravity : scene.run.gravity) +
             ", the constraints' fixed components held and their velocities integrated over the "
             "phase as displacements";
      if (k > 0)
        out +=
            "; from the state the phase before leaves (positions, stresses, plastic strains), "
            "a small-strain step on the current geometry; the bodies it solves are at rest at "
            "its end (their kinetic energy is booked as damped)";
    }
    if (!scene.walls.empty()) out += "; the walls as frictionless contact (an exact active set)";
    if (!held.empty())
      out += "; held where they are" + std::string(k > 0 ? " (their velocities kept)" : "") + ": " +
             held;
    out +=
        "; not in this phase: contacts, erosion, conversion, failure (damage), bulk "
        "viscosity, and rate and temperature effects (Johnson-Cook on its quasi-static "
        "curve at the initial temperature)\n";
  }
  return out;
}

double Model::run_implicit_phase(const PhaseSpec& phase, std::ostream* /*log*/) {
  throw InputError(phase.where, "phases",
                   std::string("a ") + to_string(phase.kind) +
                       " phase solves mesh bodies, and this model has none (particles are held "
                       "in such a phase)");
}

}  // namespace afemp::core
