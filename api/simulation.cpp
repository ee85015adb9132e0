// afemp::Simulation (include/afemp/simulation.hpp), the one orchestrator of a run: the scene
// checked, the model the scene describes (coupling::make_model), the warnings and the size
// estimate before the run, and the run loop of core/time_loop.cpp advanced a step at a time or
// to the end (stopped on request), with views of the solvers' arrays between steps; at the
// end, the scene's reference checks (analysis/reference_checks.cpp). `afemp run` and `afemp
// check` go through it.
#include "afemp/simulation.hpp"

#include <stdexcept>
#include <utility>

#include "analysis/reference_checks.hpp"
#include "core/contact_warnings.hpp"
#include "core/parallel.hpp"
#include "core/phases.hpp"
#include "core/plausibility.hpp"
#include "core/rank_link.hpp"
#include "core/resource_guard.hpp"
#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "coupling/coupled_model.hpp"
#include "coupling/make_model.hpp"
#include "fem/fe_model.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp {

Scene read_scene(const std::string& path) {
  return core::read_scene(path);
}

void check_scene(const Scene& scene) {
  core::check_scene(scene);
}

int thread_count() {
  return core::thread_count();
}

void set_thread_count(int n) {
  core::set_thread_count(n);
}

std::string readable_count(double count) {
  return core::readable_count(count);
}

std::string readable_duration(double seconds) {
  return core::readable_duration(seconds);
}

std::string pace_warning(double elapsed, double fraction) {
  return core::pace_warning(elapsed, fraction);
}

struct Simulation::Impl {
  Impl(Scene s, SimulationOptions o) : scene(std::move(s)), options(std::move(o)) {
    core::check_scene(scene);
    model = coupling::make_model(scene);
    if (auto* m = dynamic_cast<mpm::MpmModel*>(model.get())) mpm = &m->solver();
    if (auto* f = dynamic_cast<fem::FeModel*>(model.get())) fe = &f->solver();
    if (auto* c = dynamic_cast<coupling::CoupledModel*>(model.get())) {
      mpm = &c->mpm();
      fe = &c->fe();
    }
    if (options.ranks) divide(*options.ranks);
    if (!options.defer_start) start();
  }

  // A run divided among MPI ranks: particles by the grid's blocks, meshes by their elements,
  // and in a coupled scene both, from their start or a checkpoint, which the time loop then
  // reads on every rank.
  void divide(core::RankLink& link) {
    if (auto* particles = dynamic_cast<mpm::MpmModel*>(model.get()))
      return particles->divide_among_ranks(link, options.balance);
    if (auto* meshes = dynamic_cast<fem::FeModel*>(model.get()))
      return meshes->divide_among_ranks(link);
    if (auto* coupled = dynamic_cast<coupling::CoupledModel*>(model.get()))
      return coupled->divide_among_ranks(link, options.balance);
    throw std::logic_error("Simulation: a model of no known kind to divide among ranks");
  }

  // The time loop: the initial state written, or the checkpoint's taken.
  void start() {
    if (loop) throw std::logic_error("afemp::Simulation: start() was called already");
    core::RunOptions run;
    run.output_directory = options.output_directory;
    run.write_fields = options.write_fields;
    run.progress = options.progress;
    run.progress_seconds = options.progress_seconds;
    run.stop_requested = options.stop_requested;
    run.checkpoint_requested = options.checkpoint_requested;
    run.restart_from = options.restart_from;
    run.phase_log = options.phase_log;
    if (core::RankLink* link = options.ranks) {
      run.agree = [link](double value) { return link->max_over_ranks(value); };
      run.rank = link->rank();
      run.ranks = link->ranks();
      // A static or implicit phase is solved on rank 0 in a model of its own (TimeLoop).
      run.whole_model = [this] { return coupling::make_model(scene); };
      run.from_rank_0 = [link](std::vector<std::byte>& bytes) {
        link->broadcast_from_rank_0(bytes);
      };
      run.add_over_ranks = [link](std::span<double> values) { link->sum_in_rank_order(values); };
    }
    loop = std::make_unique<core::TimeLoop>(*model, scene, run);
  }

  // The loop of a started run.
  core::TimeLoop& started() {
    if (!loop)
      throw std::logic_error("afemp::Simulation: start() first (SimulationOptions::defer_start)");
    return *loop;
  }

  void call_back(Simulation& self) {
    for (const StepCallback& f : callbacks) f(self);
  }

  // One step towards `until`, then the callbacks.
  void step(Simulation& self, double until) {
    if (finished_run)
      throw std::logic_error("afemp::Simulation: finish() was called; the run takes no more steps");
    started().step(until);
    call_back(self);
  }

  // Views of one element container; `body` keeps the per-element body indices the view shows.
  template <class Elements>
  static ElementFields elements(Elements& e, std::vector<std::int32_t>& body) {
    constexpr int corners = Elements::corners;
    static_assert(sizeof(e.nodes[0]) == corners * sizeof(std::int32_t),
                  "an element's node indices are contiguous");
    ElementFields out;
    out.connectivity = {e.nodes.empty() ? nullptr : e.nodes.front().data(),
                        e.nodes.size() * static_cast<std::size_t>(corners)};
    out.nodes_per_element = corners;
    out.alive = e.alive;
    body.assign(e.size(), 0);
    out.first_point.assign(e.size(), 0);
    out.points_per_element.assign(e.size(), 1);
    for (const fem::ElementBatch& b : e.batches)
      for (std::size_t k = b.begin; k < b.end; ++k) {
        body[k] = b.body;
        out.points_per_element[k] = b.points_per_element;
        out.first_point[k] =
            b.point_begin + (k - b.begin) * static_cast<std::size_t>(b.points_per_element);
      }
    out.body = body;
    out.stress = e.stress;
    out.plastic_strain = e.plastic_strain;
    out.temperature = e.temperature;
    out.energy = e.energy;
    out.damage = e.damage;
    out.history = e.history;
    out.history_count = e.history_count;
    return out;
  }

  Scene scene;  // the models keep a reference: it lives as long as they do
  SimulationOptions options;
  std::unique_ptr<core::Model> model;
  mpm::MpmSolver* mpm = nullptr;
  fem::FeSolver* fe = nullptr;
  std::unique_ptr<core::TimeLoop> loop;
  std::vector<StepCallback> callbacks;
  std::vector<std::int32_t> hex_body, truss_body;
  bool finished_run = false;
};

Simulation::Simulation(Scene scene, SimulationOptions options)
    : impl_(std::make_unique<Impl>(std::move(scene), std::move(options))) {}

Simulation::~Simulation() = default;

const Scene& Simulation::scene() const {
  return impl_->scene;
}
std::string Simulation::describe() const {
  return core::describe_phases(impl_->scene) + impl_->model->describe();
}
double Simulation::stable_time_step() const {
  return impl_->model->stable_time_step();
}
double Simulation::time() const {
  return impl_->model->time();
}
long Simulation::step_count() const {
  return impl_->model->step_count();
}
bool Simulation::finished() const {
  return impl_->finished_run || (impl_->loop && impl_->loop->finished());
}
Energies Simulation::energies() const {
  return impl_->loop ? impl_->loop->energies() : impl_->model->energies();
}

std::vector<std::string> Simulation::warnings() const {
  std::vector<std::string> out = core::contact_warnings(impl_->scene, *impl_->model);
  for (const core::SceneWarning& w : core::plausibility_warnings(impl_->scene))
    out.push_back(w.text());
  return out;
}

RunEstimate Simulation::estimate() const {
  const core::Model& model = *impl_->model;
  const Scene& scene = impl_->scene;
  RunEstimate e;
  e.time_step = model.stable_time_step();
  e.steps = core::explicit_span(scene) / e.time_step;
  e.planned_steps = core::planned_steps(scene, e.time_step);
  e.points = model.particle_count() + model.element_count();
  e.bytes = model.bytes();
  e.threads = core::thread_count();
  const double points = static_cast<double>(e.points);
  e.wall_seconds = core::estimated_wall_seconds(points * e.planned_steps, e.threads);
  e.warnings = core::size_warnings(scene, points, e.time_step, e.threads);
  return e;
}

void Simulation::start() {
  impl_->start();
}

void Simulation::step() {
  if (!finished()) impl_->step(*this, impl_->scene.run.end_time);
}

void Simulation::run_to(double t) {
  while (!finished() && time() < t * (1.0 - 1e-12)) impl_->step(*this, t);
}

RunSummary Simulation::run() {
  if (!impl_->finished_run) impl_->started().run([this] { impl_->call_back(*this); });
  return finish();
}

RunSummary Simulation::finish() {
  if (impl_->finished_run) throw std::logic_error("afemp::Simulation: finish() was called already");
  core::TimeLoop& loop = impl_->started();
  impl_->finished_run = true;
  RunSummary summary = loop.finish();
  analysis::check_references(*impl_->model, impl_->scene, summary);
  return summary;
}

void Simulation::on_step(StepCallback callback) {
  impl_->callbacks.push_back(std::move(callback));
}

std::string Simulation::checkpoint() {
  return impl_->started().checkpoint("program");
}

ParticleFields Simulation::particles() {
  if (impl_->mpm == nullptr) return {};
  mpm::Particles& p = impl_->mpm->mutable_particles();
  return {p.position,       p.velocity,    p.mass,   p.volume, p.stress,
          p.plastic_strain, p.temperature, p.energy, p.damage, p.history,
          p.history_count,  p.body,        p.id};
}

NodeFields Simulation::nodes() {
  if (impl_->fe == nullptr) return {};
  fem::FeNodes& n = impl_->fe->mutable_nodes();
  if (n.external_force.size() != n.size()) n.external_force.assign(n.size(), Vec3{});
  return {n.position, n.velocity, n.mass, n.body, n.external_force};
}

ElementFields Simulation::hexahedra() {
  return impl_->fe ? Impl::elements(impl_->fe->mutable_hexahedra(), impl_->hex_body)
                   : ElementFields{};
}

ElementFields Simulation::trusses() {
  return impl_->fe ? Impl::elements(impl_->fe->mutable_trusses(), impl_->truss_body)
                   : ElementFields{};
}

std::vector<Vec3> Simulation::node_forces() const {
  std::vector<Vec3> f;
  if (impl_->fe == nullptr) return f;
  f.resize(impl_->fe->nodes().size());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = impl_->fe->node_force(i);
  return f;
}

}  // namespace afemp
