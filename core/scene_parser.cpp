// The scene parser: turns a parsed TOML document into a checked Scene (docs/scene-format.md).
// Each section is read through a TableReader, so that every key is type-, range- and
// spelling-checked and every error names the file, the line and the full dotted key.
#include "core/scene_parser.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <utility>

#include "core/axisymmetric_refusals.hpp"
#include "core/far_field_refusals.hpp"
#include "core/materials/initial_pressure.hpp"
#include "core/materials/model_parameters.hpp"
#include "core/mixed_pressure_refusals.hpp"
#include "core/phases.hpp"
#include "core/reproducible_refusals.hpp"
#include "core/scene_ranges.hpp"
#include "core/shape_function_refusals.hpp"
#include "core/total_lagrangian_refusals.hpp"

namespace afemp::core::scene_detail {

// ---------------------------------------------------------------------------------------------
// Small helpers

std::string format_number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string join(const std::vector<std::string>& items, bool quoted) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) s += ", ";
    s += quoted ? "\"" + items[i] + "\"" : items[i];
  }
  return s;
}

std::string describe_type(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

int line_of(const toml::source_region& r) {
  return static_cast<int>(r.begin.line);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// TableReader

TableReader::TableReader(const toml::table& table, std::string prefix, std::string file)
    : table_(table), prefix_(std::move(prefix)), file_(std::move(file)) {}

void TableReader::known(std::initializer_list<std::string_view> keys) {
  for (std::string_view k : keys)
    if (std::find(known_.begin(), known_.end(), k) == known_.end()) known_.emplace_back(k);
}

void TableReader::known(const std::vector<std::string>& keys) {
  for (const std::string& k : keys)
    if (std::find(known_.begin(), known_.end(), k) == known_.end()) known_.emplace_back(k);
}

void TableReader::check_unknown() const {
  // toml++ iterates keys alphabetically; report the first unknown key in file order instead,
  // which is the one a user reading the file top-down expects.
  const toml::key* first = nullptr;
  for (auto&& [k, v] : table_) {
    (void)v;
    if (std::find(known_.begin(), known_.end(), k.str()) != known_.end()) continue;
    if (!first || k.source().begin.line < first->source().begin.line) first = &k;
  }
  if (!first) return;
  const int line = first->source().begin.line > 0 ? line_of(first->source()) : where().line;
  throw InputError(SourceLocation{file_, line}, dotted(first->str()),
                   "unknown key; allowed keys here: " + join(known_, false));
}

bool TableReader::has(std::string_view key) const {
  return table_.get(key) != nullptr;
}

std::string TableReader::dotted(std::string_view key) const {
  return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
}

SourceLocation TableReader::where() const {
  return {file_, line_of(table_.source())};
}

SourceLocation TableReader::where(std::string_view key) const {
  if (const toml::node* n = table_.get(key); n && n->source().begin.line > 0)
    return {file_, line_of(n->source())};
  return where();
}

void TableReader::fail(std::string_view key, const std::string& message) const {
  throw InputError(where(key), dotted(key), message);
}

void TableReader::type_error(std::string_view key, const toml::node& node,
                             std::string_view expected) const {
  fail(key, "expected " + std::string(expected) + ", got " + describe_type(node));
}

const toml::node* TableReader::lookup(std::string_view key) {
  known({key});
  return table_.get(key);
}

std::optional<double> TableReader::optional_number(std::string_view key, const Range& range) {
  const toml::node* n = lookup(key);
  if (!n) return std::nullopt;
  double v = 0.0;
  if (const auto* i = n->as_integer())
    v = static_cast<double>(i->get());
  else if (const auto* f = n->as_floating_point())
    v = f->get();
  else
    type_error(key, *n, "a number");
  if (!std::isfinite(v) || !range.contains(v))
    fail(key, "value " + format_number(v) + " is out of range; allowed: " + range.describe());
  return v;
}

double TableReader::required_number(std::string_view key, const Range& range) {
  const auto v = optional_number(key, range);
  if (!v) fail(key, "required key is missing (a number, " + range.describe() + ")");
  return *v;
}

double TableReader::number(std::string_view key, double fallback, const Range& range) {
  return optional_number(key, range).value_or(fallback);
}

long TableReader::integer(std::string_view key, long fallback, long lo, long hi) {
  const toml::node* n = lookup(key);
  if (!n) return fallback;
  const auto* i = n->as_integer();
  if (!i) type_error(key, *n, "an integer");
  const std::int64_t v = i->get();
  if (v < lo || v > hi) {
    std::string allowed = hi == std::numeric_limits<long>::max()
                              ? "value >= " + std::to_string(lo)
                              : std::to_string(lo) + " <= value <= " + std::to_string(hi);
    fail(key, "value " + std::to_string(v) + " is out of range; allowed: " + allowed);
  }
  return static_cast<long>(v);
}

bool TableReader::boolean(std::string_view key, bool fallback) {
  const toml::node* n = lookup(key);
  if (!n) return fallback;
  const auto* b = n->as_boolean();
  if (!b) type_error(key, *n, "a boolean (true or false)");
  return b->get();
}

std::string TableReader::string(std::string_view key, const std::string& fallback) {
  const toml::node* n = lookup(key);
  if (!n) return fallback;
  const auto* s = n->as_string();
  if (!s) type_error(key, *n, "a string");
  return s->get();
}

std::string TableReader::required_string(std::string_view key) {
  if (!has(key)) {
    known({key});
    fail(key, "required key is missing (a string)");
  }
  return string(key, "");
}

std::vector<std::string> TableReader::strings(std::string_view key) {
  const toml::node* n = lookup(key);
  if (!n) return {};
  if (const auto* s = n->as_string()) return {s->get()};
  const auto* a = n->as_array();
  if (!a) type_error(key, *n, "an array of strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto* s = a->get(i)->as_string();
    if (!s)
      fail(key, "expected an array of strings; element " + std::to_string(i) + " is " +
                    describe_type(*a->get(i)));
    out.push_back(s->get());
  }
  return out;
}

std::vector<double> TableReader::numbers(std::string_view key, const Range& range) {
  const toml::node* n = lookup(key);
  if (!n) return {};
  if (!n->as_array()) return {required_number(key, range)};
  const auto* a = n->as_array();
  if (a->empty()) fail(key, "expected a number or a non-empty array of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    double v = 0.0;
    if (const auto* ii = e.as_integer())
      v = static_cast<double>(ii->get());
    else if (const auto* f = e.as_floating_point())
      v = f->get();
    else
      fail(key, "expected an array of numbers; element " + std::to_string(i) + " is " +
                    describe_type(e));
    if (!std::isfinite(v) || !range.contains(v))
      fail(key, "element " + std::to_string(i) + ", " + format_number(v) +
                    ", is out of range; allowed: " + range.describe());
    out.push_back(v);
  }
  return out;
}

std::vector<std::array<double, 2>> TableReader::pairs(std::string_view key) {
  const toml::node* n = lookup(key);
  std::vector<std::array<double, 2>> out;
  if (!n) return out;
  const auto* a = n->as_array();
  if (!a || a->empty()) fail(key, "expected a non-empty array of [a, b] pairs of numbers");
  auto number = [](const toml::node* e, double& v) {
    if (const auto* ii = e ? e->as_integer() : nullptr)
      v = static_cast<double>(ii->get());
    else if (const auto* f = e ? e->as_floating_point() : nullptr)
      v = f->get();
    else
      return false;
    return std::isfinite(v);
  };
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto* pair = a->get(i)->as_array();
    std::array<double, 2> p{};
    if (!pair || pair->size() != 2 || !number(pair->get(0), p[0]) || !number(pair->get(1), p[1]))
      fail(key, "element " + std::to_string(i) + ": expected a pair [a, b] of finite numbers");
    out.push_back(p);
  }
  return out;
}

std::array<int, 3> TableReader::integers3(std::string_view key, int lo, int hi) {
  const toml::node* n = lookup(key);
  std::array<int, 3> out{0, 0, 0};
  if (!n) return out;
  const auto* a = n->as_array();
  if (!a || a->size() != 3) fail(key, "expected an array of 3 integers");
  for (std::size_t i = 0; i < 3; ++i) {
    const auto* v = a->get(i)->as_integer();
    if (!v || v->get() < lo || v->get() > hi)
      fail(key, "element " + std::to_string(i) + " must be an integer in " + std::to_string(lo) +
                    ".." + std::to_string(hi));
    out[i] = static_cast<int>(v->get());
  }
  return out;
}

Vec3 TableReader::as_vec3(std::string_view key, const toml::node& node) const {
  const auto* a = node.as_array();
  if (!a) type_error(key, node, "an array of 3 numbers");
  if (a->size() != 3)
    fail(key, "expected an array of 3 numbers, got an array of " + std::to_string(a->size()));
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    const toml::node& e = *a->get(static_cast<std::size_t>(i));
    if (const auto* ii = e.as_integer())
      v[i] = static_cast<double>(ii->get());
    else if (const auto* f = e.as_floating_point())
      v[i] = f->get();
    else
      fail(key, "expected an array of 3 numbers; element " + std::to_string(i) + " is " +
                    describe_type(e));
    if (!std::isfinite(v[i])) fail(key, "element " + std::to_string(i) + " is not a finite number");
  }
  return v;
}

std::optional<Vec3> TableReader::optional_vec3(std::string_view key) {
  const toml::node* n = lookup(key);
  if (!n) return std::nullopt;
  return as_vec3(key, *n);
}

Vec3 TableReader::required_vec3(std::string_view key) {
  const auto v = optional_vec3(key);
  if (!v) fail(key, "required key is missing (an array of 3 numbers)");
  return *v;
}

Vec3 TableReader::vec3(std::string_view key, const Vec3& fallback) {
  return optional_vec3(key).value_or(fallback);
}

std::size_t TableReader::choice(std::string_view key,
                                std::initializer_list<std::string_view> allowed,
                                const std::optional<std::size_t>& fallback, bool ignore_case) {
  return choice(key, std::span<const std::string_view>(allowed.begin(), allowed.size()), fallback,
                ignore_case);
}

std::size_t TableReader::choice(std::string_view key, std::span<const std::string_view> allowed,
                                const std::optional<std::size_t>& fallback, bool ignore_case) {
  std::vector<std::string> names(allowed.begin(), allowed.end());
  const toml::node* n = lookup(key);
  if (!n) {
    if (!fallback) fail(key, "required key is missing; allowed values: " + join(names, true));
    return *fallback;
  }
  const auto* s = n->as_string();
  if (!s)
    fail(key,
         "expected a string, got " + describe_type(*n) + "; allowed values: " + join(names, true));
  const std::string& value = s->get();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (ignore_case ? lower(value) == lower(names[i]) : value == names[i]) return i;
  fail(key, "unknown value \"" + value + "\"; allowed values: " + join(names, true) +
                (ignore_case ? " (case-insensitive)" : ""));
}

const toml::table* TableReader::optional_table(std::string_view key) {
  const toml::node* n = lookup(key);
  if (!n) return nullptr;
  const auto* t = n->as_table();
  if (!t) type_error(key, *n, "a table");
  return t;
}

const toml::table& TableReader::required_table(std::string_view key) {
  const toml::table* t = optional_table(key);
  if (!t) fail(key, "required table is missing");
  return *t;
}

// ---------------------------------------------------------------------------------------------
// Sections

namespace {

void read_run(TableReader& r, RunSettings& run) {
  r.known({"title",
           "end_time",
           "time_step_factor",
           "element_time_step_factor",
           "time_step",
           "max_steps",
           "output_every",
           "history_every",
           "energy_error_limit",
           "output_strain",
           "gravity",
           "terminate",
           "units",
           "quiet",
           "history_interval",
           "output_times",
           "checkpoint_every",
           "checkpoint_wall_every",
           "checkpoint_keep",
           "reproducible",
           "untranslated"});
  r.check_unknown();
  namespace range = scene_ranges::run;
  run.title = r.string("title", run.title);
  run.end_time = r.required_number("end_time", range::end_time);
  run.time_step_factor =
      r.number("time_step_factor", run.time_step_factor, range::time_step_factor);
  run.element_time_step_factor = r.number("element_time_step_factor", run.element_time_step_factor,
                                          range::element_time_step_factor);
  run.fixed_time_step = r.number("time_step", run.fixed_time_step, range::time_step);
  run.max_steps = r.integer("max_steps", run.max_steps, range::max_steps.lo, range::max_steps.hi);
  run.output_every = r.number("output_every", run.output_every, range::output_every);
  run.history_every = r.integer("history_every", run.history_every, range::history_every.lo,
                                range::history_every.hi);
  run.history_interval =
      r.number("history_interval", run.history_interval, range::history_interval);
  if (r.has("history_interval") && r.has("history_every"))
    r.fail("history_interval",
           "give history_every (steps) or history_interval (simulated "
           "time) between history rows, not both");
  if (r.has("output_times")) {
    run.output_times = r.numbers("output_times", range::output_times);
    for (std::size_t k = 0; k < run.output_times.size(); ++k) {
      if (k > 0 && !(run.output_times[k] > run.output_times[k - 1]))
        r.fail("output_times", "the times must increase; " + format_number(run.output_times[k]) +
                                   " follows " + format_number(run.output_times[k - 1]));
      if (run.output_times[k] > run.end_time)
        r.fail("output_times", "time " + format_number(run.output_times[k]) +
                                   " lies beyond end_time = " + format_number(run.end_time) +
                                   " (the final state is always written)");
    }
  }
  run.energy_error_limit =
      r.number("energy_error_limit", run.energy_error_limit, range::energy_error_limit);
  run.output_strain = r.boolean("output_strain", run.output_strain);
  run.gravity = r.vec3("gravity", run.gravity);
  if (r.has("units"))
    run.units = std::string(scene_ranges::kUnitSystems[r.choice(
        "units", std::span<const std::string_view>(scene_ranges::kUnitSystems), std::nullopt)]);
  if (r.has("quiet")) run.quiet = r.strings("quiet");
  if (r.has("untranslated")) {
    run.untranslated = r.strings("untranslated");
    run.untranslated_where = r.where("untranslated");
  }
  run.checkpoint_every =
      r.number("checkpoint_every", run.checkpoint_every, range::checkpoint_every);
  run.checkpoint_wall_every =
      r.number("checkpoint_wall_every", run.checkpoint_wall_every, range::checkpoint_wall_every);
  run.checkpoint_keep =
      static_cast<int>(r.integer("checkpoint_keep", run.checkpoint_keep, range::checkpoint_keep.lo,
                                 range::checkpoint_keep.hi));
  run.reproducible = r.boolean("reproducible", run.reproducible);
  run.reproducible_where = r.where("reproducible");
}

void read_grid(TableReader& r, GridSettings& grid) {
  r.known({"cell", "min", "max", "boundary", "far_field", "axisymmetric"});
  r.check_unknown();
  grid.cell = r.required_number("cell", scene_ranges::grid::cell);
  grid.min = r.required_vec3("min");
  grid.max = r.required_vec3("max");
  grid.axisymmetric = r.boolean("axisymmetric", false);
  if (grid.axisymmetric) {
    // The r-z plane: x the radius from the axis, no extent across it (the hoop direction).
    if (grid.min.y != 0.0 || grid.max.y != 0.0)
      r.fail("min",
             "an axisymmetric grid lies in the r-z plane y = 0: give min and max as "
             "[r, 0, z] (their y components " +
                 format_number(grid.min.y) + " and " + format_number(grid.max.y) + " must be 0)");
    if (grid.min.x != 0.0)
      r.fail("min",
             "an axisymmetric grid starts at the axis: min's x component (the radius) "
             "must be 0, not " +
                 format_number(grid.min.x));
    grid.faces[static_cast<std::size_t>(Face::xmin)] = FaceCondition::symmetric;
  }
  for (int a = 0; a < 3; ++a)
    if (!(grid.max[a] > grid.min[a]) && !(grid.axisymmetric && a == 1))
      r.fail("max", "max must exceed min in every component; component " + std::to_string(a) +
                        ": max " + format_number(grid.max[a]) + " <= min " +
                        format_number(grid.min[a]));
  if (const toml::table* b = r.optional_table("boundary")) {
    TableReader br(*b, r.dotted("boundary"), r.file());
    static constexpr std::string_view face_names[6] = {"xmin", "xmax", "ymin",
                                                       "ymax", "zmin", "zmax"};
    br.known({"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"});
    br.check_unknown();
    for (int f = 0; f < 6; ++f)
      grid.faces[static_cast<std::size_t>(f)] = static_cast<FaceCondition>(
          br.choice(face_names[f], {"free", "fixed", "symmetric", "wall", "outflow", "absorbing"},
                    static_cast<std::size_t>(grid.faces[static_cast<std::size_t>(f)])));
    if (grid.axisymmetric) {
      for (std::string_view hoop : {"ymin", "ymax"})
        if (br.has(hoop))
          br.fail(hoop,
                  "an axisymmetric grid has no faces across the r-z plane (y is the hoop "
                  "direction); remove it");
      if (grid.faces[static_cast<std::size_t>(Face::xmin)] != FaceCondition::symmetric)
        br.fail("xmin",
                "the x = 0 face of an axisymmetric grid is the axis: it must be "
                "\"symmetric\" (the default there)");
    }
  }
  // One cell across the plane, the particles at its middle (mpm/axisymmetric.hpp).
  if (grid.axisymmetric) make_axisymmetric(grid);
  if (const toml::table* t = r.optional_table("far_field")) {
    TableReader fr(*t, r.dotted("far_field"), r.file());
    fr.known({"centre", "pressure", "stress"});
    fr.check_unknown();
    FarField far;
    far.centre = fr.required_vec3("centre");
    far.pressure = fr.number("pressure", far.pressure, scene_ranges::grid::far_field_pressure);
    far.absolute_stress =
        fr.choice("stress", {"gauge", "absolute"}, far.absolute_stress ? 1 : 0) == 1;
    if (!grid.has_face(FaceCondition::absorbing))
      r.fail("far_field",
             "the far field acts through absorbing faces, and no face of "
             "boundary is \"absorbing\"; set boundary = { xmax = \"absorbing\", "
             "... } on the faces that open onto the fluid");
    grid.far_field = far;
  }
}

void read_mpm(TableReader& r, MpmSettings& mpm) {
  r.known({"scheme", "shape_function", "transfer", "flip", "jaumann", "formulation", "pressure",
           "splitting"});
  r.check_unknown();
  mpm.scheme = static_cast<UpdateScheme>(r.choice("scheme", {"USF", "USL", "MUSL", "USAVG"},
                                                  static_cast<std::size_t>(mpm.scheme), true));
  mpm.shape = static_cast<ShapeFunction>(
      r.choice("shape_function", {"linear", "gimp", "bspline2", "bspline3", "cpdi1", "cpdi2"},
               static_cast<std::size_t>(mpm.shape)));
  mpm.transfer = static_cast<Transfer>(
      r.choice("transfer", {"flip", "apic"}, static_cast<std::size_t>(mpm.transfer)));
  mpm.flip = r.number("flip", mpm.flip, scene_ranges::mpm::flip);
  if (mpm.transfer == Transfer::apic) {
    if (const std::optional<std::string> why = apic_shape_refusal(mpm.shape, mpm.transfer))
      r.fail("transfer", *why);
    if (r.has("flip"))
      r.fail("flip",
             "the PIC/FLIP blend applies to transfer = \"flip\" only; remove it or set "
             "transfer = \"flip\"");
  }
  if (const std::optional<std::string> why = absolute_stress_shape_refusal(mpm.grid, mpm.shape))
    r.fail("shape_function", *why);
  if (const std::optional<std::string> why = spline_grid_refusal(mpm.grid, mpm.shape))
    r.fail("shape_function", *why);
  if (const std::optional<std::string> why = absorbing_face_shape_refusal(mpm.grid, mpm.shape))
    r.fail("shape_function", *why);
  mpm.jaumann = r.boolean("jaumann", mpm.jaumann);
  mpm.formulation =
      static_cast<Formulation>(r.choice("formulation", {"updated-lagrangian", "total-lagrangian"},
                                        static_cast<std::size_t>(mpm.formulation)));
  mpm.pressure = static_cast<PressureField>(
      r.choice("pressure", {"standard", "mixed"}, static_cast<std::size_t>(mpm.pressure)));
  if (const toml::table* t = r.optional_table("splitting")) {
    if (const std::optional<std::string> why = cpdi_splitting_refusal(mpm.shape))
      r.fail("splitting", *why);
    TableReader sr(*t, r.dotted("splitting"), r.file());
    sr.known({"alpha", "max_particles", "bodies", "axes"});  // bodies: resolved once read
    sr.check_unknown();
    SplittingSettings s;
    s.alpha = sr.number("alpha", s.alpha, scene_ranges::mpm::split_alpha);
    s.max_particles = static_cast<std::size_t>(sr.integer(
        "max_particles", static_cast<long>(s.max_particles),
        scene_ranges::mpm::split_max_particles.lo, scene_ranges::mpm::split_max_particles.hi));
    if (sr.has("axes")) {
      s.axes = {false, false, false};
      for (const std::string& axis : sr.strings("axes")) {
        if (axis != "x" && axis != "y" && axis != "z")
          sr.fail("axes", "unknown axis \"" + axis + "\"; allowed: \"x\", \"y\", \"z\"");
        s.axes[static_cast<std::size_t>(axis[0] - 'x')] = true;
      }
      if (!s.axes[0] && !s.axes[1] && !s.axes[2])
        sr.fail("axes",
                "name at least one axis (\"x\", \"y\", \"z\"), or leave the key out "
                "to split along all three");
    }
    mpm.splitting = s;
  }
  if (const auto why = total_lagrangian_mpm_refusal(mpm)) r.fail(why->first, why->second);
  if (const auto why = mixed_pressure_mpm_refusal(mpm)) r.fail(why->first, why->second);
}

// A strength model with a pressure law of its own (Holmquist-Johnson-Cook concrete) goes with
// that law, and no other model takes it; the material's elastic constants then come from G and
// the law's bulk modulus. Drucker-Prager's own law is the linear elastic one: it takes no eos.
void pair_own_pressure_law(TableReader& r, Material& m, std::optional<double> shear_modulus) {
  std::string needs, needs_keys, law_of;
  double k = 0.0;
  std::visit(
      [&](const auto& s, const auto& e) {
        using S = std::decay_t<decltype(s)>;
        using E = std::decay_t<decltype(e)>;
        if constexpr (HasOwnPressureLaw<S>) {
          if constexpr (std::is_same_v<typename S::PressureLaw, NoEos>) {
            if (!std::is_same_v<E, NoEos>)
              r.fail("eos", "strength model \"" + std::string(S::name) +
                                "\" takes no eos: its pressure is linear elastic, K = E / (3 "
                                "(1 - 2 nu)); remove eos");
          } else {
            needs = S::PressureLaw::name;
            for (const std::string& key : parameter_keys<typename S::PressureLaw>({}))
              needs_keys += ", " + key;
          }
        }
        if constexpr (IsOwnPressureLaw<E>) {
          law_of = E::strength_model;
          k = e.elastic_modulus();
        }
      },
      m.strength, m.eos);
  const std::string strength(model_name(m.strength)), eos(model_name(m.eos));
  if (!needs.empty() && eos != needs)
    r.fail(r.has("eos") ? "eos" : "strength", "strength model \"" + strength +
                                                  "\" needs eos = { model = \"" + needs + "\"" +
                                                  needs_keys + " }");
  if (!law_of.empty() && strength != law_of)
    r.fail("eos", "eos model \"" + eos + "\" is the pressure law of strength model \"" + law_of +
                      "\" and goes with it only");
  if (law_of.empty()) {
    if (shear_modulus)
      r.fail("G",
             "G is for a strength model with a pressure law of its own (eos hjc-compaction), "
             "whose bulk modulus it completes; give E and nu");
    return;
  }
  if (!shear_modulus)
    r.fail("eos", "eos model \"" + eos +
                      "\" sets the bulk modulus; give the material's shear "
                      "modulus G instead of E and nu");
  if (r.has("E") || r.has("nu"))
    r.fail(r.has("E") ? "E" : "nu", "give G only: eos " + eos + " sets the bulk modulus");
  if (!(3.0 * k >= 2.0 * *shear_modulus))
    r.fail("G", "value " + format_number(*shear_modulus) + " needs the bulk modulus of eos " + eos +
                    ", " + format_number(k) + ", >= 2 G / 3 (Poisson's ratio >= 0)");
  m.set_shear_and_bulk_modulus(*shear_modulus, k);
}

// Reads a model's parameters (Model::parameters, in the model's own file) from its table:
// every key it names is allowed, each value range-checked with the file, line and key.
class SceneParameters final : public ParameterVisitor {
 public:
  SceneParameters(TableReader& r, const MaterialConstants& material) : r_(r), material_(material) {}
  void required(std::string_view key, double& value, const Range& range) override {
    value = r_.required_number(key, range);
  }
  void optional(std::string_view key, double& value, double fallback, const Range& range) override {
    value = r_.number(key, fallback, range);
  }
  void choice(std::string_view key, std::size_t& value, std::span<const std::string_view> allowed,
              std::optional<std::size_t> fallback) override {
    value = r_.choice(key, allowed, fallback);
  }
  void require(bool ok, std::string_view key, const std::string& message) override {
    if (!ok) r_.fail(key, message);
  }
  bool has(std::string_view key) const override { return r_.has(key); }
  bool reading() const override { return true; }
  const MaterialConstants& material() const override { return material_; }

 private:
  TableReader& r_;
  const MaterialConstants& material_;
};

// The model of Variant the scene names `name` (one of model_names<Variant>()), read from r.
template <class Variant>
Variant read_named_model(TableReader& r, std::string_view name, const MaterialConstants& material) {
  std::optional<Variant> result;
  for_each_alternative<Variant>([&]<class Model>(std::size_t) {
    if constexpr (requires { Model::name; }) {
      if (result || Model::name != name) return;
      r.known(parameter_keys<Model>(material));
      r.check_unknown();
      Model model{};
      SceneParameters v(r, material);
      visit_parameters(model, v);
      result = model;
    }
  });
  return *result;
}

// A model chosen by `model = "NAME"` among the named alternatives of Variant.
template <class Variant>
Variant read_model(TableReader& r, const MaterialConstants& material) {
  r.known({"model"});
  static const std::vector<std::string_view> names = model_names<Variant>();
  return read_named_model<Variant>(r, names[r.choice("model", names, std::nullopt)], material);
}

// A registered user strength model (afemp/user_material.hpp): its parameters by name, every
// one required.
StrengthModel read_user_strength(TableReader& r, const std::string& name) {
  UserStrength u;
  u.definition = find_strength_model(name);
  r.known(u.definition->parameters);
  r.check_unknown();
  for (const std::string& key : u.definition->parameters)
    u.parameters.push_back(r.required_number(key, Range::any()));
  return u;
}

StrengthModel read_strength(TableReader& r, const MaterialConstants& material) {
  r.known({"model"});
  // The built-in models, then the user models registered by the program reading the scene.
  const std::vector<std::string> user = registered_strength_models();
  std::vector<std::string_view> names = model_names<StrengthModel>();
  const std::size_t builtin = names.size();
  for (const std::string& name : user) names.push_back(name);
  const std::size_t i = r.choice("model", names, std::nullopt);
  if (i < builtin) return read_named_model<StrengthModel>(r, names[i], material);
  return read_user_strength(r, user[i - builtin]);
}

Material read_material(TableReader& r, const std::string& name) {
  r.known({"density", "E", "nu", "G", "strength", "eos", "specific_heat", "taylor_quinney",
           "temperature", "failure_strain", "failure", "burn", "pressure_cutoff"});
  r.check_unknown();
  Material m;
  m.name = name;
  namespace range = scene_ranges::material;
  m.density = r.required_number("density", range::density);
  // A material with the HJC compaction law gives G; PC / muc is its bulk modulus.
  const std::optional<double> shear_modulus = r.optional_number("G", range::shear_modulus);
  // A fluid (strength model "fluid") may leave out E and nu: it has no shear.
  bool fluid = false;
  if (const toml::table* t = r.optional_table("strength"))
    if (const auto* model = t->get_as<std::string>("model")) fluid = model->get() == "fluid";
  if (!shear_modulus && !(fluid && !r.has("E") && !r.has("nu"))) {
    m.youngs_modulus = r.required_number("E", range::youngs_modulus);
    m.poisson_ratio = r.required_number("nu", range::poisson_ratio);
  }
  const MaterialConstants constants{m.density, m.youngs_modulus, m.bulk_modulus()};
  if (const toml::table* t = r.optional_table("strength")) {
    TableReader sr(*t, r.dotted("strength"), r.file());
    m.strength = read_strength(sr, constants);
  }
  if (const toml::table* t = r.optional_table("eos")) {
    TableReader er(*t, r.dotted("eos"), r.file());
    m.eos = read_model<EquationOfState>(er, constants);
  }
  pair_own_pressure_law(r, m, shear_modulus);
  m.thermal.specific_heat =
      r.number("specific_heat", m.thermal.specific_heat, range::specific_heat);
  m.thermal.taylor_quinney =
      r.number("taylor_quinney", m.thermal.taylor_quinney, range::taylor_quinney);
  m.thermal.initial_temperature =
      r.number("temperature", m.thermal.initial_temperature, range::temperature);
  m.failure_strain = r.number("failure_strain", m.failure_strain, range::failure_strain);
  if (const toml::table* t = r.optional_table("failure")) {
    if (m.failure_strain > 0.0)
      r.fail("failure_strain",
             "give failure_strain or failure, not both (failure_strain is "
             "failure = { model = \"plastic-strain\", strain = ... })");
    TableReader fr(*t, r.dotted("failure"), r.file());
    m.failure = read_model<FailureModel>(fr, constants);
  } else if (m.failure_strain > 0.0) {
    m.failure = PlasticStrainFailure{m.failure_strain};
  }
  if (r.has("pressure_cutoff")) {
    m.pressure_cutoff = r.required_number("pressure_cutoff", range::pressure_cutoff);
    if (const std::optional<std::string> why = pressure_cutoff_refusal(m))
      r.fail("pressure_cutoff", *why);
  }
  if (const toml::table* t = r.optional_table("burn")) {
    TableReader br(*t, r.dotted("burn"), r.file());
    br.known({"D", "pcj", "mode"});
    br.check_unknown();
    ProgrammedBurn b;
    b.detonation_velocity = br.required_number("D", range::detonation_velocity);
    b.cj_pressure = br.required_number("pcj", range::cj_pressure);
    if (br.has("mode")) {  // without it, both terms (ProgrammedBurn's default)
      const std::size_t mode = br.choice(
          "mode", {"lighting-time+volumetric", "lighting-time", "volumetric"}, std::nullopt);
      b.lighting_time = mode != 2;
      b.volumetric = mode != 1;
    }
    if (!std::holds_alternative<Jwl>(m.eos))
      r.fail("burn",
             "a burn (high explosive) needs eos = { model = \"jwl\", ... }: the burn "
             "fraction scales the detonation products' pressure");
    m.burn = b;
  }
  try {
    m.validate();
  } catch (const std::invalid_argument& e) {
    throw InputError(r.where(), r.prefix(), e.what());
  }
  return m;
}

std::string relative_to_scene(const std::string& file, const std::string& scene_path) {
  // Relative to the scene file, so that a scene directory can be moved as a whole.
  std::filesystem::path p(file);
  if (p.is_relative()) p = std::filesystem::path(scene_path).parent_path() / p;
  return p.lexically_normal().string();
}

// The shapes each discretisation accepts.
std::vector<std::string> shapes_for(Discretisation d) {
  switch (d) {
    case Discretisation::particles:
      return {"box", "cylinder", "cone", "sphere", "points"};
    case Discretisation::hexahedra:
      return {"box", "cylinder", "sphere", "mesh"};
    case Discretisation::trusses:
      return {"line", "rebar", "mesh"};
  }
  return {};
}

// [bodies.shape.box]: min and max corners.
BoxShape read_box(TableReader& s) {
  s.known({"min", "max"});
  s.check_unknown();
  BoxShape box{s.required_vec3("min"), s.required_vec3("max")};
  for (int a = 0; a < 3; ++a)
    if (!(box.max[a] > box.min[a]))
      s.fail("max", "max must exceed min in every component (component " + std::to_string(a) + ")");
  return box;
}

// [bodies.shape.cylinder]: base, axis, radius, length and an optional ogive nose.
CylinderShape read_cylinder(TableReader& s, Discretisation d) {
  s.known({"base", "axis", "radius", "length", "nose"});
  s.check_unknown();
  CylinderShape c;
  c.base = s.required_vec3("base");
  const Vec3 axis = s.vec3("axis", c.axis);
  const double len = norm(axis);
  if (!(len > 0.0)) s.fail("axis", "the axis must be a non-zero vector");
  c.axis = (1.0 / len) * axis;
  c.radius = s.required_number("radius", scene_ranges::shape::radius);
  c.length = s.required_number("length", scene_ranges::shape::length);
  if (const toml::table* t = s.optional_table("nose")) {
    TableReader n(*t, s.dotted("nose"), s.file());
    n.known({"crh", "meplat"});
    n.check_unknown();
    c.nose.crh = n.required_number("crh", scene_ranges::shape::nose_crh);
    c.nose.meplat = n.number("meplat", c.nose.meplat, scene_ranges::shape::nose_meplat);
    if (!(c.nose.meplat < 2.0 * c.radius))
      n.fail("meplat", "the flat tip's diameter must be less than the cylinder's, " +
                           format_number(2.0 * c.radius));
    if (d == Discretisation::hexahedra && !(c.nose.meplat > 0.0))
      n.fail("meplat",
             "a nose meshed with hexahedra needs a flat tip (meplat > 0): the "
             "elements at a sharp tip would have no width");
    const double nose = ogive_nose_length(c.nose, c.radius);
    if (!(nose < c.length))
      n.fail("crh", "the nose (" + format_number(nose) +
                        " long) must be shorter than the "
                        "cylinder's length, " +
                        format_number(c.length));
  }
  return c;
}

// [bodies.shape.cone]: a cylinder with a top radius, solid or with a wall.
CylinderShape read_cone(TableReader& s) {
  s.known({"base", "axis", "radius", "top_radius", "length", "wall"});
  s.check_unknown();
  CylinderShape c;
  c.base = s.required_vec3("base");
  const Vec3 axis = s.vec3("axis", c.axis);
  if (!(norm(axis) > 0.0)) s.fail("axis", "the axis must be a non-zero vector");
  c.axis = (1.0 / norm(axis)) * axis;
  c.radius = s.required_number("radius", scene_ranges::shape::cone_radius);
  c.top_radius = s.required_number("top_radius", scene_ranges::shape::cone_radius);
  c.length = s.required_number("length", scene_ranges::shape::length);
  if (!(c.radius > 0.0 || c.top_radius > 0.0))
    s.fail("top_radius", "a cone needs a radius > 0 at one end at least");
  c.wall = s.number("wall", c.wall, scene_ranges::shape::cone_wall);
  return c;
}

// [bodies.shape.sphere]: centre and radius.
SphereShape read_sphere(TableReader& s) {
  s.known({"centre", "radius"});
  s.check_unknown();
  SphereShape sp;
  sp.centre = s.required_vec3("centre");
  sp.radius = s.required_number("radius", scene_ranges::shape::radius);
  return sp;
}

// [bodies.shape.mesh]: a mesh file, relative to the scene, its parts, scale and shift.
MeshFileShape read_mesh_file(TableReader& s, const std::string& scene_path) {
  s.known({"file", "parts", "scale", "translate"});
  s.check_unknown();
  MeshFileShape m;
  const std::string file = s.required_string("file");
  if (file.empty()) s.fail("file", "the mesh file name is empty");
  m.path = relative_to_scene(file, scene_path);
  m.parts = s.strings("parts");
  m.scale = s.number("scale", m.scale, scene_ranges::shape::mesh_scale);
  m.translate = s.vec3("translate", m.translate);
  return m;
}

// [bodies.shape.line]: a straight line from one point to another.
LineShape read_line(TableReader& s) {
  s.known({"from", "to"});
  s.check_unknown();
  LineShape l{s.required_vec3("from"), s.required_vec3("to")};
  if (!(norm(l.to - l.from) > 0.0)) s.fail("to", "the line has zero length");
  return l;
}

// [bodies.shape.rebar]: mats of bars in planes across a box, their spacing, diameter and
// cover.
RebarShape read_rebar(TableReader& s) {
  s.known({"min", "max", "normal", "position", "spacing", "diameter", "cover"});
  s.check_unknown();
  RebarShape m;
  m.min = s.required_vec3("min");
  m.max = s.required_vec3("max");
  for (int a = 0; a < 3; ++a)
    if (!(m.max[a] > m.min[a])) s.fail("max", "max must exceed min in every component");
  m.normal_axis = static_cast<int>(s.choice("normal", {"x", "y", "z"}, std::nullopt));
  if (!s.has("position"))
    s.fail("position",
           "required key is missing (a number, or an array of numbers: one mat per "
           "layer)");
  m.positions = s.numbers("position", Range::any());
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    if (m.positions[i] < m.min[m.normal_axis] || m.positions[i] > m.max[m.normal_axis])
      s.fail("position", "every mat's plane must lie between min and max along its normal (" +
                             format_number(m.positions[i]) + " does not)");
  m.spacing = s.required_number("spacing", scene_ranges::shape::rebar_spacing);
  m.diameter = s.required_number("diameter", scene_ranges::shape::rebar_diameter);
  m.cover = s.required_number("cover", scene_ranges::shape::rebar_cover);
  return m;
}

// [bodies.shape.points]: a file of points, relative to the scene.
PointListShape read_points(TableReader& s, const std::string& scene_path) {
  s.known({"file"});
  s.check_unknown();
  const std::string file = s.required_string("file");
  if (file.empty()) s.fail("file", "the points file name is empty");
  PointListShape points;
  points.path = relative_to_scene(file, scene_path);
  return points;
}

Shape read_shape(TableReader& r, const std::string& scene_path, Discretisation d) {
  r.known({"box", "cylinder", "cone", "sphere", "points", "mesh", "line", "rebar"});
  r.check_unknown();
  const std::vector<std::string> allowed = shapes_for(d);
  std::vector<std::string> given;
  for (std::string_view k :
       {"box", "cylinder", "cone", "sphere", "points", "mesh", "line", "rebar"})
    if (r.has(k)) given.emplace_back(k);
  if (given.size() != 1)
    throw InputError(r.where(), r.prefix(),
                     "give exactly one of " + join(allowed, false) + " (got " +
                         (given.empty() ? std::string("none") : join(given, false)) + ")");
  const std::string& kind = given.front();
  if (std::find(allowed.begin(), allowed.end(), kind) == allowed.end())
    throw InputError(r.where(kind), r.dotted(kind),
                     "a body of " + std::string(to_string(d)) + " takes one of " +
                         join(allowed, false) + ", not " + kind);
  TableReader s(r.required_table(kind), r.dotted(kind), r.file());
  if (kind == "box") return read_box(s);
  if (kind == "cylinder") return read_cylinder(s, d);
  if (kind == "cone") return read_cone(s);
  if (kind == "sphere") return read_sphere(s);
  if (kind == "mesh") return read_mesh_file(s, scene_path);
  if (kind == "line") return read_line(s);
  if (kind == "rebar") return read_rebar(s);
  return read_points(s, scene_path);
}

// A graded box axis: [end, elements] segments from lo to hi, the ends increasing and the last
// one hi, each segment divided into that many equal elements; empty when the key is absent.
std::vector<std::array<double, 2>> read_graded_axis(TableReader& r, const char* key, double lo,
                                                    double hi) {
  std::vector<std::array<double, 2>> segments = r.pairs(key);
  double start = lo;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const double end = segments[k][0], n = segments[k][1];
    const std::string which = "segment " + std::to_string(k) + " ([" + format_number(end) + ", " +
                              format_number(n) + "])";
    if (!(end > start))
      r.fail(key, which + ": its end must lie beyond " + format_number(start) +
                      "; allowed: [end, elements] pairs with ends increasing from the box's "
                      "min to its max");
    const scene_ranges::Count elements = scene_ranges::mesh::graded_elements;
    if (!(n >= static_cast<double>(elements.lo) && n <= static_cast<double>(elements.hi) &&
          n == std::floor(n)))
      r.fail(key, which + ": the element count must be a whole number in [" +
                      std::to_string(elements.lo) + ", " + std::to_string(elements.hi) + "]");
    start = end;
  }
  if (!segments.empty() && std::abs(start - hi) > 1e-9 * (hi - lo))
    r.fail(key, "the last segment ends at " + format_number(start) + ", not at the box's max " +
                    format_number(hi) + "; allowed: [end, elements] pairs ending at the max");
  return segments;
}

void read_mesh_density(TableReader& r, const BodySpec& b, MeshDensity& m) {
  const bool box = std::holds_alternative<BoxShape>(b.shape);
  const bool cylinder = std::holds_alternative<CylinderShape>(b.shape);
  const bool line = std::holds_alternative<LineShape>(b.shape);
  const bool rebar = std::holds_alternative<RebarShape>(b.shape);
  const bool sphere = std::holds_alternative<SphereShape>(b.shape);
  if (box) r.known({"size", "divisions", "x", "y", "z"});
  if (sphere) r.known({"size", "across", "sectors"});
  if (cylinder) r.known({"size", "core", "ring", "axial", "sectors"});
  if (line) r.known({"size", "segments"});
  if (rebar) r.known({"size"});
  r.check_unknown();
  namespace range = scene_ranges::mesh;
  m.size = r.number("size", m.size, range::size);
  if (box) {
    if (r.has("divisions"))
      m.divisions = r.integers3("divisions", static_cast<int>(range::divisions.lo),
                                static_cast<int>(range::divisions.hi));
    const BoxShape& shape = std::get<BoxShape>(b.shape);
    bool all_graded = true;
    for (std::size_t d = 0; d < 3; ++d) {
      const char* axis = d == 0 ? "x" : d == 1 ? "y" : "z";
      m.graded[d] = read_graded_axis(r, axis, shape.min[d], shape.max[d]);
      all_graded = all_graded && !m.graded[d].empty();
      if (!m.graded[d].empty() && m.divisions[0] > 0)
        r.fail(axis, "give divisions or graded axes (with size for the others), not both");
    }
    if (m.size == 0.0 && m.divisions[0] == 0 && !all_graded)
      r.fail("divisions",
             "give divisions = [nx, ny, nz], an element size, or x, y and z as [end, elements] "
             "segments");
  }
  if (cylinder) {
    m.core = static_cast<int>(r.integer("core", m.core, range::core.lo, range::core.hi));
    m.ring = static_cast<int>(r.integer("ring", m.ring, range::ring.lo, range::ring.hi));
    m.axial = static_cast<int>(r.integer("axial", m.axial, range::axial.lo, range::axial.hi));
    m.sectors =
        static_cast<int>(r.integer("sectors", m.sectors, range::sectors.lo, range::sectors.hi));
    if (m.sectors == 3) r.fail("sectors", "allowed values: 1 (quarter), 2 (half), 4 (full)");
    if (m.size == 0.0 && (m.core == 0 || m.ring == 0 || m.axial == 0))
      r.fail("core", "give core, ring and axial divisions, or an element size");
  }
  if (sphere) {
    // Elements across the diameter: core n/2 and two shells of n/4 (fem/mesh_generation.hpp).
    m.divisions[0] =
        static_cast<int>(r.integer("across", m.divisions[0], range::across.lo, range::across.hi));
    if (m.divisions[0] % 4 != 0)
      r.fail("across",
             "must be a multiple of 4 (a core of across/2 elements between two shells "
             "of across/4 layers)");
    m.sectors =
        static_cast<int>(r.integer("sectors", m.sectors, range::sectors.lo, range::sectors.hi));
    if (m.sectors == 3) r.fail("sectors", "allowed values: 1 (quarter), 2 (half), 4 (full)");
    if (m.size == 0.0 && m.divisions[0] == 0) r.fail("across", "give across or an element size");
  }
  if (line) {
    m.segments =
        static_cast<int>(r.integer("segments", m.segments, range::segments.lo, range::segments.hi));
    if (m.size == 0.0 && m.segments == 0)
      r.fail("segments", "give segments or a truss length size");
  }
  if (rebar && m.size == 0.0) r.fail("size", "give the truss length size of the bars");
}

// Keys that belong to the other discretisations are errors, not silently ignored: `key` of
// body b applies to bodies of d1 or d2 only.
void only_for(TableReader& r, const BodySpec& b, std::string_view key, Discretisation d1,
              Discretisation d2) {
  if (r.has(key) && b.discretisation != d1 && b.discretisation != d2)
    r.fail(key, "applies to bodies of " + std::string(to_string(d1)) +
                    (d1 != d2 ? " or " + std::string(to_string(d2)) : std::string()) + ", not to " +
                    to_string(b.discretisation));
}

// The keys of one discretisation that a body of another gives (only_for), read first.
void check_discretisation_keys(TableReader& r, const BodySpec& b) {
  using D = Discretisation;
  only_for(r, b, "particles_per_cell", D::particles, D::particles);
  only_for(r, b, "mesh", D::hexahedra, D::trusses);
  only_for(r, b, "element", D::hexahedra, D::hexahedra);
  only_for(r, b, "hourglass", D::hexahedra, D::hexahedra);
  only_for(r, b, "bulk_viscosity", D::hexahedra, D::particles);
  only_for(r, b, "erosion", D::hexahedra, D::trusses);
  only_for(r, b, "area", D::trusses, D::trusses);
  only_for(r, b, "prestress", D::trusses, D::trusses);
  only_for(r, b, "bonded_to", D::hexahedra, D::trusses);  // resolved once every body is read
  only_for(r, b, "outside", D::particles, D::particles);  // resolved once every body is read
  only_for(r, b, "conversion", D::hexahedra, D::hexahedra);
  only_for(r, b, "pressure", D::particles, D::particles);
  only_for(r, b, "initial_stress", D::particles, D::hexahedra);
}

// A body's initial_stress table: the geostatic state of soil at rest (whether the body can
// take it is checked once it is read, against [run] gravity).
GeostaticStress read_initial_stress(const toml::table& table, TableReader& r) {
  TableReader gr(table, r.dotted("initial_stress"), r.file());
  gr.known({"model", "K0", "surface"});
  gr.check_unknown();
  gr.choice("model", {"geostatic"}, std::nullopt);
  GeostaticStress g;
  g.surface = gr.required_number("surface", scene_ranges::body::geostatic_surface);
  g.k0 = gr.required_number("K0", scene_ranges::body::earth_pressure_at_rest);
  return g;
}

// A body's [hourglass] table: the form and its coefficient; left out, the coefficient is the
// form's default (HourglassSettings::default_coefficient).
HourglassSettings read_hourglass(const toml::table& table, TableReader& r) {
  HourglassSettings hourglass;
  TableReader hr(table, r.dotted("hourglass"), r.file());
  hr.known({"form", "coefficient"});
  hr.check_unknown();
  hourglass.form =
      static_cast<HourglassForm>(hr.choice("form", {"viscous", "stiffness", "assumed_strain"},
                                           static_cast<std::size_t>(hourglass.form)));
  hourglass.coefficient =
      hr.optional_number("coefficient", scene_ranges::body::hourglass_range(hourglass.form));
  return hourglass;
}

// A body's erosion table: the criteria that delete its elements.
ErosionSettings read_erosion(const toml::table& table, TableReader& r) {
  TableReader er(table, r.dotted("erosion"), r.file());
  er.known({"plastic_strain", "material_failure", "volume_ratio", "time_step"});
  er.check_unknown();
  namespace range = scene_ranges::erosion;
  ErosionSettings e;
  e.plastic_strain = er.number("plastic_strain", e.plastic_strain, range::plastic_strain);
  e.material_failure = er.boolean("material_failure", e.material_failure);
  e.volume_ratio = er.number("volume_ratio", e.volume_ratio, range::volume_ratio);
  e.time_step = er.number("time_step", e.time_step, range::time_step);
  return e;
}

// A body's conversion table: the criteria that turn its elements into particles (AFEMP).
ConversionSettings read_conversion(const toml::table& table, TableReader& r) {
  TableReader cr(table, r.dotted("conversion"), r.file());
  cr.known({"plastic_strain", "volumetric_strain", "jacobian_ratio", "negative_jacobian",
            "time_step_fraction", "damage", "points"});
  cr.check_unknown();
  namespace range = scene_ranges::conversion;
  ConversionSettings c;
  c.plastic_strain = cr.number("plastic_strain", c.plastic_strain, range::plastic_strain);
  c.volumetric_strain =
      cr.number("volumetric_strain", c.volumetric_strain, range::volumetric_strain);
  c.jacobian_ratio = cr.number("jacobian_ratio", c.jacobian_ratio, range::jacobian_ratio);
  c.negative_jacobian = cr.boolean("negative_jacobian", c.negative_jacobian);
  c.time_step_fraction =
      cr.number("time_step_fraction", c.time_step_fraction, range::time_step_fraction);
  c.damage = cr.number("damage", c.damage, range::damage);
  c.points = static_cast<int>(cr.integer("points", c.points, range::points.lo, range::points.hi));
  if (const std::optional<std::string> why = no_conversion_criterion(c)) r.fail("conversion", *why);
  return c;
}

// rigid = true, or a table of the fixed components; refused with erosion, conversion or
// bonded_to. Sets b.rigid unless rigid = false.
void read_rigid(const toml::node& node, TableReader& r, BodySpec& b) {
  const toml::node* n = &node;
  RigidSettings rigid;
  bool set = true;
  if (const auto* flag = n->as_boolean()) {
    set = flag->get();
  } else if (const toml::table* t = n->as_table()) {
    TableReader rr(*t, r.dotted("rigid"), r.file());
    rr.known({"fixed"});
    rr.check_unknown();
    static constexpr const char* dof[6] = {"x", "y", "z", "rx", "ry", "rz"};
    for (const std::string& name : rr.strings("fixed")) {
      if (name == "all") {
        rigid.fixed.fill(true);
        continue;
      }
      const auto* component =
          std::find_if(std::begin(dof), std::end(dof), [&](const char* d) { return name == d; });
      if (component == std::end(dof))
        rr.fail("fixed", "unknown component \"" + name +
                             "\"; allowed: \"x\", \"y\", \"z\", \"rx\", \"ry\", \"rz\", \"all\"");
      rigid.fixed[static_cast<std::size_t>(component - std::begin(dof))] = true;
    }
  } else {
    r.fail("rigid",
           "expected true or a table { fixed = [\"x\", ..., \"rz\"] }, got " + describe_type(*n));
  }
  if (set) {
    for (const char* key : {"erosion", "conversion", "bonded_to"})
      if (r.has(key))
        r.fail(key,
               "a rigid body's elements carry no stress; remove " + std::string(key) + " or rigid");
    b.rigid = rigid;
  }
}

BodySpec read_body(TableReader& r, const std::map<std::string, int>& materials,
                   const std::vector<Material>& material_list, const std::string& scene_path) {
  r.known({"name",
           "material",
           "discretisation",
           "shape",
           "initial_stress",
           "particles_per_cell",
           "velocity",
           "temperature",
           "internal_energy",
           "mesh",
           "element",
           "hourglass",
           "bulk_viscosity",
           "erosion",
           "area",
           "bonded_to",
           "conversion",
           "rigid",
           "outside",
           "layout",
           "pressure",
           "overlap_allowed",
           "prestress"});
  // Name the body in messages as soon as its name is readable, even for an unknown key.
  if (const toml::node* n = r.table().get("name");
      n && n->is_string() && !n->as_string()->get().empty())
    r.set_prefix("bodies." + n->as_string()->get());
  r.check_unknown();
  BodySpec b;
  b.where = r.where();
  b.name = r.required_string("name");
  if (b.name.empty()) r.fail("name", "a body name must not be empty");
  r.set_prefix("bodies." + b.name);
  const std::string material = r.required_string("material");
  const auto it = materials.find(material);
  if (it == materials.end()) {
    std::vector<std::string> defined;
    for (const Material& m : material_list) defined.push_back(m.name);
    r.fail("material", "unknown material \"" + material + "\"; defined materials: " +
                           (defined.empty() ? std::string("(none)") : join(defined, true)));
  }
  b.material = it->second;
  b.discretisation =
      static_cast<Discretisation>(r.choice("discretisation", {"particles", "hexahedra", "trusses"},
                                           static_cast<std::size_t>(b.discretisation)));
  TableReader sr(r.required_table("shape"), r.dotted("shape"), r.file());
  b.shape = read_shape(sr, scene_path, b.discretisation);
  namespace range = scene_ranges::body;
  b.velocity = r.vec3("velocity", b.velocity);
  b.temperature = r.optional_number("temperature", range::temperature);
  b.internal_energy = r.number("internal_energy", b.internal_energy, range::internal_energy);
  check_discretisation_keys(r, b);
  using D = Discretisation;
  b.pressure = r.optional_number("pressure", range::pressure);
  if (b.pressure)
    if (const std::optional<std::string> why = initial_pressure_refusal(
            material_list[static_cast<std::size_t>(b.material)], *b.pressure, b.internal_energy))
      r.fail("pressure", *why);
  if (const toml::table* t = r.optional_table("initial_stress"))
    b.initial_stress = read_initial_stress(*t, r);
  if (r.has("rigid") && b.discretisation != D::hexahedra)
    r.fail("rigid", std::string("a rigid body is made of hexahedra (its mass and inertia come from "
                                "their volumes), not of ") +
                        to_string(b.discretisation) +
                        "; model a rigid indenter or anvil as hexahedra with rigid = true");
  b.particles_per_cell =
      static_cast<int>(r.integer("particles_per_cell", b.particles_per_cell,
                                 range::particles_per_cell.lo, range::particles_per_cell.hi));
  only_for(r, b, "layout", D::particles, D::particles);
  b.layout = static_cast<BodySpec::Layout>(
      r.choice("layout", {"lattice", "shells"}, static_cast<std::size_t>(b.layout)));
  if (b.layout == BodySpec::Layout::shells && !std::holds_alternative<SphereShape>(b.shape))
    r.fail("layout",
           "layout = \"shells\" places particles in shells that follow a sphere; "
           "the body's shape is not a sphere (allowed for other shapes: \"lattice\")");
  // Unset, the default of core::bulk_viscosity_of applies.
  if (const toml::table* t = r.optional_table("bulk_viscosity")) {
    TableReader vr(*t, r.dotted("bulk_viscosity"), r.file());
    vr.known({"linear", "quadratic"});
    vr.check_unknown();
    BulkViscositySettings q;
    q.linear = vr.number("linear", q.linear, range::bulk_linear);
    q.quadratic = vr.number("quadratic", q.quadratic, range::bulk_quadratic);
    b.bulk_viscosity = q;
  }
  if (b.discretisation == D::particles) return b;

  const bool generated = !std::holds_alternative<MeshFileShape>(b.shape);
  if (generated) {
    if (!r.has("mesh")) r.fail("mesh", "a generated mesh needs its density: mesh = { size = ... }");
    TableReader mr(r.required_table("mesh"), r.dotted("mesh"), r.file());
    read_mesh_density(mr, b, b.mesh);
  } else if (r.has("mesh")) {
    r.fail("mesh", "an imported mesh takes its density from the file; remove this key");
  }
  b.element = static_cast<HexFormulation>(
      r.choice("element", {"one-point", "full"}, static_cast<std::size_t>(b.element)));
  if (const toml::table* t = r.optional_table("hourglass")) b.hourglass = read_hourglass(*t, r);
  if (const toml::table* t = r.optional_table("erosion")) b.erosion = read_erosion(*t, r);
  if (const toml::table* t = r.optional_table("conversion")) b.conversion = read_conversion(*t, r);
  if (const toml::node* n = r.table().get("rigid")) read_rigid(*n, r, b);
  b.area = r.number("area", b.area, range::area);
  b.prestress = r.number("prestress", b.prestress, range::prestress);
  if (b.discretisation == D::trusses && std::holds_alternative<LineShape>(b.shape) && b.area == 0.0)
    r.fail("area", "a truss line needs its cross-section area");
  return b;
}

int body_index(TableReader& r, std::string_view key, const std::string& name, const Scene& scene,
               bool mesh_only = true) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].name == name) {
      if (mesh_only && scene.bodies[i].discretisation == Discretisation::particles)
        r.fail(key, "body \"" + name + "\" is made of particles; this applies to mesh bodies");
      return static_cast<int>(i);
    }
    names.push_back(scene.bodies[i].name);
  }
  r.fail(key, "unknown body \"" + name + "\"; bodies: " + join(names, true));
}

NodeSelector read_selector(TableReader& r) {
  r.known({"box", "plane", "set"});
  r.check_unknown();
  int given = 0;
  for (std::string_view k : {"box", "plane", "set"}) given += r.has(k) ? 1 : 0;
  if (given != 1) r.fail("", "give exactly one of box, plane, set");
  NodeSelector s;
  if (r.has("set")) {
    s.kind = NodeSelector::Kind::set;
    s.set = r.required_string("set");
    return s;
  }
  if (r.has("box")) {
    s.kind = NodeSelector::Kind::box;
    TableReader b(r.required_table("box"), r.dotted("box"), r.file());
    b.known({"min", "max"});
    b.check_unknown();
    s.min = b.required_vec3("min");
    s.max = b.required_vec3("max");
    for (int a = 0; a < 3; ++a)
      if (s.max[a] < s.min[a]) b.fail("max", "max must not be below min in any component");
    return s;
  }
  s.kind = NodeSelector::Kind::plane;
  TableReader p(r.required_table("plane"), r.dotted("plane"), r.file());
  p.known({"point", "normal", "tolerance"});
  p.check_unknown();
  s.point = p.required_vec3("point");
  const Vec3 n = p.required_vec3("normal");
  if (!(norm(n) > 0.0)) p.fail("normal", "the normal must be a non-zero vector");
  s.normal = (1.0 / norm(n)) * n;
  s.tolerance = p.number("tolerance", s.tolerance, scene_ranges::selector_tolerance);
  return s;
}

// A piecewise-linear history: [time, factor] pairs, times >= 0 and strictly increasing.
std::vector<std::array<double, 2>> read_curve(TableReader& r, std::string_view key) {
  std::vector<std::array<double, 2>> curve = r.pairs(key);
  for (std::size_t k = 0; k < curve.size(); ++k)
    if (curve[k][0] < 0.0 || (k > 0 && !(curve[k][0] > curve[k - 1][0])))
      r.fail(key, "point " + std::to_string(k) + ": time " + format_number(curve[k][0]) +
                      " is negative or not after the previous point's; give [time, factor] "
                      "pairs with times >= 0 and increasing");
  return curve;
}

ConstraintSpec read_constraint(TableReader& r, const Scene& scene) {
  r.known({"nodes", "body", "fixed", "velocity", "components", "curve"});
  r.check_unknown();
  ConstraintSpec c;
  c.where = r.where();
  TableReader nr(r.required_table("nodes"), r.dotted("nodes"), r.file());
  c.nodes = read_selector(nr);
  if (r.has("body")) c.body = body_index(r, "body", r.required_string("body"), scene);
  if (c.body >= 0 && scene.bodies[static_cast<std::size_t>(c.body)].rigid)
    r.fail("body",
           "body \"" + scene.bodies[static_cast<std::size_t>(c.body)].name +
               "\" is rigid; hold it with rigid = { fixed = [\"x\", ..., \"rz\"] } instead");
  if (c.body >= 0 && scene.bodies[static_cast<std::size_t>(c.body)].bonded_to >= 0)
    r.fail("body", "body \"" + scene.bodies[static_cast<std::size_t>(c.body)].name +
                       (bonded_to_particles(scene, scene.bodies[static_cast<std::size_t>(c.body)])
                            ? "\" is bonded to particles and moves with the grid; constrain the "
                              "grid ([grid] boundary) instead"
                            : "\" is tied into hexahedra and moves with them; constrain its "
                              "host's nodes instead"));
  if (r.has("fixed") == r.has("velocity"))
    r.fail("fixed",
           "give either fixed = [\"x\", \"y\", \"z\"] (a subset, or \"all\") or "
           "velocity = [vx, vy, vz]");
  // The components a constraint acts on: fixed's list, or velocity's `components` (all three
  // by default), each "x", "y", "z" or "all".
  auto read_components = [&](std::string_view key) {
    for (const std::string& comp : r.strings(key)) {
      if (comp == "all") {
        c.components = {true, true, true};
      } else if (comp == "x" || comp == "y" || comp == "z") {
        c.components[static_cast<std::size_t>(comp[0] - 'x')] = true;
      } else {
        r.fail(key, "unknown component \"" + comp +
                        "\"; allowed values: \"x\", \"y\", "
                        "\"z\", \"all\"");
      }
    }
    if (!c.components[0] && !c.components[1] && !c.components[2])
      r.fail(key, "name at least one component");
  };
  if (r.has("velocity")) {
    c.velocity = r.required_vec3("velocity");
    if (r.has("components"))
      read_components("components");
    else
      c.components = {true, true, true};
    if (r.has("curve")) c.curve = read_curve(r, "curve");
    return c;
  }
  if (r.has("curve"))
    r.fail("curve", "a curve scales a prescribed velocity over time; give velocity with it");
  if (r.has("components"))
    r.fail("components",
           "components selects what a prescribed velocity acts on; with fixed, "
           "name the components in fixed");
  read_components("fixed");
  return c;
}

WallSpec read_wall(TableReader& r, const Scene& scene) {
  r.known({"point", "normal", "velocity", "friction", "bodies"});
  r.check_unknown();
  WallSpec w;
  w.where = r.where();
  w.point = r.required_vec3("point");
  const Vec3 n = r.required_vec3("normal");
  if (!(norm(n) > 0.0)) r.fail("normal", "the normal must be a non-zero vector");
  w.normal = (1.0 / norm(n)) * n;
  w.velocity = r.vec3("velocity", w.velocity);
  w.friction = r.number("friction", w.friction, scene_ranges::wall_friction);
  for (const std::string& name : r.strings("bodies")) {
    w.bodies.push_back(body_index(r, "bodies", name, scene, false));
    if (scene.bodies[static_cast<std::size_t>(w.bodies.back())].rigid)
      r.fail("bodies", "body \"" + name +
                           "\" is rigid; walls act on deformable mesh bodies (a "
                           "rigid body meets others through [[contact]], and is held by its "
                           "rigid.fixed components)");
    if (scene.bodies[static_cast<std::size_t>(w.bodies.back())].bonded_to >= 0)
      r.fail(
          "bodies",
          "body \"" + name +
              (bonded_to_particles(scene, scene.bodies[static_cast<std::size_t>(w.bodies.back())])
                   ? "\" is bonded to particles and moves with the grid; walls act on free "
                     "mesh bodies (use a [grid] boundary wall face)"
                   : "\" is tied into hexahedra and moves with them; walls act on free mesh "
                     "bodies (name its host)"));
  }
  return w;
}

// The keys of a weld: none beyond the two bodies of particles it joins.
void read_weld_contact(TableReader& r, const BodySpec& a, const BodySpec& b, bool self) {
  for (const char* key : {"friction", "distance_factor", "penalty"})
    if (r.has(key))
      r.fail(key,
             "a weld adds nothing to the step: the bodies share one velocity field; "
             "remove " +
                 std::string(key));
  if (self || a.discretisation != Discretisation::particles ||
      b.discretisation != Discretisation::particles)
    r.fail("method",
           "a weld names two different bodies of particles (meshes weld to "
           "particles by bonded_to)");
}

// The keys of penalty contact between meshes, and the pairs it takes.
void read_penalty_contact(TableReader& r, ContactSpec& c, const BodySpec& a, const BodySpec& b,
                          bool self, bool meshes) {
  if (r.has("distance_factor"))
    r.fail("distance_factor",
           "distance_factor sets where grid contact acts; penalty contact "
           "acts where the surfaces meet (remove it, or set method = \"grid\")");
  if (!meshes)
    r.fail("method",
           "penalty contact acts between meshes (hexahedra, or trusses on "
           "hexahedra); a body of particles meets others by method = \"grid\"");
  if (a.discretisation == Discretisation::trusses && b.discretisation == Discretisation::trusses)
    r.fail("bodies",
           "two bodies of trusses have no surface to meet: penalty contact needs a "
           "body of hexahedra on one side (truss nodes meet hexahedron faces)");
  if (self && a.discretisation != Discretisation::hexahedra)
    r.fail("bodies", "self-contact needs a body of hexahedra (a surface that may fold)");
  if (self && a.rigid) r.fail("bodies", "a rigid body cannot fold onto itself");
  // The fraction of the predicted penetration one step takes out (fem/mesh_contact.hpp):
  // 1 closes it within the step; a velocity correction, not a spring the step must resolve,
  // so any value in (0, 1] is stable.
  c.penalty = r.number("penalty", c.penalty, scene_ranges::contact::penalty);
}

// The keys of surface contact between particles and hexahedra, and the pairs it takes.
void read_surface_contact(TableReader& r, ContactSpec& c, const BodySpec& a, const BodySpec& b,
                          bool self) {
  if (r.has("distance_factor"))
    r.fail("distance_factor",
           "distance_factor sets where grid contact acts; surface contact "
           "acts where the particles' boundary meets the faces (remove it)");
  const bool one_each = (a.discretisation == Discretisation::particles) !=
                        (b.discretisation == Discretisation::particles);
  const BodySpec& m = a.discretisation == Discretisation::particles ? b : a;
  if (self || !one_each || m.discretisation != Discretisation::hexahedra)
    r.fail("method",
           "surface contact is between a body of particles and a body of hexahedra "
           "(deformable or rigid); meshes meet each other by method = \"penalty\", "
           "particles by method = \"grid\"");
  // The fraction of the predicted penetration one step takes out, as for penalty contact.
  c.penalty = r.number("penalty", c.penalty, scene_ranges::contact::penalty);
}

// The keys of grid contact, the pairs it takes and the scheme and grid it needs.
void read_grid_contact(TableReader& r, ContactSpec& c, const Scene& scene, const BodySpec& a,
                       const BodySpec& b, bool self, bool meshes) {
  if (r.has("penalty"))
    r.fail("penalty",
           "penalty scales the stiffness of penalty contact; grid contact has none "
           "(remove it, or set method = \"penalty\" between meshes)");
  if (self) r.fail("bodies", "a body cannot be in grid contact with itself");
  if (a.rigid || b.rigid)
    r.fail("bodies", "body \"" + (a.rigid ? a.name : b.name) +
                         "\" is rigid; rigid bodies meet meshes through penalty contact and "
                         "particles through method = \"surface\" (grid contact does not take "
                         "them)");
  if (meshes)
    r.fail("method",
           "both bodies are meshes; grid contact needs a particle body on one side "
           "(meshes meet each other by method = \"penalty\", the default)");
  if (scene.mpm.scheme == UpdateScheme::USAVG && (a.discretisation != Discretisation::particles ||
                                                  b.discretisation != Discretisation::particles))
    r.fail("bodies",
           "grid contact of a mesh with particles needs [mpm] scheme = \"MUSL\" (the "
           "default) or \"USF\"; USAVG takes grid contact between bodies of particles");
  if (!scene.has_grid)
    r.fail("bodies", "grid contact needs a [grid] section covering the bodies (cell, min, max)");
  // USL takes the strain from the contact-corrected velocity that also moves the particles,
  // and in the head-on test of tests/mpm/test_grid_contact.cpp it lost 79 % of the energy
  // (MUSL and USF: 9-10 %).
  if (scene.mpm.scheme == UpdateScheme::USL)
    r.fail("bodies",
           "grid contact needs [mpm] scheme = \"MUSL\" (the default) or \"USF\"; "
           "with USL the bodies lose most of their energy in contact");
  c.distance_factor =
      r.number("distance_factor", c.distance_factor, scene_ranges::contact::distance_factor);
}

ContactSpec read_contact(TableReader& r, const Scene& scene) {
  r.known({"bodies", "method", "friction", "distance_factor", "penalty", "name"});
  r.check_unknown();
  ContactSpec c;
  c.where = r.where();
  const std::vector<std::string> names = r.strings("bodies");
  if (names.size() != 2 && names.size() != 1)
    r.fail("bodies",
           "name two bodies, e.g. bodies = [\"projectile\", \"plate\"], or one body "
           "of hexahedra for its self-contact");
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string& name = names[std::min(k, names.size() - 1)];
    c.bodies[k] = body_index(r, "bodies", name, scene, false);
    const BodySpec& body = scene.bodies[static_cast<std::size_t>(c.bodies[k])];
    if (body.bonded_to >= 0)
      r.fail("bodies", "body \"" + name + "\" is bonded to \"" +
                           scene.bodies[static_cast<std::size_t>(body.bonded_to)].name +
                           "\" and moves with it; name that body in the contact");
  }
  const BodySpec& a = scene.bodies[static_cast<std::size_t>(c.bodies[0])];
  const BodySpec& b = scene.bodies[static_cast<std::size_t>(c.bodies[1])];
  const auto mesh = [](const BodySpec& body) {
    return body.discretisation != Discretisation::particles;
  };
  const bool self = c.bodies[0] == c.bodies[1];
  const bool meshes = mesh(a) && mesh(b);
  c.method = static_cast<ContactMethod>(
      r.choice("method", {"grid", "penalty", "weld", "surface"}, meshes ? 1 : 0));
  for (const ContactSpec& other : scene.contacts)
    if ((other.bodies[0] == c.bodies[0] && other.bodies[1] == c.bodies[1]) ||
        (other.bodies[0] == c.bodies[1] && other.bodies[1] == c.bodies[0]))
      r.fail("bodies",
             "this pair already has a contact (line " + std::to_string(other.where.line) + ")");
  c.friction = r.number("friction", c.friction, scene_ranges::contact::friction);
  if (r.has("name")) {  // left out: contact_name's default, BODY1-BODY2
    c.name = r.required_string("name");
    if (const std::optional<std::string> why = contact_name_refusal(c.name)) r.fail("name", *why);
  }
  switch (c.method) {
    case ContactMethod::weld:
      read_weld_contact(r, a, b, self);
      break;
    case ContactMethod::penalty:
      read_penalty_contact(r, c, a, b, self, meshes);
      break;
    case ContactMethod::surface:
      read_surface_contact(r, c, a, b, self);
      break;
    case ContactMethod::grid:
      read_grid_contact(r, c, scene, a, b, self, meshes);
      break;
  }
  return c;
}

// Reads an optional array of tables [[KEY]] with `read` for each element.
template <class Read>
void read_table_array(TableReader& r, std::string_view key, const std::string& path, Read read) {
  if (!r.has(key)) return;
  const toml::node* node = r.table().get(key);
  const toml::array* a = node->as_array();
  if (!a || !a->is_array_of_tables())
    throw InputError(
        r.where(key), std::string(key),
        "expected an array of tables ([[" + std::string(key) + "]]), got " + describe_type(*node));
  for (std::size_t i = 0; i < a->size(); ++i) {
    TableReader t(*a->get(i)->as_table(), std::string(key) + "[" + std::to_string(i) + "]", path);
    read(t);
  }
}

VelocityReference read_velocity_reference(TableReader& r, const Scene& scene) {
  r.known({"body", "component", "value", "tolerance"});
  r.check_unknown();
  VelocityReference v;
  v.where = r.where();
  const std::string body = r.required_string("body");
  std::vector<std::string> names;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    names.push_back(scene.bodies[b].name);
    if (scene.bodies[b].name == body) v.body = static_cast<int>(b);
  }
  if (v.body < 0) r.fail("body", "unknown body \"" + body + "\"; bodies: " + join(names, true));
  if (r.has("component")) {  // left out: the magnitude (VelocityReference's -1)
    v.component = static_cast<int>(r.choice("component", {"x", "y", "z", "magnitude"}, 3));
    if (v.component == 3) v.component = -1;
  }
  v.value = r.required_number("value", Range::any());
  if (v.value == 0.0) r.fail("value", "the error is relative to the value, which must not be 0");
  v.tolerance = r.number("tolerance", v.tolerance, scene_ranges::reference::tolerance);
  return v;
}

void read_reference(TableReader& r, Scene& scene) {
  r.known({"taylor", "velocity", "energy"});
  r.check_unknown();
  // velocity: one inline table or an array of them.
  if (const toml::node* n = r.table().get("velocity")) {
    if (const toml::table* t = n->as_table()) {
      TableReader vr(*t, r.dotted("velocity"), r.file());
      scene.velocity_references.push_back(read_velocity_reference(vr, scene));
    } else if (const toml::array* a = n->as_array();
               a && !a->empty() && a->is_homogeneous<toml::table>()) {
      for (std::size_t i = 0; i < a->size(); ++i) {
        TableReader vr(*a->get(i)->as_table(), r.dotted("velocity") + "[" + std::to_string(i) + "]",
                       r.file());
        scene.velocity_references.push_back(read_velocity_reference(vr, scene));
      }
    } else {
      r.fail("velocity",
             "expected { body = ..., component = ..., value = ..., tolerance = ... } or an "
             "array of such tables");
    }
  }
  if (const toml::table* t = r.optional_table("energy")) {
    TableReader er(*t, r.dotted("energy"), r.file());
    er.known({"tolerance"});
    er.check_unknown();
    scene.energy_tolerance =
        er.required_number("tolerance", scene_ranges::reference::energy_tolerance);
  }
  if (const toml::table* t = r.optional_table("taylor")) {
    TableReader tr(*t, r.dotted("taylor"), r.file());
    tr.known({"L", "D", "W", "tolerance"});
    tr.check_unknown();
    TaylorReference ref;
    ref.length = tr.required_number("L", scene_ranges::reference::taylor_length);
    ref.impact_diameter = tr.required_number("D", scene_ranges::reference::taylor_length);
    ref.bulge_diameter = tr.required_number("W", scene_ranges::reference::taylor_length);
    ref.tolerance = tr.number("tolerance", ref.tolerance, scene_ranges::reference::tolerance);
    scene.taylor_reference = ref;
  }
}

// [[probes]]: exactly one of particle, node, element, mean_velocity, extreme. Whether the
// index names an existing particle, node or element is known once the model is built: the
// model checks it at the start of the run (Model::resolve_probes) with this table's line.
ProbeSpec read_probe(TableReader& r, const Scene& scene) {
  r.known({"name", "particle", "node", "element", "mean_velocity", "extreme", "force", "interval"});
  r.check_unknown();
  ProbeSpec p;
  p.where = r.where();
  p.key = r.prefix();
  p.name = r.required_string("name");
  if (p.name.empty() ||
      p.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                               "0123456789_-") != std::string::npos)
    r.fail("name",
           "a probe name (its file probes/NAME.csv) must be non-empty and hold only "
           "letters, digits, '_' and '-'");
  for (const ProbeSpec& other : scene.probes)
    if (other.name == p.name)
      r.fail("name", "duplicate probe name \"" + p.name + "\" (first defined at line " +
                         std::to_string(other.where.line) + ")");
  const std::vector<std::string_view> kinds = {"particle",      "node",    "element",
                                               "mean_velocity", "extreme", "force"};
  int given = 0;
  for (std::size_t k = 0; k < kinds.size(); ++k)
    if (r.has(kinds[k])) {
      p.kind = static_cast<ProbeKind>(k);
      ++given;
    }
  if (given != 1)
    throw InputError(
        r.where(), r.prefix(),
        "give exactly one of particle = { body, index | near }, node = { ... }, "
        "element = { ... }, mean_velocity = \"BODY\", extreme = { field, of, box, body "
        "}, force = \"CONTACT\" (a [[contact]]'s name, \"wallK\" or a rigid body)");
  p.interval = r.number("interval", p.interval, scene_ranges::probe_interval);
  const auto is_particles = [&](int b) {
    return scene.bodies[static_cast<std::size_t>(b)].discretisation == Discretisation::particles;
  };
  if (p.kind == ProbeKind::mean_velocity) {
    p.body = body_index(r, "mean_velocity", r.required_string("mean_velocity"), scene, false);
    return p;
  }
  // Which contacts, walls and rigid bodies report forces the model knows (core/probe_recorder.cpp).
  if (p.kind == ProbeKind::force) {
    p.target = r.required_string("force");
    return p;
  }
  const std::string kind = to_string(p.kind);
  TableReader t(r.required_table(kind), r.dotted(kind), r.file());
  if (p.kind == ProbeKind::extreme) {
    t.known({"field", "of", "box", "body"});
    t.check_unknown();
    p.field = static_cast<ProbeField>(t.choice(
        "field",
        {"pressure", "von_mises", "plastic_strain", "speed", "vx", "vy", "vz", "x", "y", "z"},
        std::nullopt));
    p.maximum = t.choice("of", {"max", "min"}, p.maximum ? 0 : 1) == 0;
    if (t.has("body")) p.body = body_index(t, "body", t.required_string("body"), scene, false);
    TableReader b(t.required_table("box"), t.dotted("box"), r.file());
    b.known({"min", "max"});
    b.check_unknown();
    p.box_min = b.required_vec3("min");
    p.box_max = b.required_vec3("max");
    for (int a = 0; a < 3; ++a)
      if (p.box_max[a] < p.box_min[a]) b.fail("max", "max must not be below min in any component");
    return p;
  }
  t.known({"body", "index", "near"});
  t.check_unknown();
  p.body = body_index(t, "body", t.required_string("body"), scene, p.kind != ProbeKind::particle);
  if (p.kind == ProbeKind::particle && !is_particles(p.body))
    t.fail("body", "body \"" + scene.bodies[static_cast<std::size_t>(p.body)].name +
                       "\" is a mesh; a particle probe watches a body of particles (use node or "
                       "element)");
  if (t.has("index") == t.has("near"))
    t.fail("index", "give either index = I (0-based within the body) or near = [x, y, z] (the " +
                        kind + " nearest to it at the start)");
  if (t.has("index"))
    p.index = t.integer("index", 0, 0, std::numeric_limits<std::int32_t>::max());
  else
    p.near = t.required_vec3("near");
  return p;
}

// The materials, numbered in file order (toml++ keeps keys sorted, so they are sorted by
// position): each name's index.
std::map<std::string, int> read_materials(TableReader& r, Scene& scene, const std::string& path) {
  const toml::table& mats = r.required_table("materials");
  std::vector<std::pair<const toml::key*, const toml::node*>> entries;
  for (auto&& [k, v] : mats) entries.emplace_back(&k, &v);
  std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    const auto& sa = a.second->source().begin;
    const auto& sb = b.second->source().begin;
    return sa.line != sb.line ? sa.line < sb.line : sa.column < sb.column;
  });
  std::map<std::string, int> material_index;
  for (const auto& [k, v] : entries) {
    const std::string key = "materials." + std::string(k->str());
    const toml::table* t = v->as_table();
    if (!t)
      throw InputError(SourceLocation{path, line_of(v->source())}, key,
                       "expected a table [materials.NAME], got " + describe_type(*v));
    TableReader mr(*t, key, path);
    material_index[std::string(k->str())] = static_cast<int>(scene.materials.size());
    scene.materials.push_back(read_material(mr, std::string(k->str())));
    scene.material_where.push_back(mr.where());
  }
  if (scene.materials.empty())
    throw InputError(r.where("materials"), "materials", "define at least one material");
  return material_index;
}

// The [[bodies]], each checked against the grid's lattice and the names before it; returns
// their array (the cross-references below read it again).
const toml::array& read_bodies(TableReader& r, Scene& scene,
                               const std::map<std::string, int>& material_index,
                               const std::string& path) {
  const toml::node* bodies_node = r.has("bodies") ? r.table().get("bodies") : nullptr;
  if (!bodies_node)
    throw InputError(SourceLocation{path, 0}, "bodies",
                     "at least one body is required ([[bodies]] tables)");
  const toml::array* bodies = bodies_node->as_array();
  if (bodies && bodies->empty())
    throw InputError(r.where("bodies"), "bodies", "at least one body is required");
  if (!bodies || !bodies->is_array_of_tables())
    throw InputError(
        r.where("bodies"), "bodies",
        "expected an array of tables ([[bodies]]), got " + describe_type(*bodies_node));
  for (std::size_t i = 0; i < bodies->size(); ++i) {
    const toml::table& t = *bodies->get(i)->as_table();
    TableReader br(t, "bodies[" + std::to_string(i) + "]", path);
    BodySpec b = read_body(br, material_index, scene.materials, path);
    if (b.initial_stress)
      if (const std::optional<std::string> why =
              geostatic_stress_refusal(scene.materials[static_cast<std::size_t>(b.material)],
                                       scene.run.gravity, b.pressure.has_value()))
        br.fail("initial_stress", *why);
    if (const std::optional<std::string> why = absolute_stress_lattice_refusal(scene.mpm.grid, b))
      br.fail("particles_per_cell", *why);
    for (const BodySpec& other : scene.bodies)
      if (other.name == b.name)
        br.fail("name", "duplicate body name \"" + b.name + "\" (first defined at line " +
                            std::to_string(other.where.line) + ")");
    scene.bodies.push_back(std::move(b));
  }
  return *bodies;
}

// Failure keys a body's discretisation would not use (failure_key_refusal), at the line of the
// material's key or of the body's.
void check_failure_keys(const toml::table& root, const toml::array& bodies, const Scene& scene,
                        const std::string& path) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodySpec& b = scene.bodies[i];
    const Material& m = scene.materials[static_cast<std::size_t>(b.material)];
    const std::optional<FailureKeyRefusal> refusal = failure_key_refusal(b, m);
    if (!refusal) continue;
    if (refusal->of_material) {
      const toml::table& t = *root["materials"][m.name].as_table();
      TableReader(t, "materials." + m.name, path).fail(refusal->key, refusal->message);
    }
    const toml::table& t = *bodies.get(i)->as_table();
    if (const toml::table* e = t["erosion"].as_table(); e && refusal->key != "erosion")
      TableReader(*e, "bodies." + b.name + ".erosion", path)
          .fail(refusal->key.substr(std::string_view("erosion.").size()), refusal->message);
    TableReader(t, "bodies." + b.name, path).fail(refusal->key, refusal->message);
  }
}

// Adaptive conversion: the particles need the grid, and the remaining elements bond to them.
void check_conversions(const toml::array& bodies, const Scene& scene, const std::string& path) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!scene.bodies[i].conversion) continue;
    const toml::table& t = *bodies.get(i)->as_table();
    TableReader br(t, "bodies." + scene.bodies[i].name, path);
    if (!scene.has_grid)
      br.fail("conversion",
              "converted elements become particles on the background grid; add a "
              "[grid] section (cell, min, max) covering where they may convert");
    if (scene.mpm.scheme == UpdateScheme::USL || scene.mpm.scheme == UpdateScheme::USAVG)
      br.fail("conversion",
              "conversion bonds the remaining elements to the new particles, which "
              "needs [mpm] scheme = \"MUSL\" (the default) or \"USF\"");
    if (t.contains("bonded_to"))
      br.fail("conversion",
              "a body bonded to particles cannot also convert; remove one of "
              "bonded_to and conversion");
  }
}

// The bodies that split ([mpm] splitting.bodies), once the bodies are read.
void read_splitting_bodies(TableReader& r, Scene& scene, const std::string& path) {
  if (const toml::table* m = r.optional_table("mpm"))
    if (const toml::table* t = m->get_as<toml::table>("splitting");
        t != nullptr && t->contains("bodies")) {
      TableReader sr(*t, "mpm.splitting", path);
      for (const std::string& name : sr.strings("bodies")) {
        const int b = body_index(sr, "bodies", name, scene, false);
        if (scene.bodies[static_cast<std::size_t>(b)].discretisation != Discretisation::particles)
          sr.fail("bodies", "body \"" + name + "\" is not of particles; only particles split");
        scene.mpm.splitting->bodies.push_back(b);
      }
    }
}

// Particle bodies placed around others (water around a charge): the bodies named by outside.
void read_outside(const toml::array& bodies, Scene& scene, const std::string& path) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const toml::table& t = *bodies.get(i)->as_table();
    if (!t.contains("outside")) continue;
    TableReader br(t, "bodies." + scene.bodies[i].name, path);
    for (const std::string& name : br.strings("outside")) {
      const int o = body_index(br, "outside", name, scene, false);
      const BodySpec& other = scene.bodies[static_cast<std::size_t>(o)];
      if (static_cast<std::size_t>(o) == i) br.fail("outside", "a body cannot lie outside itself");
      if (std::holds_alternative<PointListShape>(other.shape) ||
          std::holds_alternative<MeshFileShape>(other.shape))
        br.fail("outside", "body \"" + name +
                               "\" has no inside to leave out (a point list or "
                               "a mesh file); name bodies with a box, cylinder or sphere");
      scene.bodies[i].outside.push_back(o);
    }
  }
}

// The bodies each body is meant to overlap (overlap_allowed).
void read_overlap_allowed(const toml::array& bodies, Scene& scene, const std::string& path) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const toml::table& t = *bodies.get(i)->as_table();
    if (!t.contains("overlap_allowed")) continue;
    TableReader br(t, "bodies." + scene.bodies[i].name, path);
    for (const std::string& name : br.strings("overlap_allowed")) {
      const int o = body_index(br, "overlap_allowed", name, scene, false);
      if (static_cast<std::size_t>(o) == i)
        br.fail("overlap_allowed", "a body is not checked against itself; name other bodies");
      scene.bodies[i].overlap_allowed.push_back(o);
    }
  }
}

// Bonded coupling: the host named by each mesh body's bonded_to.
void read_bonded_to(const toml::array& bodies, Scene& scene, const std::string& path) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const toml::table& t = *bodies.get(i)->as_table();
    if (!t.contains("bonded_to")) continue;
    TableReader br(t, "bodies." + scene.bodies[i].name, path);
    const std::string host = br.required_string("bonded_to");
    const int h = body_index(br, "bonded_to", host, scene, false);
    const BodySpec& hb = scene.bodies[static_cast<std::size_t>(h)];
    const BodySpec& b = scene.bodies[i];
    if (hb.discretisation == Discretisation::hexahedra) {
      // Rebar tied into solid elements: trusses only, in a deformable host of its own.
      if (b.discretisation != Discretisation::trusses)
        br.fail("bonded_to", "body \"" + host +
                                 "\" is a body of hexahedra; only trusses are tied into "
                                 "hexahedra (rebar in solid elements); hexahedra bond to a body "
                                 "of particles");
      if (hb.rigid)
        br.fail("bonded_to", "body \"" + host +
                                 "\" is rigid; trusses are tied into deformable hexahedra (a "
                                 "rigid body carries no stress for the rebar to share)");
      const toml::table& ht = *bodies.get(static_cast<std::size_t>(h))->as_table();
      if (ht.contains("bonded_to"))
        br.fail("bonded_to", "body \"" + host +
                                 "\" is bonded to another body itself; tie the trusses into a "
                                 "body of hexahedra that moves on its own");
    } else if (hb.discretisation != Discretisation::particles) {
      br.fail("bonded_to", "body \"" + host +
                               "\" is a body of trusses; a mesh body bonds to a body of "
                               "particles (its nodes join that body's velocity field on the "
                               "grid), and trusses may also be tied into a body of hexahedra");
    } else if (scene.mpm.scheme == UpdateScheme::USL || scene.mpm.scheme == UpdateScheme::USAVG) {
      br.fail("bonded_to",
              "bonded coupling needs [mpm] scheme = \"MUSL\" (the default) or "
              "\"USF\"");
    }
    scene.bodies[i].bonded_to = h;
  }
}

// One [[absorbing]] boundary: its nodes, and the body of hexahedra whose faces they lie on.
AbsorbingSpec read_absorbing(TableReader& t, const Scene& scene) {
  t.known({"nodes", "body"});
  t.check_unknown();
  AbsorbingSpec a;
  a.where = t.where();
  TableReader nr(t.required_table("nodes"), t.dotted("nodes"), t.file());
  a.nodes = read_selector(nr);
  if (t.has("body")) {
    a.body = body_index(t, "body", t.required_string("body"), scene);
    if (scene.bodies[static_cast<std::size_t>(a.body)].discretisation != Discretisation::hexahedra)
      t.fail("body", "an absorbing boundary lies on the faces of hexahedra; body \"" +
                         scene.bodies[static_cast<std::size_t>(a.body)].name +
                         "\" is not a body of hexahedra (particles take \"absorbing\" "
                         "faces from [grid] boundary)");
    if (scene.bodies[static_cast<std::size_t>(a.body)].rigid)
      t.fail("body", "body \"" + scene.bodies[static_cast<std::size_t>(a.body)].name +
                         "\" is rigid: no waves cross it to absorb");
  }
  return a;
}

// One [[loads]] entry: the body, the region of its faces or particles, the traction or total
// force, and its curve; what the body's kind allows is load_refusal's (scene_check.cpp).
LoadSpec read_load(TableReader& t, const Scene& scene) {
  t.known({"body", "nodes", "particles", "traction", "force", "curve"});
  t.check_unknown();
  LoadSpec l;
  l.where = t.where();
  l.body = body_index(t, "body", t.required_string("body"), scene, false);
  const bool particles =
      scene.bodies[static_cast<std::size_t>(l.body)].discretisation == Discretisation::particles;
  const char* region = particles ? "particles" : "nodes";
  const char* other = particles ? "nodes" : "particles";
  if (t.has(other))
    t.fail(other, std::string("body \"") + scene.bodies[static_cast<std::size_t>(l.body)].name +
                      "\" is " + (particles ? "made of particles" : "a mesh body") +
                      "; its load's region is `" + region + " = { ... }`");
  TableReader rr(t.required_table(region), t.dotted(region), t.file());
  l.region = read_selector(rr);
  if (t.has("traction") == t.has("force"))
    t.fail("traction",
           "give either traction = [tx, ty, tz] (per unit initial area) or force = [fx, fy, fz] "
           "(the total)");
  l.traction = t.has("traction");
  l.value = t.required_vec3(l.traction ? "traction" : "force");
  if (t.has("curve")) l.curve = read_curve(t, "curve");
  if (const std::optional<LoadRefusal> why = load_refusal(scene, l)) t.fail(why->key, why->message);
  return l;
}

// After each [[contact]]: at most 31 bodies in grid contact (one velocity field each).
void check_grid_contact_bodies(TableReader& t, const Scene& scene) {
  std::vector<bool> named(scene.bodies.size(), false);
  int count = 0;
  for (const ContactSpec& c : scene.contacts)
    for (int b : c.bodies)
      if (c.method == ContactMethod::grid && !named[static_cast<std::size_t>(b)]) {
        named[static_cast<std::size_t>(b)] = true;
        ++count;
      }
  if (count > 31)
    t.fail("bodies",
           "at most 31 bodies can take part in grid contact (each has its own "
           "velocity field on the grid)");
}

// [run] terminate, which names a body.
void read_terminate(TableReader& r, Scene& scene, const std::string& path) {
  TableReader run(r.required_table("run"), "run", path);
  if (const toml::table* t = run.optional_table("terminate")) {
    TableReader tr(*t, "run.terminate", path);
    tr.known({"body", "travel"});
    tr.check_unknown();
    RunSettings::Termination term;
    term.body = body_index(tr, "body", tr.required_string("body"), scene, false);
    term.travel = tr.required_number("travel", scene_ranges::run::terminate_travel);
    scene.run.terminate = term;
  }
}

// [[phases]] (core/phases.hpp): each entry's keys, then the sequence and the bodies, checked
// as check_scene checks a scene built in code. The last phase's end_time may be left out (0:
// [run]'s, core::phase_end).
void read_phases(TableReader& r, Scene& scene, const std::string& path) {
  std::size_t count = 0;
  if (r.has("phases"))
    if (const toml::array* a = r.table().get("phases")->as_array()) count = a->size();
  read_table_array(r, "phases", path, [&](TableReader& t) {
    PhaseSpec p;
    p.where = t.where();
    static constexpr PhaseKind kinds[] = {PhaseKind::static_load, PhaseKind::implicit_dynamics,
                                          PhaseKind::relaxation, PhaseKind::explicit_dynamics};
    p.kind =
        kinds[t.choice("kind", {"static", "implicit", "relaxation", "explicit"}, std::nullopt)];
    const bool last = scene.phases.size() + 1 == count;
    p.end_time = last ? t.number("end_time", p.end_time, scene_ranges::run::end_time)
                      : t.required_number("end_time", scene_ranges::run::end_time);
    if (p.kind == PhaseKind::static_load || p.kind == PhaseKind::implicit_dynamics) {
      namespace ranges = scene_ranges::phase;
      if (p.kind == PhaseKind::static_load) {
        p.load_steps = static_cast<int>(
            t.integer("load_steps", p.load_steps, ranges::load_steps.lo, ranges::load_steps.hi));
      } else {
        p.time_step = t.required_number("time_step", ranges::implicit_time_step);
        p.alpha = t.number("alpha", p.alpha, ranges::hht_alpha);
      }
      p.max_iterations =
          static_cast<int>(t.integer("max_iterations", p.max_iterations, ranges::max_iterations.lo,
                                     ranges::max_iterations.hi));
      p.tolerance = t.number("tolerance", p.tolerance, ranges::tolerance);
      p.gravity = t.optional_vec3("gravity");
      for (const std::string& name : t.strings("bodies"))
        p.bodies.push_back(body_index(t, "bodies", name, scene, false));
    } else if (p.kind == PhaseKind::relaxation) {
      namespace ranges = scene_ranges::phase;
      p.tolerance = t.number("tolerance", p.tolerance, ranges::relaxation_tolerance);
      p.damping_factor = t.number("damping_factor", p.damping_factor, ranges::damping_factor);
      p.check_every =
          t.integer("check_every", p.check_every, ranges::check_every.lo, ranges::check_every.hi);
      p.relaxation_step_factor =
          t.number("time_step_factor", p.relaxation_step_factor, ranges::relaxation_step_factor);
    }
    t.check_unknown();
    scene.phases.push_back(std::move(p));
  });
  check_phases(scene, [](const SourceLocation& where, const std::string& key,
                         const std::string& message) { throw InputError(where, key, message); });
}

// Constraints, absorbing boundaries and walls without bodies act on mesh nodes.
void check_mesh_conditions(const Scene& scene, const std::string& path) {
  if ((!scene.constraints.empty() || !scene.absorbing.empty()) && !has_mesh(scene))
    throw InputError(SourceLocation{path, 0},
                     !scene.absorbing.empty() ? "absorbing" : "constraints",
                     "constraints and absorbing boundaries act on mesh nodes, and the scene has "
                     "no mesh body; particles take their boundary conditions from [grid] "
                     "boundary (and [[walls]] that name them)");
  for (const WallSpec& w : scene.walls)
    if (w.bodies.empty() && !has_mesh(scene))
      throw InputError(w.where, "walls.bodies",
                       "a wall without bodies acts on every mesh body, and the scene has none; "
                       "name the particle bodies it meets (bodies = [\"...\"]): it then acts at "
                       "their particles' boundary");
}

// One [[detonations]] entry: a point, a plane or a line, and its time.
DetonationSpec read_detonation(TableReader& t, const std::string& path) {
  t.known({"point", "plane", "line", "time", "shadow"});
  t.check_unknown();
  DetonationSpec d;
  d.where = t.where();
  const int given = (t.has("point") ? 1 : 0) + (t.has("plane") ? 1 : 0) + (t.has("line") ? 1 : 0);
  if (given != 1)
    t.fail("point",
           "give one of point = [x, y, z], plane = { point = [..], normal = [..] } "
           "or line = { from = [..], to = [..] }");
  if (t.has("point")) {
    d.point = t.required_vec3("point");
  } else if (const toml::table* p = t.optional_table("plane")) {
    TableReader pr(*p, t.dotted("plane"), path);
    pr.known({"point", "normal"});
    pr.check_unknown();
    d.kind = DetonationSpec::Kind::plane;
    d.point = pr.required_vec3("point");
    const Vec3 n = pr.required_vec3("normal");
    if (!(norm(n) > 0.0)) pr.fail("normal", "the normal must be a non-zero vector");
    d.normal = (1.0 / norm(n)) * n;
  } else if (const toml::table* l = t.optional_table("line")) {
    TableReader lr(*l, t.dotted("line"), path);
    lr.known({"from", "to"});
    lr.check_unknown();
    d.kind = DetonationSpec::Kind::line;
    d.point = lr.required_vec3("from");
    d.end = lr.required_vec3("to");
  }
  d.time = t.number("time", d.time, scene_ranges::detonation_time);
  d.shadow = t.boolean("shadow", d.shadow);
  return d;
}

}  // namespace

void check_explosives(const Scene& scene) {
  const BodySpec* explosive = nullptr;
  for (const BodySpec& b : scene.bodies) {
    if (!scene.materials[static_cast<std::size_t>(b.material)].is_explosive()) continue;
    explosive = &b;
    if (b.discretisation == Discretisation::trusses)
      throw InputError(b.where, "material",
                       "body \"" + b.name +
                           "\" is a body of trusses "
                           "of a high explosive; explosives are particles or hexahedra");
    if (b.conversion)
      throw InputError(b.where, "conversion",
                       "body \"" + b.name +
                           "\" is a high explosive; "
                           "its hexahedra burn where they are and do not convert into particles");
  }
  if (explosive != nullptr && scene.detonations.empty())
    throw InputError(explosive->where, "detonations",
                     "body \"" + explosive->name +
                         "\" is a high explosive (its material has a "
                         "burn) and the scene has no [[detonations]] to light it: add one (point, "
                         "plane or line, and a time)");
  if (explosive == nullptr && !scene.detonations.empty())
    throw InputError(scene.detonations.front().where, "detonations",
                     "no body is of a high explosive (a material with burn = { D, pcj }) for "
                     "the detonation to light");
}

std::vector<std::string_view> builtin_strength_models() {
  return model_names<StrengthModel>();
}

Scene scene_from_toml(const toml::table& root, const std::string& path) {
  Scene scene;
  scene.path = path;
  TableReader r(root, "", path);
  r.known({"run", "grid", "mpm", "materials", "bodies", "constraints", "absorbing", "loads",
           "walls", "contact", "reference", "probes", "detonations", "phases"});
  r.check_unknown();

  {
    TableReader run(r.required_table("run"), "run", path);
    read_run(run, scene.run);
  }
  if (const toml::table* t = r.optional_table("grid")) {
    TableReader grid(*t, "grid", path);
    read_grid(grid, scene.mpm.grid);
    scene.has_grid = true;
    scene.grid_where = grid.where("max");
  }
  if (const toml::table* t = r.optional_table("mpm")) {
    TableReader mpm(*t, "mpm", path);
    read_mpm(mpm, scene.mpm);
  }
  const std::map<std::string, int> material_index = read_materials(r, scene, path);
  const toml::array& bodies = read_bodies(r, scene, material_index, path);
  if (has_particles(scene) && !scene.has_grid)
    throw InputError(SourceLocation{path, 0}, "grid",
                     "bodies of particles need a [grid] section (cell, min, max)");
  check_failure_keys(root, bodies, scene, path);
  check_conversions(bodies, scene, path);
  read_splitting_bodies(r, scene, path);
  read_outside(bodies, scene, path);
  read_overlap_allowed(bodies, scene, path);
  read_bonded_to(bodies, scene, path);
  read_table_array(r, "constraints", path,
                   [&](TableReader& t) { scene.constraints.push_back(read_constraint(t, scene)); });
  read_table_array(r, "absorbing", path,
                   [&](TableReader& t) { scene.absorbing.push_back(read_absorbing(t, scene)); });
  read_table_array(r, "loads", path,
                   [&](TableReader& t) { scene.loads.push_back(read_load(t, scene)); });
  read_table_array(r, "walls", path,
                   [&](TableReader& t) { scene.walls.push_back(read_wall(t, scene)); });
  read_table_array(r, "contact", path, [&](TableReader& t) {
    scene.contacts.push_back(read_contact(t, scene));
    check_grid_contact_bodies(t, scene);
  });
  read_terminate(r, scene, path);
  check_mesh_conditions(scene, path);
  read_table_array(r, "detonations", path,
                   [&](TableReader& t) { scene.detonations.push_back(read_detonation(t, path)); });
  check_explosives(scene);
  if (const toml::table* t = r.optional_table("reference")) {
    TableReader ref(*t, "reference", path);
    read_reference(ref, scene);
  }
  read_table_array(r, "probes", path,
                   [&](TableReader& t) { scene.probes.push_back(read_probe(t, scene)); });
  read_phases(r, scene, path);
  if (const std::optional<std::string> why = reproducible_refusal(scene))
    throw InputError(scene.run.reproducible_where, "run.reproducible", *why);
  if (const std::optional<AxisymmetricRefusal> no = axisymmetric_refusal(scene))
    throw InputError(no->where, no->key, no->why);
  return scene;
}

}  // namespace afemp::core::scene_detail
