// Checkpoints of a run and what a restart checks (docs/restart.md). A checkpoint is one HDF5
// file, RUN_DIR/checkpoints/step_NNNNNNNNNNNN.h5, written beside its final name and renamed
// over it, so that a run killed while writing leaves the previous checkpoint as it was. It
// holds a header (the format, the scene's text and the hashes of the files it reads, the
// thread and rank counts, step and time), the model's state (Model::state), the time loop's
// bookkeeping and the output bookkeeping (frames written, the byte length of the history, probe and
// event files) that a restart truncates those files to before it appends.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace afemp::core {

class StateArchive;

// The layout version written into every checkpoint; a checkpoint of another one is refused.
inline constexpr std::int32_t checkpoint_format = 2;

struct CheckpointHeader {
  std::int32_t format = checkpoint_format;
  std::string scene_path;
  std::string scene_text;                // the scene's TOML as the run read it
  std::vector<std::string> files;        // files the scene reads (meshes, point lists)
  std::vector<std::uint64_t> file_hash;  // FNV-1a of each at the checkpoint (0: unreadable)
  std::int32_t threads = 0;
  // The MPI ranks of the run that wrote it (1: one process); a later item, 1 when absent. A
  // checkpoint is one process's whatever wrote it, and restarts on any count.
  std::int32_t ranks = 1;
  long step = 0;
  double time = 0.0;
  std::string reason;  // "interval", "wall time", "SIGUSR1", "SIGINT", ...
};

// The header of a scene's run now (threads: core::thread_count()).
CheckpointHeader checkpoint_header(const Scene& scene, long step, double time, std::string reason);
// Saves or reads the header (group "header"); reading refuses another format.
void visit_header(StateArchive& archive, CheckpointHeader& header);
// Reads only the header of a checkpoint file.
CheckpointHeader read_checkpoint_header(const std::string& path);

// RUN_DIR/checkpoints, and the file of a checkpoint at `step` in it.
std::string checkpoint_directory(const std::string& run_directory);
std::string checkpoint_path(const std::string& run_directory, long step);
// The complete checkpoints in RUN_DIR/checkpoints, oldest first (half-written .tmp files are
// not among them).
std::vector<std::string> list_checkpoints(const std::string& run_directory);
// The newest checkpoint of a run directory; throws CheckpointError saying what the directory
// holds when there is none.
std::string newest_checkpoint(const std::string& run_directory);

// Differences between the scene a checkpoint was written for and the scene now, one line per
// key ("materials.steel.yield: 350 in the checkpoint, 300 now (scene.toml line 12)"), and per
// file the scene reads whose contents changed. Keys that only steer the run and its output may
// change (run.end_time, run.max_steps, run.output_every, run.output_times, run.history_every,
// run.history_interval, run.checkpoint_*, run.title, run.quiet, run.untranslated, run.units,
// run.energy_error_limit); an empty result means the restart may go on.
std::vector<std::string> scene_changes(const CheckpointHeader& saved, const Scene& now);

// " (the disk holding DIRECTORY has N bytes free: it is full)" when less than 64 MiB is free
// there, else "": appended to write errors.
std::string disk_full_note(const std::string& directory);

// 64-bit FNV-1a of a file's bytes (0 if it cannot be read).
std::uint64_t file_hash(const std::string& path);

}  // namespace afemp::core
