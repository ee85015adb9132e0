// A run of the MPM solver to its end time with output, history, progress and the guard.
#include "mpm/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "core/output/field_writer.hpp"
#include "core/output/history.hpp"
#include "core/output/run_directory.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {

double energy_balance_error(const Energies& now, const Energies& initial, double max_kinetic) {
  const double e0 = initial.total();
  const double scale = std::max(std::abs(e0) + std::abs(now.external_work), max_kinetic);
  if (scale <= 0.0) return 0.0;
  return (now.total() - e0 - now.external_work) / scale;
}

namespace {

// Derived per-particle fields for output, kept between frames.
class FrameWriter {
 public:
  explicit FrameWriter(const std::string& directory) : writer_(directory, "particles") {}

  void write(const MpmSolver& s) {
    const Particles& p = s.particles();
    const std::size_t n = p.size();
    pressure_.resize(n);
    von_mises_.resize(n);
    density_.resize(n);
    body_.resize(n);
    id_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      pressure_[i] = core::pressure(p.stress[i]);
      von_mises_[i] = core::von_mises(p.stress[i]);
      density_[i] = p.mass[i] / p.volume[i];
      body_[i] = p.body[i];
      id_[i] = p.id[i];
    }
    std::vector<core::FieldView>& fields = views_;
    fields = {
        core::vector_field("velocity", p.velocity.data()),
        core::tensor_field("stress", p.stress.data()),
        core::scalar_field("pressure", pressure_.data()),
        core::scalar_field("von_mises", von_mises_.data()),
        core::scalar_field("plastic_strain", p.plastic_strain.data()),
        core::scalar_field("temperature", p.temperature.data()),
        core::scalar_field("density", density_.data()),
        core::scalar_field("internal_energy", p.energy.data()),
        core::scalar_field("body", body_.data()),
        core::scalar_field("id", id_.data()),
    };
    if (!p.strain.empty()) fields.push_back(core::tensor_field("strain", p.strain.data()));
    writer_.write_frame(s.time(), s.step_count(), n, core::as_doubles(p.position.data()), fields);
  }
  std::size_t frames() const { return writer_.frames(); }

 private:
  core::FieldWriter writer_;
  std::vector<double> pressure_, von_mises_, density_, body_, id_;
  std::vector<core::FieldView> views_;
};

core::HistoryRow history_row(const MpmSolver& s, const Energies& e, double dt, double error) {
  core::HistoryRow r;
  r.step = s.step_count();
  r.time = s.time();
  r.dt = dt;
  r.kinetic = e.kinetic;
  r.internal = e.internal;
  r.plastic = e.plastic;
  r.elastic = e.internal - e.plastic;
  r.external_work = e.external_work;
  r.total = e.total();
  r.energy_error = error;
  for (const BodySums& b : e.bodies)
    r.bodies.push_back({b.momentum, b.mass > 0.0 ? (1.0 / b.mass) * b.momentum : core::Vec3{}});
  return r;
}

}  // namespace

Simulation::Simulation(const core::Scene& scene)
    : scene_(scene), solver_(scene, generate_particles(scene)) {}

RunSummary Simulation::run(const RunOptions& options) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
  const core::RunSettings& rs = scene_.run;

  std::unique_ptr<FrameWriter> frames;
  std::unique_ptr<core::HistoryWriter> history;
  if (!options.output_directory.empty()) {
    core::OutputPaths paths;
    paths.directory = options.output_directory;
    if (options.write_fields) frames = std::make_unique<FrameWriter>(paths.directory);
    std::vector<std::string> names;
    for (const auto& b : scene_.bodies) names.push_back(b.name);
    history = std::make_unique<core::HistoryWriter>(core::history_path(paths), names);
  }

  RunSummary sum;
  sum.particles = solver_.particles().size();
  sum.initial = solver_.energies();
  double max_kinetic = sum.initial.kinetic;
  sum.min_dt = 1e300;

  auto record = [&](double dt) {
    const Energies e = solver_.energies();
    max_kinetic = std::max(max_kinetic, e.kinetic);
    const double err = energy_balance_error(e, sum.initial, max_kinetic);
    sum.max_energy_error = std::max(sum.max_energy_error, std::abs(err));
    if (history) history->write(history_row(solver_, e, dt, err));
    return err;
  };

  double dt = solver_.stable_time_step();
  record(dt);
  if (frames) frames->write(solver_);
  double next_output = rs.output_every > 0.0 ? rs.output_every : 1e300;
  double next_progress = options.progress_seconds;
  double last_error = 0.0;
  const double end = rs.end_time;

  while (solver_.time() < end * (1.0 - 1e-12) && (rs.max_steps <= 0 || solver_.step_count() < rs.max_steps)) {
    const double stable = solver_.stable_time_step();
    // The statistics describe the stable step; the last step may be cut to land on end.
    sum.min_dt = std::min(sum.min_dt, stable);
    sum.max_dt = std::max(sum.max_dt, stable);
    dt = std::min(stable, end - solver_.time());
    solver_.step(dt);  // throws SimulationError: files written so far are already flushed
    const long k = solver_.step_count();
    if (k % rs.history_every == 0) last_error = record(dt);
    if (frames && solver_.time() >= next_output * (1.0 - 1e-9) && solver_.time() < end * (1.0 - 1e-12)) {
      frames->write(solver_);
      next_output += rs.output_every;
    }
    if (options.progress && elapsed() >= next_progress) {
      const Energies e = solver_.energies();
      options.progress({k, solver_.time(), dt, end, elapsed(),
                        energy_balance_error(e, sum.initial, std::max(max_kinetic, e.kinetic))});
      next_progress = elapsed() + options.progress_seconds;
    }
  }
  if (solver_.step_count() % rs.history_every != 0) last_error = record(dt);
  if (frames) frames->write(solver_);  // the final state, always

  sum.steps = solver_.step_count();
  sum.time = solver_.time();
  sum.wall_seconds = elapsed();
  sum.particle_steps_per_second =
      sum.wall_seconds > 0.0 ? static_cast<double>(sum.particles) * sum.steps / sum.wall_seconds
                             : 0.0;
  sum.final = solver_.energies();
  sum.energy_error = last_error;
  sum.stage_counts = solver_.stage_counts();
  sum.stage_seconds = solver_.stage_seconds();
  sum.field_frames = frames ? frames->frames() : 0;
  if (sum.min_dt > sum.max_dt) sum.min_dt = sum.max_dt = dt;
  if (scene_.taylor_reference) {
    for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
      if (!std::holds_alternative<core::CylinderShape>(scene_.bodies[b].shape)) continue;
      sum.taylor = measure_taylor(solver_.particles(), scene_, static_cast<int>(b));
      sum.taylor_error = taylor_mean_error(*sum.taylor, *scene_.taylor_reference);
      break;
    }
  }
  if (options.progress)
    options.progress({sum.steps, sum.time, dt, end, sum.wall_seconds, sum.energy_error});
  return sum;
}

}  // namespace afemp::mpm
