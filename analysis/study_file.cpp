// The study file (docs/study-format.md): [study], [[metrics]] and [[runs]], read with the
// scene parser's checked TableReader so that its mistakes read like a scene's, and each run's
// scene built from its scene file with the run's overrides applied to the TOML tree.
#include "analysis/study_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/scene_parser.hpp"

namespace afemp::analysis {

using core::scene_detail::describe_type;
using core::scene_detail::join;
using core::scene_detail::Range;
using core::scene_detail::TableReader;

const char* to_string(MetricKind k) {
  switch (k) {
    case MetricKind::taylor:
      return "taylor";
    case MetricKind::velocity:
      return "velocity";
    case MetricKind::crater:
      return "crater";
    case MetricKind::hole:
      return "hole";
    case MetricKind::wave_front:
      return "wave_front";
    case MetricKind::frequency:
      return "frequency";
    case MetricKind::force:
      return "force";
  }
  return "?";
}

std::vector<std::string> value_columns(const MetricSpec& m) {
  switch (m.kind) {
    case MetricKind::taylor:
      return {m.name + ".L", m.name + ".D", m.name + ".W"};
    case MetricKind::crater:
      return {m.name + ".depth", m.name + ".diameter"};
    default:
      return {m.name};
  }
}

bool StudyPlan::has_reference(std::size_t metric) const {
  return std::any_of(runs.begin(), runs.end(),
                     [&](const StudyRun& r) { return r.references[metric].has_value(); });
}

namespace {

int line_of(const toml::source_region& r) {
  return static_cast<int>(r.begin.line);
}

std::string format_number_short(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

toml::table parse_toml(const std::string& text, const std::string& path) {
  try {
    return toml::parse(std::string_view(text), std::string_view(path));
  } catch (const toml::parse_error& e) {
    throw InputError(SourceLocation{path, static_cast<int>(e.source().begin.line)}, "",
                     "TOML syntax error: " + std::string(e.description()));
  }
}

std::string read_text(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(SourceLocation{path, 0}, "",
                     std::string("cannot open ") + what + " '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A TOML value as text ("0.25", "\"MUSL\"", "[1, 2]").
std::string toml_text(const toml::node& n) {
  std::ostringstream os;
  n.visit([&](const auto& v) { os << v; });
  return os.str();
}

// Which metric kinds a key of [[metrics]] applies to (kind, name, reference and tolerance:
// every kind).
struct MetricKey {
  std::string_view key;
  std::vector<MetricKind> kinds;
};
const std::vector<MetricKey>& metric_keys() {
  using K = MetricKind;
  static const std::vector<MetricKey> keys = {
      {"body", {K::taylor, K::velocity, K::crater, K::hole}},
      {"component", {K::velocity}},
      {"point", {K::crater, K::hole}},
      {"normal", {K::crater, K::hole}},
      {"ring", {K::crater}},
      {"threshold", {K::crater}},
      {"band", {K::hole}},
      {"probes", {K::wave_front}},
      {"probe", {K::frequency, K::force}},
      {"quantity", {K::wave_front, K::frequency, K::force}},
      {"fraction", {K::wave_front}},
      {"until", {K::wave_front}},
  };
  return keys;
}

// A metric's reference from its TOML value: the study-wide `reference`, or one run's, which
// `key` names in messages ("runs[1].reference.crater[2]").
MetricReference read_reference(const MetricSpec& m, const toml::node& node, const std::string& key,
                               const std::string& file) {
  const SourceLocation at{file, line_of(node.source())};
  MetricReference out;
  if (m.kind == MetricKind::taylor || m.kind == MetricKind::crater) {
    const bool taylor = m.kind == MetricKind::taylor;
    const toml::table* t = node.as_table();
    if (!t)
      throw InputError(
          at, key,
          std::string("expected ") +
              (taylor ? "{ L = ..., D = ..., W = ... }" : "{ depth = ..., diameter = ... }") +
              ", got " + describe_type(node));
    TableReader ref(*t, key, file);
    if (taylor) {
      ref.known({"L", "D", "W"});
      ref.check_unknown();
      TaylorReference tr;
      tr.length = ref.required_number("L", Range::positive());
      tr.impact_diameter = ref.required_number("D", Range::positive());
      tr.bulge_diameter = ref.required_number("W", Range::positive());
      tr.tolerance = m.tolerance;
      out.taylor = tr;
    } else {
      ref.known({"depth", "diameter"});
      ref.check_unknown();
      out.crater = CraterReference{ref.required_number("depth", Range::positive()),
                                   ref.required_number("diameter", Range::positive())};
    }
    return out;
  }
  auto number = [](const toml::node& n) -> std::optional<double> {
    if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
    if (const auto* f = n.as_floating_point()) return f->get();
    return std::nullopt;
  };
  ScalarReference s;
  const toml::array* a = node.as_array();
  if (a && a->size() == 2 && number(*a->get(0)) && number(*a->get(1))) {
    s = {*number(*a->get(0)), *number(*a->get(1)), true};
  } else if (const auto v = number(node)) {
    s.low = s.high = *v;
  } else {
    std::string got = describe_type(node);
    if (a && a->size() == 2)
      got = "an array of " + describe_type(*a->get(0)) + " and " + describe_type(*a->get(1));
    else if (a)
      got =
          "an array of " + std::to_string(a->size()) + (a->size() == 1 ? " element" : " elements");
    throw InputError(at, key, "expected a number or a band [low, high] of two numbers, got " + got);
  }
  if (!std::isfinite(s.low) || !std::isfinite(s.high))
    throw InputError(at, key, "a reference must be a finite number");
  if (!s.band && s.low == 0.0)
    throw InputError(at, key, "the error is relative to the reference, which must not be 0");
  if (s.band && !(s.low <= s.high))
    throw InputError(at, key,
                     "a band [low, high] needs low <= high; got [" + format_number_short(s.low) +
                         ", " + format_number_short(s.high) + "]");
  if (s.band && !(s.low * s.high > 0.0))
    throw InputError(at, key,
                     "a band's bounds must have one sign and neither be 0: the error is relative "
                     "to the nearer bound");
  out.scalar = s;
  return out;
}

MetricSpec read_metric(TableReader& r) {
  MetricSpec m;
  m.where = r.where();
  r.known({"kind", "name", "body", "component", "point", "normal", "ring", "threshold", "band",
           "probes", "probe", "quantity", "fraction", "until", "reference", "tolerance"});
  r.check_unknown();
  m.kind = static_cast<MetricKind>(
      r.choice("kind", {"taylor", "velocity", "crater", "hole", "wave_front", "frequency", "force"},
               std::nullopt));
  m.name = r.string("name", to_string(m.kind));
  if (m.name.empty() || m.name.find_first_of(",.\"\n") != std::string::npos)
    r.fail("name", "a metric name must be non-empty and hold no comma, dot, quote or newline");
  for (const MetricKey& k : metric_keys()) {
    if (!r.has(k.key) || std::find(k.kinds.begin(), k.kinds.end(), m.kind) != k.kinds.end())
      continue;
    std::vector<std::string> kinds;
    for (MetricKind kind : k.kinds) kinds.push_back(to_string(kind));
    r.fail(k.key,
           "applies to kind " + join(kinds, true) + " only, not \"" + to_string(m.kind) + "\"");
  }
  m.tolerance = r.number("tolerance", 0.0, Range::non_negative());
  switch (m.kind) {
    case MetricKind::taylor:
      m.body = r.required_string("body");
      break;
    case MetricKind::velocity:
      m.body = r.required_string("body");
      m.component = static_cast<int>(r.choice("component", {"x", "y", "z", "magnitude"}, 3));
      if (m.component == 3) m.component = -1;
      break;
    case MetricKind::crater:
    case MetricKind::hole: {
      m.body = r.required_string("body");
      m.point = r.required_vec3("point");
      const Vec3 n = r.required_vec3("normal");
      if (!(norm(n) > 0.0)) r.fail("normal", "the normal must be a non-zero vector");
      m.normal = (1.0 / norm(n)) * n;
      if (m.kind == MetricKind::hole) {
        m.band = r.required_number("band", Range::positive());
        break;
      }
      m.ring = r.required_number("ring", Range::positive());
      m.threshold = r.required_number("threshold", Range::positive());
      break;
    }
    case MetricKind::wave_front:
      m.probes = r.strings("probes");
      if (m.probes.size() < 2)
        r.fail("probes",
               "name two or more probes along the wave's path, e.g. probes = [\"near\", \"far\"]");
      m.quantity = r.required_string("quantity");
      m.fraction = r.number("fraction", 0.5, {0.0, 1.0, true, false});
      m.until = r.number("until", 0.0, Range::positive());
      break;
    case MetricKind::frequency:
    case MetricKind::force:
      m.probes = {r.required_string("probe")};
      m.quantity = r.required_string("quantity");
      break;
  }
  if (r.has("reference"))
    m.reference = read_reference(m, *r.table().get("reference"), r.dotted("reference"), r.file());
  return m;
}

// [[runs]]: one run, or one per value when `resolution` is an array (every `set` and
// `reference` value is then an array of as many values, the k-th for the k-th run).
void read_runs(TableReader& r, const std::string& study_path,
               const std::vector<MetricSpec>& metrics, std::vector<StudyRun>& out) {
  r.known({"method", "scene", "resolution", "set", "reference", "label"});
  r.check_unknown();
  StudyRun base;
  base.where = r.where();
  base.method = r.required_string("method");
  if (base.method.empty() || base.method.find_first_of(",\"\n") != std::string::npos)
    r.fail("method", "a method name must be non-empty and hold no comma, quote or newline");
  std::filesystem::path scene = r.required_string("scene");
  if (scene.is_relative()) scene = std::filesystem::path(study_path).parent_path() / scene;
  base.scene_path = scene.lexically_normal().string();
  const std::string label = r.string("label", "");
  const std::vector<double> resolutions = r.numbers("resolution", Range::positive());
  const bool sweep = r.has("resolution") && r.table().get("resolution")->is_array();
  const std::size_t count = sweep ? resolutions.size() : 1;
  // set = { "grid.cell" = 0.5 } or set = { grid.cell = 0.5 } (TOML's dotted keys make
  // nested tables): every leaf, by its dotted path.
  std::vector<std::pair<std::string, const toml::node*>> leaves;
  auto flatten = [&](auto& self, const toml::table& t, const std::string& prefix) -> void {
    for (const auto& [key, node] : t) {
      const std::string k = prefix + std::string(key.str());
      if (const toml::table* sub = node.as_table())
        self(self, *sub, k + ".");
      else
        leaves.emplace_back(k, &node);
    }
  };
  std::vector<std::pair<std::string, const toml::node*>> set;
  if (const toml::table* t = r.optional_table("set")) {
    flatten(flatten, *t, "");
    for (const auto& [k, node_ptr] : leaves) {
      const toml::node& node = *node_ptr;
      if (sweep) {
        const auto* a = node.as_array();
        if (!a || a->size() != count)
          throw InputError(SourceLocation{r.file(), line_of(node.source())},
                           r.dotted("set") + "." + k,
                           "with resolution = [" + std::to_string(count) +
                               " values], every set value must be an array of " +
                               std::to_string(count) + " values, one per run");
      }
      set.emplace_back(k, &node);
    }
  }
  // reference = { NAME = ... }: the metric's reference for these runs, in place of its
  // study-wide one.
  for (const MetricSpec& m : metrics) base.references.push_back(m.reference);
  std::vector<std::pair<std::size_t, const toml::node*>> references;  // metric index, value
  if (const toml::table* t = r.optional_table("reference")) {
    for (const auto& [key, node] : *t) {
      const std::string name(key.str()), dotted = r.dotted("reference") + "." + name;
      const SourceLocation at{r.file(), line_of(node.source())};
      const auto m = std::find_if(metrics.begin(), metrics.end(),
                                  [&](const MetricSpec& spec) { return spec.name == name; });
      if (m == metrics.end()) {
        std::vector<std::string> names;
        for (const MetricSpec& spec : metrics) names.push_back(spec.name);
        const std::string known = names.empty() ? "this study has none" : join(names, true);
        throw InputError(at, dotted,
                         "no metric is named \"" + name +
                             "\"; reference = { NAME = ... } takes a [[metrics]] name: " + known);
      }
      if (sweep) {
        const auto* a = node.as_array();
        if (!a || a->size() != count)
          throw InputError(at, dotted,
                           "with resolution = [" + std::to_string(count) +
                               " values], every reference value must be an array of " +
                               std::to_string(count) +
                               " values, one per run (a band: [[low, high], ...])");
      }
      references.emplace_back(static_cast<std::size_t>(m - metrics.begin()), &node);
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    StudyRun run = base;
    if (!resolutions.empty()) run.resolution = resolutions[i];
    for (const auto& [k, node] : set)
      run.overrides.push_back({k, toml_text(sweep ? *node->as_array()->get(i) : *node)});
    for (const auto& [k, node] : references) {
      const std::string key = r.dotted("reference") + "." + metrics[k].name;
      run.references[k] = sweep ? read_reference(metrics[k], *node->as_array()->get(i),
                                                 key + "[" + std::to_string(i) + "]", r.file())
                                : read_reference(metrics[k], *node, key, r.file());
    }
    std::ostringstream l;
    if (!label.empty())
      l << label;
    else
      l << run.method;
    if (run.resolution) l << ", resolution " << format_number_short(*run.resolution);
    run.label = l.str();
    out.push_back(std::move(run));
  }
}

}  // namespace

StudyPlan parse_study(const std::string& text, const std::string& path) {
  const toml::table root = parse_toml(text, path);
  TableReader top(root, "", path);
  top.known({"study", "metrics", "runs"});
  top.check_unknown();
  StudyPlan plan;
  plan.path = path;
  if (!top.has("study"))
    top.fail("study", "a study file needs a [study] table (title, threads, plot)");
  TableReader s(top.required_table("study"), "study", path);
  s.known({"title", "threads", "plot", "energy_tolerance", "plot_value", "x_label"});
  s.check_unknown();
  plan.title = s.string("title", std::filesystem::path(path).stem().string());
  plan.threads = static_cast<int>(s.integer("threads", 0, 0, 4096));
  plan.energy_tolerance = s.number("energy_tolerance", 0.0, Range::non_negative());
  const toml::node* metrics = root.get("metrics");
  if (metrics && !metrics->is_array_of_tables()) top.fail("metrics", "expected [[metrics]] tables");
  std::set<std::string> names;
  if (metrics) {
    const auto& a = *metrics->as_array();
    for (std::size_t i = 0; i < a.size(); ++i) {
      TableReader mr(*a.get(i)->as_table(), "metrics[" + std::to_string(i) + "]", path);
      plan.metrics.push_back(read_metric(mr));
      if (!names.insert(plan.metrics.back().name).second)
        mr.fail("name", "a second metric named \"" + plan.metrics.back().name +
                            "\"; give each its own name = \"...\"");
    }
  }
  const toml::node* runs = root.get("runs");
  if (!runs || !runs->is_array_of_tables() || runs->as_array()->empty())
    top.fail("runs", "a study needs at least one [[runs]] table (method, scene, resolution, set)");
  const auto& ra = *runs->as_array();
  for (std::size_t i = 0; i < ra.size(); ++i) {
    TableReader rr(*ra.get(i)->as_table(), "runs[" + std::to_string(i) + "]", path);
    read_runs(rr, path, plan.metrics, plan.runs);
  }
  // A tolerance needs a reference in some run (a run without one reports the value only).
  for (std::size_t k = 0; k < plan.metrics.size(); ++k)
    if (plan.metrics[k].tolerance > 0.0 && !plan.has_reference(k))
      TableReader(*metrics->as_array()->get(k)->as_table(), "metrics[" + std::to_string(k) + "]",
                  path)
          .fail("tolerance",
                "a tolerance needs a reference to compare with: reference = ... here, " +
                    ("or reference = { " + plan.metrics[k].name + " = ... }") +
                    " in a [[runs]] table");
  // The plotted metric: named, or the first with a reference.
  if (s.has("plot")) {
    plan.plot = s.required_string("plot");
    const auto it = std::find_if(plan.metrics.begin(), plan.metrics.end(),
                                 [&](const MetricSpec& m) { return m.name == plan.plot; });
    std::vector<std::string> with_reference;
    for (std::size_t k = 0; k < plan.metrics.size(); ++k)
      if (plan.has_reference(k)) with_reference.push_back(plan.metrics[k].name);
    if (plan.plot != "energy" &&
        (it == plan.metrics.end() ||
         !plan.has_reference(static_cast<std::size_t>(it - plan.metrics.begin()))))
      s.fail("plot",
             "names the metric whose error is plotted: one with a reference (" +
                 (with_reference.empty() ? std::string("none here") : join(with_reference, true)) +
                 "), or \"energy\" for the energy-balance error");
  }
  if (plan.plot.empty())
    for (std::size_t k = 0; k < plan.metrics.size(); ++k)
      if (plan.has_reference(k)) {
        plan.plot = plan.metrics[k].name;
        break;
      }
  if (plan.plot.empty()) plan.plot = "energy";
  // The value plotted against the runs' resolution.
  plan.plot_value = s.string("plot_value", "");
  plan.x_label = s.string("x_label", plan.x_label);
  if (s.has("plot_value")) {
    std::vector<std::string> columns;
    for (const MetricSpec& m : plan.metrics)
      for (const std::string& c : value_columns(m)) columns.push_back(c);
    if (std::find(columns.begin(), columns.end(), plan.plot_value) == columns.end())
      s.fail("plot_value",
             "names the value column plotted against resolution: " +
                 (columns.empty() ? std::string("this study has no metric") : join(columns, true)));
    if (std::none_of(plan.runs.begin(), plan.runs.end(),
                     [](const StudyRun& r) { return r.resolution.has_value(); }))
      s.fail("plot_value",
             "plots the value against the runs' resolution, and no [[runs]] table gives one: "
             "resolution = ... (or [...], one run per value)");
  }
  // Build every run's scene now: a mistake stops the study before the first run.
  for (const StudyRun& run : plan.runs) {
    const Scene scene = build_run_scene(plan, run);
    for (const MetricSpec& m : plan.metrics) {
      for (const std::string& name : m.probes) {
        const auto p = std::find_if(scene.probes.begin(), scene.probes.end(),
                                    [&](const ProbeSpec& probe) { return probe.name == name; });
        if (p == scene.probes.end())
          throw InputError(m.where,
                           m.kind == MetricKind::wave_front ? "metrics.probes" : "metrics.probe",
                           "metric \"" + m.name + "\" reads probe \"" + name + "\", which run \"" +
                               run.label + "\" (scene " + run.scene_path + ") does not have");
        if (m.kind == MetricKind::force && p->kind != ProbeKind::force)
          throw InputError(m.where, "metrics.probe",
                           "a force metric reads a force probe (force = \"wall1\", a contact's "
                           "name, ...); probe \"" +
                               name + "\" is a " + to_string(p->kind) + " probe");
        const std::vector<std::string> columns = probe_columns(p->kind);
        if (std::find(columns.begin(), columns.end(), m.quantity) == columns.end())
          throw InputError(m.where, "metrics.quantity",
                           "probe \"" + name + "\" is a " + to_string(p->kind) +
                               " probe; its columns are " + join(columns, true));
        if (m.kind == MetricKind::wave_front &&
            (p->kind == ProbeKind::mean_velocity || p->kind == ProbeKind::extreme))
          throw InputError(
              m.where, "metrics.probes",
              "a wave front is timed at probes with a place (particle, node, element); "
              "probe \"" +
                  name + "\" is a " + to_string(p->kind) + " probe");
      }
      if (m.body.empty()) continue;
      const auto b = std::find_if(scene.bodies.begin(), scene.bodies.end(),
                                  [&](const BodySpec& body) { return body.name == m.body; });
      if (b == scene.bodies.end())
        throw InputError(m.where, "metrics.body",
                         "metric \"" + m.name + "\" measures body \"" + m.body +
                             "\", which run \"" + run.label + "\" (scene " + run.scene_path +
                             ") does not have");
      const auto* bar = std::get_if<CylinderShape>(&b->shape);
      if (m.kind == MetricKind::taylor && (bar == nullptr || bar->top_radius >= 0.0))
        throw InputError(m.where, "metrics.body",
                         "a taylor metric measures a cylinder; body \"" + m.body + "\" of " +
                             run.scene_path + " is not one");
    }
  }
  return plan;
}

StudyPlan read_study(const std::string& path) {
  return parse_study(read_text(path, "study file"), path);
}

Scene build_run_scene(const StudyPlan& plan, const StudyRun& run) {
  const std::string text = read_text(run.scene_path, "scene file");
  toml::table root = parse_toml(text, run.scene_path);
  std::string context = "run \"" + run.label + "\" (scene " + run.scene_path;
  for (std::size_t i = 0; i < run.overrides.size(); ++i)
    context += (i == 0 ? " with " : ", ") + run.overrides[i].path + " = " + run.overrides[i].value;
  context += "): ";
  for (const StudyRun::Override& o : run.overrides) {
    auto fail = [&](const std::string& message) -> void {
      throw InputError(run.where, "set." + o.path, message);
    };
    std::vector<std::string> segments;
    std::stringstream ss(o.path);
    for (std::string seg; std::getline(ss, seg, '.');) segments.push_back(seg);
    if (segments.empty() || std::any_of(segments.begin(), segments.end(),
                                        [](const std::string& x) { return x.empty(); }))
      fail("a scene key as a dotted path: \"grid.cell\", \"bodies.NAME.mesh.size\"");
    toml::table* t = &root;
    std::string walked;
    for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
      walked += (walked.empty() ? "" : ".") + segments[i];
      toml::node* n = t->get(segments[i]);
      if (!n) {  // a table the scene left out ([mpm] with its defaults): start it
        t = t->insert_or_assign(segments[i], toml::table{}).first->second.as_table();
      } else if (toml::table* sub = n->as_table()) {
        t = sub;
      } else if (n->is_array_of_tables()) {
        if (i + 2 >= segments.size())
          fail("'" + walked + "' is a list of tables: name the element and the key, '" + walked +
               ".NAME.KEY' (or '" + walked + ".INDEX.KEY', counted from 0)");
        toml::array& a = *n->as_array();
        const std::string& pick = segments[i + 1];
        std::vector<std::string> names;
        toml::table* found = nullptr;
        for (auto& e : a) {
          toml::table& et = *e.as_table();
          const std::string name = et["name"].value_or(std::string());
          if (!name.empty()) names.push_back(name);
          if (name == pick) found = &et;
        }
        // Tables without names ([[constraints]], [[phases]]) are picked by their index, counted
        // from 0 as the scene's messages count them ("constraints[2]").
        const bool index =
            pick.size() <= 9 && pick.find_first_not_of("0123456789") == std::string::npos;
        if (!found && index && std::stoul(pick) < a.size())
          found = a.get(std::stoul(pick))->as_table();
        if (!found && names.empty())
          fail("scene " + run.scene_path + " has no '" + walked + "' " +
               (index ? "numbered " + pick : "named \"" + pick + "\"") +
               "; its tables have no names: pick one by its index, 0 to " +
               std::to_string(a.size() - 1));
        if (!found)
          fail("scene " + run.scene_path + " has no '" + walked + "' named \"" + pick +
               "\"; it has " + join(names, true));
        t = found;
        ++i;
        walked += "." + segments[i];
      } else {
        fail("'" + walked + "' in scene " + run.scene_path + " is not a table");
      }
    }
    const toml::table value = parse_toml("v = " + o.value, plan.path);
    value.get("v")->visit([&](const auto& v) { t->insert_or_assign(segments.back(), v); });
  }
  try {
    return core::scene_detail::scene_from_toml(root, run.scene_path);
  } catch (const InputError& e) {
    throw InputError(run.where, "runs", context + e.what());
  }
}

}  // namespace afemp::analysis
