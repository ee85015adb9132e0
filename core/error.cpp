#include "core/error.hpp"

namespace afemp::core {

namespace {
std::string input_message(const SourceLocation& where, const std::string& key,
                          const std::string& message) {
  std::string s = where.file.empty() ? std::string("<input>") : where.file;
  if (where.line > 0) s += ":" + std::to_string(where.line);
  s += ": ";
  if (!key.empty()) s += "key '" + key + "': ";
  return s + message;
}

std::string simulation_message(long step, double time, const std::string& entity,
                               const std::string& field, const std::string& detail) {
  return "step " + std::to_string(step) + " (t = " + std::to_string(time) + "): " + entity +
         ", field '" + field + "': " + detail;
}
}  // namespace

InputError::InputError(const SourceLocation& where, const std::string& key,
                       const std::string& message)
    : std::runtime_error(input_message(where, key, message)), where_(where), key_(key) {}

SimulationError::SimulationError(long step, double time, const std::string& entity,
                                 const std::string& field, const std::string& detail)
    : std::runtime_error(simulation_message(step, time, entity, field, detail)), step_(step) {}

}  // namespace afemp::core
