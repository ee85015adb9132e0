// Private to afemp_core: a thin checked reader over toml++ tables, used by the scene parser.
// Every value read goes through it so that unknown keys, wrong types and out-of-range values
// all produce the same InputError: "FILE:LINE: key 'a.b.c': what is wrong and what is allowed".
#pragma once

#include <toml++/toml.h>

#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "afemp/errors.hpp"
#include "afemp/model_parameters.hpp"
#include "afemp/tensor.hpp"
#include "core/scene.hpp"

namespace afemp::core::scene_detail {

using core::Range;  // afemp/model_parameters.hpp

// Reads the keys of one TOML table. It remembers every key it was told about (known) and every
// key it read (consumed), so check_unknown() can reject a typo and list the keys that exist.
class TableReader {
 public:
  // prefix: the dotted path of this table ("" for the root), for messages.
  TableReader(const toml::table& table, std::string prefix, std::string file);

  const toml::table& table() const { return table_; }
  const std::string& prefix() const { return prefix_; }
  const std::string& file() const { return file_; }
  // Messages name the table by a new prefix from here on (a body, once its name is known).
  void set_prefix(std::string prefix) { prefix_ = std::move(prefix); }

  // Declares keys as allowed without reading them.
  void known(std::initializer_list<std::string_view> keys);
  void known(const std::vector<std::string>& keys);
  // Throws for the first (by line) key of the table that is not known, listing the known keys.
  // Call it before reading so that a typo in a required key is reported as the typo it is.
  void check_unknown() const;

  bool has(std::string_view key) const;
  // "prefix.key".
  std::string dotted(std::string_view key) const;
  // The line of the key's value when present, else the table's own line.
  SourceLocation where(std::string_view key) const;
  SourceLocation where() const;
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

  double required_number(std::string_view key, const Range& range);
  double number(std::string_view key, double fallback, const Range& range);
  std::optional<double> optional_number(std::string_view key, const Range& range);
  long integer(std::string_view key, long fallback, long lo, long hi);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, const std::string& fallback);
  std::string required_string(std::string_view key);
  std::optional<Vec3> optional_vec3(std::string_view key);
  Vec3 required_vec3(std::string_view key);
  Vec3 vec3(std::string_view key, const Vec3& fallback);
  // An array of strings (a single string is taken as a list of one); empty when absent.
  std::vector<std::string> strings(std::string_view key);
  // A number or an array of numbers, each within `range` (a single number is a list of one);
  // empty when absent.
  std::vector<double> numbers(std::string_view key, const Range& range);
  // An array of [a, b] pairs of finite numbers, at least one; empty when absent.
  std::vector<std::array<double, 2>> pairs(std::string_view key);
  // An array of exactly three integers in [lo, hi].
  std::array<int, 3> integers3(std::string_view key, int lo, int hi);
  // One of `allowed` (the canonical spellings); returns the index into `allowed`.
  std::size_t choice(std::string_view key, std::initializer_list<std::string_view> allowed,
                     const std::optional<std::size_t>& fallback, bool ignore_case = false);
  std::size_t choice(std::string_view key, std::span<const std::string_view> allowed,
                     const std::optional<std::size_t>& fallback, bool ignore_case = false);
  // A sub-table (inline or not); nullptr when absent.
  const toml::table* optional_table(std::string_view key);
  const toml::table& required_table(std::string_view key);

 private:
  const toml::node* lookup(std::string_view key);  // marks known, nullptr when absent
  [[noreturn]] void type_error(std::string_view key, const toml::node& node,
                               std::string_view expected) const;
  Vec3 as_vec3(std::string_view key, const toml::node& node) const;

  const toml::table& table_;
  std::string prefix_;
  std::string file_;
  std::vector<std::string> known_;  // in the order the parser asked, for "allowed keys" lists
};

// "a string", "an integer", ... for type errors.
std::string describe_type(const toml::node& node);
// "a, b, c" and "\"a\", \"b\"".
std::string join(const std::vector<std::string>& items, bool quoted);
// The scene-file names of the built-in strength models (the parser's table), which a user
// strength model may not take.
std::vector<std::string_view> builtin_strength_models();
std::string format_number(double v);

// An explosive body needs something to light it and detonations an explosive; explosives are
// particles or hexahedra that do not convert. For the parser and the check of a scene built in
// code alike.
void check_explosives(const Scene& scene);

// Builds and checks a Scene from a parsed document.
Scene scene_from_toml(const toml::table& root, const std::string& path);

}  // namespace afemp::core::scene_detail
