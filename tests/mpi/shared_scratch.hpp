// A scratch file every rank of an MPI test names alike, and a divided model's checkpoint written
// there and read back (header only; not a test file itself).
#pragma once

#include <stdlib.h>  // mkdtemp

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/rank_link.hpp"
#include "core/state_archive.hpp"

namespace afemp::test {

// Collective: the path `file` in a new directory rank 0 made under the temporary directory, the
// same on every rank; "" on every rank when rank 0 could not make one.
inline std::string shared_scratch_file(core::RankLink& link, const std::string& file) {
  std::string path;
  if (link.rank() == 0) {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "afemp-mpi-test-XXXXXX").string();
    if (mkdtemp(pattern.data()) != nullptr) path = pattern + "/" + file;
  }
  const std::vector<std::byte> told = link.gather(core::bytes_of(path))[0];
  return {reinterpret_cast<const char*>(told.data()), told.size()};
}

// Collective: once every rank is done with it, rank 0 removes the file's directory.
inline void remove_shared_scratch(core::RankLink& link, const std::string& path) {
  link.max_over_ranks(0.0);
  if (link.rank() == 0) std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

// Collective: the divided model's checkpoint (prepare_checkpoint() on every rank, then rank 0
// writes it alone, as one process's file); every rank returns once the file is whole.
template <class Model>
void save_checkpoint(core::RankLink& link, Model& model, const std::string& path) {
  model.prepare_checkpoint();
  if (link.rank() == 0) {
    core::StateArchive a(path, core::StateArchive::Mode::save);
    model.state(a);
    a.close();
  }
  link.max_over_ranks(0.0);
}

// The checkpoint read into a model (divided among ranks or not).
template <class Model>
void load_checkpoint(Model& model, const std::string& path) {
  core::StateArchive a(path, core::StateArchive::Mode::load);
  model.state(a);
}

}  // namespace afemp::test
