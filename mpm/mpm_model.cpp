// The MPM solver behind the core::Model interface (mpm/mpm_model.hpp).
#include "mpm/mpm_model.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/appendf.hpp"
#include "core/state_archive.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {

MpmModel::MpmModel(const core::Scene& scene)
    : scene_(scene),
      solver_(scene, generate_particles(scene)),
      history_names_(core::history_field_names(scene)) {}

void MpmModel::divide_among_ranks(core::RankLink& link, const core::RankBalance& balance) {
  solver_.divide_among_ranks(link, balance);
}

void MpmModel::resolve_probes(std::span<const core::ProbeSpec> probes) {
  if (!solver_.on_ranks()) {
    probes_.resolve(probes, solver_.particles(), scene_);
    return;
  }
  // An index counts the body's particles in id order, a point finds the nearest of them: among
  // every rank's, the same on every rank.
  probes_.resolve(probes, solver_.gathered_particles(true), scene_);
}

void MpmModel::sample_probes(std::span<double> out) const {
  probes_.sample(solver_.particles(), out);
  if (solver_.on_ranks()) probes_.merge_ranks(solver_.values_of_every_rank(out), out);
}

core::PointBlock MpmModel::particle_block() {
  if (!solver_.on_ranks()) return particle_block(solver_.particles());
  gathered_ = solver_.gathered_particles(false);
  return particle_block(gathered_);
}

void MpmModel::write_fields(core::FieldWriter& writer) {
  const core::PointBlock block = particle_block();
  writer.write_frame(solver_.time(), solver_.step_count(), block.n_points, block.positions,
                     block.fields);
}

// The fields the schema names for output (particles.hpp), then those derived from them.
core::PointBlock MpmModel::particle_block(const Particles& p) {
  const std::size_t n = p.size();
  std::vector<core::FieldView>& fields = fields_;
  fields.clear();
  std::size_t integer = 0;
  p.for_each_field([&](const ParticleField& field, const auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if (!field.output || !p.has(field)) return;
    if constexpr (std::is_same_v<T, double>) {
      fields.push_back(core::scalar_field(field.output, a.data()));
    } else if constexpr (std::is_same_v<T, Vec3>) {
      fields.push_back(core::vector_field(field.output, a.data()));
    } else if constexpr (std::is_same_v<T, SymTensor>) {
      fields.push_back(core::tensor_field(field.output, a.data()));
    } else if constexpr (std::is_integral_v<T>) {
      if (integers_.size() <= integer) integers_.resize(integer + 1);
      std::vector<double>& copy = integers_[integer++];
      copy.assign(a.begin(), a.end());
      fields.push_back(core::scalar_field(field.output, copy.data()));
    } else {  // the field output has no full (unsymmetric) tensors or corner sets: none names one
      static_assert(std::is_same_v<T, core::Mat3> || std::is_same_v<T, std::array<Vec3, 8>>);
      throw std::logic_error(std::string("particle field ") + field.name + " cannot be written");
    }
  });
  pressure_.resize(n);
  von_mises_.resize(n);
  density_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    pressure_[i] = core::pressure(p.stress[i]);
    von_mises_[i] = core::von_mises(p.stress[i]);
    density_[i] = p.mass[i] / p.volume[i];
  }
  fields.push_back(core::scalar_field("pressure", pressure_.data()));
  fields.push_back(core::scalar_field("von_mises", von_mises_.data()));
  fields.push_back(core::scalar_field("density", density_.data()));
  // User strength models' history variables, one scalar field per variable.
  const std::size_t hc = p.history_count;
  history_.resize(hc);
  for (std::size_t k = 0; k < hc; ++k) {
    history_[k].resize(n);
    for (std::size_t i = 0; i < n; ++i) history_[k][i] = p.history[i * hc + k];
    fields.push_back(core::scalar_field(history_names_[k], std::span<const double>(history_[k])));
  }
  return {"particles", n, core::as_doubles(p.position.data()), fields};
}

std::vector<core::StageTiming> MpmModel::stage_timings() const {
  std::vector<core::StageTiming> out;
  const auto& stages = solver_.plan().stages;
  for (std::size_t i = 0; i < stages.size(); ++i)
    out.push_back({stages[i].name, solver_.stage_counts()[i], solver_.stage_seconds()[i]});
  // On ranks (this rank's): moving particles to their ranks after each step, and the
  // rebalances (their count in the name: the summary prints names and seconds).
  if (solver_.on_ranks()) {
    out.push_back({"migration", solver_.step_count(), solver_.migration_seconds()});
    const long n = solver_.rebalances();
    out.push_back({"rebalance (" + std::to_string(n) + (n == 1 ? " time)" : " times)"), n,
                   solver_.balance_seconds()});
  }
  return out;
}

namespace {

const char* shape_name(const core::Shape& s) {
  switch (s.index()) {
    case 0:
      return "box";
    case 1:
      return "cylinder";
    case 2:
      return "sphere";
    default:
      return "points";
  }
}

}  // namespace

std::vector<core::EnergyColumn> MpmModel::energy_columns() const {
  std::vector<core::EnergyColumn> out;
  if (core::has_particle_walls(scene_)) core::declare_energy_columns(out, core::kSlidingEnergies);
  return out;
}

// A scene of particles alone reports its walls' forces (wallK, as FeModel::force_columns names
// them) and its grid contacts' (penalty contacts and rigid bodies need meshes).
std::vector<std::string> MpmModel::force_columns() const {
  std::vector<std::string> out;
  for (std::size_t w = 0; w < scene_.walls.size(); ++w)
    core::append_force_columns(out, "wall" + std::to_string(w + 1));
  append_grid_contact_columns(out, scene_);
  return out;
}

void MpmModel::force_values(std::vector<double>& out) const {
  out.clear();
  for (std::size_t w = 0; w < scene_.walls.size(); ++w)
    core::append_force_values(out, solver_.wall_forces()[w], scene_.walls[w].normal);
  append_grid_contact_values(out, solver_);
}

std::vector<std::string> unbooked_particle_energies(const core::Scene& scene) {
  std::vector<std::string> out;
  const core::MpmSettings& m = scene.mpm;
  std::string transfers;
  if (m.transfer == core::Transfer::apic)
    core::appendf(transfers, "APIC, %s", core::to_string(m.scheme));
  else
    core::appendf(transfers, "FLIP blend %g, %s", m.flip, core::to_string(m.scheme));
  out.push_back("the particle-grid transfers (" + transfers +
                "): what mapping to the grid and back smooths away");
  for (const core::ContactSpec& c : scene.contacts)
    if (c.method == core::ContactMethod::grid)
      out.push_back("grid contact " + core::contact_name(scene, c) +
                    " (its dissipation is estimated in the contact column, not part of total)");
  for (std::size_t f = 0; f < m.grid.faces.size(); ++f) {
    const core::FaceCondition c = m.grid.faces[f];
    if (c == core::FaceCondition::wall || c == core::FaceCondition::fixed) {
      out.push_back(
          "the grid faces that hold the material (wall, fixed): the normal velocity they "
          "stop");
      break;
    }
  }
  if (core::has_particle_walls(scene))
    out.push_back("the normal catch of [[walls]] at particles (friction is booked as sliding)");
  return out;
}

void append_grid_contact_columns(std::vector<std::string>& columns, const core::Scene& scene) {
  for (const core::ContactSpec& c : scene.contacts)
    if (c.method == core::ContactMethod::grid)
      core::append_force_columns(columns, core::contact_name(scene, c));
}

void append_grid_contact_values(std::vector<double>& out, const MpmSolver& solver) {
  for (const MpmSolver::InterfaceForce& f : solver.grid_contact_forces()) {
    const Vec3 total = f.normal + f.tangential;
    out.insert(out.end(),
               {total.x, total.y, total.z, core::norm(f.normal), core::norm(f.tangential)});
  }
}

std::string MpmModel::describe() const {
  solver_.prepare();
  const core::Scene& scene = scene_;
  const auto& g = solver_.grid();
  const auto& p = solver_.particles();
  std::string out;
  core::appendf(out, "grid: cell %g, %d x %d x %d cells over [%g, %g] x [%g, %g] x [%g, %g]\n",
                g.cell(), g.cells()[0], g.cells()[1], g.cells()[2], scene.mpm.grid.min.x,
                scene.mpm.grid.max.x, scene.mpm.grid.min.y, scene.mpm.grid.max.y,
                scene.mpm.grid.min.z, scene.mpm.grid.max.z);
  if (scene.mpm.grid.axisymmetric)
    out +=
        "axisymmetric about the z axis: x is the radius, each particle a ring (volume and mass "
        "2 pi r A); the internal force and the strain take the hoop terms (mpm/axisymmetric.hpp)\n";
  out += "faces:";
  for (int f = 0; f < 6; ++f)
    core::appendf(out, " %s=%s", core::to_string(static_cast<core::Face>(f)),
                  core::to_string(scene.mpm.grid.faces[static_cast<std::size_t>(f)]));
  out += "\n";
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (scene.bodies[b].discretisation != core::Discretisation::particles) continue;
    std::size_t count = 0;
    double mass = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body[i] == static_cast<int>(b)) {
        ++count;
        mass += p.mass[i];
      }
    const auto& body = scene.bodies[b];
    core::appendf(out, "body %s: %s of %s, %zu particles (%d per cell per direction), mass %.6g\n",
                  body.name.c_str(), shape_name(body.shape),
                  scene.materials[static_cast<std::size_t>(body.material)].name.c_str(), count,
                  body.particles_per_cell, mass);
    if (const core::BulkViscositySettings q = core::bulk_viscosity_of(scene_, body);
        q.linear > 0.0 || q.quadratic > 0.0)
      core::appendf(out, "  bulk viscosity: linear %g, quadratic %g (length: the cell)\n", q.linear,
                    q.quadratic);
    else
      out += "  bulk viscosity: off\n";
  }
  core::appendf(out,
                "particles: %zu; active cells: %zu; active grid blocks: %zu (%zu node slots)\n",
                p.size(), solver_.active_cells(), g.active_block_count(), g.slot_count());
  out += solver_.plan().describe();
  return out;
}

core::BodyPoints MpmModel::body_points(int body) const {
  const Particles whole = solver_.on_ranks() ? solver_.gathered_particles(true) : Particles{};
  const Particles& p = solver_.on_ranks() ? whole : solver_.particles();
  core::BodyPoints out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != body) continue;
    out.position.push_back(p.position[i]);
    // A particle fills a cube of its volume, or an axisymmetric ring's square of its r-z area.
    out.half_size.push_back(
        0.5 * particle_edge(p.volume[i], p.position[i], scene_.mpm.grid.axisymmetric));
  }
  return out;
}

std::vector<std::string> MpmModel::summary_warnings() const {
  const Particles whole = solver_.on_ranks() ? solver_.gathered_particles(true) : Particles{};
  const Particles& p = solver_.on_ranks() ? whole : solver_.particles();
  std::vector<std::size_t> failed(scene_.bodies.size(), 0), all(scene_.bodies.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto b = static_cast<std::size_t>(p.body[i]);
    ++all[b];
    if (p.damage[i] >= 1.0) ++failed[b];
  }
  std::vector<std::string> out;
  for (std::size_t b = 0; b < failed.size(); ++b) {
    if (failed[b] == 0) continue;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%zu of %zu particles of body \"%s\" failed (damage 1: they carry no shear "
                  "and no tension)",
                  failed[b], all[b], scene_.bodies[b].name.c_str());
    out.emplace_back(buf);
  }
  return out;
}

void MpmModel::state(core::StateArchive& archive) {
  solver_.state(archive);
}

}  // namespace afemp::mpm
