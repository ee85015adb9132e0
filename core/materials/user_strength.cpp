// The registry of user strength models (include/afemp/user_material.hpp): a name-keyed table
// that the scene parser and Materials built in code look models up in. Registration takes a
// lock; look-ups happen when a scene is read or built, never inside the time loop (a Material
// holds its definition through a shared pointer).
#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>

#include "afemp/errors.hpp"
#include "afemp/user_material.hpp"
#include "core/scene_parser.hpp"

namespace afemp::core {

namespace {

struct Registry {
  std::mutex lock;
  std::map<std::string, std::shared_ptr<const UserStrengthDefinition>> models;
};

Registry& registry() {
  static Registry r;
  return r;
}

[[noreturn]] void fail(const std::string& name, const std::string& message) {
  throw InputError({"user strength model registration", 0}, name, message);
}

// The names for a message: "a, b, c", or "(none)".
std::string listed(const std::vector<std::string>& names) {
  return names.empty() ? "(none)" : scene_detail::join(names, false);
}

}  // namespace

void register_strength_model(UserStrengthDefinition definition) {
  const std::string name = definition.name;
  if (name.empty()) fail("name", "a user strength model needs a name");
  for (std::string_view b : scene_detail::builtin_strength_models())
    if (name == b) fail(name, "is a built-in strength model; choose another name");
  if (!definition.update) fail(name, "has no update function");
  if (!definition.initial_history.empty() &&
      definition.initial_history.size() != definition.history_variables.size())
    fail(name, "initial_history has " + std::to_string(definition.initial_history.size()) +
                   " values for " + std::to_string(definition.history_variables.size()) +
                   " history variables");
  if (definition.softens_with_temperature && !definition.reads_temperature)
    fail(name, "softens_with_temperature needs reads_temperature");
  const std::vector<std::string>& keys = definition.parameters;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i].empty() || keys[i] == "model")
      fail(name, "parameter name '" + keys[i] + "' is empty or reserved (the model key)");
    if (std::find(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(i), keys[i]) !=
        keys.begin() + static_cast<std::ptrdiff_t>(i))
      fail(name, "parameter '" + keys[i] + "' is declared twice");
  }
  Registry& r = registry();
  const std::lock_guard<std::mutex> guard(r.lock);
  if (r.models.count(name)) fail(name, "is already registered");
  r.models.emplace(name, std::make_shared<const UserStrengthDefinition>(std::move(definition)));
}

std::shared_ptr<const UserStrengthDefinition> find_strength_model(const std::string& name) {
  Registry& r = registry();
  {
    const std::lock_guard<std::mutex> guard(r.lock);
    const auto it = r.models.find(name);
    if (it != r.models.end()) return it->second;
  }
  fail(name, "no user strength model of that name is registered; registered: " +
                 listed(registered_strength_models()));
}

std::vector<std::string> registered_strength_models() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> guard(r.lock);
  std::vector<std::string> names;
  for (const auto& [name, definition] : r.models) names.push_back(name);
  return names;
}

UserStrength user_strength(const std::string& name,
                           const std::vector<std::pair<std::string, double>>& parameters) {
  UserStrength u;
  u.definition = find_strength_model(name);
  const std::vector<std::string>& declared = u.definition->parameters;
  for (const auto& [key, value] : parameters)
    if (std::find(declared.begin(), declared.end(), key) == declared.end())
      fail(name, "unknown parameter '" + key + "'; the model's parameters: " + listed(declared));
  for (const std::string& key : declared) {
    const auto it = std::find_if(parameters.begin(), parameters.end(),
                                 [&](const auto& kv) { return kv.first == key; });
    if (it == parameters.end())
      fail(name, "parameter '" + key + "' missing; the model's parameters: " + listed(declared));
    u.parameters.push_back(it->second);
  }
  return u;
}

}  // namespace afemp::core
