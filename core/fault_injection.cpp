// The crash tests' hook of core/fault_injection.hpp.
#include "core/fault_injection.hpp"

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <string>

namespace afemp::core {

namespace {

struct Fault {
  std::string name;
  long remaining = 0;
  Fault() {
    const char* spec = std::getenv("AFEMP_FAULT");
    if (spec == nullptr) return;
    const char* colon = std::strchr(spec, ':');
    if (colon == nullptr) return;
    name.assign(spec, colon);
    char* end = nullptr;
    remaining = std::strtol(colon + 1, &end, 10);
    if (end != nullptr && *end == '@') {
      const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
      if (rank == nullptr) rank = std::getenv("PMI_RANK");
      if (rank == nullptr || std::strtol(rank, nullptr, 10) != std::strtol(end + 1, nullptr, 10))
        remaining = 0;
    }
  }
};

Fault& fault() {
  static Fault f;
  return f;
}

}  // namespace

void fault_point(const char* name) {
  Fault& f = fault();
  if (f.remaining <= 0 || f.name != name) return;
  if (--f.remaining == 0) std::raise(SIGKILL);
}

}  // namespace afemp::core
