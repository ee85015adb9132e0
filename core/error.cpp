#include <sstream>

#include "afemp/errors.hpp"

namespace afemp::core {

namespace {
std::string input_message(const SourceLocation& where, const std::string& key,
                          const std::string& message) {
  // ostringstream rather than string concatenation: GCC 12 warns falsely (-Wrestrict) on
  // the latter at -O3.
  std::ostringstream s;
  s << (where.file.empty() ? std::string("<input>") : where.file);
  if (where.line > 0) s << ':' << where.line;
  s << ": ";
  if (!key.empty()) s << "key '" << key << "': ";
  s << message;
  return s.str();
}

std::string simulation_message(long step, double time, const std::string& entity,
                               const std::string& field, const std::string& detail) {
  std::ostringstream s;
  s << "step " << step << " (t = " << time << "): " << entity << ", field '" << field
    << "': " << detail;
  return s.str();
}
}  // namespace

InputError::InputError(const SourceLocation& where, const std::string& key,
                       const std::string& message)
    : std::runtime_error(input_message(where, key, message)), where_(where), key_(key) {}

SimulationError::SimulationError(long step, double time, const std::string& entity,
                                 const std::string& field, const std::string& detail)
    : std::runtime_error(simulation_message(step, time, entity, field, detail)), step_(step) {}

}  // namespace afemp::core
