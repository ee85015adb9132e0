// Sizing a scene before it is built (core/resource_guard.hpp).
#include "core/resource_guard.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <variant>

#include "afemp/errors.hpp"
#include "core/phases.hpp"

namespace afemp::core {

namespace {

constexpr double pi = 3.14159265358979323846;

double shape_volume(const Shape& shape) {
  if (const auto* b = std::get_if<BoxShape>(&shape))
    return std::abs((b->max.x - b->min.x) * (b->max.y - b->min.y) * (b->max.z - b->min.z));
  if (const auto* c = std::get_if<CylinderShape>(&shape)) {
    if (c->top_radius >= 0.0)  // a frustum
      return pi * c->length *
             (c->radius * c->radius + c->radius * c->top_radius + c->top_radius * c->top_radius) /
             3.0;
    return pi * c->radius * c->radius * c->length;
  }
  if (const auto* s = std::get_if<SphereShape>(&shape))
    return 4.0 / 3.0 * pi * s->radius * s->radius * s->radius;
  return 0.0;
}

// The area of a shape's r-z section about the z axis (an axisymmetric grid's particles).
double section_area(const Shape& shape) {
  if (const auto* b = std::get_if<BoxShape>(&shape))
    return std::abs((b->max.x - std::max(b->min.x, 0.0)) * (b->max.z - b->min.z));
  if (const auto* c = std::get_if<CylinderShape>(&shape))
    return c->length * (c->top_radius >= 0.0 ? 0.5 * (c->radius + c->top_radius) : c->radius);
  if (const auto* s = std::get_if<SphereShape>(&shape)) return 0.5 * pi * s->radius * s->radius;
  return 0.0;
}

std::string gib(double bytes) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return buf;
}

}  // namespace

SizeEstimate estimate_size(const Scene& scene) {
  SizeEstimate e;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& body = scene.bodies[b];
    double points = 0.0;
    if (body.discretisation == Discretisation::particles) {
      if (const auto* list = std::get_if<PointListShape>(&body.shape)) {
        points = static_cast<double>(list->points.size());
      } else if (scene.has_grid && scene.mpm.grid.cell > 0.0) {
        const double spacing = scene.mpm.grid.cell / body.particles_per_cell;
        // Axisymmetric: one ring per r-z square (mpm/axisymmetric.hpp).
        points = scene.mpm.grid.axisymmetric
                     ? section_area(body.shape) / (spacing * spacing)
                     : shape_volume(body.shape) / (spacing * spacing * spacing);
      }
      e.particles += points;
    } else if (const auto* mesh = std::get_if<MeshFileShape>(&body.shape)) {
      points = static_cast<double>(mesh->arrays.hexahedra.size() + mesh->arrays.trusses.size());
      e.elements += points;
    } else if (body.discretisation == Discretisation::hexahedra) {
      const MeshDensity& m = body.mesh;
      const auto* box = std::get_if<BoxShape>(&body.shape);
      if (box && m.divisions[0] > 0)
        points = static_cast<double>(m.divisions[0]) * m.divisions[1] * m.divisions[2];
      else if (box && (!m.graded[0].empty() || !m.graded[1].empty() || !m.graded[2].empty())) {
        points = 1.0;
        for (std::size_t d = 0; d < 3; ++d) {
          double n = 0.0;
          for (const auto& segment : m.graded[d]) n += segment[1];
          points *=
              m.graded[d].empty() ? std::ceil((box->max[d] - box->min[d]) / m.size - 1e-9) : n;
        }
      } else if (m.size > 0.0)
        points = shape_volume(body.shape) / (m.size * m.size * m.size) *
                 (m.sectors > 0 && m.sectors < 4 ? m.sectors / 4.0 : 1.0);
      e.elements += points;
    }
    if (points > e.largest_points) {
      e.largest_points = points;
      e.largest_body = static_cast<int>(b);
    }
  }
  e.bytes = (e.particles + e.elements) * SizeEstimate::bytes_per_point;
  return e;
}

double available_memory() {
  std::ifstream in("/proc/meminfo");
  for (std::string line; std::getline(in, line);) {
    std::istringstream s(line);
    std::string key;
    double kib = 0.0;
    if (s >> key >> kib && key == "MemAvailable:") return kib * 1024.0;
  }
  return 0.0;
}

void refuse_oversized_scene(const Scene& scene) {
  const SizeEstimate e = estimate_size(scene);
  const double available = available_memory();
  if (!(available > 0.0) || e.bytes <= available || e.largest_body < 0) return;
  const BodySpec& body = scene.bodies[static_cast<std::size_t>(e.largest_body)];
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "the scene would make about %s particles and %s elements (body \"%s\": %s), "
                "at least %s of memory, and this machine has %s available; coarsen the "
                "[grid] cell, particles_per_cell or the mesh, or use a symmetry model",
                readable_count(e.particles).c_str(), readable_count(e.elements).c_str(),
                body.name.c_str(), readable_count(e.largest_points).c_str(), gib(e.bytes).c_str(),
                gib(available).c_str());
  throw InputError(body.where, "bodies", buf);
}

std::string readable_duration(double seconds) {
  char buf[48];
  if (!(seconds < 1e300)) return "forever";
  if (seconds < 120.0)
    std::snprintf(buf, sizeof buf, "%.0f s", seconds);
  else if (seconds < 7200.0)
    std::snprintf(buf, sizeof buf, "%.1f min", seconds / 60.0);
  else if (seconds < 2.0 * 86400.0)
    std::snprintf(buf, sizeof buf, "%.1f h", seconds / 3600.0);
  else if (seconds < 1000.0 * 86400.0)
    std::snprintf(buf, sizeof buf, "%.1f days", seconds / 86400.0);
  else
    std::snprintf(buf, sizeof buf, "%.2g years", seconds / (365.25 * 86400.0));
  return buf;
}

double estimated_wall_seconds(double point_steps, int threads) {
  return point_steps / (nominal_point_steps_per_thread_second * std::max(threads, 1));
}

double planned_steps(const Scene& scene, double dt) {
  const double steps = explicit_span(scene) / dt;
  return scene.run.max_steps > 0 ? std::min(steps, static_cast<double>(scene.run.max_steps))
                                 : steps;
}

std::string wall_time_warning(double point_steps, int threads) {
  const double seconds = estimated_wall_seconds(point_steps, threads);
  if (!(seconds > 86400.0)) return "";
  return "the run is estimated to take " + readable_duration(seconds) + " (" +
         readable_count(point_steps) + " point-steps on " + std::to_string(threads) +
         " thread(s) at about 1.5 million per thread and second); check end_time, the cell and "
         "mesh sizes and the units, and keep checkpoints on ([run] checkpoint_wall_every, "
         "docs/restart.md)";
}

std::vector<std::string> size_warnings(const Scene& scene, double points, double dt, int threads) {
  const double steps = explicit_span(scene) / dt;
  if (steps > 1e9 && scene.run.max_steps <= 0) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "about %s steps to end_time = %g at dt = %.3g: %s point-steps, days of "
                  "computing at tens of millions a second; check end_time and the units (mm, ms, "
                  "g: 1 s is 1000), or bound the run with [run] max_steps",
                  readable_count(steps).c_str(), scene.run.end_time, dt,
                  readable_count(steps * points).c_str());
    return {buf};
  }
  const std::string w = wall_time_warning(points * planned_steps(scene, dt), threads);
  if (w.empty()) return {};
  return {w};
}

std::string pace_warning(double elapsed, double fraction) {
  if (!(elapsed >= 20.0) || !(fraction > 0.0)) return "";
  const double rest = elapsed * (1.0 - fraction) / fraction;
  if (!(rest > 86400.0)) return "";
  char pct[32];
  std::snprintf(pct, sizeof pct, "%.3g %%", 100.0 * fraction);
  return "at its pace so far (" + std::string(pct) + " of the end time in " +
         readable_duration(elapsed) + ") the run needs " + readable_duration(rest) +
         " more; checkpoints keep it restartable ([run] checkpoint_wall_every, docs/restart.md)";
}

}  // namespace afemp::core
