// History CSV writing with stdio (one formatted line, one fwrite, one fflush per row) and the
// matching reader. "%.10e" keeps 11 significant digits: enough to see a 1e-10 energy drift,
// short enough to read in a terminal.
#include "core/output/history.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "core/output/run_directory.hpp"

namespace afemp::core {

namespace {

void append_number(std::string& line, double v) {
  char buf[40];
  const int len = std::snprintf(buf, sizeof buf, ",%.10e", v);
  line.append(buf, static_cast<std::size_t>(len));
}

std::string errno_text(int err) {
  return std::error_code(err, std::generic_category()).message();
}

}  // namespace

HistoryWriter::HistoryWriter(std::string path, std::vector<std::string> body_names, bool outflow,
                             std::vector<std::string> extra)
    : path_(std::move(path)),
      body_names_(std::move(body_names)),
      outflow_(outflow),
      extra_(std::move(extra)) {
  for (const std::string& name : body_names_)
    if (name.empty() || name.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument("HistoryWriter: body name '" + name +
                                  "' cannot be a CSV column prefix (empty, or has , \" or a "
                                  "line break)");
  const std::filesystem::path parent = std::filesystem::path(path_).parent_path();
  if (!parent.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    if (ec)
      throw std::runtime_error(parent.string() +
                               ": cannot create output directory: " + ec.message());
  }
  errno = 0;
  file_.reset(std::fopen(path_.c_str(), "w"));
  if (!file_)
    throw std::runtime_error(path_ + ": cannot create history file: " + errno_text(errno));
  const std::string head = header();
  if (std::fwrite(head.data(), 1, head.size(), file_.get()) != head.size() ||
      std::fflush(file_.get()) != 0)
    throw std::runtime_error(path_ + ": cannot write history header: " + errno_text(errno));
  bytes_ = head.size();
}

HistoryWriter::HistoryWriter(std::string path, std::vector<std::string> body_names, bool outflow,
                             std::vector<std::string> extra, Resume resume)
    : path_(std::move(path)),
      body_names_(std::move(body_names)),
      outflow_(outflow),
      extra_(std::move(extra)) {
  const std::string head = header();
  if (resume.bytes < head.size())
    throw std::runtime_error(path_ + ": cannot continue the history: the checkpoint counts " +
                             std::to_string(resume.bytes) + " bytes, less than its header");
  {
    std::ifstream in(path_, std::ios::binary);
    std::string first(head.size(), '\0');
    in.read(first.data(), static_cast<std::streamsize>(first.size()));
    if (first != head)
      throw std::runtime_error(path_ +
                               ": cannot continue the history: its columns are not the "
                               "ones this scene writes");
  }
  cut_to_checkpoint(path_, resume.bytes);
  errno = 0;
  file_.reset(std::fopen(path_.c_str(), "ab"));
  if (!file_)
    throw std::runtime_error(path_ + ": cannot append to the history: " + errno_text(errno));
  bytes_ = resume.bytes;
  rows_ = resume.rows;
}

std::string HistoryWriter::header() const {
  std::string header =
      "step,time,dt,kinetic,internal,elastic,plastic,viscous,hourglass,"
      "stabilisation,eroded,converted,contact,external_work,total,energy_error";
  if (outflow_) header += ",outflow,outflow_mass,outflow_px,outflow_py,outflow_pz";
  for (const std::string& name : body_names_)
    for (const char* c : {".px", ".py", ".pz", ".vx", ".vy", ".vz", ".kinetic", ".internal"})
      header += "," + name + c;
  for (const std::string& name : extra_) header += "," + name;
  header += '\n';
  return header;
}

void HistoryWriter::write(const HistoryRow& row) {
  if (row.bodies.size() != body_names_.size())
    throw std::invalid_argument("HistoryWriter::write: row has " +
                                std::to_string(row.bodies.size()) + " bodies, the file has " +
                                std::to_string(body_names_.size()) + " (" + path_ + ")");
  line_ = std::to_string(row.step);
  for (const double v : {row.time, row.dt, row.kinetic, row.internal, row.elastic, row.plastic,
                         row.viscous, row.hourglass, row.stabilisation, row.eroded, row.converted,
                         row.contact, row.external_work, row.total, row.energy_error})
    append_number(line_, v);
  if (outflow_) {
    append_number(line_, row.outflow);
    append_number(line_, row.outflow_mass);
    for (int i = 0; i < 3; ++i) append_number(line_, row.outflow_momentum[i]);
  }
  for (const BodyHistory& b : row.bodies) {
    for (int i = 0; i < 3; ++i) append_number(line_, b.momentum[i]);
    for (int i = 0; i < 3; ++i) append_number(line_, b.mean_velocity[i]);
    append_number(line_, b.kinetic);
    append_number(line_, b.internal);
  }
  if (row.extra.size() != extra_.size())
    throw std::invalid_argument("HistoryWriter::write: row has " +
                                std::to_string(row.extra.size()) + " extra values, the file has " +
                                std::to_string(extra_.size()) + " columns (" + path_ + ")");
  for (const double v : row.extra) append_number(line_, v);
  line_ += '\n';
  if (std::fwrite(line_.data(), 1, line_.size(), file_.get()) != line_.size() ||
      std::fflush(file_.get()) != 0)
    throw std::runtime_error(path_ + ": cannot write history row at step " +
                             std::to_string(row.step) + ": " + errno_text(errno));
  ++rows_;
  bytes_ += line_.size();
}

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  throw std::out_of_range("CSV has no column '" + name + "'");
}

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open CSV file: " + errno_text(errno));
  CsvTable table;
  std::string line;
  int line_no = 0;
  auto split = [](const std::string& s) {
    std::vector<std::string> cells;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = s.find(',', start);
      cells.push_back(s.substr(start, comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    return cells;
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (table.header.empty()) {
      table.header = split(line);
      continue;
    }
    const std::vector<std::string> cells = split(line);
    if (cells.size() != table.header.size())
      throw std::runtime_error(path + ":" + std::to_string(line_no) + ": " +
                               std::to_string(cells.size()) + " values, header has " +
                               std::to_string(table.header.size()));
    std::vector<double> values;
    values.reserve(cells.size());
    for (const std::string& cell : cells) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (cell.empty() || end != cell.c_str() + cell.size())
        throw std::runtime_error(path + ":" + std::to_string(line_no) + ": '" + cell +
                                 "' is not a number");
      values.push_back(v);
    }
    table.rows.push_back(std::move(values));
  }
  if (table.header.empty()) throw std::runtime_error(path + ": empty CSV file (no header)");
  return table;
}

}  // namespace afemp::core
