// The walks over a model's parameters that are not the scene parser's: listing its keys and
// checking a model built in code (afemp/model_parameters.hpp).
#include "core/materials/model_parameters.hpp"

#include <cmath>
#include <stdexcept>

#include "core/scene_parser.hpp"

namespace afemp::core {

using scene_detail::format_number;

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  const bool lo_ok = lo_open ? v > lo : v >= lo;
  const bool hi_ok = hi_open ? v < hi : v <= hi;
  return lo_ok && hi_ok;
}

std::string Range::describe() const {
  const bool has_lo = std::isfinite(lo);
  const bool has_hi = std::isfinite(hi);
  if (!has_lo && !has_hi) return "any finite number";
  if (has_lo && !has_hi)
    return std::string("value ") + (lo_open ? "> " : ">= ") + format_number(lo);
  if (!has_lo) return std::string("value ") + (hi_open ? "< " : "<= ") + format_number(hi);
  return format_number(lo) + (lo_open ? " < " : " <= ") + "value" + (hi_open ? " < " : " <= ") +
         format_number(hi);
}

std::string format_value(double v) {
  return format_number(v);
}

std::string out_of_range(double value, const std::string& allowed) {
  return "value " + format_number(value) + " is out of range; allowed: " + allowed;
}

namespace {

// Collects the keys, leaving every value at its default.
class KeyList final : public ParameterVisitor {
 public:
  explicit KeyList(const MaterialConstants& material) : material_(material) {}
  void required(std::string_view key, double&, const Range&) override { add(key); }
  void optional(std::string_view key, double&, double, const Range&) override { add(key); }
  void choice(std::string_view key, std::size_t&, std::span<const std::string_view>,
              std::optional<std::size_t>) override {
    add(key);
  }
  void require(bool, std::string_view, const std::string&) override {}
  bool has(std::string_view) const override { return false; }
  bool reading() const override { return true; }
  const MaterialConstants& material() const override { return material_; }
  std::vector<std::string> keys;

 private:
  void add(std::string_view key) { keys.emplace_back(key); }
  const MaterialConstants& material_;
};

// Checks the values a model holds. Conditions are written so that NaN fails them too.
class Check final : public ParameterVisitor {
 public:
  Check(const std::string& name, const std::string& what, const MaterialConstants& material)
      : name_(name), what_(what), material_(material) {}
  void required(std::string_view key, double& value, const Range& range) override {
    if (std::isfinite(value) && range.contains(value)) return;
    fail(key, out_of_range(value, range.describe()));
  }
  void optional(std::string_view key, double& value, double, const Range& range) override {
    required(key, value, range);
  }
  void choice(std::string_view key, std::size_t& value, std::span<const std::string_view> allowed,
              std::optional<std::size_t>) override {
    if (value >= allowed.size())
      fail(key, "choice " + std::to_string(value) + " is out of range; allowed: 0 to " +
                    std::to_string(allowed.size() - 1));
  }
  void require(bool ok, std::string_view key, const std::string& message) override {
    if (!ok) fail(key, message);
  }
  bool has(std::string_view) const override { return true; }
  bool reading() const override { return false; }
  const MaterialConstants& material() const override { return material_; }

 private:
  [[noreturn]] void fail(std::string_view key, const std::string& what) const {
    throw std::invalid_argument("material '" + name_ + "': " + what_ + std::string(key) + ": " +
                                what);
  }
  const std::string& name_;
  const std::string& what_;
  const MaterialConstants& material_;
};

}  // namespace

std::vector<std::string> parameter_keys(const MaterialConstants& material,
                                        void (*visit)(ParameterVisitor&,
                                                      const MaterialConstants&)) {
  KeyList list(material);
  visit(list, material);
  return list.keys;
}

void check_parameters(const std::string& material_name, const std::string& what,
                      const MaterialConstants& material,
                      void (*visit)(ParameterVisitor&, const void*), const void* model) {
  Check check(material_name, what, material);
  visit(check, model);
}

}  // namespace afemp::core
