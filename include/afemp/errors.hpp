// Errors a user can act on: input errors name the file, line, key and what is allowed;
// simulation errors name the step, the point and the field that went bad.
#pragma once

#include <stdexcept>
#include <string>

namespace afemp::core {

/// Where a value came from in an input file (line 0: unknown / whole file).
struct SourceLocation {
  std::string file{};
  int line = 0;
};

/// A problem with a scene or data file. what() reads "FILE:LINE: key 'KEY': MESSAGE".
class InputError : public std::runtime_error {
 public:
  InputError(const SourceLocation& where, const std::string& key, const std::string& message);
  const SourceLocation& where() const { return where_; }
  const std::string& key() const { return key_; }

 private:
  SourceLocation where_;
  std::string key_;
};

/// A simulation that went bad (NaN/Inf, particle left the grid). what() names the step,
/// the entity (particle id, node) and the field.
class SimulationError : public std::runtime_error {
 public:
  SimulationError(long step, double time, const std::string& entity, const std::string& field,
                  const std::string& detail);
  long step() const { return step_; }

 private:
  long step_;
};

/// A checkpoint that cannot be written or read, or a restart refused (the scene changed):
/// what() names the file, the item or keys and the reason (docs/restart.md).
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::CheckpointError;
using core::InputError;
using core::SimulationError;
using core::SourceLocation;
}  // namespace afemp
