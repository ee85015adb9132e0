// The probe recorder of core/probe_recorder.hpp.
#include "core/probe_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "core/output/run_directory.hpp"
#include "core/state_archive.hpp"

namespace afemp::core {

ProbeRecorder::ProbeRecorder(Model& model, const std::vector<ProbeSpec>& probes,
                             const std::string& directory, bool resume)
    : specs_(probes),
      next_(probes.size(), 0.0),
      due_(probes.size(), 0),
      buffer_(probe_stride * probes.size()) {
  model.resolve_probes(specs_);
  const std::vector<std::string> force_names = model.force_columns();
  for (const ProbeSpec& p : specs_) {
    ProbeSeries s;
    s.name = p.name;
    s.kind = p.kind;
    s.columns = probe_columns(p.kind);
    std::vector<std::size_t> reads;
    if (p.kind == ProbeKind::force) {
      // The model's columns TARGET.*, whose suffixes become the probe's columns.
      s.columns.clear();
      const std::string prefix = p.target + ".";
      std::vector<std::string> groups;
      for (std::size_t c = 0; c < force_names.size(); ++c) {
        const std::string& n = force_names[c];
        if (n.compare(0, prefix.size(), prefix) == 0) {
          reads.push_back(c);
          s.columns.push_back(n.substr(prefix.size()));
        }
        const std::string group = n.substr(0, n.rfind('.'));
        if (groups.empty() || groups.back() != group) groups.push_back(group);
      }
      if (reads.empty()) {
        std::string known;
        for (const std::string& g : groups) known += (known.empty() ? "\"" : ", \"") + g + "\"";
        throw InputError(p.where, p.key + ".force",
                         "no contact, wall, rigid or bonded body reports forces as \"" + p.target +
                             "\"; those of this scene: " + (known.empty() ? "(none)" : known));
      }
    }
    force_columns_.push_back(std::move(reads));
    series_.push_back(std::move(s));
  }
  if (directory.empty() || specs_.empty()) return;
  const std::filesystem::path dir = std::filesystem::path(directory) / "probes";
  directory_ = dir.string();
  if (resume) return;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create: " + ec.message());
  for (const ProbeSeries& s : series_) {
    const std::string file = path(s);
    files_.emplace_back(file, std::ios::trunc);
    if (!files_.back()) throw std::runtime_error(file + ": cannot write");
    files_.back() << "time";
    for (const std::string& c : s.columns) files_.back() << ',' << c;
    files_.back() << '\n';
  }
}

std::string ProbeRecorder::path(const ProbeSeries& s) const {
  return (std::filesystem::path(directory_) / (s.name + ".csv")).string();
}

void ProbeRecorder::state(StateArchive& a) {
  const StateArchive::Group group(a, "probes");
  std::vector<std::uint64_t> bytes;
  if (!a.loading())
    for (std::ofstream& f : files_) {
      f.flush();
      if (!f) throw std::runtime_error("probe file: cannot write (disk full?)");
      bytes.push_back(static_cast<std::uint64_t>(f.tellp()));
    }
  a.item("bytes", bytes);
  a.item("next", next_);
  std::uint64_t n = series_.size();
  a.item("count", n);
  if (n != series_.size())
    throw CheckpointError(a.where("count") + ": " + std::to_string(n) +
                          " probes in the checkpoint, " + std::to_string(series_.size()) +
                          " in the scene");
  for (std::size_t k = 0; k < series_.size(); ++k) {
    const StateArchive::Group one(a, std::to_string(k));
    a.item("time", series_[k].time);
    a.item("values", series_[k].values);
  }
  if (!a.loading() || directory_.empty()) return;
  if (bytes.size() != series_.size())
    throw CheckpointError(a.where("bytes") + ": the checkpointed run wrote no probe files");
  for (std::size_t k = 0; k < series_.size(); ++k) {
    const std::string file = path(series_[k]);
    cut_to_checkpoint(file, bytes[k]);
    files_.emplace_back(file, std::ios::app);
    if (!files_.back()) throw std::runtime_error(file + ": cannot write");
  }
}

void ProbeRecorder::sample(const Model& model, bool history_row, bool last) {
  const double t = model.time();
  bool any = false;
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    const double interval = specs_[k].interval;
    const ProbeSeries& s = series_[k];
    const bool fresh = s.time.empty() || s.time.back() < t;
    bool due = fresh && (interval > 0.0 ? t >= next_[k] * (1.0 - 1e-9) : history_row);
    if (last && fresh) due = true;
    due_[k] = due ? 1 : 0;
    any = any || due;
    if (due && interval > 0.0)
      while (next_[k] <= t * (1.0 + 1e-9)) next_[k] += interval;
  }
  if (!any) return;
  std::fill(buffer_.begin(), buffer_.end(), std::numeric_limits<double>::quiet_NaN());
  model.sample_probes(buffer_);
  forces_.clear();
  bool energies_read = false;
  Energies e;
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    if (!due_[k]) continue;
    const ProbeSpec& p = specs_[k];
    double* v = buffer_.data() + k * probe_stride;
    if (p.kind == ProbeKind::force) {
      // A rigid body reports up to 12 columns, more than probe_stride: its own row.
      if (forces_.empty()) model.force_values(forces_);
      force_row_.resize(force_columns_[k].size());
      for (std::size_t c = 0; c < force_columns_[k].size(); ++c)
        force_row_[c] = forces_[force_columns_[k][c]];
      v = force_row_.data();
    }
    if (p.kind == ProbeKind::mean_velocity) {
      if (!energies_read) e = model.energies(), energies_read = true;
      const BodySums& b = e.bodies.at(static_cast<std::size_t>(p.body));
      // The mean velocity is the momentum over the mass (the centre of mass's velocity).
      const Vec3 mean = b.mass > 0.0 ? (1.0 / b.mass) * b.momentum : Vec3{};
      v[0] = mean.x, v[1] = mean.y, v[2] = mean.z;
    }
    ProbeSeries& s = series_[k];
    s.time.push_back(t);
    s.values.insert(s.values.end(), v, v + s.columns.size());
    if (files_.empty()) continue;
    std::ofstream& f = files_[k];
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", t);
    f << buf;
    for (std::size_t c = 0; c < s.columns.size(); ++c) {
      if (std::isnan(v[c]))
        f << ",nan";
      else {
        std::snprintf(buf, sizeof buf, ",%.9g", v[c]);
        f << buf;
      }
    }
    f << '\n';
  }
}

}  // namespace afemp::core
