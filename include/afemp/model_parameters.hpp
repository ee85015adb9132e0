// How a material model states its parameters, once: each strength model, equation of state and
// failure model lists its scene-file keys with their ranges and the rules that join them in
// one function, `parameters(ParameterVisitor&)`, defined in the model's own file. The scene
// parser visits it to read a table (errors name the file, line and key) and Material::validate
// visits it to check a material built in code, so a range is written once and holds for both.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace afemp::core {

/// An allowed interval for a number; each end may be open, closed or absent.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() {
    return {0.0, std::numeric_limits<double>::infinity(), false, false};
  }
  static Range any() { return {}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  /// (lo, inf) and [lo, inf).
  static Range above(double lo) {
    return {lo, std::numeric_limits<double>::infinity(), true, false};
  }
  static Range at_least(double lo) {
    return {lo, std::numeric_limits<double>::infinity(), false, false};
  }

  /// NaN is never contained: a scene must not smuggle "nan" through a range check.
  bool contains(double v) const;
  /// "0 < value <= 1", "value > 0", "any finite number".
  std::string describe() const;
};

/// What a material's elastic constants and density are while its models are read or checked
/// (an EOS takes its reference density from the material, the linear EOS its default bulk
/// modulus, J2 its tangent modulus's bound).
struct MaterialConstants {
  double density = 0.0;
  double youngs_modulus = 0.0;
  double bulk_modulus = 0.0;
};

/// Walks a model's parameters: reading a scene table (reading() true: each call sets the value
/// from the table or its default) or checking a model built in code (each call checks the
/// value it holds). Not for hot loops: it runs once per material.
class ParameterVisitor {
 public:
  virtual ~ParameterVisitor() = default;
  /// A parameter the scene must give, within range.
  virtual void required(std::string_view key, double& value, const Range& range) = 0;
  /// A parameter with a default, within range when given.
  virtual void optional(std::string_view key, double& value, double fallback,
                        const Range& range) = 0;
  /// A parameter that names one of `allowed` (a string in the scene file), held as its index;
  /// `fallback` when the table leaves it out (none: required).
  virtual void choice(std::string_view key, std::size_t& value,
                      std::span<const std::string_view> allowed,
                      std::optional<std::size_t> fallback) = 0;
  /// A rule joining parameters: unless ok, an error at `key` saying `message` (what is wrong
  /// and what is allowed).
  virtual void require(bool ok, std::string_view key, const std::string& message) = 0;
  /// Reading: whether the table gives the key; checking: true.
  virtual bool has(std::string_view key) const = 0;
  virtual bool reading() const = 0;
  virtual const MaterialConstants& material() const = 0;
};

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::ParameterVisitor;
using core::Range;
}  // namespace afemp
