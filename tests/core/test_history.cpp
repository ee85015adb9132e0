// HistoryWriter and the output path conventions: the header names per-body columns, rows
// read back to 1e-10 relative, each row is on disk as soon as write() returns, and errors
// name the path.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/output/history.hpp"
#include "core/output/run_directory.hpp"
#include "scratch_dir.hpp"

namespace afemp::core {
namespace {

namespace fs = std::filesystem;

using TempDir = afemp::test::ScratchDir;

HistoryRow make_row(int r) {
  HistoryRow row;
  row.step = 100L * r;
  row.time = 1.0e-3 * r / 3.0;
  row.dt = 1.234567890123e-7;
  row.kinetic = 5.5e3 - 1.0 / (r + 1.0);
  row.internal = 7.0 / 3.0 * r;
  row.elastic = 0.1 * r;
  row.viscous = 0.01 * r;
  row.plastic = row.internal - row.elastic - row.viscous;
  row.hourglass = 1.0e-3 * r;
  row.stabilisation = 2.0e-4 * r;
  row.eroded = r / 11.0;
  row.converted = r / 13.0;
  row.contact = 0.125 * r;
  row.external_work = -2.0e-9 * r;
  row.total = row.kinetic + row.internal + row.hourglass + row.eroded + row.converted;
  row.energy_error = r == 0 ? 0.0 : 3.3e-12 * r;
  row.bodies = {{{1.0 + r, -2.0 / 3.0, 1e5}, {0.5, 0.25 * r, -190.0}, 0.75 * r, 1.0 / 3.0},
                {{0.0, 0.0, -1.0 / 7.0}, {r / 9.0, 0.0, 0.0}, 2.5e3, r / 17.0}};
  return row;
}

std::vector<double> flatten(const HistoryRow& row) {
  std::vector<double> v = {static_cast<double>(row.step),
                           row.time,
                           row.dt,
                           row.kinetic,
                           row.internal,
                           row.elastic,
                           row.plastic,
                           row.viscous,
                           row.hourglass,
                           row.stabilisation,
                           row.eroded,
                           row.converted,
                           row.contact,
                           row.external_work,
                           row.total,
                           row.energy_error};
  for (const BodyHistory& b : row.bodies) {
    for (int i = 0; i < 3; ++i) v.push_back(b.momentum[i]);
    for (int i = 0; i < 3; ++i) v.push_back(b.mean_velocity[i]);
    v.push_back(b.kinetic);
    v.push_back(b.internal);
  }
  return v;
}

void expect_close(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    EXPECT_LE(std::abs(got[i] - want[i]), 1e-10 * std::abs(want[i])) << "column " << i;
}

TEST(History, HeaderListsPerBodyColumnsAndRowsReadBack) {
  const TempDir dir;
  const std::string path = (dir / "out/history.csv").string();  // parent is created
  HistoryWriter w(path, {"bar", "anvil"});
  const CsvTable empty = read_csv(path);  // header on disk before any row
  const std::vector<std::string> expected_header = {
      "step",          "time",          "dt",        "kinetic",       "internal",    "elastic",
      "plastic",       "viscous",       "hourglass", "stabilisation", "eroded",      "converted",
      "contact",       "external_work", "total",     "energy_error",  "bar.px",      "bar.py",
      "bar.pz",        "bar.vx",        "bar.vy",    "bar.vz",        "bar.kinetic", "bar.internal",
      "anvil.px",      "anvil.py",      "anvil.pz",  "anvil.vx",      "anvil.vy",    "anvil.vz",
      "anvil.kinetic", "anvil.internal"};
  EXPECT_EQ(empty.header, expected_header);
  EXPECT_TRUE(empty.rows.empty());

  for (int r = 0; r < 3; ++r) {
    w.write(make_row(r));
    // Flushed: the row is readable while the writer is still open (survives a crash).
    const CsvTable t = read_csv(path);
    ASSERT_EQ(t.rows.size(), static_cast<std::size_t>(r + 1));
    expect_close(t.rows.back(), flatten(make_row(r)));
  }
  EXPECT_EQ(w.rows(), 3u);
  const CsvTable t = read_csv(path);
  EXPECT_EQ(t.column("anvil.vx"), 27u);
  EXPECT_EQ(t.rows[2][t.column("step")], 200.0);
  for (int r = 0; r < 3; ++r) expect_close(t.rows[r], flatten(make_row(r)));
}

TEST(History, NoBodiesGivesTheGlobalColumnsOnly) {
  const TempDir dir;
  const std::string path = (dir / "h.csv").string();
  HistoryWriter w(path, {});
  HistoryRow row = make_row(1);
  row.bodies.clear();
  w.write(row);
  const CsvTable t = read_csv(path);
  EXPECT_EQ(t.header.size(), 16u);
  ASSERT_EQ(t.rows.size(), 1u);
  expect_close(t.rows[0], flatten(row));
}

TEST(History, RejectsMismatchedRowsAndBadNames) {
  const TempDir dir;
  HistoryWriter w((dir / "h.csv").string(), {"one"});
  EXPECT_THROW(w.write(make_row(0)), std::invalid_argument);  // two bodies for one name
  EXPECT_EQ(w.rows(), 0u);
  EXPECT_THROW(HistoryWriter((dir / "x.csv").string(), {"a,b"}), std::invalid_argument);
  EXPECT_THROW(HistoryWriter((dir / "y.csv").string(), {""}), std::invalid_argument);
}

TEST(History, UnwritablePathThrowsNamingIt) {
  try {
    HistoryWriter w("/proc/afemp_no/history.csv", {"bar"});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/afemp_no"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_csv("/proc/afemp_no/history.csv"), std::runtime_error);
}

TEST(OutputPaths, DefaultDirectoryIsRunsSlashSceneStem) {
  EXPECT_EQ(default_output_directory("examples/taylor_bar/mpm.toml"), "runs/taylor_bar-mpm");
  EXPECT_EQ(default_output_directory("/abs/path/taylor.scene.toml"), "runs/path-taylor.scene");
  EXPECT_EQ(default_output_directory("plain"), "runs/plain");
  EXPECT_EQ(default_output_directory(""), "runs/run");
  const OutputPaths p = default_output_paths("examples/taylor_bar/mpm.toml");
  EXPECT_EQ(p.directory, "runs/taylor_bar-mpm");
  EXPECT_EQ(fields_h5_path(p), "runs/taylor_bar-mpm/fields.h5");
  EXPECT_EQ(fields_xmf_path(p), "runs/taylor_bar-mpm/fields.xmf");
  EXPECT_EQ(history_path(p), "runs/taylor_bar-mpm/history.csv");
}

}  // namespace
}  // namespace afemp::core
