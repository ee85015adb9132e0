// A run's directory: where a run writes by default, the files it holds (fields.xmf and .h5,
// history.csv, probes/, the event files, checkpoints/), its checkpoints and what a restart from
// it checks. docs/restart.md.
#pragma once

#include <string>
#include <vector>

#include "afemp/scene.hpp"

namespace afemp::core {

/// The names of a run directory's main files.
struct OutputPaths {
  std::string directory{};                   ///< everything of one run goes here
  std::string fields_stem = "fields";        ///< DIR/STEM.h5 and DIR/STEM.xmf: the field frames
  std::string history_file = "history.csv";  ///< DIR/history.csv: energies and momenta per row
  /// DIR/warnings.txt: RunSummary::warnings, one a line, written when the run finishes
  std::string warnings_file = "warnings.txt";
};

}  // namespace afemp::core

namespace afemp {

using core::OutputPaths;

/// Where `afemp run` writes when given no directory: "runs/FOLDER-NAME" for a scene
/// "some/FOLDER/NAME.toml", relative to the working directory (folder and name: the examples
/// name their scenes after the method, taylor_bar/mpm.toml).
std::string default_output_directory(const std::string& scene_path);

/// The complete checkpoints of a run directory (RUN_DIR/checkpoints/step_N.h5), oldest first.
std::vector<std::string> list_checkpoints(const std::string& run_directory);

/// The newest checkpoint in a run directory; throws CheckpointError when there is none, saying
/// what writes one.
std::string newest_checkpoint(const std::string& run_directory);

/// What a checkpoint's header says of the run that wrote it.
struct CheckpointInfo {
  long step = 0;      ///< steps taken
  double time = 0.0;  ///< simulated time
  /// Threads of the run that wrote it: a restart at another count goes on correctly, but not
  /// bit for bit as the uninterrupted run.
  int threads = 0;
  /// What asked for it: "checkpoint_every", "checkpoint_wall_every", "SIGUSR1", "stopped" (a
  /// run stopped by SimulationOptions::stop_requested) or "program" (Simulation::checkpoint).
  std::string reason{};
  /// MPI ranks of the run that wrote it (1: one process). The checkpoint holds the whole run
  /// whatever the count, and restarts in one process or on any count of ranks.
  int ranks = 1;
};

/// Reads a checkpoint's header. Throws CheckpointError when it cannot be read.
CheckpointInfo read_checkpoint_info(const std::string& checkpoint);

/// The checkpoint `scene` continues from in a run directory (`afemp run SCENE --restart DIR`):
/// its newest, once the scene is found to be the one the checkpoint was written for (only the
/// end time, output, history and checkpoint settings may change). Throws CheckpointError naming
/// the keys that changed; nothing is built or written before.
std::string restart_checkpoint(const std::string& run_directory, const Scene& scene);

/// " (the disk holding DIRECTORY has N bytes free: it is full)" when less than 64 MiB is free
/// there, else "": for a message about a write into `directory` that failed.
std::string disk_full_note(const std::string& directory);

/// For a program's main(), before any HDF5 call: the process then ends without HDF5's exit-time
/// cleanup, which (HDF5 1.10) crashes on a file whose writes failed (a full disk) and would turn
/// a reported output error into a segmentation fault; the operating system closes the files.
void skip_hdf5_exit_cleanup();

}  // namespace afemp
