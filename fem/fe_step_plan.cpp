// The FE step plan of fem/fe_step_plan.hpp: each stage where the scene needs it, in the order
// FeSolver::begin_step and finish_step run them, with its reason.
#include "fem/fe_step_plan.hpp"

#include "core/appendf.hpp"
#include "core/materials/model_descriptions.hpp"
#include "core/scene.hpp"

namespace afemp::fem {

namespace {

using core::BodySpec;
using core::Discretisation;

// "bar: ...; plate: ...": one part per body that has it.
void add_body(std::string& why, const BodySpec& body, const std::string& what) {
  why += (why.empty() ? "" : "; ") + body.name + ": " + what;
}

// What body's points are made of: its material's strength model, EOS and failure
// (core/materials/model_descriptions.hpp, as the MPM plan names them).
std::string material_models(const core::Scene& scene, const BodySpec& body) {
  const core::Material& m = scene.materials[static_cast<std::size_t>(body.material)];
  return m.name + " (strength " + core::strength_description(m.strength) + ", EOS " +
         core::eos_description(m.eos) + ", failure " + core::failure_description(m) + ")";
}

// How body's hexahedra integrate and stabilise (fem/hexahedron_one_point.cpp, hourglass.cpp,
// hourglass_assumed_strain.cpp, hexahedron_full.cpp) and their bulk viscosity.
std::string hexahedron_formulation(const core::Scene& scene, const BodySpec& body) {
  std::string out;
  if (body.element == core::HexFormulation::full)
    out = "fully integrated (2x2x2) with B-bar volumetric integration";
  else if (body.hourglass.form == core::HourglassForm::assumed_strain)
    core::appendf(out,
                  "one-point, assumed-strain (Belytschko-Bindeman ASQBI) stabilisation "
                  "from the elastic constants, scale %g",
                  body.hourglass.effective_coefficient());
  else
    core::appendf(out, "one-point, %s hourglass control Q_hg = %g",
                  core::to_string(body.hourglass.form), body.hourglass.effective_coefficient());
  const core::BulkViscositySettings q = core::bulk_viscosity_of(scene, body);
  if (q.linear > 0.0 || q.quadratic > 0.0)
    core::appendf(out, ", bulk viscosity linear %g, quadratic %g", q.linear, q.quadratic);
  else
    out += ", no bulk viscosity";
  // A hyperelastic strength reads F, which the element takes from its nodes
  // (fem/hexahedron_deformation_gradient.hpp).
  if (scene.materials[static_cast<std::size_t>(body.material)].reads_deformation_gradient())
    out += body.element == core::HexFormulation::full
               ? ", stress at each Gauss point's F-bar from the nodes"
               : ", stress at the centre's F from the nodes";
  return out + ", material " + material_models(scene, body);
}

// The criteria of body's erosion (fem/hexahedron_update.cpp, truss_update.cpp).
std::string erosion_criteria(const core::Scene& scene, const BodySpec& body) {
  const core::ErosionSettings& e = *body.erosion;
  std::string out;
  if (e.plastic_strain > 0.0) core::appendf(out, "plastic strain %g, ", e.plastic_strain);
  if (e.material_failure)
    out += "material failure (" +
           core::failure_description(scene.materials[static_cast<std::size_t>(body.material)]) +
           "), ";
  if (e.volume_ratio > 0.0) core::appendf(out, "volume ratio %g, ", e.volume_ratio);
  if (e.time_step > 0.0) core::appendf(out, "time step %g, ", e.time_step);
  return out + "inverted elements";
}

// The criteria of body's conversion (fem/element_retirement.cpp) and what an element becomes
// (coupling/element_conversion.cpp).
std::string conversion_criteria(const BodySpec& body) {
  const core::ConversionSettings& c = *body.conversion;
  std::string when;
  auto add = [&](const char* format, double value) {
    if (!when.empty()) when += ", ";
    core::appendf(when, format, value);
  };
  if (c.plastic_strain > 0.0) add("plastic strain >= %g", c.plastic_strain);
  if (c.damage > 0.0) add("damage >= %g", c.damage);
  if (c.volumetric_strain > 0.0) add("|V/V0 - 1| >= %g", c.volumetric_strain);
  if (c.jacobian_ratio > 0.0) add("scaled Jacobian < %g", c.jacobian_ratio);
  if (c.time_step_fraction > 0.0) add("critical step < %g h/c", c.time_step_fraction);
  if (c.negative_jacobian) when += when.empty() ? "inversion" : ", inversion";
  const int particles = c.points * c.points * c.points;
  std::string out;
  core::appendf(out, "%d particle%s per element when ", particles, particles == 1 ? "" : "s");
  return out + when;
}

}  // namespace

FeStepPlan build_fe_step_plan(const core::Scene& scene, std::size_t imposed_nodes,
                              std::size_t curved_components, std::size_t absorbing_nodes,
                              std::size_t loaded_nodes) {
  FeStepPlan plan;
  auto& s = plan.stages;
  const core::Vec3& g = scene.run.gravity;
  std::string forces = "element forces gathered per node";
  if (g.x != 0.0 || g.y != 0.0 || g.z != 0.0) forces += ", gravity m g";
  forces += " and any loads a program sets give v^{n+1/2} = v^{n-1/2} + dt f / m";
  if (loaded_nodes > 0)
    core::appendf(forces,
                  "; [[loads]]: surface tractions on %zu nodes, t times each face's integral of "
                  "N_a over its initial area, at each step's start time",
                  loaded_nodes);
  if (imposed_nodes > 0)
    core::appendf(forces, "; imposed velocity components on %zu nodes (constraints)",
                  imposed_nodes);
  if (curved_components > 0)
    core::appendf(forces, ", %zu node components following a curve (taken at mid-step)",
                  curved_components);
  if (absorbing_nodes > 0)
    core::appendf(forces,
                  "; absorbing boundary on %zu nodes: Lysmer-Kuhlemeyer dashpots rho c_L along "
                  "the face normal, rho c_S across it, applied implicitly",
                  absorbing_nodes);
  for (const BodySpec& body : scene.bodies)
    if (core::tied_into_hexahedra(scene, body))
      core::appendf(forces,
                    "; the nodes of %s tied into the hexahedra of %s: their lumped masses and "
                    "forces carried by the host's nodes (N_a m, N_a f), their motion the host's, "
                    "v = sum N_a v_a",
                    body.name.c_str(),
                    scene.bodies[static_cast<std::size_t>(body.bonded_to)].name.c_str());
  s.push_back({FeStageKind::nodal_update, "nodal update", forces});
  std::string rigid;
  for (const BodySpec& body : scene.bodies)
    if (body.rigid) {
      std::string fixed;
      static constexpr const char* dof[6] = {"x", "y", "z", "rx", "ry", "rz"};
      for (int a = 0; a < 6; ++a)
        if (body.rigid->fixed[static_cast<std::size_t>(a)])
          fixed += std::string(fixed.empty() ? "" : " ") + dof[a];
      add_body(rigid, body, fixed.empty() ? "free" : "fixed " + fixed);
    }
  if (!rigid.empty())
    s.push_back(
        {FeStageKind::rigid_bodies, "rigid bodies",
         "resultant force and moment -> momenta, rotation (Rodrigues), node velocities; " + rigid});
  std::string contacts;
  for (const core::ContactSpec& c : scene.contacts) {
    if (c.method != core::ContactMethod::penalty) continue;
    const bool self = c.bodies[0] == c.bodies[1];
    core::appendf(
        contacts,
        "%s%s: %s, penalty s = %g (k = %g / (w dt^2), w the inverse mass of the pair), friction %g",
        contacts.empty() ? "" : "; ", core::contact_name(scene, c).c_str(),
        self ? "self-contact, node-to-surface" : "node-to-surface both ways", c.penalty, c.penalty,
        c.friction);
  }
  if (!contacts.empty())
    s.push_back({FeStageKind::mesh_contact, "mesh contact",
                 "slave nodes behind master faces at the predicted x^{n+1} = x^n + dt v^{n+1/2} "
                 "(binned search) get the impulses that take the fraction s of the penetration "
                 "out (projected Gauss-Seidel, Coulomb friction); surfaces rebuilt when elements "
                 "erode or convert; " +
                     contacts});
  if (!scene.walls.empty()) {
    std::string why;
    core::appendf(why, "%zu planar wall(s): nodes kept on their side", scene.walls.size());
    s.push_back({FeStageKind::rigid_walls, "rigid walls", why});
  }

  std::string hexahedra, trusses, erosion, conversion;
  for (const BodySpec& body : scene.bodies) {
    if (body.discretisation == Discretisation::hexahedra && !body.rigid)
      add_body(hexahedra, body, hexahedron_formulation(scene, body));
    if (body.discretisation == Discretisation::trusses)
      add_body(trusses, body, "material " + material_models(scene, body));
    if (body.discretisation != Discretisation::particles && body.erosion)
      add_body(erosion, body, erosion_criteria(scene, body));
    if (body.discretisation == Discretisation::hexahedra && body.conversion)
      add_body(conversion, body, conversion_criteria(body));
  }
  if (!hexahedra.empty())
    s.push_back({FeStageKind::hexahedra, "hexahedra",
                 "strain rate from v^{n+1/2} on the mid-step geometry, Jaumann stress update, "
                 "forces on the end-of-step geometry, critical step; " +
                     hexahedra});
  if (!trusses.empty())
    s.push_back(
        {FeStageKind::trusses, "trusses",
         "axial strain rate, uniaxial stress update, axial forces, critical step; " + trusses});
  if (!erosion.empty())
    s.push_back({FeStageKind::erosion, "erosion",
                 "an element that meets a criterion leaves with its energy (erosion.csv), the "
                 "node masses follow the live elements; " +
                     erosion});
  // Where no body erodes, the node masses after a conversion are this stage's.
  if (!conversion.empty())
    s.push_back({FeStageKind::conversion, "conversion",
                 "a hexahedron inside the grid that meets a criterion becomes particles with "
                 "its mass, momentum and state (AFEMP, Lian et al. 2013, §2.6), the node masses "
                 "follow the live elements; " +
                     conversion});
  return plan;
}

int FeStepPlan::index(FeStageKind kind) const {
  for (std::size_t i = 0; i < stages.size(); ++i)
    if (stages[i].kind == kind) return static_cast<int>(i);
  return -1;
}

std::vector<std::string> FeStepPlan::stage_names() const {
  std::vector<std::string> names;
  for (const FeStage& st : stages) names.push_back(st.name);
  return names;
}

std::string FeStepPlan::describe() const {
  std::string out;
  int i = 1;
  for (const FeStage& st : stages) {
    core::appendf(out, "  %d. ", i++);
    out += st.name + "  -- " + st.why + "\n";
  }
  return out;
}

}  // namespace afemp::fem
