// The run directory of the public API (include/afemp/run_directory.hpp): the library's own
// conventions (core/output/run_directory.hpp, core/checkpoint.hpp) under their public names,
// and the restart's scene check before anything is built.
#include "afemp/run_directory.hpp"

#include "core/checkpoint.hpp"
#include "core/output/field_writer.hpp"
#include "core/output/run_directory.hpp"

namespace afemp {

std::string default_output_directory(const std::string& scene_path) {
  return core::default_output_directory(scene_path);
}

std::vector<std::string> list_checkpoints(const std::string& run_directory) {
  return core::list_checkpoints(run_directory);
}

std::string newest_checkpoint(const std::string& run_directory) {
  return core::newest_checkpoint(run_directory);
}

CheckpointInfo read_checkpoint_info(const std::string& checkpoint) {
  const core::CheckpointHeader h = core::read_checkpoint_header(checkpoint);
  return {h.step, h.time, h.threads, h.reason, h.ranks};
}

std::string restart_checkpoint(const std::string& run_directory, const Scene& scene) {
  const std::string checkpoint = core::newest_checkpoint(run_directory);
  const std::vector<std::string> changes =
      core::scene_changes(core::read_checkpoint_header(checkpoint), scene);
  if (changes.empty()) return checkpoint;
  std::string text = "cannot restart from " + checkpoint +
                     ": the scene changed since the checkpoint (only the end time, output, "
                     "history and checkpoint settings may):";
  for (const std::string& c : changes) text += "\n  " + c;
  throw CheckpointError(text);
}

std::string disk_full_note(const std::string& directory) {
  return core::disk_full_note(directory);
}

void skip_hdf5_exit_cleanup() {
  core::skip_hdf5_exit_cleanup();
}

}  // namespace afemp
