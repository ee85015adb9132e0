// The library's entry point: a Simulation is a model made from a Scene (built in code, or read
// from a scene file with afemp::read_scene), stepped one step at a time or run to an end time,
// with its fields readable and writable between steps and callbacks after each step.
// docs/library.md is the tutorial; examples/library/ a project to copy.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "afemp/errors.hpp"
#include "afemp/run.hpp"
#include "afemp/run_directory.hpp"
#include "afemp/scene.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {
class RankLink;  // core/rank_link.hpp (not installed): a run divided among MPI ranks
}

namespace afemp {

/// Reads and checks a scene file (docs/scene-format.md). Throws InputError naming the file,
/// line, key and what is allowed.
Scene read_scene(const std::string& path);

/// Checks a scene as the scene-file parser would (ranges, references between objects, what
/// goes with what). Throws InputError naming the object and field by the scene file's dotted
/// key ("bodies.plate.particles_per_cell") and what is allowed. Simulation calls it.
void check_scene(const Scene& scene);

/// The material points of a model (particles), as views into its arrays. Valid until the next
/// step: a step may reorder the particles (follow one by `id`) and conversion adds some.
/// Writable fields may be changed between steps (a program's boundary condition or load).
struct ParticleFields {
  std::span<Vec3> position{};          ///< current position
  std::span<Vec3> velocity{};          ///< velocity
  std::span<const double> mass{};      ///< mass (constant)
  std::span<double> volume{};          ///< current volume (density = mass / volume)
  std::span<SymTensor> stress{};       ///< Cauchy stress
  std::span<double> plastic_strain{};  ///< equivalent plastic strain
  std::span<double> temperature{};     ///< temperature
  std::span<double> energy{};          ///< specific internal energy (per unit mass)
  std::span<double> damage{};          ///< scalar damage in [0, 1]
  /// Strength models' history variables (a user model's, or a built-in model's own such as
  /// HJC's largest compaction), history_count per particle, point-major:
  /// particle i's variable v is history[i * history_count + v].
  std::span<double> history{};
  std::size_t history_count = 0;         ///< the most any of the scene's materials declares
  std::span<const std::int32_t> body{};  ///< index of the body in Scene::bodies
  std::span<const std::int32_t> id{};    ///< stable id, unchanged by reordering
  std::size_t size() const { return position.size(); }
};

/// The nodes of the model's meshes (every hexahedron and truss body, in body order).
struct NodeFields {
  std::span<Vec3> position{};      ///< x^n
  std::span<Vec3> velocity{};      ///< v^{n-1/2}: central differences keep half-step velocities
  std::span<const double> mass{};  ///< lumped mass (0: the node has no live element)
  std::span<const std::int32_t> body{};  ///< index of the body in Scene::bodies
  /// Loads the program applies, one per node, held until changed; they act over the next steps
  /// on the nodes the FE update moves (not on nodes bonded to particles), and their work is
  /// booked as external work in the energy balance.
  std::span<Vec3> external_force{};
  std::size_t size() const { return position.size(); }
};

/// The elements of one kind (hexahedra, or trusses) with their integration-point state: element
/// e's points are points_per_element[e] consecutive entries from first_point[e].
struct ElementFields {
  /// Node indices, nodes_per_element per element (element e's from e * nodes_per_element).
  std::span<const std::int32_t> connectivity{};
  int nodes_per_element = 0;               ///< 8 (hexahedra) or 2 (trusses)
  std::span<const std::uint8_t> alive{};   ///< 0: eroded or converted into particles
  std::span<const std::int32_t> body{};    ///< index of the body in Scene::bodies
  std::vector<std::size_t> first_point{};  ///< first integration point of each element
  std::vector<int> points_per_element{};   ///< 1 (one-point, truss) or 8 (B-bar)
  std::span<SymTensor> stress{};           ///< per point (trusses: the axial stress as xx)
  std::span<double> plastic_strain{};      ///< per point
  std::span<double> temperature{};         ///< per point
  std::span<double> energy{};              ///< per point, specific internal energy
  std::span<double> damage{};              ///< per point
  /// Strength models' history variables (as for particles), history_count per point, point-major.
  std::span<double> history{};
  std::size_t history_count = 0;  ///< the most any of the scene's materials declares
  std::size_t size() const { return alive.size(); }
};

/// Where and how a Simulation writes its output; all optional.
struct SimulationOptions {
  /// Run directory for fields.xmf/.h5, history.csv, probes and event files; empty: none.
  std::string output_directory;
  bool write_fields = true;  ///< fields.xmf/.h5 (with an output directory)
  /// Called about every progress_seconds of wall time while run() or run_to() step.
  std::function<void(const Progress&)> progress;
  double progress_seconds = 0.5;
  /// A checkpoint to continue from (newest_checkpoint(output_directory), docs/restart.md): the
  /// model, built from the same scene, takes its state and the run's files in
  /// output_directory are continued. A scene read from a file is compared with the one the
  /// checkpoint was written for (only end time, output, history and checkpoint settings may
  /// differ; CheckpointError names the keys otherwise); one built in code is not.
  std::string restart_from;
  /// Asked before each step of run(): true ends the run there; the run then writes a
  /// checkpoint of the state after its last whole step (RunSummary::checkpoint, or
  /// checkpoint_error), the final history row, frame and summary (RunSummary::interrupted).
  /// `afemp run` asks whether SIGINT or SIGTERM came (afemp/interrupt.hpp).
  std::function<bool()> stop_requested;
  /// Asked after each step: true writes a checkpoint there and the run goes on; the answer
  /// must clear the request (`afemp run`: SIGUSR1, afemp/interrupt.hpp).
  std::function<bool()> checkpoint_requested;
  /// The constructor builds the model and stops there; start() writes the initial state (or
  /// continues from restart_from). A program prints warnings() and estimate() first, as
  /// `afemp run` does, and what start() throws is then the run's, not the scene's.
  bool defer_start = false;
  /// A scene's static and implicit phases print each Newton iteration here when set, and every
  /// phase what the next starts from (`afemp run`: standard output); OUTPUT/static_phase.csv
  /// and implicit_phase.csv have the iterations in any case. On ranks rank 0 solves a static or
  /// implicit phase and alone prints its iterations.
  std::ostream* phase_log = nullptr;
  /// A run divided among MPI ranks (docs/parallel.md): every rank builds the Simulation with
  /// the same scene and its link to the others, and makes the same calls in the same order.
  /// Particles divide by the grid's blocks, meshes by their elements, coupled scenes both
  /// (std::invalid_argument names what does not divide yet). Rank 0 writes
  /// the output and the checkpoints, each the whole run's as one process's; restart_from then
  /// names the same file on every rank, and a checkpoint restarts on any rank count, or in one
  /// process. nullptr: this process runs the whole scene.
  core::RankLink* ranks = nullptr;
  /// How such a run rebalances its ranks as the material moves (RankBalance).
  RankBalance balance{};
};

/// The threads a run uses: OpenMP's (OMP_NUM_THREADS, or every core), or set_thread_count's; 1
/// without OpenMP. A restart at the count of the run that wrote the checkpoint ends bit for bit
/// as the uninterrupted run.
int thread_count();
/// Sets the threads of the runs that follow (n > 0).
void set_thread_count(int n);

/// A model made from a scene: MPM, FE, or both coupled on the background grid, as the scene
/// asks; the same model `afemp run` makes from the same scene, stepped by the same loop
/// (history rows, field frames, probes, energy guard). Nothing is printed and nothing exits:
/// bad input throws InputError, a run that goes bad throws SimulationError (naming the step, the
/// point and the field; what was written stays on disk).
class Simulation {
 public:
  /// A callback after each step (a program's load, boundary condition or output).
  using StepCallback = std::function<void(Simulation&)>;

  /// Checks the scene (check_scene), builds the model and writes the initial state (with
  /// SimulationOptions::defer_start, start() writes it).
  explicit Simulation(Scene scene, SimulationOptions options = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// The scene the model was made from.
  const Scene& scene() const;
  /// What `afemp check` prints: the discretisation, the stages one step runs and why.
  std::string describe() const;
  /// The step the next step() takes: the stable step times the scene's factor (or the fixed step).
  double stable_time_step() const;
  double time() const;      ///< simulated time
  long step_count() const;  ///< steps taken
  /// Whether the run has reached the scene's end time, max_steps or [run] terminate.
  bool finished() const;
  /// Energies now, with per-body mass, momentum, kinetic and internal energy.
  Energies energies() const;
  /// What may run against the scene's intent, one line each: bodies that meet with no contact,
  /// bond or conversion between them (particles on one grid weld, meshes pass through), then
  /// values implausible for the scene's units and mistakes that run silently ([run] quiet
  /// silences keys). `afemp check` and `afemp run` print them before the run.
  std::vector<std::string> warnings() const;
  /// The run's size before it starts: its step, steps, points, memory and wall time at the
  /// nominal pace on thread_count() threads, with the warnings of a run too long to be meant.
  RunEstimate estimate() const;

  /// With SimulationOptions::defer_start: writes the initial state (the first history row and
  /// frame), or takes the state of SimulationOptions::restart_from and continues its files;
  /// once, before any step, checkpoint() or finish(). Until then the views show the model as
  /// built.
  void start();

  /// One step at the stable step (cut so as not to pass the end time), then the callbacks;
  /// nothing once finished().
  void step();
  /// Steps until `time` (the last step cut to land on it) or until finished().
  void run_to(double time);
  /// Steps to the end, or until SimulationOptions::stop_requested answers true, and returns
  /// finish().
  RunSummary run();
  /// The final history row and frame, and the summary with the scene's reference checks (a
  /// run that stop_requested ended writes its checkpoint first). Call once; the Simulation
  /// takes no step after it.
  RunSummary finish();

  /// Adds a callback run after every step, in the order added.
  void on_step(StepCallback callback);
  /// Writes a checkpoint of the state now into OUTPUT/checkpoints and returns its path (""
  /// without an output directory); the run goes on. Throws CheckpointError, the previous
  /// checkpoints kept, when it cannot be written.
  std::string checkpoint();

  ParticleFields particles();  ///< empty without particle bodies
  NodeFields nodes();          ///< empty without mesh bodies
  ElementFields hexahedra();   ///< empty without hexahedra
  ElementFields trusses();     ///< empty without trusses
  /// The internal (element) force on each mesh node at the current state.
  std::vector<Vec3> node_forces() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace afemp
