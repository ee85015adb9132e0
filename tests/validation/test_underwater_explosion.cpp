// The underwater explosion of examples/underwater_explosion (validation label: about 6 min on 2
// threads): a 4 mm TNT sphere (W = 0.437 g) lit at its centre in water, an eighth of it, 1 mm
// cells. Reference: Cole's empirical law for TNT, P_max = 52.4 (W^(1/3) / R)^1.13 MPa (W in kg,
// R in m; R. H. Cole, Underwater Explosions, 1948), which holds from about 10 charge radii out.
// The peak water pressure at each probe (15, 17.5, 20 and 22.5 charge radii: R = 60 ... 90 mm,
// on the diagonal) within 15 % of it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "afemp/probes.hpp"
#include "analysis/reference_checks.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"
#include "example_text.hpp"

namespace afemp::coupling {
namespace {

TEST(UnderwaterExplosion, PeakShockPressureFollowsColesLawFromFifteenChargeRadii) {
  const core::Scene scene = core::parse_scene(test::example_text("underwater_explosion/scene.toml"),
                                              "scene.toml");
  const std::unique_ptr<core::Model> model = make_model(scene);
  const core::RunSummary s = analysis::run(*model, scene, {});
  const double w = 4.0 / 3.0 * M_PI * 64.0 * 1.63e-3 / 1000.0;  // kg
  int within = 0;
  for (const int r : {60, 70, 80, 90}) {
    const ProbeSeries* probe = nullptr;
    const std::string name = std::string("r").append(std::to_string(r));
    for (const ProbeSeries& p : s.probes)
      if (p.name == name) probe = &p;
    ASSERT_NE(probe, nullptr) << r;
    double peak = 0.0;
    for (std::size_t k = 0; k < probe->rows(); ++k)
      peak = std::max(peak, probe->at(k, static_cast<std::size_t>(probe->column("pressure"))));
    const double cole = 52.4 * std::pow(std::cbrt(w) / (r / 1000.0), 1.13);
    std::printf("R = %d mm (%.1f charge radii): peak %.1f MPa, Cole %.1f MPa (%+.1f %%)\n", r,
                r / 4.0, peak, cole, 100.0 * (peak / cole - 1.0));
    EXPECT_NEAR(peak, cole, 0.15 * cole) << "R = " << r << " mm";
    within += std::abs(peak / cole - 1.0) <= 0.15;
  }
  EXPECT_GE(within, 3);
}

}  // namespace
}  // namespace afemp::coupling
