// The FE solver behind the core::Model interface (fem/fe_model.hpp).
#include "fem/fe_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

#include "core/appendf.hpp"
#include "core/state_archive.hpp"
#include "fem/mesh_quality.hpp"

namespace afemp::fem {

namespace {

// Sizes every per-element output array to n zeros.
void zeroed(std::size_t n, std::initializer_list<std::vector<double>*> arrays) {
  for (std::vector<double>* a : arrays) a->assign(n, 0.0);
}

}  // namespace

FeModel::FeModel(const core::Scene& scene)
    : scene_(scene),
      solver_(scene),
      eroded_(scene.bodies.size(), 0),
      history_names_(core::history_field_names(scene)) {}

void FeModel::write_fields(core::FieldWriter& writer) {
  solver_.gather_elements();  // on MPI ranks: rank 0 writes every rank's elements
  writer.write_frame(solver_.time(), solver_.step_count(), {}, mesh_blocks());
}

void FeModel::divide_among_ranks(core::RankLink& link) {
  // A phase's static or implicit solve assembles the whole mesh in one process: on ranks rank 0
  // solves it in an undivided model of its own (core::TimeLoop::solve_phase_on_rank_0).
  solver_.divide_among_ranks(link);
}

void FeModel::sample_probes(std::span<double> out) const {
  if (probes_.reads_elements()) solver_.gather_elements();  // on ranks: rank 0 samples them all
  probes_.sample(solver_, out);
}

const std::vector<core::MeshBlock>& FeModel::mesh_blocks() {
  const FeNodes& n = solver_.nodes();
  displacement_.resize(n.size());
  for (std::size_t i = 0; i < n.size(); ++i)
    displacement_[i] = n.position[i] - n.initial_position[i];
  node_fields_ = {core::vector_field("velocity", std::span<const core::Vec3>(n.velocity)),
                  core::vector_field("displacement", std::span<const core::Vec3>(displacement_))};
  const std::vector<core::FieldView>& node_fields = node_fields_;
  std::vector<core::MeshBlock>& blocks = blocks_;
  blocks.clear();
  std::vector<core::FieldView>& hex_fields = hex_fields_;
  std::vector<core::FieldView>& truss_fields = truss_fields_;
  const HexElements& h = solver_.hexahedra();
  if (!h.empty()) {
    const std::size_t ne = h.size();
    // The element means of the point fields the schema names for output (element_store.hpp),
    // then those derived from them and the element's own.
    hex_fields.clear();
    std::size_t scalars = 0, tensors = 0;
    const std::vector<core::SymTensor>* stress = nullptr;  // the mean stress
    for_each_point_field(h, [&](const PointField& field, const auto& a, std::size_t) {
      using T = typename std::decay_t<decltype(a)>::value_type;
      if (field.output == nullptr || a.empty()) return;
      std::vector<T>* mean = nullptr;
      if constexpr (std::is_same_v<T, double>) {
        if (hex_scalars_.size() <= scalars) hex_scalars_.resize(scalars + 1);
        mean = &hex_scalars_[scalars++];
      } else {
        static_assert(std::is_same_v<T, core::SymTensor>);
        if (hex_tensors_.size() <= tensors) hex_tensors_.resize(tensors + 1);
        mean = &hex_tensors_[tensors++];
        if (&a == &h.stress) stress = mean;
      }
      mean->assign(ne, T{});
      for (const ElementBatch& b : h.batches)
        for (std::size_t e = b.begin; e < b.end; ++e) {
          const std::size_t p0 =
              b.point_begin + (e - b.begin) * static_cast<std::size_t>(b.points_per_element);
          const double w = 1.0 / b.points_per_element;
          for (int g = 0; g < b.points_per_element; ++g)
            (*mean)[e] += w * a[p0 + static_cast<std::size_t>(g)];
        }
      if constexpr (std::is_same_v<T, double>)
        hex_fields.push_back(core::scalar_field(field.output, std::span<const double>(*mean)));
      else
        hex_fields.push_back(core::tensor_field(field.output, std::span<const T>(*mean)));
    });
    zeroed(ne, {&hex_pressure_, &hex_von_mises_, &hex_density_, &hex_alive_, &hex_body_});
    hex_connectivity_.resize(8 * ne);
    const std::size_t hc = h.history_count;
    hex_history_.assign(hc, std::vector<double>(ne, 0.0));
    for (const ElementBatch& b : h.batches)
      for (std::size_t e = b.begin; e < b.end; ++e) {
        const std::size_t p0 =
            b.point_begin + (e - b.begin) * static_cast<std::size_t>(b.points_per_element);
        const double w = 1.0 / b.points_per_element;
        for (int g = 0; g < b.points_per_element; ++g) {
          const std::size_t p = p0 + static_cast<std::size_t>(g);
          for (std::size_t v = 0; v < hc; ++v) hex_history_[v][e] += w * h.history[p * hc + v];
        }
        hex_pressure_[e] = core::pressure((*stress)[e]);
        hex_von_mises_[e] = core::von_mises((*stress)[e]);
        hex_density_[e] = h.mass[e] / h.volume[e];
        hex_alive_[e] = h.alive[e];
        hex_body_[e] = b.body;
        for (std::size_t a = 0; a < 8; ++a) hex_connectivity_[8 * e + a] = h.nodes[e][a];
      }
    hex_fields.push_back(core::scalar_field("pressure", std::span<const double>(hex_pressure_)));
    hex_fields.push_back(core::scalar_field("von_mises", std::span<const double>(hex_von_mises_)));
    hex_fields.push_back(core::scalar_field("density", std::span<const double>(hex_density_)));
    hex_fields.push_back(core::scalar_field("alive", std::span<const double>(hex_alive_)));
    hex_fields.push_back(core::scalar_field("body", std::span<const double>(hex_body_)));
    // User strength models' history variables, element means, one scalar field per variable.
    for (std::size_t v = 0; v < hc; ++v)
      hex_fields.push_back(
          core::scalar_field(history_names_[v], std::span<const double>(hex_history_[v])));
    blocks.push_back({"hexahedra", core::CellKind::hexahedron, n.size(),
                      core::as_doubles(n.position.data()), ne, hex_connectivity_.data(),
                      node_fields, hex_fields});
  }
  const TrussElements& t = solver_.trusses();
  if (!t.empty()) {
    const std::size_t ne = t.size();
    zeroed(ne, {&truss_stress_, &truss_force_, &truss_plastic_, &truss_temperature_, &truss_alive_,
                &truss_body_});
    truss_connectivity_.resize(2 * ne);
    for (const ElementBatch& b : t.batches)
      for (std::size_t e = b.begin; e < b.end; ++e) {
        const std::size_t p = b.point_begin + (e - b.begin);
        truss_stress_[e] = t.stress[p].xx;
        truss_force_[e] = t.axial_force(b, e, n.position);
        truss_plastic_[e] = t.plastic_strain[p];
        truss_temperature_[e] = t.temperature[p];
        truss_alive_[e] = t.alive[e];
        truss_body_[e] = b.body;
        truss_connectivity_[2 * e] = t.nodes[e][0];
        truss_connectivity_[2 * e + 1] = t.nodes[e][1];
      }
    truss_fields = {core::scalar_field("axial_stress", std::span<const double>(truss_stress_)),
                    core::scalar_field("axial_force", std::span<const double>(truss_force_)),
                    core::scalar_field("plastic_strain", std::span<const double>(truss_plastic_)),
                    core::scalar_field("temperature", std::span<const double>(truss_temperature_)),
                    core::scalar_field("alive", std::span<const double>(truss_alive_)),
                    core::scalar_field("body", std::span<const double>(truss_body_))};
    const std::size_t thc = t.history_count;
    truss_history_.assign(thc, std::vector<double>(ne, 0.0));
    for (const ElementBatch& b : t.batches)
      for (std::size_t e = b.begin; e < b.end; ++e)
        for (std::size_t v = 0; v < thc; ++v)
          truss_history_[v][e] = t.history[(b.point_begin + (e - b.begin)) * thc + v];
    for (std::size_t v = 0; v < thc; ++v)
      truss_fields.push_back(
          core::scalar_field(history_names_[v], std::span<const double>(truss_history_[v])));
    blocks.push_back({"trusses", core::CellKind::line, n.size(),
                      core::as_doubles(n.position.data()), ne, truss_connectivity_.data(),
                      node_fields, truss_fields});
  }
  return blocks;
}

std::vector<core::StageTiming> FeModel::stage_timings() const {
  std::vector<core::StageTiming> out;
  const std::vector<FeStage>& stages = solver_.plan().stages;
  for (std::size_t i = 0; i < stages.size(); ++i)
    out.push_back({stages[i].name, solver_.step_count(), solver_.stage_seconds()[i]});
  if (solver_.on_ranks())
    out.push_back(
        {"element results to every rank", solver_.step_count(), solver_.exchange_seconds()});
  return out;
}

std::vector<core::EventLog> FeModel::take_events() {
  const core::Energies e = solver_.energies();
  // Only once the hourglass energy matters at all (not round-off in the first steps).
  // On MPI ranks the energies and the records are collective; rank 0 warns and writes them.
  if (hourglass_warning_step_ < 0 && e.hourglass > 0.1 * e.internal &&
      e.hourglass > 1e-3 * (e.kinetic + e.internal + e.hourglass)) {
    hourglass_warning_step_ = solver_.step_count();
    if (solver_.rank() == 0)
      std::fprintf(stderr,
                   "afemp: warning: at step %ld the hourglass energy %.4g exceeds 10 %% of the "
                   "internal energy %.4g: refine the mesh, use the stiffness form or full "
                   "integration\n",
                   solver_.step_count(), e.hourglass, e.internal);
  }
  core::EventLog log{"erosion.csv", "time,kind,id,body,reason,energy,mass", {}};
  for (const ErosionEvent& ev : solver_.take_erosion_events()) {
    if (std::string_view(ev.kind) != "node") ++eroded_[static_cast<std::size_t>(ev.body)];
    char buf[256];
    std::snprintf(buf, sizeof buf, "%.10e,%s,%lld,%s,%s,%.10e,%.10e", ev.time, ev.kind,
                  static_cast<long long>(ev.id),
                  scene_.bodies[static_cast<std::size_t>(ev.body)].name.c_str(), ev.reason.c_str(),
                  ev.energy, ev.mass);
    log.rows.emplace_back(buf);
  }
  std::vector<core::EventLog> out{log};
  for (core::EventLog& rows : phase_logs_) out.push_back(std::move(rows));
  phase_logs_.clear();
  return out;
}

std::vector<core::BodyStress> FeModel::body_stresses() const {
  std::vector<core::BodyStress> out(scene_.bodies.size());
  solver_.for_each_live_element([&](const ElementStore& el, const ElementBatch& b, std::size_t p0) {
    if (b.rigid) return;
    for (int g = 0; g < b.points_per_element; ++g)
      out[static_cast<std::size_t>(b.body)].add(el.stress[p0 + static_cast<std::size_t>(g)]);
  });
  return out;
}

std::vector<std::string> FeModel::summary_warnings() const {
  std::vector<std::string> out;
  for (std::size_t b = 0; b < eroded_.size(); ++b) {
    if (eroded_[b] == 0) continue;
    std::size_t elements = 0;
    for (const std::vector<ElementBatch>* batches :
         {&solver_.hexahedra().batches, &solver_.trusses().batches})
      for (const ElementBatch& batch : *batches)
        if (static_cast<std::size_t>(batch.body) == b) elements += batch.end - batch.begin;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%ld of %zu elements of body \"%s\" eroded (erosion.csv lists them): their "
                  "mass and energy left the model",
                  eroded_[b], elements, scene_.bodies[b].name.c_str());
    out.emplace_back(buf);
  }
  return out;
}

std::vector<core::EnergyColumn> FeModel::energy_columns() const {
  std::vector<core::EnergyColumn> out;
  if (!solver_.mesh_contacts().empty()) core::declare_energy_columns(out, core::kSlidingEnergies);
  if (!scene_.walls.empty()) core::declare_energy_columns(out, core::kWallEnergy);
  return out;
}

std::vector<std::string> FeModel::force_columns() const {
  std::vector<std::string> out;
  auto add = [&](const std::string& name, std::initializer_list<const char*> parts) {
    for (const char* p : parts) out.push_back(name + p);
  };
  for (const MeshContact& c : solver_.mesh_contacts())
    core::append_force_columns(out, core::contact_name(scene_, c.spec));
  for (std::size_t w = 0; w < scene_.walls.size(); ++w)
    core::append_force_columns(out, "wall" + std::to_string(w + 1));
  for (const RigidBody& r : solver_.rigid_bodies()) {
    const std::string& name = scene_.bodies[static_cast<std::size_t>(r.body)].name;
    add(name, {".fx", ".fy", ".fz", ".mx", ".my", ".mz"});
    if (std::find(r.fixed.begin(), r.fixed.end(), true) != r.fixed.end())
      add(name, {".rfx", ".rfy", ".rfz", ".rmx", ".rmy", ".rmz"});
  }
  return out;
}

void FeModel::force_values(std::vector<double>& out, std::span<const core::Vec3> wall_extra) const {
  out.clear();
  auto add = [&](const core::Vec3& v) { out.insert(out.end(), {v.x, v.y, v.z}); };
  for (const MeshContact& c : solver_.mesh_contacts()) {
    add(c.normal_force + c.tangential_force);
    const bool self = c.spec.bodies[0] == c.spec.bodies[1];
    out.push_back(self ? c.normal_sum : core::norm(c.normal_force));
    out.push_back(self ? c.tangential_sum : core::norm(c.tangential_force));
  }
  for (std::size_t w = 0; w < scene_.walls.size(); ++w)
    core::append_force_values(
        out, solver_.wall_forces()[w] + (wall_extra.empty() ? core::Vec3{} : wall_extra[w]),
        scene_.walls[w].normal);
  for (const RigidBody& r : solver_.rigid_bodies()) {
    add(r.force);
    add(r.moment);
    if (std::find(r.fixed.begin(), r.fixed.end(), true) != r.fixed.end()) {
      add(r.reaction);
      add(r.reaction_moment);
    }
  }
}

std::string FeModel::describe() const {
  std::string out = describe_mesh();
  out +=
      "step plan (explicit FE, central differences; no particles, so no background grid is "
      "allocated and no grid stage runs):\n";
  out += solver_.plan().describe();
  return out;
}

std::string FeModel::describe_mesh() const {
  std::string out;
  const MeshQualityReport q = mesh_quality(solver_.mesh());
  const FeNodes& n = solver_.nodes();
  // The masses each body owns (a tied body's lent to its host's nodes counted as its own).
  const core::Energies sums = solver_.energies();
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const core::BodySpec& body = scene_.bodies[b];
    if (body.discretisation == core::Discretisation::particles) continue;
    std::size_t nodes = 0;
    for (std::size_t i = 0; i < n.size(); ++i)
      if (n.body[i] == static_cast<int>(b)) ++nodes;
    const double mass = sums.bodies[b].mass;
    const bool hexes = body.discretisation == core::Discretisation::hexahedra;
    const ElementStore& el = hexes ? static_cast<const ElementStore&>(solver_.hexahedra())
                                   : static_cast<const ElementStore&>(solver_.trusses());
    std::size_t count = 0;
    for (const ElementBatch& batch : el.batches)
      if (batch.body == static_cast<int>(b)) count += batch.end - batch.begin;
    core::appendf(out, "body %s: %zu %s of %s, %zu nodes, mass %.6g%s\n", body.name.c_str(), count,
                  hexes ? "hexahedra" : "trusses",
                  scene_.materials[static_cast<std::size_t>(body.material)].name.c_str(), nodes,
                  mass,
                  core::tied_into_hexahedra(scene_, body)
                      ? (", tied into the hexahedra of " +
                         scene_.bodies[static_cast<std::size_t>(body.bonded_to)].name +
                         " (its nodes follow them; their nodes carry its mass and forces)")
                            .c_str()
                      : "");
  }
  std::size_t imposed = 0;
  for (std::uint8_t m : n.imposed) imposed += m ? 1 : 0;
  core::appendf(out, "nodes: %zu (%zu with imposed velocity components); rigid walls: %zu\n",
                n.size(), imposed, scene_.walls.size());
  if (q.hexahedra > 0)
    core::appendf(out,
                  "mesh quality: min scaled Jacobian %.3f (hexahedron %d), max aspect ratio %.2f "
                  "(hexahedron %d), %zu inverted, volume %.6g\n",
                  q.min_scaled_jacobian, q.worst_jacobian_element, q.max_aspect_ratio,
                  q.worst_aspect_element, q.inverted, q.total_volume);
  if (q.lines > 0)
    core::appendf(out, "trusses: shortest %.4g (truss %d)\n", q.min_line_length, q.shortest_line);
  // Rigid elements set no step: a scene of rigid meshes only leaves it to the particles.
  const double limit = solver_.element_step_limit();
  if (std::isfinite(limit))
    core::appendf(out, "smallest element time step: %.6g at %s\n",
                  limit / scene_.run.element_time_step_factor,
                  solver_.smallest_step_element().c_str());
  else
    out += "smallest element time step: none (every element is rigid)\n";
  return out;
}

void FeModel::state(core::StateArchive& archive) {
  solver_.state(archive);
  const core::StateArchive::Group group(archive, "fe_model");
  archive.item("hourglass_warning_step", hourglass_warning_step_);
  archive.item("eroded_elements", eroded_);
}

}  // namespace afemp::fem
