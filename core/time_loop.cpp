// The run loop of core/time_loop.hpp: stable step, output at the requested interval, history
// rows, progress and the summary (the scene's reference checks come after it, from
// analysis/reference_checks.cpp). Moved here from the MPM solver so that FE and coupled runs
// share it.
#include "core/time_loop.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>

#include "core/checkpoint.hpp"
#include "core/contact_warnings.hpp"
#include "core/dynamic_relaxation.hpp"
#include "core/fault_injection.hpp"
#include "core/output/history.hpp"
#include "core/output/run_directory.hpp"
#include "core/phases.hpp"
#include "core/probe_recorder.hpp"
#include "core/state_archive.hpp"

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

std::vector<std::string> history_bodies(const Scene& scene) {
  std::vector<std::string> names;
  for (const auto& b : scene.bodies) names.push_back(b.name);
  return names;
}

// The columns after the body columns: the energies the model's contacts declare (and a
// relaxation phase's damping, the loop's), then the interface forces.
std::vector<std::string> history_extra(const std::vector<EnergyColumn>& energies,
                                       const Model& model) {
  std::vector<std::string> extra;
  for (const EnergyColumn& c : energies) extra.emplace_back(c.name);
  for (std::string& c : model.force_columns()) extra.push_back(std::move(c));
  return extra;
}

void visit_energies(StateArchive& a, const char* name, Energies& e) {
  const StateArchive::Group group(a, name);
  a.item("kinetic", e.kinetic);
  a.item("internal", e.internal);
  a.item("plastic", e.plastic);
  a.item("viscous", e.viscous);
  a.item("hourglass", e.hourglass);
  a.item("stabilisation", e.stabilisation);
  a.item("eroded", e.eroded);
  a.item("converted", e.converted);
  a.item("external_work", e.external_work);
  a.item("contact", e.contact);
  a.item("sliding", e.sliding);
  a.item("friction", e.friction);
  a.item("wall", e.wall);
  a.item("outflow", e.outflow);
  a.item("outflow_mass", e.outflow_mass);
  a.item("outflow_momentum", e.outflow_momentum);
  a.item("damped", e.damped);
  a.item("bodies", e.bodies);
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
  // A checkpoint: the files and their lengths; restoring cuts each to its length and appends.
  void state(StateArchive& a) {
    std::vector<std::string> names;
    std::vector<std::uint64_t> bytes;
    for (auto& [name, file] : files_) {
      file.flush();
      if (!file) throw std::runtime_error(directory_ + "/" + name + ": cannot write");
      names.push_back(name);
      bytes.push_back(static_cast<std::uint64_t>(file.tellp()));
    }
    const StateArchive::Group group(a, "events");
    a.item("files", names);
    a.item("bytes", bytes);
    if (!a.loading() || directory_.empty()) return;
    if (bytes.size() != names.size()) throw CheckpointError(a.where("bytes") + ": one per file");
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::string path = directory_ + "/" + names[k];
      cut_to_checkpoint(path, bytes[k]);
      std::ofstream& f = files_[names[k]];
      f.open(path, std::ios::app);
      if (!f) throw std::runtime_error(path + ": cannot write");
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
      // On ranks, rank 0 alone writes the probe files (the others sample with it).
      probes_(std::make_unique<ProbeRecorder>(
          model, scene.probes, options.rank == 0 ? options.output_directory : std::string(),
          !options.restart_from.empty())),
      energy_columns_(model.energy_columns()) {
  if (options_.agree) {
    // On ranks every decision is made alike: the progress comes at the shortest interval any
    // rank asks (one printing to a terminal asks more often), on every rank.
    options_.progress_seconds = -options_.agree(-options_.progress_seconds);
    if (!options_.progress) options_.progress = [](const Progress&) {};
  }
  overlaps_ = std::make_unique<OverlapCheck>(scene);
  if (overlaps_->empty()) overlaps_.reset();
  if (books_damped_energy(scene_)) energy_columns_.push_back({"damped", &Energies::damped});
  if (!options_.restart_from.empty()) {
    restore(options_.restart_from);
    return;
  }
  if (!options_.output_directory.empty()) {
    OutputPaths paths;
    paths.directory = options_.output_directory;
    if (options_.write_fields)
      frames_ = std::make_unique<FieldWriter>(paths.directory, paths.fields_stem);
    history_ = std::make_unique<HistoryWriter>(history_path(paths), history_bodies(scene_),
                                               scene_.mpm.grid.has_face(FaceCondition::outflow),
                                               history_extra(energy_columns_, model_));
    events_ = std::make_unique<EventFiles>(paths.directory);
  }
  sum_.particles = model_.particle_count();
  sum_.elements = model_.element_count();
  sum_.initial = energies();
  max_kinetic_ = sum_.initial.kinetic;
  sum_.min_dt = 1e300;
  last_time_ = model_.time();
  if (scene_.run.terminate) last_velocity_ = mean_velocity(sum_.initial);
  dt_ = model_.stable_time_step();
  warnings_.start(dt_);
  record(dt_);
  probes_->sample(model_, true);
  if (frames_) model_.write_fields(*frames_);
  next_output_ = scene_.run.output_every > 0.0 ? scene_.run.output_every : 1e300;
  next_history_ = scene_.run.history_interval;
  next_progress_ = options_.progress_seconds;
  if (scene_.run.checkpoint_every > 0.0) next_checkpoint_ = scene_.run.checkpoint_every;
  if (scene_.run.checkpoint_wall_every > 0.0)
    next_checkpoint_wall_ = scene_.run.checkpoint_wall_every;
}

Energies TimeLoop::energies() const {
  Energies e = model_.energies();
  e.damped = damped_;
  return e;
}

void TimeLoop::run_phase(const PhaseSpec& phase) {
  // Before a static or implicit phase that follows another: a checkpoint of the state it starts
  // from, so that a solve that fails can be run again from there with other settings
  // (docs/restart.md). A successful phase's checkpoint at its end (the same step) replaces it.
  std::string start;
  if (phase.kind != PhaseKind::relaxation && model_.time() > 0.0)
    start = checkpoint(std::string("the start of the ") + to_string(phase.kind) + " phase");
  try {
    if (phase.kind == PhaseKind::relaxation)
      run_relaxation(phase);
    else if (options_.ranks > 1)
      damped_ += solve_phase_on_rank_0(phase);
    else
      damped_ += model_.run_implicit_phase(phase, options_.phase_log);
  } catch (const SimulationError&) {
    // A static or implicit phase on ranks fails on every rank at once (rank 0's solve, its
    // outcome sent to every rank), so its frame can be written together.
    keep_failure(phase.kind != PhaseKind::relaxation && options_.ranks > 1);
    if (!start.empty() && options_.phase_log)
      *options_.phase_log << "the checkpoint " << start
                          << " holds the state the phase started from: a restart from it runs the "
                             "phase again, with other load_steps, max_iterations, tolerance, "
                             "time_step or alpha if the scene now gives them\n";
    throw;
  }
  const RunSettings& rs = scene_.run;
  const double t = model_.time();
  last_time_ = t;
  dt_ = model_.stable_time_step();
  record(0.0);
  last_step_recorded_ = true;
  probes_->sample(model_, true);
  // A last phase's state is the run's final one, which finish() writes.
  if (frames_ && !finished()) model_.write_fields(*frames_);
  if (options_.phase_log || options_.ranks > 1) print_switch(phase);
  // The explicit phase's frames, rows and checkpoints fall due from here on, not at the times
  // the static phase passed over.
  if (rs.output_every > 0.0)
    while (next_output_ <= t * (1.0 + 1e-9)) next_output_ += rs.output_every;
  while (next_listed_ < rs.output_times.size() && rs.output_times[next_listed_] <= t * (1.0 + 1e-9))
    ++next_listed_;
  if (rs.history_interval > 0.0)
    while (next_history_ <= t * (1.0 + 1e-9)) next_history_ += rs.history_interval;
  if (rs.checkpoint_every > 0.0)
    while (next_checkpoint_ <= t * (1.0 + 1e-9)) next_checkpoint_ += rs.checkpoint_every;
  if (!options_.output_directory.empty() && !finished())
    checkpoint(std::string("the end of the ") + to_string(phase.kind) + " phase");
}

double TimeLoop::solve_phase_on_rank_0(const PhaseSpec& phase) {
  if (!options_.whole_model || !options_.from_rank_0)
    throw std::logic_error("TimeLoop: a phase on ranks needs RunOptions::whole_model, from_rank_0");
  // The state holds no pending events: they go to their files first (rank 0's).
  const std::vector<EventLog> pending = model_.take_events();
  if (events_) events_->write(pending);
  model_.prepare_checkpoint();
  enum Outcome : char { solved, simulation_error, other_error };
  char outcome = solved;
  double damped = 0.0;
  std::string why;
  std::exception_ptr error;
  std::vector<std::byte> state;
  const std::string kind = to_string(phase.kind);
  std::unique_ptr<Model> whole;
  if (options_.rank == 0) try {
      std::vector<std::byte> before;
      {
        StateArchive a("the state the " + kind + " phase starts from", StateArchive::InMemory{});
        model_.state(a);
        before = a.image();
      }
      whole = options_.whole_model();
      StateArchive in("the state the " + kind + " phase starts from", before);
      whole->state(in);
      damped = whole->run_implicit_phase(phase, options_.phase_log);
      const std::vector<EventLog> rows = whole->take_events();
      if (events_) events_->write(rows);
      StateArchive out("the state the " + kind + " phase ends in", StateArchive::InMemory{});
      whole->state(out);
      state = out.image();
    } catch (const std::exception& e) {
      outcome = dynamic_cast<const SimulationError*>(&e) ? simulation_error : other_error;
      why = e.what();
      error = std::current_exception();
      // The iterations of a solve that failed go to their file, as in one process.
      if (whole && events_) try {
          events_->write(whole->take_events());
        } catch (const std::exception&) {
        }
      // A solve that failed leaves in its model the state one process's model keeps (the last
      // converged load or time step), which every rank takes below, so that the frame the run
      // keeps (keep_failure, on every rank) shows it as one process's does.
      if (whole && outcome == simulation_error) try {
          StateArchive out("the state the " + kind + " phase failed in", StateArchive::InMemory{});
          whole->state(out);
          state = out.image();
        } catch (const std::exception&) {
          state.clear();
        }
    }
  // What came of it (the outcome, whether a failed solve's state follows, the damped energy,
  // rank 0's message), then the state.
  const std::size_t text = 2 + sizeof damped;
  std::vector<std::byte> head(text + why.size());
  head[0] = static_cast<std::byte>(outcome);
  head[1] = static_cast<std::byte>(outcome != solved && !state.empty());
  std::memcpy(head.data() + 2, &damped, sizeof damped);
  std::memcpy(head.data() + text, why.data(), why.size());
  options_.from_rank_0(head);
  outcome = static_cast<char>(head[0]);
  const bool failed_state = head[1] != std::byte{0};
  std::memcpy(&damped, head.data() + 2, sizeof damped);
  why.assign(reinterpret_cast<const char*>(head.data()) + text, head.size() - text);
  if (failed_state) {
    options_.from_rank_0(state);
    StateArchive a("the state the " + kind + " phase failed in", state);
    model_.state(a);
  }
  if (error) std::rethrow_exception(error);
  if (outcome == simulation_error)
    throw SimulationError(model_.step_count(), model_.time(), "rank 0's " + kind + " phase",
                          "solve", "rank 0 says why: " + why);
  if (outcome != solved)
    throw std::runtime_error("the " + kind + " phase failed on rank 0, which says why: " + why);
  options_.from_rank_0(state);
  StateArchive a("the state the " + kind + " phase ends in", state);
  model_.state(a);
  return damped;
}

void TimeLoop::print_switch(const PhaseSpec& phase) const {
  const Energies e = energies();
  std::vector<BodyStress> stress = model_.body_stresses();
  if (options_.ranks > 1) {
    // Every rank's points: their count summed, the extremes of the ranks that have any.
    std::vector<double> points, most;
    for (const BodyStress& b : stress) {
      const bool any = b.points > 0;
      points.push_back(static_cast<double>(b.points));
      most.insert(most.end(), {any ? b.max_von_mises : -1e300, any ? -b.min_pressure : -1e300,
                               any ? b.max_pressure : -1e300});
    }
    options_.add_over_ranks(points);
    for (double& v : most) v = options_.agree(v);
    for (std::size_t b = 0; b < stress.size(); ++b) {
      stress[b].points = static_cast<std::size_t>(points[b]);
      stress[b].max_von_mises = most[3 * b];
      stress[b].min_pressure = -most[3 * b + 1];
      stress[b].max_pressure = most[3 * b + 2];
    }
  }
  if (!options_.phase_log) return;
  char line[320];
  std::snprintf(line, sizeof line,
                "the %s phase ends at t = %.6g: internal energy %.6g, kinetic %.6g, external "
                "work %.6g%s; %s these stresses:\n",
                to_string(phase.kind), model_.time(), e.internal, e.kinetic, e.external_work,
                books_damped_energy(scene_) ? (", damped " + std::to_string(e.damped)).c_str() : "",
                finished() ? "the run ends with" : "the next phase starts from");
  *options_.phase_log << line;
  for (std::size_t b = 0; b < stress.size() && b < scene_.bodies.size(); ++b) {
    if (stress[b].points == 0) continue;
    std::snprintf(line, sizeof line,
                  "  %s: von Mises up to %.6g, pressure %.6g to %.6g (%zu points)\n",
                  scene_.bodies[b].name.c_str(), stress[b].max_von_mises, stress[b].min_pressure,
                  stress[b].max_pressure, stress[b].points);
    *options_.phase_log << line;
  }
}

void TimeLoop::run_relaxation(const PhaseSpec& phase) {
  // The bodies with an initial velocity are held at rest through the relaxation and set moving
  // at its end; the kinetic energy taken from them and given back is booked as damped.
  const std::vector<int> moving = moving_bodies(scene_);
  auto hold = [&] {
    for (int b : moving) model_.set_body_velocity(b, Vec3{});
  };
  double before = model_.energies().kinetic;
  for (int b : moving) model_.hold_body(b, true);
  hold();
  damped_ += before - model_.energies().kinetic;
  const double damped_start = damped_;
  RelaxationSettings s;
  s.tolerance = phase_tolerance(phase);
  s.factor = phase.damping_factor;
  s.check_every = phase.check_every;
  s.time_step_factor = phase.relaxation_step_factor;
  s.end = phase.end_time - model_.time();
  const RelaxationResult r = relax(
      model_, s,
      [&](const RelaxationCheck& c) {
        damped_ = damped_start + c.damped;
        dt_ = model_.stable_time_step();
        record(dt_);
        if (options_.progress) {
          // Against the phase's end: the relaxation stops there at the latest.
          const Energies e = energies();
          options_.progress({model_.step_count(), model_.time(), dt_, phase.end_time, elapsed(),
                             energy_balance_error(e, sum_.initial, max_kinetic_)});
        }
        if (options_.phase_log)
          *options_.phase_log << "relaxation: step " << c.steps << ", t " << c.time
                              << ": kinetic energy " << c.recent << ", " << c.ratio
                              << " of its peak " << c.peak << " (tolerance " << s.tolerance
                              << ")\n";
      },
      hold);
  damped_ = damped_start + r.damped;
  if (options_.phase_log || options_.ranks > 1) print_damping_force(r);
  model_.set_clock(phase.end_time);
  before = model_.energies().kinetic;
  for (int b : moving) {
    model_.hold_body(b, false);
    model_.set_body_velocity(b, scene_.bodies[static_cast<std::size_t>(b)].velocity);
  }
  damped_ -= model_.energies().kinetic - before;
}

// What the damping still held at convergence (RelaxationResult::damping_force): a steady force
// the relaxation did not balance hides below any kinetic-energy tolerance, so it is printed
// beside it, and flagged where its part along gravity passes 1 % of the body's weight (the
// supports then carry the weight to no better than that). The bodies held at rest are left out
// (what holds them is not the damping).
void TimeLoop::print_damping_force(const RelaxationResult& r) const {
  const Energies e = model_.energies();  // collective on ranks
  if (!options_.phase_log) return;
  const double g = norm(scene_.run.gravity);
  const std::vector<int> held = moving_bodies(scene_);
  char line[480];
  for (std::size_t b = 0; b < r.damping_force.size() && b < scene_.bodies.size(); ++b) {
    const Vec3& d = r.damping_force[b];
    if (!(norm(d) > 0.0) || std::find(held.begin(), held.end(), static_cast<int>(b)) != held.end())
      continue;
    const double weight = b < e.bodies.size() ? e.bodies[b].mass * g : 0.0;
    if (weight > 0.0) {
      const double along = std::abs(dot(d, scene_.run.gravity)) / g;
      const bool flag = along > 0.01 * weight;
      std::snprintf(line, sizeof line,
                    "  %s%s: the damping held (%.4g, %.4g, %.4g) at the last step, along gravity "
                    "%.3g %% of its weight%s\n",
                    flag ? "warning: " : "", scene_.bodies[b].name.c_str(), d.x, d.y, d.z,
                    100.0 * along / weight,
                    flag ? ": a force the relaxation has not balanced (a body drifting at the "
                           "damping's terminal velocity keeps a kinetic energy far below the "
                           "tolerance); a smaller tolerance lets it settle"
                         : "");
    } else {
      std::snprintf(line, sizeof line,
                    "  %s: the damping held (%.4g, %.4g, %.4g) at the last step\n",
                    scene_.bodies[b].name.c_str(), d.x, d.y, d.z);
    }
    *options_.phase_log << line;
  }
}

TimeLoop::~TimeLoop() = default;

double TimeLoop::elapsed() const {
  const double t = wall_offset_ +
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return options_.agree ? options_.agree(t) : t;
}

// [run] terminate: the body's centre of mass moves with its mean velocity p / m, integrated
// by the trapezoidal rule over the history rows (history_every steps apart).
Vec3 TimeLoop::mean_velocity(const Energies& e) const {
  const BodySums& b = e.bodies.at(static_cast<std::size_t>(scene_.run.terminate->body));
  return b.mass > 0.0 ? (1.0 / b.mass) * b.momentum : Vec3{};
}

double TimeLoop::record(double dt) {
  const Energies e = energies();
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
  warnings_.row(model_.time(), e, err);
  if (overlaps_) overlaps_->check(model_);
  if (history_) {
    HistoryRow row = history_row(model_, e, dt, err);
    for (const EnergyColumn& c : energy_columns_) row.extra.push_back(e.*c.value);
    model_.force_values(forces_);
    row.extra.insert(row.extra.end(), forces_.begin(), forces_.end());
    history_->write(row);
  }
  if (events_) events_->write(model_.take_events());
  // Three rows in a row: a start-up transient (a velocity imposed on nodes at rest, before the
  // work it does has accumulated) can pass the limit for a row; a growing mode stays.
  const double limit = scene_.run.energy_error_limit;
  rows_beyond_ = limit > 0.0 && !(std::abs(err) <= limit) ? rows_beyond_ + 1 : 0;
  if (rows_beyond_ >= 3) {
    // The error is the whole run's (on ranks summed in rank order and sent to every rank, the
    // same bits everywhere): every rank stops at this row, and their frame is written together.
    keep_failure(options_.ranks > 1);
    throw_energy_runaway(model_, scene_, e, sum_.initial, err);
  }
  return err;
}

bool TimeLoop::finished() const {
  const RunSettings& rs = scene_.run;
  return !(model_.time() < rs.end_time * (1.0 - 1e-12)) || through_ ||
         (rs.max_steps > 0 && model_.step_count() >= rs.max_steps);
}

void TimeLoop::step(double until) {
  if (const PhaseSpec* phase = phase_due(scene_, model_.time())) {
    run_phase(*phase);
    return;
  }
  const RunSettings& rs = scene_.run;
  const double end = rs.end_time;
  // The explicit steps stop where the next static or implicit phase starts.
  until = std::min({until, end, next_phase_start(scene_, model_.time())});
  const double stable = model_.stable_time_step();
  // The statistics describe the stable step; the last step may be cut to land on end.
  if (stable < sum_.min_dt) {
    sum_.min_dt = stable;
    warnings_.new_low(stable, model_.time(), model_);
  }
  sum_.max_dt = std::max(sum_.max_dt, stable);
  dt_ = std::min(stable, until - model_.time());
  try {
    model_.step(dt_);
  } catch (const SimulationError&) {
    keep_failure();
    throw;
  }
  fault_point("step");
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
  // Checkpoints at [run] checkpoint_every, every checkpoint_wall_every seconds and on request
  // (SIGUSR1), after the step's output; none at the end (the run is complete).
  std::string reason;
  if (t >= next_checkpoint_ * (1.0 - 1e-9)) {
    reason = "checkpoint_every";
    while (next_checkpoint_ <= t * (1.0 + 1e-9)) next_checkpoint_ += rs.checkpoint_every;
  }
  if (elapsed() >= next_checkpoint_wall_) {
    reason = "checkpoint_wall_every";
    next_checkpoint_wall_ = elapsed() + rs.checkpoint_wall_every;
  }
  if (options_.checkpoint_requested && options_.checkpoint_requested()) reason = "SIGUSR1";
  if (!reason.empty() && !finished()) checkpoint(reason);
  if (options_.progress && elapsed() >= next_progress_) {
    const Energies e = energies();
    options_.progress({k, model_.time(), dt_, end, elapsed(),
                       energy_balance_error(e, sum_.initial, std::max(max_kinetic_, e.kinetic))});
    next_progress_ = elapsed() + options_.progress_seconds;
  }
}

void TimeLoop::keep_failure(bool every_rank) {
  if (events_) events_->write(model_.take_events());
  // On ranks a frame is a gather that every rank joins: a rank that fails alone cannot write one.
  if (!frames_ || (options_.agree && !every_rank)) return;
  try {
    model_.write_fields(*frames_);
  } catch (const std::exception&) {
    // The run's error is what the user must see; the frames written before stay valid.
  }
  // The other ranks wait until rank 0 has written the frame: the first rank to stop stops them
  // all (MPI_Abort, apps/main.cpp), which would cut rank 0's write short.
  if (every_rank && options_.agree) options_.agree(0.0);
}

void TimeLoop::run(const std::function<void()>& after_step) {
  while (!finished()) {
    if (options_.stop_requested && options_.stop_requested()) {
      stopped_ = true;
      return;
    }
    step(scene_.run.end_time);
    if (after_step) after_step();
  }
}

RunSummary TimeLoop::finish() {
  const RunSettings& rs = scene_.run;
  if (stopped_) try {
      sum_.checkpoint = checkpoint("stopped");
    } catch (const std::exception& e) {
      sum_.checkpoint_error = e.what();
    }
  sum_.interrupted = stopped_;
  sum_.restarted_at = restarted_at_;
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
  sum.final = energies();
  sum.energy_error = last_error_;
  sum.stages = model_.stage_timings();
  sum.ranks = options_.ranks;
  sum.field_frames = frames_ ? frames_->frames() : 0;
  if (sum.min_dt > sum.max_dt) sum.min_dt = sum.max_dt = dt_;
  sum.warnings = warnings_.summary(model_, sum.initial, sum.final, sum.energy_error);
  if (overlaps_)
    for (std::string& w : overlaps_->summary()) sum.warnings.push_back(std::move(w));
  if (!options_.output_directory.empty()) {
    OutputPaths paths;
    paths.directory = options_.output_directory;
    const std::string path = warnings_path(paths);
    std::ofstream out(path, std::ios::trunc);
    for (const std::string& w : sum.warnings) out << w << '\n';
    out.flush();
    if (!out) throw std::runtime_error(path + ": cannot write");
  }
  if (options_.progress)
    options_.progress({sum.steps, sum.time, dt_, rs.end_time, sum.wall_seconds, sum.energy_error});
  return sum;
}

}  // namespace afemp::core

namespace afemp::core {

namespace {

// Flushes a written file to the disk (a checkpoint must be whole before it replaces the
// previous one, even across a power cut).
void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw CheckpointError(path + ": cannot reopen to sync: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw CheckpointError(path + ": cannot sync: " + std::strerror(err));
}

// The next multiple-of-`every` time after t (an interval changed on restart), or never.
double next_after(double t, double every) {
  if (!(every > 0.0)) return 1e300;
  double next = every * std::floor(t / every + 1e-9);
  while (next <= t * (1.0 + 1e-9)) next += every;
  return next;
}

}  // namespace

std::string TimeLoop::checkpoint(const std::string& reason) {
  if (options_.output_directory.empty()) return "";
  // The model's pending events go to their files first: its state holds none.
  if (events_) events_->write(model_.take_events());
  // On ranks, what calls the other ranks comes first (the model's state gathered onto rank 0,
  // the wall time agreed): rank 0's write then calls none, so that a write failing there leaves
  // no rank waiting in a gather, and whether it failed is agreed at the end.
  model_.prepare_checkpoint();
  saving_wall_ = elapsed();
  const auto failed_elsewhere = [this](bool failed) {
    return options_.agree && options_.agree(failed ? 1.0 : 0.0) > 0.0 && !failed;
  };
  if (options_.rank != 0) {
    if (failed_elsewhere(false))
      throw CheckpointError("rank 0 could not write the checkpoint (its message says why)");
    return "";
  }
  const std::string& dir = options_.output_directory;
  const std::string path = checkpoint_path(dir, model_.step_count());
  const std::string tmp = path + ".tmp";
  std::string error;
  std::error_code ec;
  std::filesystem::create_directories(checkpoint_directory(dir), ec);
  if (ec) error = checkpoint_directory(dir) + ": cannot create: " + ec.message();
  if (error.empty()) try {
      StateArchive a(tmp, StateArchive::Mode::save);
      CheckpointHeader h = checkpoint_header(scene_, model_.step_count(), model_.time(), reason);
      h.ranks = options_.ranks;
      visit_header(a, h);
      model_.state(a);
      fault_point("checkpoint");
      visit(a);
      a.close();
      sync_file(tmp);
      std::filesystem::rename(tmp, path);
    } catch (const std::exception& e) {
      std::filesystem::remove(tmp, ec);
      error = std::string(e.what()) + disk_full_note(dir) + "; the previous checkpoints are kept";
    }
  failed_elsewhere(!error.empty());
  if (!error.empty()) throw CheckpointError(error);
  ++checkpoints_written_;
  std::vector<std::string> all = list_checkpoints(dir);
  for (std::size_t k = 0; k + static_cast<std::size_t>(scene_.run.checkpoint_keep) < all.size();
       ++k)
    std::filesystem::remove(all[k], ec);
  return path;
}

void TimeLoop::restore(const std::string& path) {
  StateArchive a(path, StateArchive::Mode::load);
  CheckpointHeader h;
  visit_header(a, h);
  const std::vector<std::string> changes = scene_changes(h, scene_);
  if (!changes.empty()) {
    std::string text = path +
                       ": restart refused: the scene changed since the checkpoint (only "
                       "the end time, output, history and checkpoint settings may):";
    for (const std::string& c : changes) text += "\n  " + c;
    throw CheckpointError(text);
  }
  model_.state(a);
  visit(a);
  restarted_at_ = model_.step_count();
  // A checkpoint half written when the run was killed: never complete, never read.
  std::error_code ec;
  if (!options_.output_directory.empty())
    for (std::filesystem::directory_iterator
             it(checkpoint_directory(options_.output_directory), ec),
         end;
         !ec && it != end; it.increment(ec))
      if (it->path().extension() == ".tmp") std::filesystem::remove(it->path(), ec);
  start_ = std::chrono::steady_clock::now();
  next_progress_ = elapsed() + options_.progress_seconds;
  if (scene_.run.checkpoint_wall_every > 0.0)
    next_checkpoint_wall_ = elapsed() + scene_.run.checkpoint_wall_every;
}

// The loop's bookkeeping and the output files' state, both ways.
void TimeLoop::visit(StateArchive& a) {
  const RunSettings& rs = scene_.run;
  {
    const StateArchive::Group group(a, "loop");
    a.item("particles", sum_.particles);
    a.item("elements", sum_.elements);
    visit_energies(a, "initial", sum_.initial);
    a.item("min_dt", sum_.min_dt);
    a.item("max_dt", sum_.max_dt);
    a.item("max_energy_error", sum_.max_energy_error);
    a.item("max_kinetic", max_kinetic_);
    a.item("damped", damped_);
    a.item("travelled", travelled_);
    a.item("last_velocity", last_velocity_);
    a.item("last_time", last_time_);
    a.item("through", through_);
    a.item("rows_beyond", rows_beyond_);
    a.item("dt", dt_);
    a.item("last_error", last_error_);
    a.item("last_step_recorded", last_step_recorded_);
    double wall = saving_wall_;
    a.item("wall_seconds", wall);
    if (a.loading()) wall_offset_ = wall;
    // The next output, history row and checkpoint times, with the settings they were made
    // from: a setting changed on restart starts its own sequence after the present time.
    double every[3] = {rs.output_every, rs.history_interval, rs.checkpoint_every};
    a.item("output_every", every[0]);
    a.item("history_interval", every[1]);
    a.item("checkpoint_every", every[2]);
    a.item("next_output", next_output_);
    a.item("next_history", next_history_);
    a.item("next_checkpoint", next_checkpoint_);
    a.item("next_listed", next_listed_);
    if (a.loading()) {
      const double t = model_.time();
      if (every[0] != rs.output_every) next_output_ = next_after(t, rs.output_every);
      if (every[1] != rs.history_interval)
        next_history_ = rs.history_interval > 0.0 ? next_after(t, rs.history_interval) : 0.0;
      if (every[2] != rs.checkpoint_every) next_checkpoint_ = next_after(t, rs.checkpoint_every);
      next_listed_ = 0;
      while (next_listed_ < rs.output_times.size() &&
             t >= rs.output_times[next_listed_] * (1.0 - 1e-9))
        ++next_listed_;
    }
  }
  warnings_.state(a);
  if (overlaps_) overlaps_->state(a);
  const StateArchive::Group group(a, "output");
  std::string index = frames_ ? frames_->index_text() : std::string();
  std::uint8_t has_fields = frames_ ? 1 : 0;
  std::uint64_t history_bytes = history_ ? history_->bytes() : 0;
  std::uint64_t history_rows = history_ ? history_->rows() : 0;
  a.item("has_fields", has_fields);
  a.item("fields_index", index);
  a.item("history_bytes", history_bytes);
  a.item("history_rows", history_rows);
  // A rank's scratch copy of the output starts anew: the run's files are rank 0's.
  const bool resume = options_.rank == 0;
  if (a.loading() && !options_.output_directory.empty()) {
    OutputPaths paths;
    paths.directory = options_.output_directory;
    if (options_.write_fields)
      frames_ = has_fields && resume
                    ? std::make_unique<FieldWriter>(paths.directory, paths.fields_stem, index)
                    : std::make_unique<FieldWriter>(paths.directory, paths.fields_stem);
    const bool outflow = scene_.mpm.grid.has_face(FaceCondition::outflow);
    if (history_bytes > 0 && resume)
      history_ =
          std::make_unique<HistoryWriter>(history_path(paths), history_bodies(scene_), outflow,
                                          history_extra(energy_columns_, model_),
                                          HistoryWriter::Resume{history_bytes, history_rows});
    else
      history_ = std::make_unique<HistoryWriter>(history_path(paths), history_bodies(scene_),
                                                 outflow, history_extra(energy_columns_, model_));
    events_ = std::make_unique<EventFiles>(paths.directory);
  }
  EventFiles none("");
  (events_ && resume ? *events_ : none).state(a);
  probes_->state(a);
}

}  // namespace afemp::core
