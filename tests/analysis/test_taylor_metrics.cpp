// Taylor-bar measures (analysis/taylor_metrics.hpp; Ma 2005, §2.3.2) on a handful of points of a
// bar 10 long of radius 1 standing on z = 0. References: L from the lowest to the highest reach
// of the points (a particle reaches its half size beyond its centre), D and W twice the largest
// radial reach near the wall and near 0.2 L0 from it, the band around 0.2 L0 half the largest
// particle spacing, or half an initial element length for a mesh (its nodes lie on the
// surface); eq 2-42 for the mean error.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "analysis/taylor_metrics.hpp"

namespace afemp::analysis {
namespace {

Scene bar_scene(Discretisation d) {
  BodySpec bar;
  bar.name = "bar";
  bar.discretisation = d;
  bar.shape = CylinderShape{{0, 0, 0}, {0, 0, 1}, 1.0, 10.0, {}};
  bar.mesh.axial = 10;  // elements of length 1: a band of 0.5
  Scene scene;
  scene.bodies.push_back(bar);
  return scene;
}

TEST(TaylorMetrics, ParticlesReachHalfTheirSpacingBeyondTheirCentres) {
  const std::vector<Vec3> x = {{0, 0, 0.5}, {0.5, 0, 0.5}, {0, 0, 9.5}, {0.7, 0, 2.0}};
  const std::vector<double> half(x.size(), 0.5);
  const TaylorMeasures m = measure_taylor(bar_scene(Discretisation::particles), 0, x, half);
  EXPECT_DOUBLE_EQ(m.length, 10.0);          // 0 .. 10
  EXPECT_DOUBLE_EQ(m.impact_diameter, 2.0);  // (0.5 + 0.5) at the wall
  EXPECT_DOUBLE_EQ(m.bulge_diameter, 2.4);   // (0.7 + 0.5) at z = 2 = 0.2 L0
}

TEST(TaylorMetrics, MeshNodesAreReadInABandOfHalfAnElement) {
  const std::vector<Vec3> x = {{0, 0, 0}, {1, 0, 0}, {0, 0, 10}, {1.1, 0, 2.4}};
  const std::vector<double> half(x.size(), 0.0);
  const TaylorMeasures mesh = measure_taylor(bar_scene(Discretisation::hexahedra), 0, x, half);
  EXPECT_DOUBLE_EQ(mesh.length, 10.0);
  EXPECT_DOUBLE_EQ(mesh.impact_diameter, 2.0);
  EXPECT_DOUBLE_EQ(mesh.bulge_diameter, 2.2) << "the node 0.4 from 0.2 L0 lies in the band";
  // The same points as particles of no size: no band, no point at 0.2 L0.
  const TaylorMeasures points = measure_taylor(bar_scene(Discretisation::particles), 0, x, half);
  EXPECT_DOUBLE_EQ(points.bulge_diameter, 0.0);
}

TEST(TaylorMetrics, MeanErrorIsEquation2_42) {
  const TaylorReference ref{10.0, 2.0, 4.0, 0.0};
  EXPECT_DOUBLE_EQ(taylor_mean_error({11.0, 2.0, 3.0}, ref), (0.1 + 0.0 + 0.25) / 3.0);
}

TEST(TaylorMetrics, RefusesABodyThatIsNoFlatEndedCylinderOrHasNoPoints) {
  Scene scene = bar_scene(Discretisation::particles);
  EXPECT_THROW(measure_taylor(scene, 0, {}, {}), std::invalid_argument);
  scene.bodies[0].shape = SphereShape{{0, 0, 0}, 1.0};
  const std::vector<Vec3> x = {{0, 0, 0}};
  const std::vector<double> half = {0.5};
  EXPECT_THROW(measure_taylor(scene, 0, x, half), std::invalid_argument);
}

}  // namespace
}  // namespace afemp::analysis
