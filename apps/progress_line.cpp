#include "apps/progress_line.hpp"

#include <unistd.h>

#include <cmath>
#include <string>

#include "afemp/simulation.hpp"  // thread_count

namespace afemp::apps {

namespace {
std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "--:--";
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%02ld:%02ld", s / 60, s % 60);
  return buf;
}
}  // namespace

ProgressReporter::ProgressReporter(std::FILE* out) : out_(out), live_(isatty(fileno(out)) != 0) {}

void ProgressReporter::operator()(const Progress& p) {
  const double fraction = p.end_time > 0.0 ? p.time / p.end_time : 1.0;
  const double eta = fraction > 0.0 ? p.elapsed_seconds * (1.0 - fraction) / fraction : -1.0;
  char line[256];
  std::snprintf(line, sizeof line,
                "step %8ld  t %.4e  dt %.3e  %5.1f%%  elapsed %s  ETA %s  energy error %+.2e%%",
                p.step, p.time, p.dt, 100.0 * fraction, clock_text(p.elapsed_seconds).c_str(),
                clock_text(eta).c_str(), 100.0 * p.energy_error);
  if (live_) {
    std::fprintf(out_, "\r%s\x1b[K", line);
    pending_newline_ = true;
  } else {
    std::fprintf(out_, "%s\n", line);
  }
  std::fflush(out_);
  // Once, when the pace so far says the run will take days.
  if (!pace_warned_) {
    const std::string w = pace_warning(p.elapsed_seconds, fraction);
    if (!w.empty()) {
      finish();
      std::fprintf(stderr, "afemp: warning: %s\n", w.c_str());
      pace_warned_ = true;
    }
  }
}

void ProgressReporter::finish() {
  if (pending_newline_) std::fprintf(out_, "\n");
  pending_newline_ = false;
}

void print_summary(std::FILE* out, const Scene& scene, const RunSummary& s) {
  std::fprintf(out, "summary\n");
  std::fprintf(out, "  steps            %ld to t = %.6g (dt %.4g .. %.4g)\n", s.steps, s.time,
               s.min_dt, s.max_dt);
  if (!s.terminated.empty()) std::fprintf(out, "  stopped early    %s\n", s.terminated.c_str());
  if (s.interrupted)
    std::fprintf(out, "  stopped early    on request at t = %.6g of %.6g\n", s.time,
                 scene.run.end_time);
  std::fprintf(out, "  wall time        %.3f s with %d thread(s)\n", s.wall_seconds,
               thread_count());
  if (s.final_particles != s.particles) {
    // What changed the count: particles that left, split or were made from elements.
    std::string why;
    auto add = [&](bool yes, const char* what) {
      if (yes) why += (why.empty() ? "" : ", ") + std::string(what);
    };
    add(s.final.outflow_mass > 0.0, "outflow");
    add(scene.mpm.splitting.has_value(), "splitting");
    bool converts = false;
    for (const BodySpec& b : scene.bodies) converts = converts || b.conversion.has_value();
    add(converts, "converted elements");
    std::fprintf(out,
                 "  points           %zu particles (%zu at the end: %s), %zu "
                 "elements, %.3g point-steps/s (initial points)\n",
                 s.particles, s.final_particles, why.c_str(), s.elements, s.point_steps_per_second);
  } else
    std::fprintf(out, "  points           %zu particles, %zu elements, %.3g point-steps/s\n",
                 s.particles, s.elements, s.point_steps_per_second);
  std::fprintf(out, s.ranks > 1 ? "  stage seconds    (rank 0 of %d)" : "  stage seconds   ",
               s.ranks);
  for (std::size_t i = 0; i < s.stages.size(); ++i)
    std::fprintf(out, " %s %.2f%s", s.stages[i].name.c_str(), s.stages[i].seconds,
                 i + 1 < s.stages.size() ? "," : "\n");
  std::fprintf(out, "  energy  initial  kinetic %.6g  internal %.6g\n", s.initial.kinetic,
               s.initial.internal);
  std::fprintf(out,
               "          final    kinetic %.6g  internal %.6g (plastic work %.6g)  "
               "external work %.6g\n",
               s.final.kinetic, s.final.internal, s.final.plastic, s.final.external_work);
  if (s.final.hourglass != 0.0 || s.final.viscous != 0.0 || s.final.eroded != 0.0)
    std::fprintf(out, "                   hourglass %.6g  bulk-viscous %.6g  eroded %.6g\n",
                 s.final.hourglass, s.final.viscous, s.final.eroded);
  if (s.final.outflow_mass > 0.0)
    std::fprintf(out,
                 "                   outflow: mass %.6g, kinetic + internal %.6g left the "
                 "grid\n",
                 s.final.outflow_mass, s.final.outflow);
  if (s.final.stabilisation != 0.0)
    std::fprintf(out, "                   assumed-strain stabilisation %.6g (part of internal)\n",
                 s.final.stabilisation);
  std::fprintf(out, "  energy balance   error %+.3f %% at the end, largest %.3f %%\n",
               100.0 * s.energy_error, 100.0 * s.max_energy_error);
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const auto& body = s.final.bodies[b];
    const Vec3 v = body.mass > 0.0 ? (1.0 / body.mass) * body.momentum : Vec3{};
    std::fprintf(out, "  body %-10s  mean velocity (%.6g, %.6g, %.6g)\n",
                 scene.bodies[b].name.c_str(), v.x, v.y, v.z);
  }
  for (const ReferenceCheck& c : s.checks) {
    if (c.name.rfind("taylor", 0) == 0) continue;  // the Taylor line below says more
    std::fprintf(out, "  reference        %s: %.6g", c.name.c_str(), c.value);
    if (c.reference != 0.0) std::fprintf(out, " (ref %.6g, error %.4f)", c.reference, c.error);
    std::fprintf(
        out, "%s\n",
        c.tolerance > 0.0 ? (c.passed() ? "  (within tolerance)" : "  (OUTSIDE tolerance)") : "");
  }
  if (s.taylor && scene.taylor_reference) {
    const auto& r = *scene.taylor_reference;
    std::fprintf(out,
                 "  taylor bar       L %.3f (ref %.3f)  D %.3f (ref %.3f)  W %.3f (ref %.3f)  "
                 "mean error %.4f%s\n",
                 s.taylor->length, r.length, s.taylor->impact_diameter, r.impact_diameter,
                 s.taylor->bulge_diameter, r.bulge_diameter, s.taylor_error,
                 r.tolerance > 0.0 ? (s.taylor_error <= r.tolerance ? "  (within tolerance)"
                                                                    : "  (OUTSIDE tolerance)")
                                   : "");
  }
  // Last: what the numbers above are to be read with.
  for (const std::string& w : s.warnings) std::fprintf(out, "  warning          %s\n", w.c_str());
}

}  // namespace afemp::apps
