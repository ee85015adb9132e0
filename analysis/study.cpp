#include "analysis/study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "afemp/errors.hpp"
#include "analysis/crater_metrics.hpp"
#include "analysis/reference_checks.hpp"
#include "analysis/signal_metrics.hpp"
#include "analysis/svg_plot.hpp"
#include "analysis/taylor_metrics.hpp"
#include "core/parallel.hpp"
#include "coupling/make_model.hpp"

namespace afemp::analysis {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

int body_index(const core::Scene& scene, const std::string& name) {
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (scene.bodies[b].name == name) return static_cast<int>(b);
  return -1;  // read_study checked every run's scene
}

// A metric's value relative to its reference: |v - v_ref| / |v_ref|.
double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// The probe history a metric reads, and the column of its quantity.
const core::ProbeSeries& probe_series(const core::RunSummary& s, const std::string& name) {
  for (const core::ProbeSeries& p : s.probes)
    if (p.name == name) return p;
  throw std::logic_error("probe \"" + name + "\" not recorded");  // read_study checked the scenes
}

// Appends the metric's values (in value_columns order) and returns its error against the
// run's reference (NaN without one). initial_level: a crater metric's surface level at the
// start (analysis/crater_metrics.hpp).
double measure(const MetricSpec& m, const MetricReference& reference, const core::Scene& scene,
               const core::Model& model, const core::RunSummary& summary, double initial_level,
               std::vector<double>& values) {
  const int b = m.body.empty() ? -1 : body_index(scene, m.body);
  double value = nan;
  switch (m.kind) {
    case MetricKind::taylor: {
      const core::BodyPoints points = model.body_points(b);
      const core::TaylorMeasures t = measure_taylor(scene, b, points.position, points.half_size);
      values.insert(values.end(), {t.length, t.impact_diameter, t.bulge_diameter});
      return reference.taylor ? taylor_mean_error(t, *reference.taylor) : nan;
    }
    case MetricKind::crater: {
      const std::vector<core::Vec3> points = model.body_points(b).position;
      const CraterMeasures c =
          measure_crater(points, m.point, m.normal, initial_level, m.ring, m.threshold);
      values.insert(values.end(), {c.depth, c.diameter});
      if (!reference.crater) return nan;
      return 0.5 * (relative_error(c.depth, reference.crater->depth) +
                    relative_error(c.diameter, reference.crater->diameter));
    }
    case MetricKind::velocity: {
      const core::BodySums body = model.energies().bodies[static_cast<std::size_t>(b)];
      const core::Vec3 v = (1.0 / body.mass) * body.momentum;
      value = m.component < 0 ? core::norm(v) : v[m.component];
      break;
    }
    case MetricKind::hole:
      value = measure_hole(model.body_points(b).position, m.point, m.normal, m.band);
      break;
    case MetricKind::wave_front: {
      // Distances along the path from the first probe's place at the start.
      std::vector<double> distance, arrival;
      core::Vec3 first;
      for (std::size_t k = 0; k < m.probes.size(); ++k) {
        const core::ProbeSeries& p = probe_series(summary, m.probes[k]);
        const core::Vec3 x0{p.at(0, 0), p.at(0, 1), p.at(0, 2)};
        if (k == 0) first = x0;
        distance.push_back(core::norm(x0 - first));
        const std::vector<double> q = p.series(static_cast<std::size_t>(p.column(m.quantity)));
        std::size_t n = p.rows();  // `until`: the samples up to it
        if (m.until > 0.0)
          n = static_cast<std::size_t>(std::upper_bound(p.time.begin(), p.time.end(), m.until) -
                                       p.time.begin());
        arrival.push_back(
            arrival_time(std::span(p.time).first(n), std::span(q).first(n), m.fraction));
      }
      value = front_speed(distance, arrival);
      break;
    }
    case MetricKind::frequency: {
      const core::ProbeSeries& p = probe_series(summary, m.probes[0]);
      value =
          zero_crossing_frequency(p.time, p.series(static_cast<std::size_t>(p.column(m.quantity))));
      break;
    }
    case MetricKind::force: {
      const core::ProbeSeries& p = probe_series(summary, m.probes[0]);
      value = p.at(p.rows() - 1, static_cast<std::size_t>(p.column(m.quantity)));
      break;
    }
  }
  values.push_back(value);
  return reference.scalar ? reference_error(value, *reference.scalar) : nan;
}

// Whether metric k's references are listed as two bounds: it has a band in some run.
bool listed_as_bounds(const StudyPlan& plan, std::size_t k) {
  return std::any_of(plan.runs.begin(), plan.runs.end(), [&](const StudyRun& r) {
    return r.references[k].scalar && r.references[k].scalar->band;
  });
}

// The reference columns of a metric with a reference (StudyResult::reference_columns).
std::vector<std::string> reference_columns(const MetricSpec& m, bool bounds) {
  switch (m.kind) {
    case MetricKind::taylor:
      return {m.name + ".reference_L", m.name + ".reference_D", m.name + ".reference_W"};
    case MetricKind::crater:
      return {m.name + ".reference_depth", m.name + ".reference_diameter"};
    default:
      if (bounds) return {m.name + ".reference_low", m.name + ".reference_high"};
      return {m.name + ".reference"};
  }
}

// A run's reference in those columns (NaN where it has none).
void append_reference(const MetricSpec& m, const MetricReference& r, bool bounds,
                      std::vector<double>& out) {
  switch (m.kind) {
    case MetricKind::taylor:
      if (r.taylor)
        out.insert(out.end(),
                   {r.taylor->length, r.taylor->impact_diameter, r.taylor->bulge_diameter});
      else
        out.insert(out.end(), {nan, nan, nan});
      return;
    case MetricKind::crater:
      if (r.crater)
        out.insert(out.end(), {r.crater->depth, r.crater->diameter});
      else
        out.insert(out.end(), {nan, nan});
      return;
    default:
      out.push_back(r.scalar ? r.scalar->low : nan);
      if (bounds) out.push_back(r.scalar ? r.scalar->high : nan);
  }
}

std::string number(double v, const char* format = "%.6g") {
  if (std::isnan(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// A CSV field, quoted when it holds a comma, quote or newline.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string status(const StudyRow& row) {
  if (!row.stopped.empty()) return "stopped: " + row.stopped;
  if (row.over_tolerance.empty()) return "ok";
  std::string s = "over tolerance:";
  for (const std::string& m : row.over_tolerance) s += " " + m;
  return s;
}

// The plot_value column against the runs' resolution (runs without one left out), one line per
// method, and after them the references for it, dashed: "reference" for single values (a
// crater's or Taylor bar's: the column's component), "reference low" and "reference high" for
// bands. Each line runs in the order of resolution; runs of several methods at one resolution
// share their reference's point.
LinePlot value_plot(const StudyPlan& plan, const StudyResult& result) {
  LinePlot plot;
  plot.title = plan.title;
  plot.x_label = plan.x_label;
  plot.y_label = plan.plot_value;
  const std::size_t column = static_cast<std::size_t>(
      std::find(result.value_columns.begin(), result.value_columns.end(), plan.plot_value) -
      result.value_columns.begin());
  std::size_t metric = 0, component = 0;  // the column's metric, and which of its values
  for (std::size_t k = 0; k < plan.metrics.size(); ++k) {
    const std::vector<std::string> columns = value_columns(plan.metrics[k]);
    const auto it = std::find(columns.begin(), columns.end(), plan.plot_value);
    if (it != columns.end()) metric = k, component = static_cast<std::size_t>(it - columns.begin());
  }
  std::vector<PlotSeries> lines, references;
  auto add = [&](std::vector<PlotSeries>& to, const std::string& name, double x, double y) {
    auto it =
        std::find_if(to.begin(), to.end(), [&](const PlotSeries& s) { return s.name == name; });
    if (it == to.end()) it = to.insert(to.end(), PlotSeries{name, {}, {}, &to == &references});
    it->x.push_back(x);
    it->y.push_back(y);
  };
  for (const StudyRow& r : result.rows) {
    if (!r.run->resolution) continue;
    const double x = *r.run->resolution;
    add(lines, r.run->method, x, r.values[column]);
    const MetricReference& ref = r.run->references[metric];
    if (ref.taylor) {
      const double c[] = {ref.taylor->length, ref.taylor->impact_diameter,
                          ref.taylor->bulge_diameter};
      add(references, "reference", x, c[component]);
    } else if (ref.crater) {
      add(references, "reference", x, component == 0 ? ref.crater->depth : ref.crater->diameter);
    } else if (ref.scalar && ref.scalar->band) {
      add(references, "reference low", x, ref.scalar->low);
      add(references, "reference high", x, ref.scalar->high);
    } else if (ref.scalar) {
      add(references, "reference", x, ref.scalar->low);
    }
  }
  for (std::vector<PlotSeries>* group : {&lines, &references})
    for (PlotSeries& s : *group) {
      std::vector<std::pair<double, double>> points;
      for (std::size_t i = 0; i < s.x.size(); ++i) points.emplace_back(s.x[i], s.y[i]);
      std::stable_sort(points.begin(), points.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      if (s.dashed) points.erase(std::unique(points.begin(), points.end()), points.end());
      s.x.clear(), s.y.clear();
      for (const auto& [x, y] : points) s.x.push_back(x), s.y.push_back(y);
    }
  plot.series = std::move(lines);
  plot.series.insert(plot.series.end(), references.begin(), references.end());
  return plot;
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out)
    throw core::InputError(core::SourceLocation{path.string(), 0}, "",
                           "cannot write '" + path.string() + "'");
}

}  // namespace

double reference_error(double value, const ScalarReference& reference) {
  if (std::isnan(value)) return value;
  if (value < reference.low) return (reference.low - value) / std::abs(reference.low);
  if (value > reference.high) return (value - reference.high) / std::abs(reference.high);
  return 0.0;
}

double StudyResult::plotted_error(const StudyPlan& plan, const StudyRow& row) const {
  if (plan.plot == "energy") return std::abs(row.energy_error);
  const auto it = std::find(error_columns.begin(), error_columns.end(), plan.plot + ".error");
  return it == error_columns.end()
             ? nan
             : row.errors[static_cast<std::size_t>(it - error_columns.begin())];
}

StudyResult run_study(const StudyPlan& plan,
                      const std::function<void(const StudyResult&, const StudyRow&)>& report) {
  StudyResult result;
  std::vector<bool> has_reference, bounds;
  for (std::size_t k = 0; k < plan.metrics.size(); ++k) {
    const MetricSpec& m = plan.metrics[k];
    for (const std::string& c : value_columns(m)) result.value_columns.push_back(c);
    has_reference.push_back(plan.has_reference(k));
    bounds.push_back(listed_as_bounds(plan, k));
    if (!has_reference[k]) continue;
    result.error_columns.push_back(m.name + ".error");
    for (const std::string& c : reference_columns(m, bounds[k]))
      result.reference_columns.push_back(c);
  }
  const int threads_before = core::thread_count();
  if (plan.threads > 0) core::set_thread_count(plan.threads);
  for (const StudyRun& run : plan.runs) {
    const core::Scene scene = build_run_scene(plan, run);
    StudyRow row;
    row.run = &run;
    row.threads = core::thread_count();
    for (std::size_t k = 0; k < plan.metrics.size(); ++k)
      if (has_reference[k])
        append_reference(plan.metrics[k], run.references[k], bounds[k], row.references);
    const std::unique_ptr<core::Model> model = coupling::make_model(scene);
    row.elements = model->element_count();
    core::RunOptions options;  // no output directory: nothing written, nothing timed but the steps
    // Crater metrics: the target's surface level at the start, on the same points.
    std::vector<double> initial_level(plan.metrics.size(), nan);
    for (std::size_t k = 0; k < plan.metrics.size(); ++k) {
      const MetricSpec& m = plan.metrics[k];
      if (m.kind == MetricKind::crater)
        initial_level[k] = surface_level(model->body_points(body_index(scene, m.body)).position,
                                         m.point, m.normal);
    }
    const auto start = std::chrono::steady_clock::now();
    try {
      const core::RunSummary s = analysis::run(*model, scene, options);
      row.steps = s.steps;
      row.wall_seconds = s.wall_seconds;
      row.energy_error = s.energy_error;
      row.max_energy_error = s.max_energy_error;
      for (std::size_t k = 0; k < plan.metrics.size(); ++k) {
        const MetricSpec& m = plan.metrics[k];
        const double error =
            measure(m, run.references[k], scene, *model, s, initial_level[k], row.values);
        if (!has_reference[k]) continue;
        row.errors.push_back(error);
        // A run without a reference for the metric reports its value only.
        if (m.tolerance > 0.0 && run.references[k].has_value() && !(error <= m.tolerance))
          row.over_tolerance.push_back(m.name);
      }
      if (plan.energy_tolerance > 0.0 && !(row.max_energy_error <= plan.energy_tolerance))
        row.over_tolerance.push_back("energy");
    } catch (const core::SimulationError& err) {
      // The wall time up to the stop (the message names the step and time it stopped at).
      row.wall_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      row.stopped = err.what();
      row.steps = model->step_count();
      row.values.assign(result.value_columns.size(), nan);
      row.errors.assign(result.error_columns.size(), nan);
      row.energy_error = nan;
      row.max_energy_error = nan;
    }
    row.particles = model->particle_count();
    result.rows.push_back(std::move(row));
    if (report) report(result, result.rows.back());
  }
  core::set_thread_count(threads_before);
  return result;
}

std::string describe_row(const StudyResult& result, const StudyRow& row) {
  std::ostringstream os;
  os << row.run->label << ": " << row.steps << " steps, " << number(row.wall_seconds, "%.3g")
     << " s on " << row.threads << " thread(s)";
  if (!row.stopped.empty()) return os.str() + ", stopped: " + row.stopped;
  // "-": no value, or no reference in this run.
  for (std::size_t i = 0; i < result.value_columns.size(); ++i)
    os << ", " << result.value_columns[i] << " "
       << (std::isnan(row.values[i]) ? "-" : number(row.values[i], "%.4g"));
  for (std::size_t i = 0; i < result.error_columns.size(); ++i)
    os << ", " << result.error_columns[i] << " "
       << (std::isnan(row.errors[i]) ? "-" : number(row.errors[i], "%.4f"));
  os << ", energy error " << number(100.0 * row.energy_error, "%+.2f") << " %";
  if (!row.over_tolerance.empty()) os << " (" << status(row) << ")";
  return os.str();
}

void write_study(const StudyPlan& plan, const StudyResult& result, const std::string& directory) {
  const std::filesystem::path dir(directory);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw core::InputError(core::SourceLocation{directory, 0}, "",
                           "cannot create the output directory: " + ec.message());
  const StudyFiles files;
  // CSV: one row per run.
  std::string csv =
      "run,method,label,resolution,particles,elements,steps,wall_seconds,threads,energy_error,"
      "max_energy_error";
  for (const std::string& c : result.value_columns) csv += "," + c;
  for (const std::string& c : result.error_columns) csv += "," + c;
  for (const std::string& c : result.reference_columns) csv += "," + c;
  csv += ",status\n";
  for (std::size_t k = 0; k < result.rows.size(); ++k) {
    const StudyRow& r = result.rows[k];
    csv += std::to_string(k + 1) + "," + csv_field(r.run->method) + "," + csv_field(r.run->label) +
           "," + (r.run->resolution ? number(*r.run->resolution) : "") + "," +
           std::to_string(r.particles) + "," + std::to_string(r.elements) + "," +
           std::to_string(r.steps) + "," + number(r.wall_seconds, "%.4f") + "," +
           std::to_string(r.threads) + "," + number(r.energy_error, "%.6g") + "," +
           number(r.max_energy_error, "%.6g");
    // Appended in two steps: "," + std::string trips GCC 12's -Wrestrict.
    for (double v : r.values) (csv += ',') += number(v, "%.6g");
    for (double v : r.errors) (csv += ',') += number(v, "%.6g");
    for (double v : r.references) (csv += ',') += number(v, "%.6g");
    ((csv += ',') += csv_field(status(r))) += '\n';
  }
  write_file(dir / files.csv, csv);
  // Markdown: the same table for reading.
  std::string md = "# " + plan.title + "\n\n";
  md += "Study file `" + plan.path + "`; wall time of the time loop (no output written).\n\n";
  md +=
      "| method | resolution | particles | elements | steps | wall time (s) | threads | energy "
      "error "
      "(largest)";
  std::string rule = "|---|---|---|---|---|---|---|---";
  for (const std::string& c : result.value_columns) md += " | " + c, rule += "|---";
  for (const std::string& c : result.error_columns) md += " | " + c, rule += "|---";
  for (const std::string& c : result.reference_columns) md += " | " + c, rule += "|---";
  md += " | status |\n" + rule + "|---|\n";
  for (const StudyRow& r : result.rows) {
    md += "| " + r.run->method + " | " + (r.run->resolution ? number(*r.run->resolution) : "-") +
          " | " + std::to_string(r.particles) + " | " + std::to_string(r.elements) + " | " +
          std::to_string(r.steps) + " | " + number(r.wall_seconds, "%.3g") + " | " +
          std::to_string(r.threads) + " | " +
          (std::isnan(r.energy_error) ? std::string("-")
                                      : number(100.0 * r.energy_error, "%+.2f") + " % (" +
                                            number(100.0 * r.max_energy_error, "%.2f") + " %)");
    for (double v : r.values) md += " | " + (std::isnan(v) ? std::string("-") : number(v, "%.4g"));
    for (double v : r.errors) md += " | " + (std::isnan(v) ? std::string("-") : number(v, "%.4f"));
    for (double v : r.references)
      md += " | " + (std::isnan(v) ? std::string("-") : number(v, "%.4g"));
    std::string st = status(r);
    std::replace(st.begin(), st.end(), '|', '/');
    md += " | " + st + " |\n";
  }
  md += "\n![error against wall time](" + files.plot + ")\n";
  if (!plan.plot_value.empty())
    md += "\n![" + plan.plot_value + " against " + plan.x_label + "](" + files.value_plot + ")\n";
  write_file(dir / files.markdown, md);
  // The plot: the plotted error against wall time, one line per method in order of first
  // appearance, runs in the study's order.
  LinePlot plot;
  plot.title = plan.title;
  plot.x_label = "wall time (s), " +
                 std::to_string(result.rows.empty() ? 0 : result.rows[0].threads) + " thread(s)";
  plot.y_label = plan.plot == "energy" ? "|energy-balance error|" : plan.plot + " error";
  for (const StudyRow& r : result.rows) {
    auto it = std::find_if(plot.series.begin(), plot.series.end(),
                           [&](const PlotSeries& s) { return s.name == r.run->method; });
    if (it == plot.series.end()) {
      plot.series.push_back({r.run->method, {}, {}, false});
      it = plot.series.end() - 1;
    }
    it->x.push_back(r.wall_seconds);
    it->y.push_back(result.plotted_error(plan, r));
  }
  write_file(dir / files.plot, svg_loglog(plot));
  if (!plan.plot_value.empty())
    write_file(dir / files.value_plot, svg_linear(value_plot(plan, result)));
}

}  // namespace afemp::analysis
