// Static (implicit) solve of a mesh of hexahedra (fully integrated with B-bar, or one-point with
// the stiffness of its hourglass form: fem/hexahedron_stiffness.hpp) and 2-node trusses (elastic
// or plastic: the 1-D return map, core::small_strain_bar_update) at small strain:
// Newton-Raphson with the consistent tangent (core/materials/small_strain_tangent.hpp), a line
// search and load stepping, the tangent factorised by CHOLMOD (fem/sparse_cholesky.hpp; the
// tangents here are symmetric, so no unsymmetric solver is needed yet). Each iteration's
// residual norm and energy norm |du . r| are recorded (and printed to an optional stream); a
// load step converges when both fall below their tolerances (Bathe 1996, sec. 8.4.4). Rigid
// planar walls hold nodes exactly, by an active set (fem/wall_constraints.hpp). A step that
// fails throws StaticFailure, which names the element that yields most and keeps the state of
// the last converged step.
// solve_newmark integrates the same body in time implicitly (Newmark 1959; HHT-alpha, Hilber,
// Hughes & Taylor, EESD 5 (1977) 283-292) with the consistent mass, each time step one Newton
// solve on the same residual and tangent machinery.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "afemp/material.hpp"
#include "afemp/scene.hpp"
#include "afemp/tensor.hpp"
#include "fem/mesh.hpp"
#include "fem/sparse_assembly.hpp"
#include "fem/wall_constraints.hpp"

namespace afemp::fem {

// Component `component` (0, 1, 2) of node `node` held at `value` (at full load).
struct PrescribedDisplacement {
  std::int32_t node = 0;
  int component = 0;
  double value = 0.0;
};

// A pressure (at full load; positive pushes into the body) on a quadrilateral face whose nodes
// go counter-clockwise seen from outside, as kHexFaces lists them. Dead load: it acts on the
// undeformed face.
struct PressureFace {
  std::array<std::int32_t, 4> nodes{};
  double pressure = 0.0;
};

// How a part's hexahedra integrate, as the explicit solver's bodies say it
// (core::BodySpec::element, core::BodySpec::hourglass). One-point elements need a hourglass form
// with stiffness (stiffness or assumed_strain, with a positive coefficient): the viscous form
// resists only rates, and the implicit solves take no hourglass damping, so it is refused.
struct HexahedronFormulation {
  core::HexFormulation element = core::HexFormulation::full;
  core::HourglassSettings hourglass{};  // one-point elements
};

// Everything at full load (load factor 1); load step s of n applies the factor s / n (from an
// initial state, to the difference between the loads and the state's own internal forces).
struct StaticProblem {
  const MeshData* mesh = nullptr;         // hexahedra and lines (trusses)
  std::vector<core::Material> materials;  // one per part, mesh->part_names order
  // One per part as materials, or empty: every hexahedron fully integrated (B-bar).
  std::vector<HexahedronFormulation> hexahedra;
  std::vector<PrescribedDisplacement> prescribed;
  // Nodes of lines (trusses) tied into hexahedra (rebar in solid elements): each moves with its
  // host's nodes and carries no equations; its forces go to them through the same weights (the
  // constraint eliminated, u_s = sum_a N_a u_a). Not prescribed, on no wall.
  std::vector<TiedNode> tied;
  std::vector<core::Vec3> nodal_forces;  // one per node, or empty
  std::vector<PressureFace> pressures;
  // The acceleration of gravity: the body force rho g, as consistent nodal forces
  // (integral of rho N_a g dV = sum_b M_ab g, M the consistent mass).
  core::Vec3 gravity{};
  // The state the solve starts from, or empty for the virgin one: per hexahedron per Gauss point
  // (fem/hexahedron_full.hpp's order; a one-point element's in the first) the stress and the
  // plastic strain, per line (truss) its axial stress and plastic strain. The mesh's nodes are
  // then where the body is at that state (an explicit phase's end), and the displacements,
  // strains and work of the result are measured from there: a small-strain increment on the
  // current geometry (an updated Lagrangian step, without the initial stress's geometric
  // stiffness). One-point elements' hourglass forms start unloaded.
  std::vector<std::array<core::SymTensor, 8>> initial_stress;
  std::vector<std::array<double, 8>> initial_plastic_strain;
  std::vector<double> initial_line_stress;
  std::vector<double> initial_line_plastic_strain;
  // Fixed, frictionless rigid planes that the listed nodes may not cross; a node that touches a
  // wall at the start (of the solve, or of the Newmark run) rests on it, the others reach it as
  // they move. A prescribed component wins over a wall (the wall moves the others).
  std::vector<PlanarWall> walls;
};

struct NewtonSettings {
  int load_steps = 1;
  int max_iterations = 25;  // per load step
  // A step has converged when ||r|| <= residual_tolerance * max(||f_ext||, ||reactions||) and
  // the last iteration's |du . r| <= energy_tolerance * that of the step's first iteration (or
  // ||r|| is at round-off, below 1e3 machine epsilons of that scale, where no iteration can
  // lower either).
  double residual_tolerance = 1e-10;
  double energy_tolerance = 1e-20;
  // Line search (Crisfield 1991, sec. 9.3): step length s accepted when
  // |du . r(u + s du)| <= line_search_ratio |du . r(u)|, else regula falsi, at most
  // line_search_steps times.
  double line_search_ratio = 0.5;
  int line_search_steps = 6;
  // With walls: the most Newton solves of one step, each after the last changed the active set
  // (a node crossed a wall's plane, or a wall pulled on a node it held).
  int max_contact_rounds = 20;
  std::ostream* log = nullptr;  // one line per iteration when set
  // The BLAS's threads in the sparse factorisation and solve (SparseCholesky): 0 the run's
  // (--threads). The dense blocks' rounding follows their number, so the reproducible mode
  // ([run] reproducible) gives 1: the same bits at any thread count.
  int blas_threads = 0;
};

// One Newton iteration: the residual norm before its solve, |du . r| of its correction (0 on
// the last row of a step, which only checks convergence) and the line search's step length.
struct NewtonIteration {
  int load_step = 0;  // from 1
  int round = 0;      // the Newton solve of the step, from 0 (a new one after the walls' set
                      // changed)
  int iteration = 0;  // from 0, in its solve
  double residual = 0.0;
  double reference = 0.0;  // max(||f_ext||, ||reactions||), the residual's scale
  double energy = 0.0;
  double step_length = 0.0;
  int contacts = 0;  // (wall, node) pairs in contact during the solve
};

// The work the loads did on the body, as its points and hourglass forms took it: per point the
// stress work per unit (initial) volume int sigma : d eps, by the trapezoidal rule over the
// converged load steps (exact for an elastic body; the plastic work of a point follows to the
// same order), per truss the same of its axial stress and strain, and per one-point hexahedron
// the energy stored in its hourglass stiffness (0 for the fully integrated). Summed with the
// volumes, it is the strain energy plus the plastic work the state holds, and at equilibrium the
// work of the loads and reactions.
struct StaticWork {
  std::vector<std::array<double, 8>> points;  // per hexahedron, per Gauss point (as stress)
  std::vector<double> lines;
  std::vector<double> hourglass;
};

struct StaticResult {
  double load_factor = 0.0;              // of this state: 1 once the solve is done
  std::vector<core::Vec3> displacement;  // per node
  // Per hexahedron, per Gauss point (fem/hexahedron_full.hpp's order); a one-point element's
  // single point in all eight.
  std::vector<std::array<core::SymTensor, 8>> stress;
  std::vector<std::array<double, 8>> plastic_strain;
  std::vector<double> line_stress;  // per line (truss), axial
  std::vector<double> line_plastic_strain;
  std::vector<core::Vec3> wall_force;  // per wall, its resultant force on the nodes
  // Per prescribed dof (problem.prescribed's order), the support's force on the body there,
  // f_int - f_ext: at the start (the initial state's, against the full loads) and at this state
  // (the load factor's loads).
  std::vector<double> start_reaction, reaction;
  StaticWork work;
  std::vector<NewtonIteration> iterations;
};

// The element whose plastic strain grew most in a step (the largest increment over its Gauss
// points; a truss has one).
struct YieldingElement {
  enum class Kind { none, hexahedron, truss };  // none: no element yielded in the step
  Kind kind = Kind::none;
  std::int32_t index = -1;  // into MeshData::hexahedra or MeshData::lines
  std::string part;
  double plastic_strain_increment = 0.0;
};

// A load step that failed: Newton did not converge in its iterations, the tangent was not
// positive definite (a mechanism, or a load past the limit load), or the walls' active set did
// not settle.
struct StaticFailureDetails {
  int load_step = 0, load_steps = 0;  // the step that failed (from 1), of load_steps
  int round = 0, iteration = 0;       // in it (NewtonIteration's)
  double residual = 0.0;              // ||r|| at that iteration
  double reference = 0.0;  // its force scale; converged once residual <= tolerance * reference
  double tolerance = 0.0;
  YieldingElement most_yielding;  // at the failing iterate, over the step
  // The state after the last converged load step (load factor 0 and no displacement when the
  // first one failed); its iterations are all the solve's, the failing step's included.
  StaticResult last_converged;
};

class StaticFailure : public std::runtime_error {
 public:
  StaticFailure(const std::string& what, StaticFailureDetails details);
  const StaticFailureDetails& details() const { return *details_; }

 private:
  std::shared_ptr<const StaticFailureDetails> details_;  // shared: copying stays noexcept
};

// Throws std::invalid_argument for a problem it cannot solve (a material without a tangent,
// named; a truss without an area; one-point hexahedra
// without hourglass stiffness, naming the part and the form; bad indices; a wall that moves or
// has friction, naming it), std::runtime_error for a body whose rigid-body modes the prescribed
// dofs and the walls leave free (naming the body's parts and the modes), and StaticFailure for
// a load step that fails: a tangent that is not positive definite (naming the node and
// component), no convergence, or an active set that does not settle; its message names the
// step, the iteration, the residual against its tolerance and the element that yields most.
StaticResult solve_static(const StaticProblem& problem, const NewtonSettings& settings = {});

// Implicit dynamics: M a + (1 + alpha) f_int(u_{n+1}) - alpha f_int(u_n) = f_ext (the HHT
// form; alpha = 0 is Newmark's), u and v advanced by Newmark's formulas with
// beta = (1 - alpha)^2 / 4, gamma = 1/2 - alpha; alpha = 0 gives the trapezoidal rule (beta 1/4,
// gamma 1/2), which conserves the energy of a linear system exactly and is second order;
// alpha in [-1/3, 0) damps the high frequencies, second order still (Hughes 2000, sec. 9.3).
// Each time step is solved by Newton (with the line search) on the effective tangent
// (1 + alpha) K_t + M / (beta dt^2); M is the consistent mass rho integral N_a N_b dV of the
// 2x2x2 Gauss points (one-point elements too; not the explicit solver's lumped mass).
struct NewmarkSettings {
  double time_step = 0.0;
  int steps = 0;
  double alpha = 0.0;  // HHT, in [-1/3, 0]
  // The Newton settings of every time step (load_steps is not used: a time step is one solve).
  NewtonSettings newton;
  // Per node, or empty for zero; prescribed dofs start at their values at t = 0. The initial
  // displacement's stress is reached in one increment from the virgin state, and
  // a_0 = M^-1 (f_ext - f_int(u_0)) (zero on the prescribed dofs).
  std::vector<core::Vec3> initial_displacement;
  std::vector<core::Vec3> initial_velocity;
  // The prescribed dofs' values at time t, in problem.prescribed's order, when set: a dof then
  // moves as they say, its velocity starting at initial_velocity's (give the rate its motion
  // starts with: Newmark's formulas carry a velocity that does not match it as an oscillation)
  // and its acceleration following from Newmark's formulas. Unset: the prescribed dofs are held
  // at problem.prescribed's values from t = 0, at rest.
  std::function<void(double, std::vector<double>&)> prescribed_values;
  // Called at t = 0 and after every step with the time and the displacement, when set.
  std::function<void(double, const std::vector<core::Vec3>&)> observe;
};

struct NewmarkState {
  double time = 0.0;
  double kinetic_energy = 0.0;  // v . M v / 2
  double strain_energy = 0.0;   // stored elastic energy, p^2 / 2K + s:s / 4G integrated,
                                // one-point elements' hourglass energy and trusses' sigma^2 / 2E
  // The work done on the body since t = 0: the loads' f_ext . u and the reactions' at the
  // prescribed dofs (the trapezoidal rule over the steps, exact for the trapezoidal scheme's
  // piecewise-linear reactions). Minus the kinetic energy and the points' stress work (the
  // result's work) it is what the scheme dissipated: HHT's numerical damping, the nodes that
  // arrived on walls and, for a linear body under the trapezoidal rule, round-off.
  double external_work = 0.0;
  std::vector<core::Vec3> wall_force;  // per wall, as StaticResult's (with the inertia)
};

// The problem's loads act fully and constantly from t = 0 (no load steps).
struct NewmarkResult {
  std::vector<core::Vec3> displacement;  // per node, at the end
  std::vector<core::Vec3> velocity;
  std::vector<std::array<core::SymTensor, 8>> stress;  // at the end, as StaticResult's
  std::vector<std::array<double, 8>> plastic_strain;
  std::vector<double> line_stress;
  std::vector<double> line_plastic_strain;
  StaticWork work;                          // per point, at the end, as StaticResult's
  std::vector<NewmarkState> states;         // at t = 0 and after every step
  std::vector<NewtonIteration> iterations;  // load_step is the time step
};

// A time step that failed (Newton did not converge, a tangent that is not positive definite, or
// an active set that did not settle): its message names the step, the iteration, the residual
// and the element that yields most; the result holds the state after the last converged step
// (its states' last time), its iterations the failing step's too.
class NewmarkFailure : public std::runtime_error {
 public:
  NewmarkFailure(const std::string& what, NewmarkResult last_converged);
  const NewmarkResult& last_converged() const { return *last_; }

 private:
  std::shared_ptr<const NewmarkResult> last_;  // shared: copying stays noexcept
};

// Walls act as in the static solve, their active set settled within every time step. A node
// that reaches a wall stops on it within the step (at the step's end its velocity and
// acceleration along the normal are zero, as a prescribed dof's): a kinematic wall, which takes
// the node's normal momentum as the explicit wall does; the trapezoidal rule's energy balance
// holds but for those arrivals. Nodes on or behind a wall at t = 0 start on it (moved onto its
// plane).
// Throws as solve_static (except for an unheld body, which the mass holds; a failing step is a
// NewmarkFailure), and std::invalid_argument for a time step that is not positive or alpha
// outside [-1/3, 0].
NewmarkResult solve_newmark(const StaticProblem& problem, const NewmarkSettings& settings);

// The faces of the mesh's hexahedra whose four nodes all lie in `nodes`, as kHexFaces orders
// them (counter-clockwise from outside), for PressureFace.
std::vector<std::array<std::int32_t, 4>> faces_on_nodes(const MeshData& mesh,
                                                        std::span<const std::int32_t> nodes);

}  // namespace afemp::fem
