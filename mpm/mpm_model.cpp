// The MPM solver behind the core::Model interface (mpm/mpm_model.hpp).
#include "mpm/mpm_model.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/appendf.hpp"
#include "core/state_archive.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {

MpmModel::MpmModel(const core::Scene& scene)
    : scene_(scene),
      solver_(scene, generate_particles(scene)),
      history_names_(core::history_field_names(scene)) {}

void MpmModel::write_fields(core::FieldWriter& writer) {
  const core::PointBlock block = particle_block();
  writer.write_frame(solver_.time(), solver_.step_count(), block.n_points, block.positions,
                     block.fields);
}

core::PointBlock MpmModel::particle_block() {
  const Particles& p = solver_.particles();
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
  std::vector<core::FieldView>& fields = fields_;
  fields = {
      core::vector_field("velocity", p.velocity.data()),
      core::tensor_field("stress", p.stress.data()),
      core::scalar_field("pressure", pressure_.data()),
      core::scalar_field("von_mises", von_mises_.data()),
      core::scalar_field("plastic_strain", p.plastic_strain.data()),
      core::scalar_field("damage", p.damage.data()),
      core::scalar_field("temperature", p.temperature.data()),
      core::scalar_field("density", density_.data()),
      core::scalar_field("internal_energy", p.energy.data()),
      core::scalar_field("body", body_.data()),
      core::scalar_field("id", id_.data()),
  };
  if (!p.strain.empty()) fields.push_back(core::tensor_field("strain", p.strain.data()));
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

// Walls are the only force reporters of a scene of particles alone (penalty contacts and rigid
// bodies need meshes): wallK, as FeModel::force_columns names them.
std::vector<std::string> MpmModel::force_columns() const {
  std::vector<std::string> out;
  for (std::size_t w = 0; w < scene_.walls.size(); ++w)
    core::append_force_columns(out, "wall" + std::to_string(w + 1));
  return out;
}

void MpmModel::force_values(std::vector<double>& out) const {
  out.clear();
  for (std::size_t w = 0; w < scene_.walls.size(); ++w)
    core::append_force_values(out, solver_.wall_forces()[w], scene_.walls[w].normal);
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
  const Particles& p = solver_.particles();
  core::BodyPoints out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != body) continue;
    out.position.push_back(p.position[i]);
    out.half_size.push_back(0.5 * std::cbrt(p.volume[i]));  // a particle fills a cube of its volume
  }
  return out;
}

void MpmModel::state(core::StateArchive& archive) {
  solver_.state(archive);
}

}  // namespace afemp::mpm
