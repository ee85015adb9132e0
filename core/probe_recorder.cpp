// The probe recorder of core/probe_recorder.hpp.
#include "core/probe_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

namespace afemp::core {

ProbeRecorder::ProbeRecorder(Model& model, const std::vector<ProbeSpec>& probes,
                             const std::string& directory)
    : specs_(probes), next_(probes.size(), 0.0), due_(probes.size(), 0),
      buffer_(probe_stride * probes.size()) {
  model.resolve_probes(specs_);
  for (const ProbeSpec& p : specs_) {
    ProbeSeries s;
    s.name = p.name;
    s.kind = p.kind;
    s.columns = probe_columns(p.kind);
    series_.push_back(std::move(s));
  }
  if (directory.empty() || specs_.empty()) return;
  const std::filesystem::path dir = std::filesystem::path(directory) / "probes";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create: " + ec.message());
  for (const ProbeSeries& s : series_) {
    const std::string path = (dir / (s.name + ".csv")).string();
    files_.emplace_back(path, std::ios::trunc);
    if (!files_.back()) throw std::runtime_error(path + ": cannot write");
    files_.back() << "time";
    for (const std::string& c : s.columns) files_.back() << ',' << c;
    files_.back() << '\n';
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
  bool energies_read = false;
  Energies e;
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    if (!due_[k]) continue;
    const ProbeSpec& p = specs_[k];
    double* v = buffer_.data() + k * probe_stride;
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
