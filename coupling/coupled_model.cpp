// The coupled FE-MPM step (coupling/coupled_model.hpp; Lian et al. 2013, §2.4 contact coupling and
// §2.6 hybrid FEMP). Time integration: the FE velocities live at half steps (central differences)
// and so do the grid's updated velocities, so one dt advances both.
// Contact nodes: the grid sees a contact node with its v^{n-1/2} as momentum and
// m (v^{n+1/2} - v^{n-1/2}) / dt as force, so its field's updated velocity is the FE update's;
// the node then takes sum N dv of the contact's change to that field, which hands the FE body
// exactly the impulse the contact gave its field (momentum conserved to round-off).
// Bonded nodes: their element forces at x^n enter the host's field like the particles'
// -V sigma.grad N, and they take the particles' velocity update and the grid velocity as
// motion; the trusses' strain rate is taken from that motion, so it matches the length change.
#include "coupling/coupled_model.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "afemp/errors.hpp"
#include "core/appendf.hpp"
#include "core/grid/grid_face_margin.hpp"
#include "coupling/element_conversion.hpp"

namespace afemp::coupling {

namespace {

// Outflow faces are for particles: a mesh body reaching one would keep nodes on the grid whose
// particles (converted, or the host of bonded nodes) leave the run under them.
void refuse_mesh_at_outflow_faces(const core::Scene& scene, const fem::FeNodes& n) {
  const core::GridSettings& g = scene.mpm.grid;
  for (int f = 0; f < 6; ++f) {
    if (g.faces[static_cast<std::size_t>(f)] != core::FaceCondition::outflow) continue;
    const int a = f / 2;
    const bool high = f % 2 == 1;
    for (std::size_t i = 0; i < n.size(); ++i) {
      if (n.body[i] < 0) continue;
      const double x = n.position[i][a];
      if (high ? x < g.max[a] : x > g.min[a]) continue;
      const core::BodySpec& body = scene.bodies[static_cast<std::size_t>(n.body[i])];
      throw core::InputError(
          core::SourceLocation{scene.path, 0},
          std::string("grid.boundary.") + core::to_string(static_cast<core::Face>(f)),
          "mesh body \"" + body.name + "\" reaches the outflow face (node " + std::to_string(i) +
              " at " + std::to_string(x) +
              "); \"outflow\" is for particles: keep meshes inside "
              "an outflow face, or make the face \"free\", \"fixed\", \"symmetric\" or \"wall\"");
    }
  }
}

}  // namespace

CoupledModel::CoupledModel(const core::Scene& scene)
    : scene_(scene), fe_(scene), mpm_(scene), points_(scene) {
  const std::size_t nb = scene.bodies.size();
  std::vector<char> in_contact(nb, 0);
  for (const core::ContactSpec& c : scene.contacts)
    if (c.method == core::ContactMethod::grid)
      for (int b : c.bodies) in_contact[static_cast<std::size_t>(b)] = 1;
  surface_body_.assign(nb, 0);
  for (std::size_t b = 0; b < nb; ++b)
    surface_body_[b] =
        in_contact[b] && scene.bodies[b].discretisation == core::Discretisation::hexahedra;
  const fem::FeNodes& n = fe().nodes();
  refuse_mesh_at_outflow_faces(scene, n);
  driven_.assign(n.size(), 0);
  point_of_node_.assign(n.size(), -1);
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (n.body[i] < 0) continue;
    const auto b = static_cast<std::size_t>(n.body[i]);
    const core::BodySpec& body = scene.bodies[b];
    const bool bonded = core::bonded_to_particles(scene, body);
    if (!bonded && !in_contact[b]) continue;
    if (bonded && n.imposed[i])
      throw core::InputError(core::SourceLocation{scene.path, 0}, "constraints",
                             "a constraint holds node " + std::to_string(i) + " of body \"" +
                                 body.name +
                                 "\", which is bonded to particles and moves with "
                                 "the grid; restrict the constraint to other bodies (body = ...)");
    add_point(i, bonded, surface_body_[b] != 0);
  }
  // Where the meshes meet the grid, now or once their elements convert: a run divided among
  // ranks weighs these nodes' blocks in its partition.
  for (std::size_t i = 0; i < n.size(); ++i)
    if (n.body[i] >= 0) {
      const core::BodySpec& body = scene.bodies[static_cast<std::size_t>(n.body[i])];
      if (point_of_node_[i] >= 0 || body.conversion)
        points_.partition_points.push_back(n.position[i]);
    }
  fe().set_grid_driven(driven_);
  bonds_body_.assign(nb, 0);
  for (std::size_t b = 0; b < nb; ++b)
    if (core::bonded_to_particles(scene, scene.bodies[b])) {
      bonded_bodies_.push_back(static_cast<int>(b));
      bonds_body_[b] = 1;
    }
  bond_force_.assign(nb, core::Vec3{});
  // Hexahedra retire (and become particles) only inside the grid.
  const core::GridSettings& g = scene.mpm.grid;
  fe().set_retirement_domain({g.min, g.max, g.cell, scene.has_grid});
  bool converts = false;
  for (const core::BodySpec& body : scene.bodies) converts = converts || body.conversion;
  if (!fe_node_.empty() || converts) mpm().set_grid_points(&points_);
  if (core::has_surface_contact(scene)) {
    surface_contacts_ = std::make_unique<ParticleSurfaceContacts>(scene, fe());
    mpm().set_surface_contacts(surface_contacts_.get());
  }
}

std::size_t CoupledModel::add_point(std::size_t i, bool bonded, bool surface) {
  const fem::FeNodes& n = fe().nodes();
  if (point_of_node_[i] < 0) {
    point_of_node_[i] = static_cast<std::int64_t>(fe_node_.size());
    fe_node_.push_back(i);
    points_.resize(fe_node_.size());
    start_velocity_.resize(fe_node_.size());
  }
  const auto k = static_cast<std::size_t>(point_of_node_[i]);
  points_.body[k] = n.body[i];
  points_.bonded[k] = bonded ? 1 : 0;
  points_.position[k] = n.position[i];
  points_.velocity[k] = n.velocity[i];
  points_.mass[k] = n.mass[i];
  points_.surface[k] = surface ? 1 : 0;
  driven_[i] = bonded ? 1 : 0;
  return k;
}

void CoupledModel::convert_elements() {
  const std::vector<fem::RetiredElement> retired = fe().take_retired_elements();
  if (retired.empty()) return;
  // Built now, from the nodes' final v^{n+1/2}: the grid set the bonded nodes' velocity after
  // the element update that retired the elements.
  mpm::Particles more;
  more.history_count = fe().hexahedra().history_count;
  // Principal-strain failure: the particles carry on from their elements' accumulated strain.
  if (!fe().hexahedra().strain.empty()) more.keep(&mpm::Particles::strain, core::SymTensor{});
  // And from what they dissipated, which leaves the plastic and viscous totals with a particle
  // that leaves the grid (the particles keep it where the grid has outflow faces).
  if (!fe().hexahedra().plastic_heat.empty()) {
    more.keep(&mpm::Particles::plastic_heat, 0.0);
    more.keep(&mpm::Particles::viscous_heat, 0.0);
  }
  std::vector<Conversion> made;
  made.reserve(retired.size());
  for (const fem::RetiredElement& ev : retired) {
    made.push_back(convert_element(fe(), scene_, ev, more));
    converted_energy_ += made.back().lost_energy;
  }
  mpm().add_particles(more);
  // The nodes the converted elements shared with live ones now bond to the particles; a node
  // left with no element (mass 0) drops out. Imposed components stay imposed (see step()).
  const fem::FeNodes& n = fe().nodes();
  const fem::HexElements& hexes = fe().hexahedra();
  for (std::size_t k = 0; k < retired.size(); ++k) {
    const fem::RetiredElement& ev = retired[k];
    for (std::int32_t node : hexes.nodes[ev.element]) {
      const auto i = static_cast<std::size_t>(node);
      if (n.mass[i] > 0.0 && !driven_[i]) add_point(i, true, false);
    }
    char row[320];
    std::snprintf(row, sizeof row, "%.10e,%s,%lld,%s,%d,%.10e,%.10e,%.10e", ev.time,
                  scene_.bodies[static_cast<std::size_t>(ev.body)].name.c_str(),
                  static_cast<long long>(ev.id), ev.reason, made[k].particles,
                  hexes.mass[ev.element], made[k].kinetic_before, made[k].kinetic_after);
    conversion_rows_.emplace_back(row);
  }
  fe().set_grid_driven(driven_);
}

double CoupledModel::stable_time_step() const {
  if (scene_.run.fixed_time_step > 0.0) return scene_.run.fixed_time_step;
  // A body whose elements have all converted, or a rigid body's elements, set no step (+inf).
  double dt = std::min(mpm().stable_time_step(), fe().element_step_limit());
  // Coupled nodes cross the grid too: at most factor h per step.
  double speed2 = 0.0;
  for (std::size_t i : fe_node_)
    speed2 = std::max(speed2, core::dot(fe().nodes().velocity[i], fe().nodes().velocity[i]));
  if (speed2 > 0.0) dt = std::min(dt, mpm().stable_time_step_for_speed(std::sqrt(speed2)));
  return dt;
}

std::string CoupledModel::time_step_setter() const {
  const double fe_step = fe().element_step_limit();
  const double grid_step = mpm().stable_time_step();
  std::size_t fastest = fe_node_.size();
  double speed2 = 0.0;
  for (std::size_t k = 0; k < fe_node_.size(); ++k) {
    const core::Vec3& v = fe().nodes().velocity[fe_node_[k]];
    if (core::dot(v, v) > speed2) speed2 = core::dot(v, v), fastest = k;
  }
  const double node_step = speed2 > 0.0 ? mpm().stable_time_step_for_speed(std::sqrt(speed2))
                                        : std::numeric_limits<double>::infinity();
  if (fe_step <= grid_step && fe_step <= node_step) return fe_.time_step_setter();
  if (grid_step <= node_step) return mpm_.time_step_setter();
  const std::size_t i = fe_node_[fastest];
  char buf[200];
  std::snprintf(buf, sizeof buf, "node %zu of body '%s' crossing the grid at speed %.4g", i,
                scene_.bodies[static_cast<std::size_t>(fe().nodes().body[i])].name.c_str(),
                std::sqrt(speed2));
  return buf;
}

void CoupledModel::load_points(double dt) {
  const fem::FeNodes& n = fe().nodes();
  if (std::any_of(surface_body_.begin(), surface_body_.end(), [](char c) { return c != 0; })) {
    const std::size_t live = fe().live_hexahedra();
    if (surface_.nodes.empty() || live != surface_live_) {
      surface_ = fem::boundary_faces(fe().hexahedra(), surface_body_);
      surface_live_ = live;
    }
    fem::surface_normals(surface_, fe().hexahedra(), n.position, normal_);
    for (std::size_t k = 0; k < fe_node_.size(); ++k)
      if (points_.surface[k]) points_.normal[k] = normal_[fe_node_[k]];
  }
  // Bonded nodes' element forces act over the FE update's force step, as on the free nodes of
  // the same elements, so the impulses across the bond cancel when the step changes.
  const double force_scale = fe().force_step(dt) / dt;
  // A node on a face of the grid within round-off (core/grid/grid_face_margin.hpp) is taken onto
  // the face, as FeSolver::inside_retirement_domain counts it inside.
  const core::GridSettings& g = scene_.mpm.grid;
  const double margin = core::kGridFaceMargin * g.cell;
  for (std::size_t k = 0; k < fe_node_.size(); ++k) {
    const std::size_t i = fe_node_[k];
    const double m = n.mass[i];
    points_.position[k] = n.position[i];
    for (int a = 0; a < 3; ++a) {
      double& x = points_.position[k][a];
      if (x < g.min[a] && x >= g.min[a] - margin) x = g.min[a];
      if (x > g.max[a] && x <= g.max[a] + margin) x = g.max[a];
    }
    points_.mass[k] = m;
    if (points_.bonded[k]) {
      points_.velocity[k] = n.velocity[i];
      points_.force[k] = force_scale * fe().node_force(i);
    } else {
      points_.velocity[k] = start_velocity_[k];
      points_.force[k] = (m / dt) * (n.velocity[i] - start_velocity_[k]);
    }
  }
}

void CoupledModel::step(double dt) {
  fem::FeNodes& n = fe().mutable_nodes();
  for (std::size_t k = 0; k < fe_node_.size(); ++k)
    if (!points_.bonded[k]) start_velocity_[k] = n.velocity[fe_node_[k]];
  fe().begin_step(dt);
  const auto t0 = std::chrono::steady_clock::now();
  load_points(dt);
  // The bond's impulse on a bonded body: its momentum change less its elements' forces (which
  // the grid step took as the points' forces) and gravity's impulse.
  const bool bonds = !bonded_bodies_.empty();
  if (bonds) {
    for (int b : bonded_bodies_) bond_force_[static_cast<std::size_t>(b)] = core::Vec3{};
    for (std::size_t k = 0; k < fe_node_.size(); ++k) {
      const auto b = static_cast<std::size_t>(n.body[fe_node_[k]]);
      if (!points_.bonded[k] || !bonds_body_[b]) continue;
      bond_force_[b] -= points_.mass[k] * points_.velocity[k] +
                        dt * (points_.force[k] + points_.mass[k] * scene_.run.gravity);
    }
  }
  mpm().step(dt);
  fe().settle_contact_impulses(dt);  // rigid bodies take what surface contacts gave their nodes
  for (std::size_t k = 0; k < fe_node_.size(); ++k) {
    const std::size_t i = fe_node_[k];
    if (!(n.mass[i] > 0.0)) continue;
    if (points_.bonded[k]) {
      // Imposed components stay imposed: a symmetry plane's node that bonded to the particles
      // of converted elements (the grid face holds the particles the same way).
      core::Vec3 motion = points_.motion[k];
      for (int a = 0; a < 3; ++a)
        if (n.imposed[i] & (1u << a)) motion[a] = n.imposed_velocity[i][a];
      n.position[i] += dt * motion;
      n.velocity[i] = motion;  // the elements' strain rate (see above)
    } else {
      n.velocity[i] += points_.motion[k];
      for (int a = 0; a < 3; ++a)  // imposed components stay imposed (a support's reaction)
        if (n.imposed[i] & (1u << a)) n.velocity[i][a] = n.imposed_velocity[i][a];
    }
  }
  coupling_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fe().finish_step(dt);
  for (std::size_t k = 0; k < fe_node_.size(); ++k) {
    if (!points_.bonded[k]) continue;
    const std::size_t i = fe_node_[k];
    n.velocity[i] = points_.velocity[k];
    for (int a = 0; a < 3; ++a)
      if (n.imposed[i] & (1u << a)) n.velocity[i][a] = n.imposed_velocity[i][a];
    const auto b = static_cast<std::size_t>(n.body[i]);
    if (bonds && bonds_body_[b]) bond_force_[b] += points_.mass[k] * points_.velocity[k];
  }
  if (bonds)
    for (int b : bonded_bodies_) bond_force_[static_cast<std::size_t>(b)] *= 1.0 / dt;
  convert_elements();
}

core::Energies CoupledModel::energies() const {
  core::Energies out = fe().energies();
  out.converted = converted_energy_;
  const core::Energies m = mpm().energies();
  out.kinetic += m.kinetic;
  out.internal += m.internal;
  out.plastic += m.plastic;
  out.viscous += m.viscous;
  out.external_work += m.external_work;
  out.contact += m.contact;
  out.sliding += m.sliding;
  out.friction += m.friction;
  if (surface_contacts_) {
    // Friction's dissipation at the particles' contact with mesh faces (the normal catch, as a
    // kinematic wall's, shows in the balance).
    out.sliding += surface_contacts_->friction_work();
    out.friction += surface_contacts_->friction_work();
  }
  out.outflow += m.outflow;
  out.outflow_mass += m.outflow_mass;
  out.outflow_momentum += m.outflow_momentum;
  for (std::size_t b = 0; b < out.bodies.size(); ++b) {
    out.bodies[b].mass += m.bodies[b].mass;
    out.bodies[b].momentum += m.bodies[b].momentum;
    out.bodies[b].kinetic += m.bodies[b].kinetic;
    out.bodies[b].internal += m.bodies[b].internal;
  }
  return out;
}

std::vector<core::EnergyColumn> CoupledModel::energy_columns() const {
  std::vector<core::EnergyColumn> out = fe_.energy_columns();
  core::declare_energy_columns(out, mpm_.energy_columns());
  return out;
}

std::vector<std::string> CoupledModel::unbooked_energies() const {
  std::vector<std::string> out = mpm::unbooked_particle_energies(scene_);
  if (surface_contacts_)
    for (const ParticleSurfaceContacts::Pair& p : surface_contacts_->pairs())
      out.push_back("surface contact " + core::contact_name(scene_, p.spec) +
                    ": the normal catch of particles at mesh faces (friction is booked)");
  return out;
}

// The FE side's columns, then each surface contact's, then each grid contact's (the force on
// the contact's first body).
std::vector<std::string> CoupledModel::force_columns() const {
  std::vector<std::string> out = fe_.force_columns();
  if (surface_contacts_)
    for (const ParticleSurfaceContacts::Pair& p : surface_contacts_->pairs())
      core::append_force_columns(out, core::contact_name(scene_, p.spec));
  mpm::append_grid_contact_columns(out, scene_);
  for (int b : bonded_bodies_)
    for (const char* part : {".fx", ".fy", ".fz", ".axial_max", ".axial_min"})
      out.push_back(scene_.bodies[static_cast<std::size_t>(b)].name + part);
  return out;
}

// The FE side's forces, each wall's with what it gave the particles it names added (a wall may
// name mesh and particle bodies alike), then the surface contacts' and the grid contacts' (on
// the contact's first body, split along its normal and tangential parts).
void CoupledModel::force_values(std::vector<double>& out) const {
  fe_.force_values(out, mpm().wall_forces());
  if (surface_contacts_)
    for (const ParticleSurfaceContacts::Pair& p : surface_contacts_->pairs()) {
      // On the contact's first body, as every interface force: minus the particles' when the
      // mesh body is named first.
      const double sign = p.spec.bodies[0] == p.particles ? 1.0 : -1.0;
      const core::Vec3 f = sign * (p.normal_force + p.tangential_force);
      out.insert(out.end(),
                 {f.x, f.y, f.z, core::norm(p.normal_force), core::norm(p.tangential_force)});
    }
  mpm::append_grid_contact_values(out, mpm());
  if (bonded_bodies_.empty()) return;
  // The trusses' axial forces, by body.
  std::vector<double> most, least;
  fe().truss_axial_range(most, least);
  for (int b : bonded_bodies_) {
    const auto k = static_cast<std::size_t>(b);
    const core::Vec3& f = bond_force_[k];
    const bool any = most[k] >= least[k];
    out.insert(out.end(), {f.x, f.y, f.z, any ? most[k] : 0.0, any ? least[k] : 0.0});
  }
}

void CoupledModel::divide_among_ranks(core::RankLink& link, const core::RankBalance& balance) {
  mpm_.divide_among_ranks(link, balance);  // refuses what the particles' stages cannot divide
  fe_.divide_among_ranks(link);
}

void CoupledModel::write_fields(core::FieldWriter& writer) {
  fe().gather_elements();  // on ranks: rank 0 writes every rank's elements and particles
  const core::PointBlock points[] = {mpm_.particle_block()};
  writer.write_frame(time(), step_count(), points, fe_.mesh_blocks());
}

std::vector<core::StageTiming> CoupledModel::stage_timings() const {
  std::vector<core::StageTiming> out;
  for (core::StageTiming t : fe_.stage_timings()) {
    t.name = "fe " + t.name;
    out.push_back(t);
  }
  for (const core::StageTiming& t : mpm_.stage_timings()) out.push_back(t);
  out.push_back({"coupling (grid step included)", step_count(), coupling_seconds_});
  return out;
}

std::vector<core::EventLog> CoupledModel::take_events() {
  std::vector<core::EventLog> out = fe_.take_events();
  core::EventLog log{
      "conversion.csv", "time,body,element,reason,particles,mass,kinetic_before,kinetic_after", {}};
  log.rows.swap(conversion_rows_);
  out.push_back(std::move(log));
  return out;
}

std::vector<std::string> CoupledModel::summary_warnings() const {
  std::vector<std::string> out = fe_.summary_warnings();
  for (std::string& w : mpm_.summary_warnings()) out.push_back(std::move(w));
  return out;
}

std::string CoupledModel::describe() const {
  // The particle bodies a mesh body meets through surface contact ("a, b"), or "".
  const auto met_at_faces = [&](int body) {
    std::string names;
    for (const core::ContactSpec& c : scene_.contacts)
      if (c.method == core::ContactMethod::surface && (c.bodies[0] == body || c.bodies[1] == body))
        names +=
            (names.empty() ? "" : ", ") +
            scene_.bodies[static_cast<std::size_t>(c.bodies[0] == body ? c.bodies[1] : c.bodies[0])]
                .name;
    return names;
  };
  std::string out = mpm_.describe();
  out += fe_.describe_mesh();
  out += "coupling on the grid (FE nodes inside the grid domain only):\n";
  const fem::FeNodes& n = fe().nodes();
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const core::BodySpec& body = scene_.bodies[b];
    if (body.discretisation == core::Discretisation::particles) continue;
    std::size_t count = 0;
    for (std::size_t i : fe_node_) count += n.body[i] == static_cast<int>(b) ? 1 : 0;
    if (body.conversion) {
      std::size_t elements = 0, inside = 0;
      const fem::HexElements& hexes = fe().hexahedra();
      for (const fem::ElementBatch& batch : hexes.batches)
        if (batch.body == static_cast<int>(b))
          for (std::size_t e = batch.begin; e < batch.end; ++e) {
            ++elements;
            inside += fe().inside_retirement_domain(e) ? 1 : 0;
          }
      const core::GridSettings& g = scene_.mpm.grid;
      core::appendf(out,
                    "  body %s: AFEMP (the FE conversion stage below); only inside the grid "
                    "[%g, %g] x [%g, %g] x [%g, %g]: %zu of %zu elements lie inside now "
                    "(outside, %s); nodes shared with converted elements bond to the "
                    "particles%s\n",
                    body.name.c_str(), g.min.x, g.max.x, g.min.y, g.max.y, g.min.z, g.max.z, inside,
                    elements,
                    body.erosion                         ? "the erosion criteria apply"
                    : body.conversion->negative_jacobian ? "an inverting element stops the run"
                                                         : "none converts",
                    count > 0 ? "; the others are in grid contact (CFEMP)" : "");
    } else if (core::bonded_to_particles(scene_, body))
      core::appendf(out,
                    "  body %s: %zu nodes bonded to %s (HFEMP: they join its velocity field "
                    "and move with the grid)\n",
                    body.name.c_str(), count,
                    scene_.bodies[static_cast<std::size_t>(body.bonded_to)].name.c_str());
    else if (count > 0)
      core::appendf(out,
                    "  body %s: %zu nodes in grid contact (CFEMP: own velocity field; "
                    "contact corrections return to the nodes, elsewhere the FE update "
                    "alone)\n",
                    body.name.c_str(), count);
    else if (core::tied_into_hexahedra(scene_, body))
      core::appendf(out,
                    "  body %s: tied into the hexahedra of %s (FE only: it meets the particles "
                    "through its host)\n",
                    body.name.c_str(),
                    scene_.bodies[static_cast<std::size_t>(body.bonded_to)].name.c_str());
    else if (const std::string met = met_at_faces(static_cast<int>(b)); !met.empty())
      core::appendf(out,
                    "  body %s: meets %s at its faces (surface contact: the particles' "
                    "boundary against its faces, in the surface contact stage above)\n",
                    body.name.c_str(), met.c_str());
    else
      core::appendf(out,
                    "  body %s: FE only (in no grid or surface contact and bonded to nothing: "
                    "it does not meet the particles)\n",
                    body.name.c_str());
  }
  out += "FE stages, around each grid step (time step: the smaller of the FE and grid steps):\n";
  out += fe().plan().describe();
  return out;
}

core::BodyPoints CoupledModel::body_points(int body) const {
  core::BodyPoints points = mpm_.body_points(body);
  const core::BodyPoints nodes = fe_.body_points(body);
  points.position.insert(points.position.end(), nodes.position.begin(), nodes.position.end());
  points.half_size.insert(points.half_size.end(), nodes.half_size.begin(), nodes.half_size.end());
  return points;
}

std::size_t CoupledModel::bytes() const {
  return fe_.bytes() + mpm_.bytes() +
         points_.size() * (4 * sizeof(core::Vec3) + sizeof(double) + sizeof(std::int32_t) + 2) +
         fe_node_.capacity() * sizeof(std::size_t) +
         start_velocity_.capacity() * sizeof(core::Vec3);
}

}  // namespace afemp::coupling
