// The run loop of core/time_loop.hpp: stable step, output at the requested interval, history
// rows, progress and the summary (the scene's reference checks come after it, from
// analysis/reference_checks.cpp). Moved here from the MPM solver so that FE and coupled runs
// share it.
#include "core/time_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>

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
  r.outflow = e.outflow;
  r.outflow_mass = e.outflow_mass;
  r.outflow_momentum = e.outflow_momentum;
  for (const BodySums& b : e.bodies)
    r.bodies.push_back(
        {b.momentum, b.mass > 0.0 ? (1.0 / b.mass) * b.momentum : Vec3{}, b.kinetic, b.internal});
  return r;
}

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

TimeLoop::TimeLoop(Model& model, const Scene& scene, const RunOptions& options)
    : model_(model),
      scene_(scene),
      options_(options),
      start_(std::chrono::steady_clock::now()),
      // First: a probe naming a node or element the mesh lacks stops the run before any output.
      probes_(std::make_unique<ProbeRecorder>(model, scene.probes, options.output_directory)) {
  if (!options_.output_directory.empty()) {
    OutputPaths paths;
    paths.directory = options_.output_directory;
    if (options_.write_fields)
      frames_ = std::make_unique<FieldWriter>(paths.directory, paths.fields_stem);
    std::vector<std::string> names;
    for (const auto& b : scene_.bodies) names.push_back(b.name);
    std::vector<std::string> extra;
    if (has_mesh_contact(scene_) || has_particle_walls(scene_)) extra = {"sliding", "friction"};
    for (std::string& c : model_.force_columns()) extra.push_back(std::move(c));
    history_ = std::make_unique<HistoryWriter>(
        history_path(paths), names, scene_.mpm.grid.has_face(FaceCondition::outflow), extra);
    events_ = std::make_unique<EventFiles>(paths.directory);
  }
  sum_.particles = model_.particle_count();
  sum_.elements = model_.element_count();
  sum_.initial = model_.energies();
  max_kinetic_ = sum_.initial.kinetic;
  sum_.min_dt = 1e300;
  last_time_ = model_.time();
  if (scene_.run.terminate) last_velocity_ = mean_velocity(sum_.initial);
  dt_ = model_.stable_time_step();
  record(dt_);
  probes_->sample(model_, true);
  if (frames_) model_.write_fields(*frames_);
  next_output_ = scene_.run.output_every > 0.0 ? scene_.run.output_every : 1e300;
  next_history_ = scene_.run.history_interval;
  next_progress_ = options_.progress_seconds;
}

TimeLoop::~TimeLoop() = default;

double TimeLoop::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

// [run] terminate: the body's centre of mass moves with its mean velocity p / m, integrated
// by the trapezoidal rule over the history rows (history_every steps apart).
Vec3 TimeLoop::mean_velocity(const Energies& e) const {
  const BodySums& b = e.bodies.at(static_cast<std::size_t>(scene_.run.terminate->body));
  return b.mass > 0.0 ? (1.0 / b.mass) * b.momentum : Vec3{};
}

double TimeLoop::record(double dt) {
  const Energies e = model_.energies();
  if (scene_.run.terminate) {
    const Vec3 v = mean_velocity(e);
    travelled_ += (0.5 * (model_.time() - last_time_)) * (v + last_velocity_);
    last_velocity_ = v;
    last_time_ = model_.time();
    through_ = norm(travelled_) >= scene_.run.terminate->travel;
  }
  max_kinetic_ = std::max(max_kinetic_, e.kinetic);
  const double err = energy_balance_error(e, sum_.initial, max_kinetic_);
  sum_.max_energy_error = std::max(sum_.max_energy_error, std::abs(err));
  if (history_) {
    HistoryRow row = history_row(model_, e, dt, err);
    if (has_mesh_contact(scene_) || has_particle_walls(scene_)) row.extra = {e.sliding, e.friction};
    model_.force_values(forces_);
    row.extra.insert(row.extra.end(), forces_.begin(), forces_.end());
    history_->write(row);
  }
  if (events_) events_->write(model_.take_events());
  // Three rows in a row: a start-up transient (a velocity imposed on nodes at rest, before the
  // work it does has accumulated) can pass the limit for a row; a growing mode stays.
  const double limit = scene_.run.energy_error_limit;
  rows_beyond_ = limit > 0.0 && !(std::abs(err) <= limit) ? rows_beyond_ + 1 : 0;
  if (rows_beyond_ >= 3) throw_energy_runaway(model_, scene_, e, sum_.initial, err);
  return err;
}

bool TimeLoop::finished() const {
  const RunSettings& rs = scene_.run;
  return !(model_.time() < rs.end_time * (1.0 - 1e-12)) || through_ ||
         (rs.max_steps > 0 && model_.step_count() >= rs.max_steps);
}

void TimeLoop::step(double until) {
  const RunSettings& rs = scene_.run;
  const double end = rs.end_time;
  until = std::min(until, end);
  const double stable = model_.stable_time_step();
  // The statistics describe the stable step; the last step may be cut to land on end.
  sum_.min_dt = std::min(sum_.min_dt, stable);
  sum_.max_dt = std::max(sum_.max_dt, stable);
  dt_ = std::min(stable, until - model_.time());
  try {
    model_.step(dt_);
  } catch (const SimulationError&) {
    if (events_) events_->write(model_.take_events());  // what led up to it stays on disk
    throw;
  }
  const long k = model_.step_count();
  const double t = model_.time();
  // A history row every history_every steps, or at the first step end at or past each multiple
  // of history_interval.
  bool row = k % rs.history_every == 0;
  if (rs.history_interval > 0.0) {
    row = t >= next_history_ * (1.0 - 1e-9);
    while (next_history_ <= t * (1.0 + 1e-9)) next_history_ += rs.history_interval;
  }
  last_step_recorded_ = row;
  if (row) last_error_ = record(dt_);
  probes_->sample(model_, row);
  // Frames every output_every and at each of output_times (the first step end at or past it;
  // one frame when both fall due); the final state is written by finish().
  bool frame = t >= next_output_ * (1.0 - 1e-9);
  if (frame) next_output_ += rs.output_every;
  while (next_listed_ < rs.output_times.size() &&
         t >= rs.output_times[next_listed_] * (1.0 - 1e-9)) {
    frame = true;
    ++next_listed_;
  }
  if (frames_ && frame && t < end * (1.0 - 1e-12)) model_.write_fields(*frames_);
  if (options_.progress && elapsed() >= next_progress_) {
    const Energies e = model_.energies();
    options_.progress({k, model_.time(), dt_, end, elapsed(),
                       energy_balance_error(e, sum_.initial, std::max(max_kinetic_, e.kinetic))});
    next_progress_ = elapsed() + options_.progress_seconds;
  }
}

RunSummary TimeLoop::finish() {
  const RunSettings& rs = scene_.run;
  if (!last_step_recorded_) last_error_ = record(dt_);
  probes_->sample(model_, false, true);
  sum_.probes = probes_->take();
  if (frames_) model_.write_fields(*frames_);  // the final state, always

  if (through_) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "body '%s' travelled %.6g (terminate travel %.6g)",
                  scene_.bodies[static_cast<std::size_t>(rs.terminate->body)].name.c_str(),
                  norm(travelled_), rs.terminate->travel);
    sum_.terminated = buf;
  }
  RunSummary& sum = sum_;
  sum.steps = model_.step_count();
  sum.final_particles = model_.particle_count();
  sum.time = model_.time();
  sum.wall_seconds = elapsed();
  sum.point_steps_per_second =
      sum.wall_seconds > 0.0
          ? static_cast<double>(sum.particles + sum.elements) * sum.steps / sum.wall_seconds
          : 0.0;
  sum.final = model_.energies();
  sum.energy_error = last_error_;
  sum.stages = model_.stage_timings();
  sum.field_frames = frames_ ? frames_->frames() : 0;
  if (sum.min_dt > sum.max_dt) sum.min_dt = sum.max_dt = dt_;
  if (options_.progress)
    options_.progress({sum.steps, sum.time, dt_, rs.end_time, sum.wall_seconds, sum.energy_error});
  return sum;
}

}  // namespace afemp::core
