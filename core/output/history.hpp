// The history CSV: one row of global energies and per-body momenta whenever the caller asks
// (every run.history_every steps). Each row is flushed at once so the file survives a crash
// and can be plotted while the run goes on.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::core {

struct BodyHistory {
  Vec3 momentum;
  Vec3 mean_velocity;
  double kinetic = 0.0;
  double internal = 0.0;  // its elements' and particles' sum m e (hourglass energy is global)
};

struct HistoryRow {
  long step = 0;
  double time = 0.0, dt = 0.0, kinetic = 0.0, internal = 0.0, elastic = 0.0, plastic = 0.0,
         viscous = 0.0, hourglass = 0.0, stabilisation = 0.0, eroded = 0.0, converted = 0.0,
         contact = 0.0, external_work = 0.0, total = 0.0, energy_error = 0.0;
  // What left through outflow faces (Energies::outflow*): written only by a writer made with
  // outflow columns.
  double outflow = 0.0, outflow_mass = 0.0;
  Vec3 outflow_momentum{};
  // internal = elastic + plastic + viscous (bulk-viscous heating); elastic includes
  // stabilisation (the strain energy of assumed-strain hourglass control);
  // total = kinetic + internal + hourglass + eroded + converted + outflow (contact is an
  // estimate of what
  // the grid contact dissipated, not part of it); energy_error: the caller's relative
  // balance error (core/energies.hpp).
  std::vector<BodyHistory> bodies;  // one per body name, in the writer's order
  std::vector<double> extra;        // one per extra column, in the writer's order
};

// Columns: step,time,dt,kinetic,internal,elastic,plastic,viscous,hourglass,stabilisation,eroded,
// converted,contact,external_work,total,energy_error,
// with outflow faces also outflow,outflow_mass,outflow_px,outflow_py,outflow_pz,
// then per body NAME: NAME.px,NAME.py,NAME.pz,NAME.vx,NAME.vy,NAME.vz,NAME.kinetic,
// NAME.internal (like LS-DYNA's MATSUM per part), then the extra columns.
// step is printed as an integer, every other value with "%.10e" (11 significant digits).
class HistoryWriter {
 public:
  // Creates the parent directory if needed, truncates the file and writes the header.
  // Throws std::runtime_error naming the path and the reason if it cannot; throws
  // std::invalid_argument for an empty body name or one containing ',', '"' or a newline.
  // outflow: the scene has outflow faces (their columns are written).
  // extra: columns after the body columns (penalty contacts' sliding and friction energies,
  // interface forces), written from HistoryRow::extra.
  HistoryWriter(std::string path, std::vector<std::string> body_names, bool outflow = false,
                std::vector<std::string> extra = {});
  // Continues the file of an earlier run (a restart): checks its header is the one these
  // columns give, cuts it to `bytes` (its length at the checkpoint: rows written after it go)
  // and appends from there; `rows` is the count written up to then.
  struct Resume {
    std::size_t bytes = 0, rows = 0;
  };
  HistoryWriter(std::string path, std::vector<std::string> body_names, bool outflow,
                std::vector<std::string> extra, Resume resume);

  // Appends and flushes one row. Throws std::invalid_argument if row.bodies does not have
  // one entry per body name, std::runtime_error if the write fails (e.g. disk full).
  void write(const HistoryRow& row);

  const std::string& path() const { return path_; }
  std::size_t rows() const { return rows_; }
  // Bytes in the file so far (all flushed).
  std::size_t bytes() const { return bytes_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::string path_;
  std::vector<std::string> body_names_;
  bool outflow_ = false;
  std::vector<std::string> extra_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  std::string line_;  // reused row buffer
  std::size_t rows_ = 0;
  std::size_t bytes_ = 0;
  std::string header() const;
};

// A numeric CSV read back (for tests and tools): the first line is the header, every other
// non-empty line a row of numbers ("nan" and "inf" included).
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  // Index of a header name; throws std::out_of_range naming it if absent.
  std::size_t column(const std::string& name) const;
};

// Throws std::runtime_error naming the file and line on a missing file, a non-number, or a
// row whose length differs from the header's.
CsvTable read_csv(const std::string& path);

}  // namespace afemp::core
