// The registration every material model carries (afemp/model_parameters.hpp): its scene-file
// name (Model::name), its parameters (Model::parameters, in its own file), and the walks over
// the variants that the scene parser, Material::validate and the step plans share, so that none
// of them lists the models.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "afemp/model_parameters.hpp"

namespace afemp::core {

// A number as the scene parser writes it in messages (shortest round-trip form).
std::string format_value(double v);
// "value V is out of range; allowed: ALLOWED", the message of a range or rule not met.
std::string out_of_range(double value, const std::string& allowed);

template <class Model>
concept HasParameters = requires(Model& m, ParameterVisitor& v) {
  m.parameters(v);
};

// Visits the model's parameters (none for a model without any).
template <class Model>
void visit_parameters(Model& model, ParameterVisitor& v) {
  if constexpr (HasParameters<Model>) model.parameters(v);
}

// The keys a model's parameters() names, in its order (the scene parser's allowed keys).
std::vector<std::string> parameter_keys(const MaterialConstants& material,
                                        void (*visit)(ParameterVisitor&, const MaterialConstants&));
template <class Model>
std::vector<std::string> parameter_keys(const MaterialConstants& material) {
  return parameter_keys(material, [](ParameterVisitor& v, const MaterialConstants&) {
    Model model{};
    visit_parameters(model, v);
  });
}

// Checks a model built in code against its own ranges and rules: throws std::invalid_argument
// "material 'NAME': [what ]KEY = VALUE, must be ALLOWED".
void check_parameters(const std::string& material_name, const std::string& what,
                      const MaterialConstants& material,
                      void (*visit)(ParameterVisitor&, const void*), const void* model);
template <class Model>
void check_parameters(const Model& model, const std::string& material_name, const std::string& what,
                      const MaterialConstants& material) {
  check_parameters(
      material_name, what, material,
      [](ParameterVisitor& v, const void* m) {
        Model copy = *static_cast<const Model*>(m);
        visit_parameters(copy, v);
      },
      &model);
}

// Calls f.template operator()<Alternative>(index) for each alternative of a variant, in order.
template <class Variant, class F>
void for_each_alternative(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f.template operator()<std::variant_alternative_t<I, Variant>>(I), ...);
  }
  (std::make_index_sequence<std::variant_size_v<Variant>>{});
}

// The scene-file names of a variant's alternatives that have one (Model::name), in order.
template <class Variant>
std::vector<std::string_view> model_names() {
  std::vector<std::string_view> names;
  for_each_alternative<Variant>([&]<class Model>(std::size_t) {
    if constexpr (requires { Model::name; }) names.push_back(Model::name);
  });
  return names;
}

// The scene-file name of the model a variant holds ("" for one without a name).
template <class Variant>
std::string_view model_name(const Variant& v) {
  return std::visit(
      [](const auto& model) -> std::string_view {
        using Model = std::decay_t<decltype(model)>;
        if constexpr (requires { Model::name; })
          return Model::name;
        else
          return {};
      },
      v);
}

}  // namespace afemp::core
