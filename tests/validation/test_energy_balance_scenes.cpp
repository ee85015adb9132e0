// The energy balance of the scenes of examples/energy_balance (validation label, about 30 s
// on one thread): a block of hexahedra on a rigid wall, an FE rod on a particle plate, a
// particle sphere into a particle plate with Johnson-Cook damage, a sphere into a plate that
// converts to particles (AFEMP), and an HJC concrete block with bonded rebar struck by an FE
// rod. References and tolerances, each the law a correct account obeys:
//  * energy conservation: every history row's total (kinetic + internal + what the columns
//    book as dissipated, converted, lost or worked) equals the initial energy; where every
//    mechanism has its column (the block on the wall: the wall's catch is the `wall` column)
//    within 1 % on every row;
//  * a dissipation cannot be negative: plastic work, bulk-viscous and hourglass work, erosion,
//    conversion, wall, contact and outflow columns at or above -1e-9 E0 on every row (the
//    columns once went to -1535 and -535 in such scenes); nor can the elastic energy, internal
//    less the plastic and viscous parts, a positive quadratic form of the stress (it once went
//    to -15,110 on the wall, and in the AFEMP target to -120.3 and then -30.7, where converted
//    particles left the grid without their elements' plastic work);
//  * where a mechanism has no column of total (grid contact, whose dissipation the contact
//    column estimates, and the particle-grid transfers), a balance past 1 % is named in the
//    summary's warnings with the contact's name and its estimate, and the estimate accounts
//    for part of the gap, not more: 0 <= contact <= -(total - E0). No run makes energy: the
//    largest error above zero stays under 1 %.
// Measured (one thread, the 2-core machine, tree of this commit): block on wall -0.415 %
// (largest +0.484 %); rod on particle plate -5.57 % with the contact estimate 3.66 % of E0;
// JC particle plate -3.34 % (2.61 %); AFEMP target -6.63 % (5.31 %); HJC block with rebar
// -10.63 % (6.08 %).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "../scratch_dir.hpp"
#include "analysis/reference_checks.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"
#include "example_text.hpp"

namespace afemp::coupling {
namespace {

// history.csv as columns by name.
std::map<std::string, std::vector<double>> read_history(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::size_t k = 0;
    for (std::string value; std::getline(row, value, ',') && k < names.size(); ++k)
      columns[names[k]].push_back(std::stod(value));
  }
  return columns;
}

struct Expected {
  const char* scene;
  const char* contact;  // the grid contact the summary must name, or nullptr: every column books
};

class EnergyBalanceScene : public ::testing::TestWithParam<Expected> {};

TEST_P(EnergyBalanceScene, ClosesOrNamesWhatItDoesNotBookAndNoDissipationIsNegative) {
  const Expected x = GetParam();
  const std::string path = std::string("energy_balance/") + x.scene + ".toml";
  const core::Scene scene = core::parse_scene(test::example_text(path), path);
  test::ScratchDir dir;
  core::RunOptions options;
  options.output_directory = dir.path().string();
  options.write_fields = false;
  const std::unique_ptr<core::Model> model = make_model(scene);
  const core::RunSummary s = analysis::run(*model, scene, options);
  auto h = read_history(dir.path().string() + "/history.csv");
  ASSERT_GT(h["total"].size(), 2u);
  const double e0 = h["total"].front();
  const std::vector<double>& error = h["energy_error"];
  const double final_error = error.back();
  const double largest_gain = *std::max_element(error.begin(), error.end());
  double largest = 0.0;
  for (double e : error) largest = std::abs(e) > std::abs(largest) ? e : largest;
  const double contact = h["contact"].back();
  std::printf(
      "%s: %zu rows, energy error %+.3f %% at the end, largest %+.3f %%; contact column "
      "%.4g (%.2f %% of E0)\n",
      x.scene, error.size(), 100.0 * final_error, 100.0 * largest, contact, 100.0 * contact / e0);

  for (const char* column : {"plastic", "viscous", "hourglass", "stabilisation", "eroded",
                             "converted", "contact", "wall", "outflow"}) {
    if (!h.count(column)) continue;
    const double least = *std::min_element(h[column].begin(), h[column].end());
    EXPECT_GE(least, -1e-9 * e0) << x.scene << ": column " << column;
  }
  const double least_elastic = *std::min_element(h["elastic"].begin(), h["elastic"].end());
  EXPECT_GE(least_elastic, -1e-9 * e0) << x.scene;
  EXPECT_LT(largest_gain, 0.01) << x.scene << ": the run made energy";

  if (x.contact == nullptr) {
    EXPECT_LT(std::abs(largest), 0.01) << x.scene;
    return;
  }
  // The balance is past 1 %: the summary says which mechanisms no column books.
  ASSERT_GT(std::abs(final_error), 0.01) << x.scene;
  const std::string name = std::string("grid contact ") + x.contact;
  bool named = false;
  for (const std::string& w : s.warnings)
    named = named || (w.find("no column of total books") != std::string::npos &&
                      w.find(name) != std::string::npos &&
                      w.find("particle-grid transfers") != std::string::npos &&
                      w.find("the contact column's estimate") != std::string::npos);
  EXPECT_TRUE(named) << x.scene << ": no warning names " << name;
  EXPECT_GT(contact, 0.0) << x.scene;
  EXPECT_LE(contact, -final_error * e0) << x.scene;
}

INSTANTIATE_TEST_SUITE_P(
    Examples, EnergyBalanceScene,
    ::testing::Values(Expected{"block_wall", nullptr}, Expected{"rod_particle_plate", "rod-plate"},
                      Expected{"jc_particle_plate", "sphere-plate"},
                      Expected{"afemp_target", "sphere-plate"}, Expected{"hjc_rebar", "rod-block"}),
    [](const ::testing::TestParamInfo<Expected>& param) { return std::string(param.param.scene); });

}  // namespace
}  // namespace afemp::coupling
