// Static and implicit phases on the FE solver (fem/static_phase.hpp): the problem taken out of
// the solver with the state it starts from, fem::solve_static or fem::solve_newmark, and the
// state handed back as the explicit solver's (FeSolver's members take_static_state,
// kinetic_energy and set_velocities are defined here, beside what they take).
#include "fem/static_phase.hpp"

#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

#include "afemp/errors.hpp"
#include "core/materials/initial_pressure.hpp"
#include "core/phases.hpp"
#include "fem/fe_model.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_one_point.hpp"
#include "fem/hexahedron_stiffness.hpp"
#include "fem/hourglass.hpp"
#include "fem/hourglass_assumed_strain.hpp"
#include "fem/truss.hpp"

namespace afemp::fem {

namespace {

// The problem of a static or implicit phase: the bodies it solves taken out of the solver.
struct PhaseProblem {
  MeshData mesh;
  StaticProblem problem;
  StaticPhaseMap map;
  // Per prescribed dof, its solver node.
  std::vector<std::size_t> prescribed_node;
};

// Builds `out` (which the problem points into: build it in place) from the solver's state
// now: the bodies where they are, their points' stresses and plastic strains; the prescribed
// dofs hold the travel of the constraints' velocities from now to travel_end.
void build_problem(const FeSolver& solver, const core::Scene& scene, const core::PhaseSpec& phase,
                   double travel_end, PhaseProblem& out) {
  const std::vector<int> bodies = core::static_phase_bodies(scene, phase);
  std::vector<std::int32_t> part_of(scene.bodies.size(), -1);
  MeshData& mesh = out.mesh;
  StaticProblem& problem = out.problem;
  StaticPhaseMap& map = out.map;
  for (int b : bodies) {
    const core::BodySpec& body = scene.bodies[static_cast<std::size_t>(b)];
    part_of[static_cast<std::size_t>(b)] = static_cast<std::int32_t>(mesh.part_names.size());
    mesh.part_names.push_back(body.name);
    problem.materials.push_back(scene.materials[static_cast<std::size_t>(body.material)]);
    problem.hexahedra.push_back({body.element, body.hourglass});
  }
  const FeNodes& nodes = solver.nodes();
  const std::vector<std::int64_t>& labels = solver.mesh().node_labels;
  std::vector<std::int32_t> local(nodes.size(), -1);
  auto node = [&](std::int32_t n) {
    const auto i = static_cast<std::size_t>(n);
    if (local[i] < 0) {
      local[i] = static_cast<std::int32_t>(map.nodes.size());
      map.nodes.push_back(n);
      map.start.push_back(nodes.position[i]);
      mesh.nodes.push_back(nodes.position[i]);
      if (labels.size() == nodes.size()) mesh.node_labels.push_back(labels[i]);
    }
    return local[i];
  };
  const HexElements& hexes = solver.hexahedra();
  for (const ElementBatch& batch : hexes.batches) {
    const std::int32_t part = part_of[static_cast<std::size_t>(batch.body)];
    if (part < 0) continue;
    const auto points = static_cast<std::size_t>(batch.points_per_element);
    for (std::size_t e = batch.begin; e < batch.end; ++e) {
      if (!hexes.alive[e]) continue;
      Hexahedron h;
      for (std::size_t a = 0; a < 8; ++a) h[a] = node(hexes.nodes[e][a]);
      mesh.hexahedra.push_back(h);
      mesh.hexahedron_part.push_back(part);
      map.hexahedra.push_back(static_cast<std::int32_t>(e));
      // The points' state now: the solve starts from it.
      const std::size_t p0 = batch.point_begin + (e - batch.begin) * points;
      std::array<core::SymTensor, 8> stress{};
      std::array<double, 8> plastic{};
      for (std::size_t g = 0; g < points; ++g) {
        stress[g] = hexes.stress[p0 + g];
        plastic[g] = hexes.plastic_strain[p0 + g];
      }
      problem.initial_stress.push_back(stress);
      problem.initial_plastic_strain.push_back(plastic);
    }
  }
  const TrussElements& trusses = solver.trusses();
  for (const ElementBatch& batch : trusses.batches) {
    const std::int32_t part = part_of[static_cast<std::size_t>(batch.body)];
    if (part < 0) continue;
    for (std::size_t e = batch.begin; e < batch.end; ++e) {
      if (!trusses.alive[e]) continue;
      mesh.lines.push_back({node(trusses.nodes[e][0]), node(trusses.nodes[e][1])});
      mesh.line_part.push_back(part);
      mesh.line_area.push_back(trusses.area0[e]);
      map.trusses.push_back(static_cast<std::int32_t>(e));
      const std::size_t p = batch.point_begin + (e - batch.begin);
      problem.initial_line_stress.push_back(trusses.stress[p].xx);
      problem.initial_line_plastic_strain.push_back(trusses.plastic_strain[p]);
    }
  }
  // Trusses tied into the hexahedra solved: their nodes follow their hosts' (a node whose host
  // eroded or converted moves with its trusses alone). Their lumped masses are their hosts'.
  const EmbeddedNodes& ties = solver.embedded_nodes();
  for (std::size_t k = 0; k < ties.size(); ++k) {
    const auto s = static_cast<std::size_t>(ties.node[k]);
    if (!ties.bound(k, hexes) || local[s] < 0) continue;
    TiedNode t;
    t.node = local[s];
    for (std::size_t a = 0; a < 8; ++a) t.host[a] = node(ties.host_nodes[k][a]);
    t.weight = ties.weight[k];
    problem.tied.push_back(t);
  }
  // Loads: gravity on the explicit solver's lumped masses (so that the state handed back is
  // at rest under the same loads), a program's held nodal loads, and the constraints.
  const core::Vec3 gravity = phase.gravity ? *phase.gravity : scene.run.gravity;
  const std::vector<core::Vec3> travel = solver.imposed_travel(solver.time(), travel_end);
  // The scene's [[loads]] as they stand at the phase's end, where the constraints' travel is
  // taken too.
  const std::vector<core::Vec3> loads = solver.scene_loads_at(travel_end);
  problem.nodal_forces.resize(map.nodes.size());
  for (std::size_t k = 0; k < map.nodes.size(); ++k) {
    const auto n = static_cast<std::size_t>(map.nodes[k]);
    problem.nodal_forces[k] = nodes.mass[n] * gravity;
    if (!nodes.external_force.empty()) problem.nodal_forces[k] += nodes.external_force[n];
    if (!loads.empty()) problem.nodal_forces[k] += loads[n];
    for (int a = 0; a < 3; ++a)
      if (nodes.imposed[n] & (1u << a)) {
        problem.prescribed.push_back({static_cast<std::int32_t>(k), a, travel[n][a]});
        out.prescribed_node.push_back(n);
      }
  }
  // The walls, on the nodes of the problem they may touch (frictionless and at rest: the scene
  // check refuses the others on a solved body).
  for (std::size_t w = 0; w < solver.walls().size(); ++w) {
    PlanarWall wall{solver.walls()[w].spec, {}};
    for (std::int32_t n : solver.walls()[w].nodes)
      if (local[static_cast<std::size_t>(n)] >= 0)
        wall.nodes.push_back(local[static_cast<std::size_t>(n)]);
    if (wall.nodes.empty()) continue;
    problem.walls.push_back(std::move(wall));
    map.walls.push_back(static_cast<std::int32_t>(w));
  }
  problem.mesh = &mesh;
}

// Newton's settings of the phase: its iterations and its tolerance on the residual, the energy
// criterion's on |du . r|, which falls as the residual's square.
NewtonSettings newton_settings(const core::Scene& scene, const core::PhaseSpec& phase,
                               std::ostream* log) {
  NewtonSettings settings;
  settings.max_iterations = phase.max_iterations;
  settings.residual_tolerance = core::phase_tolerance(phase);
  settings.energy_tolerance = settings.residual_tolerance * settings.residual_tolerance;
  settings.log = log;
  if (scene.run.reproducible) settings.blas_threads = 1;
  return settings;
}

}  // namespace

ImplicitPhaseOutcome run_static_phase(FeSolver& solver, const core::Scene& scene,
                                      const core::PhaseSpec& phase, std::ostream* log,
                                      std::vector<NewtonIteration>& failed) {
  const double start = solver.time();
  PhaseProblem built;
  build_problem(solver, scene, phase, phase.end_time, built);
  const StaticProblem& problem = built.problem;
  const StaticPhaseMap& map = built.map;
  NewtonSettings settings = newton_settings(scene, phase, log);
  settings.load_steps = phase.load_steps;
  StaticResult result;
  try {
    result = solve_static(problem, settings);
  } catch (const std::invalid_argument& e) {
    throw core::InputError(phase.where, "phases", std::string("the static phase: ") + e.what());
  } catch (const StaticFailure& e) {
    // The last converged load step's state is the model's, so that the frame the run keeps
    // shows where the equilibrium was lost.
    const StaticResult& last = e.details().last_converged;
    failed = last.iterations;
    const double time = start + last.load_factor * (phase.end_time - start);
    solver.take_static_state(map, last, time);
    throw core::SimulationError(
        0, time,
        "the static phase, load step " + std::to_string(e.details().load_step) + " of " +
            std::to_string(e.details().load_steps),
        "equilibrium", std::string(e.what()) + " as the model's: the run's last frame");
  } catch (const std::runtime_error& e) {
    throw core::SimulationError(0, start, "the static phase", "equilibrium", e.what());
  }
  const double stored = solver.take_static_state(map, result, phase.end_time);
  ImplicitPhaseOutcome out;
  // After an explicit phase the equilibrium is at rest: the motion the solved bodies had is
  // taken out. The loads (constant, as the explicit phase had them) did f . u, the constraints
  // their reactions' work (by the trapezoidal rule between the start and the end), and what
  // the stresses do not hold of that work and of the motion is booked as damped. A first phase
  // is a slow loading from rest: its loads' work is the stress work take_static_state books,
  // and the bodies keep their initial velocities.
  if (start > 0.0) {
    double work = 0.0;
    for (std::size_t k = 0; k < map.nodes.size(); ++k)
      work += core::dot(problem.nodal_forces[k], result.displacement[k]);
    for (std::size_t k = 0; k < problem.prescribed.size(); ++k)
      work += 0.5 * (result.start_reaction[k] + result.reaction[k]) * problem.prescribed[k].value;
    out.dissipated = solver.kinetic_energy(map.nodes) + work - stored;
    solver.add_external_work(work - stored);
    solver.set_velocities(map.nodes, std::vector<core::Vec3>(map.nodes.size()));
  }
  out.iterations = std::move(result.iterations);
  return out;
}

ImplicitPhaseOutcome run_implicit_phase(FeSolver& solver, const core::Scene& scene,
                                        const core::PhaseSpec& phase, std::ostream* log,
                                        std::vector<NewtonIteration>& failed) {
  const double start = solver.time();
  const double span = phase.end_time - start;
  // The phase holds the loads it starts with (build_problem takes them at `start`).
  for (std::size_t k = 0; k < scene.loads.size(); ++k) {
    if (scene.bodies[static_cast<std::size_t>(scene.loads[k].body)].discretisation !=
        core::Discretisation::hexahedra)
      continue;
    const std::vector<std::array<double, 2>>& curve = scene.loads[k].curve;
    const double f0 = core::curve_factor(curve, start);
    bool varies = core::curve_factor(curve, phase.end_time) != f0;
    for (const auto& point : curve)
      varies = varies || (point[0] > start && point[0] < phase.end_time && point[1] != f0);
    if (varies)
      throw core::InputError(
          phase.where, "phases",
          "the implicit phase holds the loads it starts with, and the curve of [[loads]] entry " +
              std::to_string(k + 1) + " changes between " + std::to_string(start) + " and " +
              std::to_string(phase.end_time) +
              "; let an explicit phase carry the changing load, or keep its factor constant "
              "over the implicit phase");
  }
  PhaseProblem built;
  build_problem(solver, scene, phase, start, built);
  const StaticProblem& problem = built.problem;
  const StaticPhaseMap& map = built.map;
  NewmarkSettings settings;
  settings.steps = core::implicit_steps(phase, span);
  settings.time_step = span / settings.steps;
  settings.alpha = phase.alpha;
  settings.newton = newton_settings(scene, phase, log);
  // The phase starts from the solver's velocities (the bodies' initial velocities); the
  // constraints' components move by their velocities' travel, starting at their rate over the
  // first step.
  const FeNodes& nodes = solver.nodes();
  settings.initial_velocity.resize(map.nodes.size());
  for (std::size_t k = 0; k < map.nodes.size(); ++k)
    settings.initial_velocity[k] = nodes.velocity[static_cast<std::size_t>(map.nodes[k])];
  if (!problem.prescribed.empty()) {
    const std::vector<core::Vec3> first = solver.imposed_travel(start, start + settings.time_step);
    for (std::size_t k = 0; k < problem.prescribed.size(); ++k) {
      const PrescribedDisplacement& p = problem.prescribed[k];
      settings.initial_velocity[static_cast<std::size_t>(p.node)][p.component] =
          first[built.prescribed_node[k]][p.component] / settings.time_step;
    }
    settings.prescribed_values = [&](double t, std::vector<double>& values) {
      const std::vector<core::Vec3> travel = solver.imposed_travel(start, start + t);
      for (std::size_t k = 0; k < problem.prescribed.size(); ++k)
        values[k] = travel[built.prescribed_node[k]][problem.prescribed[k].component];
    };
  }
  NewmarkResult result;
  std::optional<std::string> failure;
  double end_time = phase.end_time;
  try {
    result = solve_newmark(problem, settings);
  } catch (const std::invalid_argument& e) {
    throw core::InputError(phase.where, "phases", std::string("the implicit phase: ") + e.what());
  } catch (const NewmarkFailure& e) {
    // The last converged step's state is the model's (handed on below), so that the frame the
    // run keeps shows where the step failed.
    result = e.last_converged();
    failure = e.what();
    end_time = start + (result.states.empty() ? 0.0 : result.states.back().time);
  } catch (const std::runtime_error& e) {
    throw core::SimulationError(
        0, start, "the implicit phase", "equilibrium",
        std::string(e.what()) + "; the model keeps its state from the phase's start");
  }
  // The state at the phase's end, then the velocities; the work the loads and constraints did
  // over the phase is the external work, and what neither the stresses nor the motion hold is
  // what the scheme dissipated.
  StaticResult end;
  end.load_factor = 1.0;
  end.displacement = std::move(result.displacement);
  end.stress = std::move(result.stress);
  end.plastic_strain = std::move(result.plastic_strain);
  end.line_stress = std::move(result.line_stress);
  end.line_plastic_strain = std::move(result.line_plastic_strain);
  end.work = std::move(result.work);
  if (!result.states.empty()) end.wall_force = result.states.back().wall_force;
  const double kinetic_before = solver.kinetic_energy(map.nodes);
  const double stored = solver.take_static_state(map, end, end_time);
  solver.set_velocities(map.nodes, result.velocity);
  const double kinetic_after = solver.kinetic_energy(map.nodes);
  const double work = result.states.empty() ? 0.0 : result.states.back().external_work;
  solver.add_external_work(work - stored);
  if (failure) {
    failed = std::move(result.iterations);
    throw core::SimulationError(0, end_time, "the implicit phase", "equilibrium",
                                *failure + " as the model's: the run's last frame");
  }
  ImplicitPhaseOutcome out;
  out.dissipated = work - stored - (kinetic_after - kinetic_before);
  out.iterations = std::move(result.iterations);
  out.states = std::move(result.states);
  return out;
}

double FeSolver::take_static_state(const StaticPhaseMap& map, const StaticResult& r, double time) {
  for (std::size_t k = 0; k < map.nodes.size(); ++k) {
    const auto n = static_cast<std::size_t>(map.nodes[k]);
    nodes_.position[n] = map.start[k] + r.displacement[k];
  }
  double work = 0.0;
  // A point's work goes to its internal energy; what its elastic energy does not hold is its
  // plastic work.
  auto take_point = [&](ElementStore& el, std::size_t p, const core::Material& mat,
                        const core::SymTensor& stress, double plastic_strain, double w) {
    const double per_mass = w / mat.density;
    const core::SymTensor before = el.stress[p];
    const bool yielded = plastic_strain > el.plastic_strain[p];
    el.stress[p] = stress;
    el.plastic_strain[p] = plastic_strain;
    el.energy[p] += per_mass;
    work += el.point_mass[p] * per_mass;
    if (yielded) {
      const double plastic =
          per_mass - (core::elastic_energy(mat, stress) - core::elastic_energy(mat, before));
      plastic_work_ += el.point_mass[p] * plastic;
      if (!el.plastic_heat.empty()) el.plastic_heat[p] += plastic;
    }
  };
  for (std::size_t k = 0; k < map.hexahedra.size(); ++k) {
    const auto e = static_cast<std::size_t>(map.hexahedra[k]);
    const ElementBatch& b = batch_of(hexes_, e);
    const core::Material& mat = scene_.materials[static_cast<std::size_t>(b.material)];
    const core::BodySpec& body = scene_.bodies[static_cast<std::size_t>(b.body)];
    const auto points = static_cast<std::size_t>(b.points_per_element);
    const std::size_t p0 = b.point_begin + (e - b.begin) * points;
    // x0: the initial geometry, from which a one-point element's hourglass state is measured
    // (such elements are solved in a first phase only, which starts there: core/phases.cpp).
    HexVectors x0, x, u, f{};
    for (std::size_t a = 0; a < 8; ++a) {
      const auto n = static_cast<std::size_t>(hexes_.nodes[e][a]);
      x0[a] = nodes_.initial_position[n];
      x[a] = nodes_.position[n];
      u[a] = x[a] - x0[a];
    }
    const OnePointHex now = one_point_hex(x);
    hexes_.volume[e] = now.volume;
    for (std::size_t g = 0; g < points; ++g) {
      take_point(hexes_, p0 + g, mat, r.stress[k][g], r.plastic_strain[k][g], r.work.points[k][g]);
      hexes_.density[p0 + g] = mat.density * hexes_.volume0[e] / now.volume;
    }
    if (points == 8) {
      std::array<core::SymTensor, 8> sigma;
      for (std::size_t g = 0; g < 8; ++g) sigma[g] = r.stress[k][g];
      add_stress_forces_bbar(full_hex(x), sigma, f);
    } else {
      add_stress_forces(now, r.stress[k][0], f);
      // The hourglass form's state: the generalised forces of the displacement (at the
      // initial geometry, as the static solve took them), in the axes the explicit form keeps.
      const HourglassStiffness hs = hourglass_stiffness(x0, one_point_hex(x0), mat, body.hourglass);
      const std::array<Vec3, 4> g = hourglass_generalised_forces(hs, u);
      const double energy = r.work.hourglass[k];
      work += energy;
      std::array<Vec3, 4> forces = g;  // global axes (the stiffness form)
      if (body.hourglass.form == core::HourglassForm::assumed_strain) {
        const AssumedStrainGeometry frame0 = assumed_strain_geometry(x0);
        const AssumedStrainGeometry frame = assumed_strain_geometry(x);
        for (std::size_t m = 0; m < 4; ++m) {
          for (std::size_t i = 0; i < 3; ++i)
            hexes_.hourglass_force[e][m][i] = core::dot(frame0.axis[i], g[m]);
          const Vec3& s = hexes_.hourglass_force[e][m];
          forces[m] = s.x * frame.axis[0] + s.y * frame.axis[1] + s.z * frame.axis[2];
        }
        stabilisation_work_ += energy;
        body_stabilisation_[static_cast<std::size_t>(b.body)] += energy;
      } else {
        hexes_.hourglass_force[e] = g;
        hourglass_work_ += energy;
      }
      const HourglassModes modes = hourglass_modes(now, x);
      for (std::size_t m = 0; m < 4; ++m)
        for (std::size_t a = 0; a < 8; ++a) f[a] -= modes.gamma[m][a] * forces[m];
    }
    for (std::size_t a = 0; a < 8; ++a) element_force_[hexes_.first_slot + 8 * e + a] = f[a];
  }
  for (std::size_t k = 0; k < map.trusses.size(); ++k) {
    const auto e = static_cast<std::size_t>(map.trusses[k]);
    const ElementBatch& b = batch_of(trusses_, e);
    const core::Material& mat = scene_.materials[static_cast<std::size_t>(b.material)];
    const std::size_t p = b.point_begin + (e - b.begin);
    core::SymTensor stress;
    stress.xx = r.line_stress[k];
    take_point(trusses_, p, mat, stress, r.line_plastic_strain[k], r.work.lines[k]);
    const auto na = static_cast<std::size_t>(trusses_.nodes[e][0]);
    const auto nb = static_cast<std::size_t>(trusses_.nodes[e][1]);
    const TrussKinematics now = truss_kinematics(nodes_.position[na], nodes_.position[nb],
                                                 nodes_.velocity[na], nodes_.velocity[nb]);
    const double area = current_area(trusses_.area0[e], trusses_.length0[e], mat.density,
                                     now.length, trusses_.density[p]);
    trusses_.volume[e] = area * now.length;
    Vec3 fa, fb;
    add_truss_forces(now, stress.xx * area, fa, fb);
    element_force_[trusses_.first_slot + 2 * e] = fa;
    element_force_[trusses_.first_slot + 2 * e + 1] = fb;
  }
  // The walls' reactions, for the history row at the switch (the explicit steps then find
  // theirs from the impulses).
  for (std::size_t k = 0; k < map.walls.size() && k < r.wall_force.size(); ++k)
    wall_force_[static_cast<std::size_t>(map.walls[k])] = r.wall_force[k];
  external_work_ += work;
  time_ = time;
  for (ElementSet* set : sets_) set->initial_critical_steps(scene_, nodes_.position);
  return work;
}

double FeSolver::kinetic_energy(std::span<const std::int32_t> nodes) const {
  double sum = 0.0;
  for (std::int32_t k : nodes) {
    const auto n = static_cast<std::size_t>(k);
    sum += 0.5 * nodes_.mass[n] * core::dot(nodes_.velocity[n], nodes_.velocity[n]);
  }
  return sum;
}

void FeSolver::set_velocities(std::span<const std::int32_t> nodes,
                              std::span<const core::Vec3> velocity) {
  for (std::size_t k = 0; k < nodes.size(); ++k)
    nodes_.velocity[static_cast<std::size_t>(nodes[k])] = velocity[k];
}

double FeModel::run_implicit_phase(const core::PhaseSpec& phase, std::ostream* log) {
  char buf[200];
  // The phase's number in the scene (from 1): a scene may have several of a kind, whose rows
  // share a file.
  const long number = &phase - scene_.phases.data() + 1;
  auto write = [&](core::EventLog& rows, const std::vector<NewtonIteration>& iterations) {
    for (const NewtonIteration& it : iterations) {
      std::snprintf(buf, sizeof buf, "%ld,%d,%d,%.6e,%.6e,%.6e,%.6g", number, it.load_step,
                    it.iteration, it.residual, it.reference, it.energy, it.step_length);
      rows.rows.emplace_back(buf);
    }
  };
  // A solve that fails leaves its iterations (the failing step's too) in `failed`, written
  // with the events the run keeps.
  std::vector<NewtonIteration> failed;
  if (phase.kind == core::PhaseKind::static_load) {
    core::EventLog rows{"static_phase.csv",
                        "phase,load_step,iteration,residual,force_scale,energy,step_length",
                        {}};
    try {
      const ImplicitPhaseOutcome out = fem::run_static_phase(solver_, scene_, phase, log, failed);
      write(rows, out.iterations);
      phase_logs_.push_back(std::move(rows));
      return out.dissipated;
    } catch (const core::SimulationError&) {
      write(rows, failed);
      phase_logs_.push_back(std::move(rows));
      throw;
    }
  }
  const double start = solver_.time();
  core::EventLog rows{"implicit_phase.csv",
                      "phase,time_step,iteration,residual,force_scale,energy,step_length",
                      {}};
  ImplicitPhaseOutcome out;
  try {
    out = fem::run_implicit_phase(solver_, scene_, phase, log, failed);
  } catch (const core::SimulationError&) {
    write(rows, failed);
    phase_logs_.push_back(std::move(rows));
    throw;
  }
  write(rows, out.iterations);
  core::EventLog energies{
      "implicit_energies.csv", "time,kinetic,strain,external_work,plastic_and_dissipated", {}};
  for (const NewmarkState& st : out.states) {
    std::snprintf(buf, sizeof buf, "%.10e,%.10e,%.10e,%.10e,%.10e", start + st.time,
                  st.kinetic_energy, st.strain_energy, st.external_work,
                  st.external_work - st.kinetic_energy - st.strain_energy +
                      out.states.front().kinetic_energy + out.states.front().strain_energy);
    energies.rows.emplace_back(buf);
  }
  phase_logs_.push_back(std::move(rows));
  phase_logs_.push_back(std::move(energies));
  return out.dissipated;
}

}  // namespace afemp::fem
