// The run loop of core/time_loop.hpp: stable step, output at the requested interval, history
// rows, progress and the summary. Moved here from the MPM solver so that FE and coupled runs
// share it.
#include "core/time_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <variant>

#include "core/output/history.hpp"
#include "core/probe_recorder.hpp"
#include "core/output/run_directory.hpp"

namespace afemp::core {

namespace {

HistoryRow history_row(const Model& m, const Energies& e, double dt, double error) {
  HistoryRow r;
  r.step = m.step_count();
  r.time = m.time();
  r.dt = dt;
  r.kinetic = e.kinetic;
  r.internal = e.internal;
  r.plastic = e.plastic;
  r.elastic = e.internal - e.plastic - e.viscous;
  r.viscous = e.viscous;
  r.hourglass = e.hourglass;
  r.stabilisation = e.stabilisation;
  r.eroded = e.eroded;
  r.converted = e.converted;
  r.contact = e.contact;
  r.external_work = e.external_work;
  r.total = e.total();
  r.energy_error = error;
  for (const BodySums& b : e.bodies)
    r.bodies.push_back(
        {b.momentum, b.mass > 0.0 ? (1.0 / b.mass) * b.momentum : Vec3{}, b.kinetic, b.internal});
  return r;
}

// Appends a model's event rows to their CSV files in the run directory (header first).
class EventFiles {
 public:
  explicit EventFiles(std::string directory) : directory_(std::move(directory)) {}
  void write(const std::vector<EventLog>& logs) {
    for (const EventLog& log : logs) {
      if (log.rows.empty()) continue;
      auto [it, fresh] = files_.try_emplace(log.file);
      if (fresh) {
        it->second.open(directory_ + "/" + log.file, std::ios::trunc);
        if (!it->second) throw std::runtime_error(directory_ + "/" + log.file + ": cannot write");
        it->second << log.header << '\n';
      }
      for (const std::string& row : log.rows) it->second << row << '\n';
      it->second.flush();
    }
  }

 private:
  std::string directory_;
  std::map<std::string, std::ofstream> files_;
};

// The guard on the energy balance: an explicit scheme past its stability limit creates energy
// (a growing mode) long before a value turns NaN, and a balance that is off by more than the
// whole energy of the run is no longer a discretisation error. Names the body whose kinetic +
// internal energy moved furthest from its start.
[[noreturn]] void throw_energy_runaway(const Model& model, const Scene& scene, const Energies& e,
                                       const Energies& initial, double error) {
  std::size_t worst = 0;
  double worst_change = -1.0;
  for (std::size_t b = 0; b < e.bodies.size() && b < initial.bodies.size(); ++b) {
    const double change = std::abs(e.bodies[b].kinetic + e.bodies[b].internal -
                                   initial.bodies[b].kinetic - initial.bodies[b].internal);
    if (change > worst_change) worst = b, worst_change = change;
  }
  char detail[400];
  std::snprintf(detail, sizeof detail,
                "the energy-balance error reached %+.3g %% (limit %.3g %%, [run] "
                "energy_error_limit; its kinetic + internal energy changed by %.4g): the scheme "
                "is unstable at this step; lower the time-step factor, or see "
                "docs/studies/stability.md for the schemes' limits",
                100.0 * error, 100.0 * scene.run.energy_error_limit, worst_change);
  const std::string body =
      worst < scene.bodies.size() ? "body " + scene.bodies[worst].name : std::string("the model");
  throw SimulationError(model.step_count(), model.time(), body, "energy balance", detail);
}

}  // namespace

RunSummary run(Model& model, const Scene& scene, const RunOptions& options) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
  const RunSettings& rs = scene.run;

  // First: a probe naming a node or element the mesh lacks stops the run before any output.
  ProbeRecorder probes(model, scene.probes, options.output_directory);
  std::unique_ptr<FieldWriter> frames;
  std::unique_ptr<HistoryWriter> history;
  std::unique_ptr<EventFiles> events;
  if (!options.output_directory.empty()) {
    OutputPaths paths;
    paths.directory = options.output_directory;
    if (options.write_fields)
      frames = std::make_unique<FieldWriter>(paths.directory, paths.fields_stem);
    std::vector<std::string> names;
    for (const auto& b : scene.bodies) names.push_back(b.name);
    history = std::make_unique<HistoryWriter>(history_path(paths), names);
    events = std::make_unique<EventFiles>(paths.directory);
  }

  RunSummary sum;
  sum.particles = model.particle_count();
  sum.elements = model.element_count();
  sum.initial = model.energies();
  double max_kinetic = sum.initial.kinetic;
  sum.min_dt = 1e300;

  // [run] terminate: the body's centre of mass moves with its mean velocity p / m, integrated
  // by the trapezoidal rule over the history rows (history_every steps apart).
  const std::optional<RunSettings::Termination>& term = rs.terminate;
  auto mean_velocity = [&](const Energies& e) {
    const BodySums& b = e.bodies.at(static_cast<std::size_t>(term->body));
    return b.mass > 0.0 ? (1.0 / b.mass) * b.momentum : Vec3{};
  };
  Vec3 travelled, last_velocity;
  double last_time = model.time();
  if (term) last_velocity = mean_velocity(sum.initial);
  bool through = false;
  int rows_beyond = 0;  // consecutive history rows with the energy balance beyond its limit

  auto record = [&](double dt) {
    const Energies e = model.energies();
    if (term) {
      const Vec3 v = mean_velocity(e);
      travelled += (0.5 * (model.time() - last_time)) * (v + last_velocity);
      last_velocity = v;
      last_time = model.time();
      through = norm(travelled) >= term->travel;
    }
    max_kinetic = std::max(max_kinetic, e.kinetic);
    const double err = energy_balance_error(e, sum.initial, max_kinetic);
    sum.max_energy_error = std::max(sum.max_energy_error, std::abs(err));
    if (history) history->write(history_row(model, e, dt, err));
    if (events) events->write(model.take_events());
    // Three rows in a row: a start-up transient (a velocity imposed on nodes at rest, before the
    // work it does has accumulated) can pass the limit for a row; a growing mode stays.
    rows_beyond = rs.energy_error_limit > 0.0 && !(std::abs(err) <= rs.energy_error_limit)
                      ? rows_beyond + 1
                      : 0;
    if (rows_beyond >= 3) throw_energy_runaway(model, scene, e, sum.initial, err);
    return err;
  };

  double dt = model.stable_time_step();
  record(dt);
  probes.sample(model, true);
  if (frames) model.write_fields(*frames);
  double next_output = rs.output_every > 0.0 ? rs.output_every : 1e300;
  double next_progress = options.progress_seconds;
  double last_error = 0.0;
  const double end = rs.end_time;

  while (model.time() < end * (1.0 - 1e-12) && !through &&
         (rs.max_steps <= 0 || model.step_count() < rs.max_steps)) {
    const double stable = model.stable_time_step();
    // The statistics describe the stable step; the last step may be cut to land on end.
    sum.min_dt = std::min(sum.min_dt, stable);
    sum.max_dt = std::max(sum.max_dt, stable);
    dt = std::min(stable, end - model.time());
    try {
      model.step(dt);
    } catch (const SimulationError&) {
      if (events) events->write(model.take_events());  // what led up to it stays on disk
      throw;
    }
    const long k = model.step_count();
    if (k % rs.history_every == 0) last_error = record(dt);
    probes.sample(model, k % rs.history_every == 0);
    if (frames && model.time() >= next_output * (1.0 - 1e-9) && model.time() < end * (1.0 - 1e-12)) {
      model.write_fields(*frames);
      next_output += rs.output_every;
    }
    if (options.progress && elapsed() >= next_progress) {
      const Energies e = model.energies();
      options.progress({k, model.time(), dt, end, elapsed(),
                        energy_balance_error(e, sum.initial, std::max(max_kinetic, e.kinetic))});
      next_progress = elapsed() + options.progress_seconds;
    }
  }
  if (model.step_count() % rs.history_every != 0) last_error = record(dt);
  probes.sample(model, false, true);
  sum.probes = probes.take();
  if (frames) model.write_fields(*frames);  // the final state, always

  if (through) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "body '%s' travelled %.6g (terminate travel %.6g)",
                  scene.bodies[static_cast<std::size_t>(term->body)].name.c_str(), norm(travelled),
                  term->travel);
    sum.terminated = buf;
  }
  sum.steps = model.step_count();
  sum.final_particles = model.particle_count();
  sum.time = model.time();
  sum.wall_seconds = elapsed();
  sum.point_steps_per_second =
      sum.wall_seconds > 0.0
          ? static_cast<double>(sum.particles + sum.elements) * sum.steps / sum.wall_seconds
          : 0.0;
  sum.final = model.energies();
  sum.energy_error = last_error;
  sum.stages = model.stage_timings();
  sum.field_frames = frames ? frames->frames() : 0;
  if (sum.min_dt > sum.max_dt) sum.min_dt = sum.max_dt = dt;
  if (scene.taylor_reference) {
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      const auto* bar = std::get_if<CylinderShape>(&scene.bodies[b].shape);
      if (bar == nullptr || bar->nose.crh > 0.0) continue;
      sum.taylor = model.measure_taylor(static_cast<int>(b));
      sum.taylor_error = taylor_mean_error(*sum.taylor, *scene.taylor_reference);
      sum.checks.push_back({"taylor mean error (eq 2-42)", sum.taylor_error, 0.0, sum.taylor_error,
                            scene.taylor_reference->tolerance});
      break;
    }
  }
  for (const VelocityReference& v : scene.velocity_references) {
    const BodySums& body = sum.final.bodies[static_cast<std::size_t>(v.body)];
    const Vec3 mean = body.mass > 0.0 ? (1.0 / body.mass) * body.momentum : Vec3{};
    const double value = v.component < 0 ? norm(mean) : mean[v.component];
    static const char* components[] = {"x", "y", "z"};
    sum.checks.push_back({"velocity of " + scene.bodies[static_cast<std::size_t>(v.body)].name + " (" +
                              (v.component < 0 ? "magnitude" : components[v.component]) + ")",
                          value, v.value, std::abs(value - v.value) / std::abs(v.value), v.tolerance});
  }
  if (scene.energy_tolerance > 0.0)
    sum.checks.push_back({"largest |energy-balance error|", sum.max_energy_error, 0.0,
                          sum.max_energy_error, scene.energy_tolerance});
  if (options.progress)
    options.progress({sum.steps, sum.time, dt, end, sum.wall_seconds, sum.energy_error});
  return sum;
}

}  // namespace afemp::core
