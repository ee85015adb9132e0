// The starter half of the FE solver: turns the scene's mesh bodies into nodes and elements
// (generated structured meshes or imported files), lumps the masses, sets the initial state,
// resolves constraints and walls to node lists, and builds the node-to-element incidence
// through which element forces are gathered without atomics.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <type_traits>

#include "afemp/errors.hpp"
#include "core/detonation_paths.hpp"
#include "core/materials/initial_pressure.hpp"
#include "core/materials/user_strength_chunk.hpp"
#include "core/parallel.hpp"
#include "fem/fe_solver.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_one_point.hpp"
#include "fem/mesh_generation.hpp"
#include "fem/mesh_import.hpp"
#include "fem/surface_faces.hpp"
#include "fem/truss.hpp"

namespace afemp::fem {

namespace {

using core::BodySpec;
using core::Discretisation;
using core::InputError;

int divisions_for(double extent, double size) {
  return std::max(1, static_cast<int>(std::ceil(extent / size - 1e-9)));
}

// The elements of one kind (and of the selected parts) of an imported mesh, with only the
// nodes they use; node sets are kept for the nodes that remain.
MeshData extract(const MeshData& in, bool hexahedra, const std::vector<std::string>& parts,
                 const BodySpec& body) {
  std::vector<char> part_wanted(in.part_names.size(), parts.empty() ? 1 : 0);
  for (const std::string& p : parts) {
    const auto it = std::find(in.part_names.begin(), in.part_names.end(), p);
    if (it == in.part_names.end()) {
      std::vector<std::string> quoted;
      for (const std::string& n : in.part_names) quoted.push_back("\"" + n + "\"");
      std::string list;
      for (std::size_t i = 0; i < quoted.size(); ++i) list += (i ? ", " : "") + quoted[i];
      throw InputError(body.where, "bodies." + body.name + ".shape.mesh.parts",
                       "the mesh has no part \"" + p + "\"; its parts: " + list);
    }
    part_wanted[static_cast<std::size_t>(it - in.part_names.begin())] = 1;
  }
  MeshData out;
  out.part_names = in.part_names;
  std::vector<std::int32_t> new_index(in.nodes.size(), -1);
  auto use = [&](std::int32_t n) {
    auto& k = new_index[static_cast<std::size_t>(n)];
    if (k < 0) {
      k = static_cast<std::int32_t>(out.nodes.size());
      out.nodes.push_back(in.nodes[static_cast<std::size_t>(n)]);
      if (!in.node_labels.empty())
        out.node_labels.push_back(in.node_labels[static_cast<std::size_t>(n)]);
    }
    return k;
  };
  if (hexahedra) {
    for (std::size_t e = 0; e < in.hexahedra.size(); ++e) {
      if (!part_wanted[static_cast<std::size_t>(in.hexahedron_part[e])]) continue;
      Hexahedron h;
      for (int a = 0; a < 8; ++a)
        h[static_cast<std::size_t>(a)] = use(in.hexahedra[e][static_cast<std::size_t>(a)]);
      out.hexahedra.push_back(h);
      out.hexahedron_part.push_back(in.hexahedron_part[e]);
    }
  } else {
    for (std::size_t e = 0; e < in.lines.size(); ++e) {
      if (!part_wanted[static_cast<std::size_t>(in.line_part[e])]) continue;
      out.lines.push_back({use(in.lines[e][0]), use(in.lines[e][1])});
      out.line_part.push_back(in.line_part[e]);
      out.line_area.push_back(in.line_area[e]);
    }
  }
  std::vector<std::int32_t> set_index(in.node_sets.size(), -1);
  for (std::size_t s = 0; s < in.node_sets.size(); ++s) {
    NamedSet kept{in.node_sets[s].name, {}};
    for (std::int32_t n : in.node_sets[s].members)
      if (new_index[static_cast<std::size_t>(n)] >= 0)
        kept.members.push_back(new_index[static_cast<std::size_t>(n)]);
    if (kept.members.empty()) continue;
    set_index[s] = static_cast<std::int32_t>(out.node_sets.size());
    out.node_sets.push_back(std::move(kept));
  }
  for (const ImportedConstraint& c : in.constraints)
    if (set_index[static_cast<std::size_t>(c.node_set)] >= 0)
      out.constraints.push_back({set_index[static_cast<std::size_t>(c.node_set)], c.fixed});
  return out;
}

// A program's mesh (core::MeshArrays) as the importers' MeshData: one part named after the
// body, its node sets, checked like a file's mesh.
MeshData mesh_from_arrays(const core::MeshArrays& a, const BodySpec& b) {
  MeshData m;
  m.nodes = a.nodes;
  m.hexahedra.assign(a.hexahedra.begin(), a.hexahedra.end());
  m.lines.assign(a.trusses.begin(), a.trusses.end());
  m.part_names.push_back(b.name);
  m.hexahedron_part.assign(m.hexahedra.size(), 0);
  m.line_part.assign(m.lines.size(), 0);
  m.line_area = a.truss_areas.empty() ? std::vector<double>(m.lines.size(), 0.0) : a.truss_areas;
  for (const core::MeshArrays::NodeSet& set : a.node_sets)
    m.node_sets.push_back({set.name, set.nodes});
  validate(m, "bodies." + b.name + ".shape.mesh (arrays)");
  return m;
}

// The mesh of one body, from its shape and density.
MeshData body_mesh(const BodySpec& b) {
  const std::string key = "bodies." + b.name + ".mesh";
  const core::MeshDensity& d = b.mesh;
  try {
    if (const auto* box = std::get_if<core::BoxShape>(&b.shape)) {
      std::array<int, 3> n = d.divisions;
      if (d.graded[0].empty() && d.graded[1].empty() && d.graded[2].empty()) {
        if (n[0] == 0)
          for (int a = 0; a < 3; ++a)
            n[static_cast<std::size_t>(a)] = divisions_for(box->max[a] - box->min[a], d.size);
        return box_mesh(*box, n);
      }
      // A graded box: its graded axes from their segments, the others one even segment at the
      // size.
      std::array<std::vector<double>, 3> lines;
      for (int a = 0; a < 3; ++a) {
        const auto u = static_cast<std::size_t>(a);
        const double extent = box->max[a] - box->min[a];
        lines[u] = graded_lines(
            box->min[a],
            d.graded[u].empty()
                ? std::vector<std::array<double, 2>>{{box->max[a],
                                                      double(divisions_for(extent, d.size))}}
                : d.graded[u]);
        if (!(std::abs(lines[u].back() - box->max[a]) <= 1e-9 * extent))
          throw std::invalid_argument("a graded axis must end at the box's max");
      }
      return box_mesh(lines);
    }
    if (const auto* c = std::get_if<core::CylinderShape>(&b.shape)) {
      int core_n = d.core, ring = d.ring, axial = d.axial;
      // A quarter arc of pi R / 2 carries core_n elements; the ring spans roughly the outer half
      // of the radius; sectors other than the whole need an even core count.
      if (core_n == 0) core_n = divisions_for(std::numbers::pi * c->radius / 2.0, d.size);
      if (d.sectors != 4 && core_n % 2 == 1) ++core_n;
      if (ring == 0) ring = divisions_for(0.5 * c->radius, d.size);
      if (axial == 0) axial = divisions_for(c->length, d.size);
      return cylinder_mesh(*c, core_n, ring, axial, d.sectors);
    }
    if (const auto* s = std::get_if<core::SphereShape>(&b.shape)) {
      int n = d.divisions[0] > 0 ? d.divisions[0] : divisions_for(2.0 * s->radius, d.size);
      n = std::max(4, (n + 3) / 4 * 4);
      return sphere_mesh(*s, n, d.sectors);
    }
    if (const auto* l = std::get_if<core::LineShape>(&b.shape)) {
      const int n =
          d.segments > 0 ? d.segments : divisions_for(core::norm(l->to - l->from), d.size);
      return truss_line(l->from, l->to, n, b.area);
    }
    if (const auto* r = std::get_if<core::RebarShape>(&b.shape)) {
      RebarMat m{r->min,     r->max,      r->normal_axis, r->positions,
                 r->spacing, r->diameter, r->cover,       d.size};
      return rebar_mat(m);
    }
  } catch (const std::invalid_argument& e) {
    throw InputError(b.where, key, e.what());
  }
  const auto& file = std::get<core::MeshFileShape>(b.shape);
  MeshData m = extract(file.path.empty() ? mesh_from_arrays(file.arrays, b) : read_mesh(file.path),
                       b.discretisation == Discretisation::hexahedra, file.parts, b);
  for (core::Vec3& x : m.nodes) x = file.scale * x + file.translate;
  const bool hexes = b.discretisation == Discretisation::hexahedra;
  if ((hexes && m.hexahedra.empty()) || (!hexes && m.lines.empty()))
    throw InputError(b.where, "bodies." + b.name + ".shape.mesh",
                     (file.path.empty() ? std::string("the arrays have no ")
                                        : "the file " + file.path + " has no ") +
                         (hexes ? "hexahedra" : "lines (trusses)") +
                         (file.parts.empty() ? std::string() : " in the selected parts"));
  for (double& a : m.line_area) {
    if (a <= 0.0) a = b.area;
    if (a <= 0.0)
      throw InputError(b.where, "bodies." + b.name + ".area",
                       "the file gives no cross-section area for some lines; set area");
  }
  return m;
}

bool inside(const core::NodeSelector& s, const core::Vec3& x) {
  switch (s.kind) {
    case core::NodeSelector::Kind::box: {
      // A relative slack so that nodes on the box faces are inside despite round-off.
      const double slack = 1e-9 * (core::norm(s.max - s.min) + 1.0);
      for (int a = 0; a < 3; ++a)
        if (x[a] < s.min[a] - slack || x[a] > s.max[a] + slack) return false;
      return true;
    }
    case core::NodeSelector::Kind::plane:
      return std::abs(core::dot(x - s.point, s.normal)) <= s.tolerance;
    case core::NodeSelector::Kind::set:
      return false;
  }
  return false;
}

}  // namespace

// Each body's mesh (empty for particles) and the range of its nodes in the solver's arrays.
struct FeSolver::BodyMeshes {
  std::vector<MeshData> meshes;
  std::vector<std::size_t> node_begin, node_end;

  // The nodes a selector holds, of one body (body >= 0) or of every body accepted by `take`,
  // each passed to f: the nodes of a named set, or those inside a box or on a plane.
  template <class Take, class F>
  void for_selected(const core::Scene& scene, const std::vector<Vec3>& position,
                    const core::NodeSelector& sel, int body, Take&& take, F&& f) const {
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      if ((body >= 0 && body != static_cast<int>(b)) || !take(scene.bodies[b])) continue;
      if (sel.kind == core::NodeSelector::Kind::set) {
        for (const NamedSet& s : meshes[b].node_sets)
          if (s.name == sel.set)
            for (std::int32_t n : s.members) f(node_begin[b] + static_cast<std::size_t>(n));
      } else {
        for (std::size_t n = node_begin[b]; n < node_end[b]; ++n)
          if (inside(sel, position[n])) f(n);
      }
    }
  }
};

namespace {

// One element's mass and volumes, its critical step to come and alive.
void add_element(ElementStore& el, double mass, double volume) {
  el.mass.push_back(mass);
  el.volume0.push_back(volume);
  el.volume.push_back(volume);
  el.critical_dt.push_back(0.0);
  el.alive.push_back(1);
}

// One integration point's initial state: every array the schema keeps for every point
// (element_store.hpp) grows by its rest value; then the material's history, the point's mass,
// the body's temperature and internal energy, the reference density.
void add_point_state(ElementStore& el, const core::Material& m, double temperature,
                     double point_mass, double energy) {
  if (energy == 0.0) energy = m.initial_energy();  // detonation products: E0 / rho0
  const std::size_t p = el.points();
  for_each_point_field(el, [](const PointField& field, auto& a, std::size_t width) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if (field.need == PointNeed::always) a.resize(a.size() + width, rest_value<T>(field));
  });
  core::initial_history(m, el.history.data() + p * el.history_count, el.history_count);
  el.point_mass[p] = point_mass;
  el.temperature[p] = temperature;
  el.energy[p] = energy;
  el.density[p] = m.density;
}

// The hexahedra of one body's mesh (its nodes from `offset`), checked for positive volumes and
// Jacobians, with one point (one-point) or eight (full integration) each.
void add_hexahedra(HexElements& hexes, const std::vector<Vec3>& position, const BodySpec& body,
                   const core::Material& mat, double temperature, const MeshData& m,
                   std::int32_t offset, const Vec3& gravity) {
  const bool full = body.element == core::HexFormulation::full;
  for (std::size_t e = 0; e < m.hexahedra.size(); ++e) {
    std::array<std::int32_t, 8> nodes;
    HexVectors x;
    for (std::size_t a = 0; a < 8; ++a) {
      nodes[a] = m.hexahedra[e][a] + offset;
      x[a] = position[static_cast<std::size_t>(nodes[a])];
    }
    const double volume = one_point_hex(x).volume;
    if (!(volume > 0.0))
      throw InputError(body.where, "bodies." + body.name,
                       "hexahedron " + std::to_string(e) + " has a non-positive volume (" +
                           std::to_string(volume) + "): check its node order");
    hexes.nodes.push_back(nodes);
    hexes.bulk_q.push_back(0.0);
    hexes.hourglass_force.push_back({});
    hexes.hourglass_power.push_back(0.0);
    add_element(hexes, mat.density * volume, volume);
    if (full) {
      const FullHex f = full_hex(x);
      if (!(min_jacobian(f) > 0.0))
        throw InputError(
            body.where, "bodies." + body.name,
            "hexahedron " + std::to_string(e) + " has a non-positive Jacobian at a Gauss point");
      for (int g = 0; g < 8; ++g)
        add_point_state(hexes, mat, temperature,
                        mat.density * f.weight[static_cast<std::size_t>(g)], body.internal_energy);
    } else {
      add_point_state(hexes, mat, temperature, mat.density * volume, body.internal_energy);
    }
    if (body.initial_stress) {
      // Soil at rest: the weight above each integration point (Gauss point g sits at
      // kHexNatural[g] / sqrt(3); the one point at the centroid), and the elastic energy it holds.
      const std::size_t points = full ? 8 : 1;
      for (std::size_t g = 0; g < points; ++g) {
        Vec3 at{};
        for (std::size_t a = 0; a < 8; ++a) {
          double n = 0.125;
          for (int i = 0; i < 3; ++i)
            n *= full ? 1.0 + kHexNatural[a][i] * kHexNatural[g][i] / std::sqrt(3.0) : 1.0;
          at += n * x[a];
        }
        const std::size_t p = hexes.points() - points + g;
        hexes.stress[p] = core::geostatic_stress(body.initial_stress->surface,
                                                 body.initial_stress->k0, gravity, mat.density, at);
        hexes.energy[p] += core::elastic_energy(mat, hexes.stress[p]);
      }
    }
  }
}

// The trusses of one body's mesh (its nodes from `offset`), checked for positive lengths.
void add_trusses(TrussElements& trusses, const std::vector<Vec3>& position, const BodySpec& body,
                 const core::Material& mat, double temperature, const MeshData& m,
                 std::int32_t offset) {
  for (std::size_t e = 0; e < m.lines.size(); ++e) {
    const std::array<std::int32_t, 2> nodes{m.lines[e][0] + offset, m.lines[e][1] + offset};
    const double length = core::norm(position[static_cast<std::size_t>(nodes[1])] -
                                     position[static_cast<std::size_t>(nodes[0])]);
    if (!(length > 0.0))
      throw InputError(body.where, "bodies." + body.name,
                       "truss " + std::to_string(e) + " has zero length");
    const double area = m.line_area[e];
    trusses.nodes.push_back(nodes);
    trusses.length0.push_back(length);
    trusses.area0.push_back(area);
    add_element(trusses, mat.density * area * length, area * length);
    add_point_state(trusses, mat, temperature, mat.density * area * length, body.internal_energy);
    if (body.prestress != 0.0) {
      // A prestressed tendon: its axial stress and the elastic energy it holds.
      const std::size_t p = trusses.points() - 1;
      trusses.stress[p].xx = body.prestress;
      trusses.energy[p] += core::elastic_energy(mat, trusses.stress[p]);
    }
  }
}

// The nodal forces of the stresses hexahedra start with (a geostatic initial stress): the
// element update computes them at the end of each step, so without these the first step would
// see none, and the body would fall freely for half a step. Walls, hourglass and bulk
// viscosity add nothing at rest.
void add_initial_stress_forces(const core::Scene& scene, const HexElements& hexes,
                               const std::vector<Vec3>& position, std::vector<Vec3>& force) {
  for (const ElementBatch& batch : hexes.batches) {
    const BodySpec& body = scene.bodies[static_cast<std::size_t>(batch.body)];
    if (!body.initial_stress || batch.rigid) continue;
    for (std::size_t e = batch.begin; e < batch.end; ++e) {
      HexVectors x, f{};
      for (std::size_t a = 0; a < 8; ++a)
        x[a] = position[static_cast<std::size_t>(hexes.nodes[e][a])];
      const std::size_t p = batch.point_begin +
                            (e - batch.begin) * static_cast<std::size_t>(batch.points_per_element);
      if (batch.points_per_element == 1) {
        add_stress_forces(one_point_hex(x), hexes.stress[p], f);
      } else {
        std::array<core::SymTensor, 8> sigma;
        for (std::size_t g = 0; g < 8; ++g) sigma[g] = hexes.stress[p + g];
        add_stress_forces_bbar(full_hex(x), sigma, f);
      }
      for (std::size_t a = 0; a < 8; ++a) force[8 * e + a] = f[a];
    }
  }
}

// The same for prestressed trusses: N = sigma A along each bar, at its slots from first_slot.
void add_prestress_forces(const core::Scene& scene, const TrussSet& trusses,
                          const std::vector<Vec3>& position, std::vector<Vec3>& force) {
  for (const ElementBatch& batch : trusses.batches) {
    const BodySpec& body = scene.bodies[static_cast<std::size_t>(batch.body)];
    if (body.prestress == 0.0) continue;
    for (std::size_t e = batch.begin; e < batch.end; ++e) {
      const Vec3& xa = position[static_cast<std::size_t>(trusses.nodes[e][0])];
      const Vec3& xb = position[static_cast<std::size_t>(trusses.nodes[e][1])];
      Vec3 fa, fb;
      add_truss_forces(truss_kinematics(xa, xb, Vec3{}, Vec3{}), body.prestress * trusses.area0[e],
                       fa, fb);
      force[trusses.first_slot + 2 * e] = fa;
      force[trusses.first_slot + 2 * e + 1] = fb;
    }
  }
}

}  // namespace

FeSolver::FeSolver(const core::Scene& scene) : scene_(scene) {
  build(scene);
}

// The set-up in order: what a later piece reads (node masses, the batches, the constraints)
// is there before it.
void FeSolver::build(const core::Scene& scene) {
  const BodyMeshes meshes = build_nodes(scene);
  build_elements(scene, meshes);
  setup_point_fields(scene);
  setup_explosives(scene);
  setup_constraints(scene, meshes);
  // The face links the surface searches sweep (erosion and conversion redo them often).
  link_faces(hexes_);
  setup_absorbing_boundaries(scene, meshes);
  setup_loads(scene, meshes);
  setup_walls(scene);
  build_incidence();
  add_initial_stress_forces(scene, hexes_, nodes_.position, element_force_);
  add_prestress_forces(scene, trusses_, nodes_.position, element_force_);
  recompute_node_masses();
  // Trusses tied into hexahedra lend their masses to their hosts' nodes and move with them.
  embedded_ = tie_embedded_nodes(scene, nodes_, hexes_);
  if (!embedded_.empty()) {
    lend_embedded_masses(embedded_, nodes_, hexes_);
    follow_hosts(embedded_, nodes_, hexes_);
  }
  // 6. Critical steps of the initial state.
  for (ElementSet* set : sets_) set->initial_critical_steps(scene, nodes_.position);
  // Rigid bodies and penalty contacts (after the node masses).
  setup_rigid_bodies();
  wall_force_.assign(scene.walls.size(), Vec3{});
  setup_mesh_contacts(scene);
  setup_step_arrays(scene);
}

// 1. Meshes, body by body; hexahedra and trusses keep body order (contiguous batches). The
// nodes start at their body's velocity, free and massless.
FeSolver::BodyMeshes FeSolver::build_nodes(const core::Scene& scene) {
  BodyMeshes m;
  m.meshes.resize(scene.bodies.size());
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& body = scene.bodies[b];
    m.node_begin.push_back(mesh_.nodes.size());
    if (body.discretisation != Discretisation::particles) {
      m.meshes[b] = body_mesh(body);
      validate(m.meshes[b], body.name);
      append(mesh_, m.meshes[b]);
    }
    m.node_end.push_back(mesh_.nodes.size());
  }
  const std::size_t n_nodes = mesh_.nodes.size();
  nodes_.position = mesh_.nodes;
  nodes_.initial_position = mesh_.nodes;
  nodes_.velocity.assign(n_nodes, Vec3{});
  nodes_.mass.assign(n_nodes, 0.0);
  nodes_.body.assign(n_nodes, -1);
  nodes_.imposed.assign(n_nodes, 0);
  nodes_.imposed_velocity.assign(n_nodes, Vec3{});
  nodes_.grid_driven.assign(n_nodes, 0);
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    for (std::size_t n = m.node_begin[b]; n < m.node_end[b]; ++n) {
      nodes_.body[n] = static_cast<std::int32_t>(b);
      nodes_.velocity[n] = scene.bodies[b].velocity;
    }
  return m;
}

// 2. Elements and their initial state, one batch per mesh body.
void FeSolver::build_elements(const core::Scene& scene, const BodyMeshes& meshes) {
  hexes_.history_count = trusses_.history_count = core::history_count(scene);
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& body = scene.bodies[b];
    if (body.discretisation == Discretisation::particles) continue;
    const core::Material& mat = scene.materials[static_cast<std::size_t>(body.material)];
    const double temperature = body.temperature.value_or(mat.thermal.initial_temperature);
    const auto offset = static_cast<std::int32_t>(meshes.node_begin[b]);
    const bool hexahedra = body.discretisation == Discretisation::hexahedra;
    ElementStore& el =
        hexahedra ? static_cast<ElementStore&>(hexes_) : static_cast<ElementStore&>(trusses_);
    ElementBatch batch;
    batch.body = static_cast<int>(b);
    batch.material = body.material;
    batch.begin = el.size();
    batch.point_begin = el.stress.size();
    if (hexahedra) {
      batch.points_per_element = body.element == core::HexFormulation::full ? 8 : 1;
      add_hexahedra(hexes_, nodes_.position, body, mat, temperature, meshes.meshes[b], offset,
                    scene.run.gravity);
    } else {
      add_trusses(trusses_, nodes_.position, body, mat, temperature, meshes.meshes[b], offset);
    }
    batch.end = el.size();
    batch.rigid = body.rigid.has_value();
    el.batches.push_back(batch);
  }
}

// The point fields only some scenes need (PointNeed, element_store.hpp), kept at their rest
// value for every point of a kind when one of its bodies needs them: what each point
// dissipated, where elements may erode or convert (ElementStore::plastic_heat: the converted
// particles carry it, and take it out of the totals if they leave through an outflow face;
// without it a converted particle that left took its plastic work out of the internal energy
// and not out of the plastic column, and the elastic energy went negative); for hexahedra (the
// truss update reads neither) the strain tensor principal-strain failure reads and a high
// explosive's burn (setup_explosives). Particles keep their own.
void FeSolver::setup_point_fields(const core::Scene& scene) {
  auto keep = [&scene](ElementStore& el, bool hexahedra) {
    bool leaving = false, strain = false, explosive = false;
    for (const ElementBatch& b : el.batches) {
      const core::Material& m = scene.materials[static_cast<std::size_t>(b.material)];
      const core::BodySpec& body = scene.bodies[static_cast<std::size_t>(b.body)];
      leaving = leaving || body.erosion.has_value() || body.conversion.has_value();
      strain = strain || (hexahedra && m.needs_strain());
      explosive = explosive || (hexahedra && m.is_explosive() && b.end > b.begin);
    }
    for_each_point_field(el, [&](const PointField& field, auto& a, std::size_t width) {
      using T = typename std::decay_t<decltype(a)>::value_type;
      const bool needed = (field.need == PointNeed::leaving && leaving) ||
                          (field.need == PointNeed::strain && strain) ||
                          (field.need == PointNeed::explosive && explosive);
      if (needed) a.assign(el.points() * width, rest_value<T>(field));
    });
  };
  keep(hexes_, true);
  keep(trusses_, false);
}

// High explosives (core/detonation_paths.hpp): each point of an explosive hexahedron lights at
// its element centre's distance (straight, or around inert bodies for a shadowed detonation)
// from the nearest detonation over D, burns over 1.5 times the element's initial edge
// cbrt(V0), and starts unburnt; other points keep the rest values (0 and 1, unread).
void FeSolver::setup_explosives(const core::Scene& scene) {
  std::vector<std::size_t> which;
  std::vector<Vec3> centres;
  std::vector<double> D;
  std::vector<std::int32_t> body;
  double spacing = 0.0;  // the largest element edge: the voxels of a shadowed detonation
  for (const ElementBatch& b : hexes_.batches) {
    const core::Material& m = scene.materials[static_cast<std::size_t>(b.material)];
    if (!m.is_explosive()) continue;
    for (std::size_t e = b.begin; e < b.end; ++e) {
      Vec3 centre;
      for (std::int32_t n : hexes_.nodes[e])
        centre += 0.125 * nodes_.position[static_cast<std::size_t>(n)];
      which.push_back(e);
      centres.push_back(centre);
      D.push_back(m.burn->detonation_velocity);
      body.push_back(b.body);
      spacing = std::max(spacing, std::cbrt(hexes_.volume0[e]));
    }
  }
  if (which.empty()) return;
  const std::vector<double> t = core::explosive_lighting_times(centres, D, body, spacing, scene);
  std::size_t k = 0;
  for (const ElementBatch& b : hexes_.batches) {
    if (!scene.materials[static_cast<std::size_t>(b.material)].is_explosive()) continue;
    for (std::size_t e = b.begin; e < b.end; ++e, ++k) {
      const std::size_t first =
          b.point_begin + (e - b.begin) * static_cast<std::size_t>(b.points_per_element);
      for (int g = 0; g < b.points_per_element; ++g) {
        hexes_.light_time[first + static_cast<std::size_t>(g)] = t[k];
        hexes_.burn[first + static_cast<std::size_t>(g)] = 0.0;
        hexes_.burn_length[first + static_cast<std::size_t>(g)] = std::cbrt(hexes_.volume0[e]);
      }
    }
  }
}

// 3. Constraints: from the scene's selectors and from imported files; then the velocity curves
// and the imposed components' initial values.
void FeSolver::setup_constraints(const core::Scene& scene, const BodyMeshes& meshes) {
  const std::size_t n_nodes = nodes_.size();
  // A rigid body is held by its own components, never node by node.
  auto refuse_rigid = [&](const core::SourceLocation& where, std::size_t n) {
    const auto b = static_cast<std::size_t>(nodes_.body[n]);
    if (!scene.bodies[b].rigid) return;
    throw InputError(where, "constraints",
                     "a constraint holds node " + std::to_string(n - meshes.node_begin[b]) +
                         " of rigid body \"" + scene.bodies[b].name +
                         "\"; restrict the constraint to deformable bodies (body = ...) and hold "
                         "the rigid body with rigid = { fixed = [...] }");
  };
  // owner: the constraint that imposes each node component last (for the velocity curves).
  std::vector<std::int32_t> owner;
  for (std::size_t ci = 0; ci < scene.constraints.size(); ++ci) {
    const core::ConstraintSpec& c = scene.constraints[ci];
    std::size_t selected = 0;
    meshes.for_selected(
        scene, nodes_.position, c.nodes, c.body, [](const BodySpec&) { return true; },
        [&](std::size_t n) {
          refuse_rigid(c.where, n);
          for (int a = 0; a < 3; ++a)
            if (c.components[static_cast<std::size_t>(a)]) {
              nodes_.imposed[n] |= static_cast<std::uint8_t>(1u << a);
              nodes_.imposed_velocity[n][a] = c.velocity[a];
              if (!c.curve.empty() && owner.empty()) owner.assign(3 * n_nodes, -1);
              if (!owner.empty())
                owner[3 * n + static_cast<std::size_t>(a)] = static_cast<std::int32_t>(ci);
            }
          ++selected;
        });
    if (selected == 0)
      throw InputError(c.where, "constraints",
                       c.nodes.kind == core::NodeSelector::Kind::set
                           ? "no mesh body has a node set named \"" + c.nodes.set + "\""
                           : std::string("the selector holds no mesh node"));
  }
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    for (const ImportedConstraint& c : meshes.meshes[b].constraints)
      for (std::int32_t n :
           meshes.meshes[b].node_sets[static_cast<std::size_t>(c.node_set)].members)
        for (int a = 0; a < 3; ++a)
          if (c.fixed[static_cast<std::size_t>(a)]) {
            const std::size_t k = meshes.node_begin[b] + static_cast<std::size_t>(n);
            refuse_rigid(scene.bodies[b].where, k);
            nodes_.imposed[k] |= static_cast<std::uint8_t>(1u << a);
            nodes_.imposed_velocity[k][a] = 0.0;
          }
  if (!owner.empty()) setup_velocity_curves(scene, owner);
  // Imposed components start at their imposed value.
  for (std::size_t n = 0; n < n_nodes; ++n)
    for (int a = 0; a < 3; ++a)
      if (nodes_.imposed[n] & (1u << a)) nodes_.velocity[n][a] = nodes_.imposed_velocity[n][a];
}

// The node components each constraint with a curve owns (owner: the constraint that imposes
// each component last), at their velocities of t = 0.
void FeSolver::setup_velocity_curves(const core::Scene& scene,
                                     const std::vector<std::int32_t>& owner) {
  for (std::size_t ci = 0; ci < scene.constraints.size(); ++ci) {
    const core::ConstraintSpec& c = scene.constraints[ci];
    if (c.curve.empty()) continue;
    VelocityCurve vc{c.curve, c.velocity, {}};
    for (std::size_t k = 0; k < owner.size(); ++k)
      if (owner[k] == static_cast<std::int32_t>(ci))
        vc.components.emplace_back(static_cast<std::uint32_t>(k / 3),
                                   static_cast<std::uint8_t>(k % 3));
    if (!vc.components.empty()) velocity_curves_.push_back(std::move(vc));
  }
  apply_velocity_curves(0.0);
}

// Absorbing boundaries: the nodes each selects (absorbing_boundary.cpp takes the faces).
void FeSolver::setup_absorbing_boundaries(const core::Scene& scene, const BodyMeshes& meshes) {
  const SurfaceFaces surface =
      scene.absorbing.empty() ? SurfaceFaces{}
                              : boundary_faces(sets_, std::vector<char>(scene.bodies.size(), 1));
  for (const core::AbsorbingSpec& a : scene.absorbing) {
    std::vector<char> selected(nodes_.size(), 0);
    meshes.for_selected(
        scene, nodes_.position, a.nodes, a.body,
        [](const BodySpec& b) { return b.discretisation == Discretisation::hexahedra && !b.rigid; },
        [&](std::size_t n) { selected[n] = 1; });
    setup_absorbing(a, selected, surface);
  }
}

// Loads on hexahedra: the nodes each selects (surface_loads.cpp takes the faces).
void FeSolver::setup_loads(const core::Scene& scene, const BodyMeshes& meshes) {
  const SurfaceFaces surface =
      scene.loads.empty() ? SurfaceFaces{}
                          : boundary_faces(sets_, std::vector<char>(scene.bodies.size(), 1));
  for (std::size_t k = 0; k < scene.loads.size(); ++k) {
    const core::LoadSpec& l = scene.loads[k];
    if (scene.bodies[static_cast<std::size_t>(l.body)].discretisation !=
        core::Discretisation::hexahedra)
      continue;  // particles: mpm/particle_loads.cpp
    std::vector<char> selected(nodes_.size(), 0);
    meshes.for_selected(
        scene, nodes_.initial_position, l.region, l.body, [](const BodySpec&) { return true; },
        [&](std::size_t n) { selected[n] = 1; });
    setup_load(k, selected, surface);
  }
}

// 4. Walls: every node of the bodies they name.
void FeSolver::setup_walls(const core::Scene& scene) {
  for (const core::WallSpec& w : scene.walls) {
    WallState state{w, {}, {}};
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      const int b = nodes_.body[n];
      if (b >= 0 && scene.bodies[static_cast<std::size_t>(b)].rigid) continue;  // deformable only
      // A node tied into hexahedra moves with its host, which the wall holds.
      if (b >= 0 && core::tied_into_hexahedra(scene, scene.bodies[static_cast<std::size_t>(b)]))
        continue;
      if (w.bodies.empty() || std::find(w.bodies.begin(), w.bodies.end(), b) != w.bodies.end())
        state.nodes.push_back(static_cast<std::int32_t>(n));
    }
    walls_.push_back(std::move(state));
  }
}

// 5. Force slots and the node -> slot incidence (CSR).
void FeSolver::build_incidence() {
  const std::size_t n_nodes = nodes_.size();
  std::size_t slots = 0;
  for (ElementSet* set : sets_) {
    set->first_slot = slots;
    slots += set->connectivity().size();
  }
  element_force_.assign(slots, Vec3{});
  std::vector<std::int64_t> count(n_nodes + 1, 0);
  for (const ElementSet* set : sets_)
    for (std::int32_t node : set->connectivity()) ++count[static_cast<std::size_t>(node) + 1];
  for (std::size_t n = 0; n < n_nodes; ++n) count[n + 1] += count[n];
  incidence_offsets_ = count;
  incidence_.assign(static_cast<std::size_t>(count[n_nodes]), 0);
  std::vector<std::int64_t> fill(count.begin(), count.end() - 1);
  for (const ElementSet* set : sets_) {
    const std::span<const std::int32_t> corners = set->connectivity();
    for (std::size_t k = 0; k < corners.size(); ++k)
      incidence_[static_cast<std::size_t>(fill[static_cast<std::size_t>(corners[k])]++)] =
          static_cast<std::int64_t>(set->first_slot + k);
  }
}

// 7. Penalty contacts between meshes, and the per-node arrays their step uses for the nodes of
// their bodies.
void FeSolver::setup_mesh_contacts(const core::Scene& scene) {
  for (const core::ContactSpec& c : scene.contacts)
    if (c.method == core::ContactMethod::penalty)
      contacts_.push_back(make_mesh_contact(c, scene, sets_, nodes_));
  if (contacts_.empty()) return;
  const std::size_t n_nodes = nodes_.size();
  predicted_.assign(n_nodes, Vec3{});
  velocity_start_.assign(n_nodes, Vec3{});
  contact_impulse_.assign(n_nodes, Vec3{});
  std::vector<char> in(scene.bodies.size(), 0);
  for (const MeshContact& c : contacts_)
    for (int b : c.spec.bodies) in[static_cast<std::size_t>(b)] = 1;
  for (std::size_t n = 0; n < n_nodes; ++n)
    if (nodes_.body[n] >= 0 && in[static_cast<std::size_t>(nodes_.body[n])])
      contact_nodes_.push_back(static_cast<std::int32_t>(n));
}

// The step's plan, and the per-thread and per-body arrays the step fills.
void FeSolver::setup_step_arrays(const core::Scene& scene) {
  std::size_t curved = 0, loaded = 0;
  for (const VelocityCurve& vc : velocity_curves_) curved += vc.components.size();
  for (const NodalLoad& l : nodal_loads_) loaded += l.nodes.size();
  plan_ = build_fe_step_plan(
      scene,
      static_cast<std::size_t>(std::count_if(nodes_.imposed.begin(), nodes_.imposed.end(),
                                             [](std::uint8_t m) { return m != 0; })),
      curved, absorbing_nodes_.size(), loaded);
  stage_seconds_.assign(plan_.stages.size(), 0.0);
  thread_sums_.assign(static_cast<std::size_t>(core::thread_count()) * core::cache_line_doubles,
                      0.0);
  body_stabilisation_.assign(scene.bodies.size(), 0.0);
  if (scene.run.reproducible) exact_mirror_.resize(thread_sums_.size());
  start_exact_sums();
  thread_erosions_.resize(static_cast<std::size_t>(core::thread_count()));
  thread_conversions_.resize(static_cast<std::size_t>(core::thread_count()));
  thread_conversion_reason_.resize(static_cast<std::size_t>(core::thread_count()));
  converted_node_.assign(nodes_.size(), 0);
  thread_failure_.resize(static_cast<std::size_t>(core::thread_count()));
  thread_error_field_.resize(static_cast<std::size_t>(core::thread_count()), "");
  thread_errors_.resize(static_cast<std::size_t>(core::thread_count()));
}

void FeSolver::recompute_node_masses() {
  std::fill(nodes_.mass.begin(), nodes_.mass.end(), 0.0);
  for (const ElementSet* set : sets_) {
    const ElementStore& el = set->store();
    const std::span<const std::int32_t> nodes = set->connectivity();
    const auto corners = static_cast<std::size_t>(set->corners());
    for (std::size_t e = 0; e < el.size(); ++e)
      if (el.alive[e])
        for (std::size_t a = 0; a < corners; ++a)
          nodes_.mass[static_cast<std::size_t>(nodes[corners * e + a])] +=
              el.mass[e] / static_cast<double>(corners);
  }
  if (!embedded_.empty()) lend_embedded_masses(embedded_, nodes_, hexes_);
}

}  // namespace afemp::fem
