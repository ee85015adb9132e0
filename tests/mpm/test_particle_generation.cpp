// Particle generation: lattice points carry exactly rho * volume, stay inside their shape and
// the grid, symmetry faces cut bodies into quarter/half models, other faces must contain them,
// and point-list files are read or rejected with file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "afemp/errors.hpp"
#include "core/scene.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

using core::BodySpec;
using core::BoxShape;
using core::CylinderShape;
using core::Face;
using core::FaceCondition;
using core::InputError;
using core::PointListShape;
using core::Scene;
using core::SphereShape;

constexpr double rho = 7.8e-3;

// One material, a grid [min, max] of cell h, all faces free unless set later.
Scene make_scene(const Vec3& min, const Vec3& max, double h) {
  Scene s;
  s.path = "gen.toml";
  s.mpm.grid.cell = h;
  s.mpm.grid.min = min;
  s.mpm.grid.max = max;
  core::Material m;
  m.name = "steel";
  m.density = rho;
  m.youngs_modulus = 200e3;
  m.poisson_ratio = 0.3;
  m.thermal.initial_temperature = 293.0;
  s.materials.push_back(m);
  return s;
}

BodySpec make_body(const std::string& name, core::Shape shape, int n) {
  BodySpec b;
  b.name = name;
  b.material = 0;
  b.shape = std::move(shape);
  b.particles_per_cell = n;
  b.where = {"gen.toml", 17};
  return b;
}

void set_face(Scene& s, Face f, FaceCondition c) {
  s.mpm.grid.faces[static_cast<int>(f)] = c;
}

double total_mass(const Particles& p) {
  double m = 0.0;
  for (double mi : p.mass) m += mi;
  return m;
}

std::string error_of(const Scene& s) {
  try {
    generate_particles(s);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

// A scratch file under the temp directory, named after the running test.
std::filesystem::path scratch_file(const std::string& contents) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto path = std::filesystem::temp_directory_path() /
                    (std::string("afemp_points_") + info->name() + ".txt");
  std::ofstream(path) << contents;
  return path;
}

TEST(ParticleGeneration, BoxOfFourCellsCubedWithTwoPerCellGives512PointsOfExactMass) {
  Scene s = make_scene({0, 0, 0}, {10, 10, 10}, 1.0);
  s.bodies.push_back(make_body("cube", BoxShape{{2, 3, 4}, {6, 7, 8}}, 2));
  const Particles p = generate_particles(s);
  ASSERT_EQ(p.size(), 512u);
  EXPECT_NEAR(total_mass(p), rho * 64.0, 1e-12 * rho * 64.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_DOUBLE_EQ(p.volume[i], 0.125);
    // Lattice offsets (k + 0.5) / n: every coordinate is a quarter or three quarters of a cell.
    EXPECT_DOUBLE_EQ(std::fmod(p.position[i].x, 0.5), 0.25);
  }
  // z-major, then y, then x.
  EXPECT_DOUBLE_EQ(p.position[0].x, 2.25);
  EXPECT_DOUBLE_EQ(p.position[1].x, 2.75);
  EXPECT_DOUBLE_EQ(p.position[1].z, 4.25);
  EXPECT_DOUBLE_EQ(p.position[511].z, 7.75);
}

TEST(ParticleGeneration, AdjacentBoxesSharingAFaceDoNotShareAPoint) {
  Scene s = make_scene({0, 0, 0}, {4, 4, 4}, 1.0);
  // The shared face x = 2.25 passes through a plane of lattice points (d = 0.5, offsets 0.25):
  // closed boxes would give those points to both bodies, half-open boxes to the right one only.
  s.bodies.push_back(make_body("left", BoxShape{{0, 0, 0}, {2.25, 4, 4}}, 2));
  s.bodies.push_back(make_body("right", BoxShape{{2.25, 0, 0}, {4, 4, 4}}, 2));
  const Particles p = generate_particles(s);
  EXPECT_EQ(p.size(), 8u * 8u * 8u);  // the whole 4^3 grid exactly once
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p.body[i], p.position[i].x < 2.25 ? 0 : 1);
}

// Reference: counting. A body placed outside another (water around a charge) leaves out its
// lattice points inside the other's shape: a 4^3 box at 2 per cell per direction (512 points)
// around a box of 2^3 cells (64 of its points) keeps 448, and the two bodies together fill the
// 4^3 grid exactly once; a sphere of radius 1.2 at a box corner leaves out the 1/8 of the
// points within 1.2 of it (counted directly).
TEST(ParticleGeneration, ABodyOutsideAnotherLeavesOutThePointsInsideIt) {
  Scene s = make_scene({0, 0, 0}, {4, 4, 4}, 1.0);
  s.bodies.push_back(make_body("charge", BoxShape{{0, 0, 0}, {2, 2, 2}}, 2));
  s.bodies.push_back(make_body("water", BoxShape{{0, 0, 0}, {4, 4, 4}}, 2));
  s.bodies[1].outside = {0};
  const Particles p = generate_particles(s);
  std::size_t water = 0;
  for (std::size_t i = 0; i < p.size(); ++i) water += p.body[i] == 1;
  EXPECT_EQ(water, 448u);
  EXPECT_EQ(p.size(), 512u);

  Scene t = make_scene({0, 0, 0}, {4, 4, 4}, 1.0);
  for (int f : {0, 2, 4})
    t.mpm.grid.faces[static_cast<std::size_t>(f)] = core::FaceCondition::symmetric;
  t.bodies.push_back(make_body("charge", SphereShape{{0, 0, 0}, 1.2}, 2));
  t.bodies.push_back(make_body("water", BoxShape{{0, 0, 0}, {4, 4, 4}}, 2));
  t.bodies[1].outside = {0};
  const Particles q = generate_particles(t);
  std::size_t inside = 0;  // lattice points (k + 0.5) / 2 within 1.2 of the origin
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 8; ++k) {
        const double x = 0.25 + 0.5 * i, y = 0.25 + 0.5 * j, z = 0.25 + 0.5 * k;
        inside += x * x + y * y + z * z <= 1.2 * 1.2;
      }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < q.size(); ++i) kept += q.body[i] == 1;
  EXPECT_EQ(kept, 512u - inside);
  EXPECT_GT(inside, 0u);
}

TEST(ParticleGeneration, QuarterCylinderFromSymmetricFacesHasAQuarterOfTheMass) {
  // Cylinder on the z axis, r = 8 cells, L = 16 cells; x >= 0 and y >= 0 kept by symmetry.
  const double r = 8.0, length = 16.0;
  Scene s = make_scene({0, 0, 0}, {12, 12, 20}, 1.0);
  set_face(s, Face::xmin, FaceCondition::symmetric);
  set_face(s, Face::ymin, FaceCondition::symmetric);
  set_face(s, Face::zmin, FaceCondition::fixed);
  s.bodies.push_back(make_body("bar", CylinderShape{{0, 0, 0}, {0, 0, 1}, r, length, {}}, 2));
  const Particles p = generate_particles(s);
  const double exact = rho * std::numbers::pi * r * r * length / 4.0;
  // The lattice resolves the circular section with spacing d = 0.5 (16 spacings per radius):
  // the axial direction is exact (L is a multiple of d), the section area is off by the points
  // of the boundary band of width ~d, at most ~2 d / r = 12% in the worst alignment and in
  // practice about 1% (1.0% here, 1.5% at r = 7.3). 3% leaves room for any alignment
  // while still catching a half or doubled model.
  EXPECT_NEAR(total_mass(p), exact, 0.03 * exact);
  for (const Vec3& x : p.position) {
    EXPECT_GT(x.x, 0.0);
    EXPECT_GT(x.y, 0.0);
    EXPECT_GE(x.z, 0.0);
    EXPECT_LT(x.z, length);
  }
}

TEST(ParticleGeneration, OgiveNosedCylinderHoldsItsMassAndNoPointOutsideTheArc) {
  // A quarter of Hanchak's projectile (R = 12.7, length 143.7, CRH 3 nose, sharp tip) in 1 mm
  // cells, 2 points per cell per direction. Reference: rho (pi R^2 L_shank + V_nose) / 4 with
  // V_nose in closed form (core/ogive_nose.hpp); 3 % as for the plain quarter cylinder above.
  // No point lies outside the profile r(t).
  CylinderShape c{{0, 0, 0}, {0, 0, 1}, 12.7, 143.7, {}};
  c.nose = {3.0, 0.0};
  Scene s = make_scene({0, 0, -1}, {14, 14, 146}, 1.0);
  set_face(s, Face::xmin, FaceCondition::symmetric);
  set_face(s, Face::ymin, FaceCondition::symmetric);
  s.bodies.push_back(make_body("projectile", c, 2));
  const Particles p = generate_particles(s);
  const double nose = core::ogive_nose_length(c.nose, c.radius), shank = c.length - nose;
  const double exact =
      rho *
      (std::numbers::pi * c.radius * c.radius * shank + core::ogive_nose_volume(c.nose, c.radius)) /
      4.0;
  EXPECT_NEAR(total_mass(p), exact, 0.03 * exact);
  std::size_t in_nose = 0;
  for (const Vec3& x : p.position) {
    const double profile =
        x.z > shank ? core::ogive_radius(c.nose, c.radius, x.z - shank) : c.radius;
    EXPECT_LE(std::hypot(x.x, x.y), profile) << x.z;
    in_nose += x.z > shank ? 1 : 0;
  }
  // The nose holds V_nose / 4 / 0.125 points to within the same band.
  const double expected_nose = core::ogive_nose_volume(c.nose, c.radius) / 4.0 / 0.125;
  EXPECT_NEAR(static_cast<double>(in_nose), expected_nose, 0.05 * expected_nose);
}

TEST(ParticleGeneration, ConicalLinerHoldsItsShellsMassAndAChargeOutsideItLeavesItsCavityEmpty) {
  // A quarter of a 60-degree conical liner 2 mm thick: the cone of base radius 20 and length
  // 34.641 along -z from z = 50 (a sharp apex) with wall = 2, i.e. without the cone inside it
  // (radius 20 - 2 / cos 30 = 17.690, length 30.641). Reference: rho pi (R^2 L - r^2 l) / 3 / 4;
  // 3 % as for the quarter cylinder (the shell is 8 spacings thick). Every point lies between the
  // two cone surfaces, and a charge placed outside the liner leaves its cavity empty.
  CylinderShape liner{{0, 0, 50}, {0, 0, -1}, 20.0, 34.641, {}};
  liner.top_radius = 0.0;
  liner.wall = 2.0;
  Scene s = make_scene({0, 0, 10}, {22, 22, 52}, 0.5);
  set_face(s, Face::xmin, FaceCondition::symmetric);
  set_face(s, Face::ymin, FaceCondition::symmetric);
  s.bodies.push_back(make_body("liner", liner, 2));
  s.bodies.push_back(make_body("charge", CylinderShape{{0, 0, 11}, {0, 0, 1}, 20.0, 39.0, {}}, 1));
  s.bodies[1].outside = {0};
  const Particles p = generate_particles(s);
  double mass = 0.0;
  std::size_t charge = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    const double r = std::hypot(x.x, x.y);
    const double outer = 20.0 * (x.z - 15.359) / 34.641, inner = 17.690 * (x.z - 19.359) / 30.641;
    if (p.body[i] == 1) {  // the charge: never inside the liner's cone, hollow included
      ++charge;
      EXPECT_TRUE(x.z <= 15.359 || r > outer - 1e-9) << x.z << " " << r;
      continue;
    }
    mass += p.mass[i];
    EXPECT_LE(r, outer + 1e-9) << x.z;  // inside the outer cone
    EXPECT_GT(r, inner - 1e-9) << x.z;  // outside the inner one
  }
  EXPECT_GT(charge, 0u);
  const double exact =
      rho * std::numbers::pi * (20.0 * 20.0 * 34.641 - 17.690 * 17.690 * 30.641) / 3.0 / 4.0;
  EXPECT_NEAR(mass, exact, 0.03 * exact);
}

TEST(ParticleGeneration, TaylorBarQuarterModelFromTheDocumentedSceneHasTheBarMass) {
  const std::string text = R"([run]
end_time = 0.08
[grid]
cell = 0.5
min = [0, 0, 0]
max = [10, 10, 28]
boundary = { zmin = "fixed", xmin = "symmetric", ymin = "symmetric" }
[materials.copper]
density = 8.93e-3
E = 117e3
nu = 0.35
[[bodies]]
name = "bar"
material = "copper"
shape = { cylinder = { base = [0, 0, 0], radius = 3.8, length = 25.4 } }
velocity = [0, 0, -190]
)";
  const Particles p = generate_particles(core::parse_scene(text, "taylor.toml"));
  const double exact = 8.93e-3 * std::numbers::pi * 3.8 * 3.8 * 25.4 / 4.0;
  // r = 15.2 spacings: same lattice argument as above.
  EXPECT_NEAR(total_mass(p), exact, 0.03 * exact);
  for (const Vec3& v : p.velocity) EXPECT_DOUBLE_EQ(v.z, -190.0);
}

TEST(ParticleGeneration, PointsNeverLieOutsideTheirShapeOrTheGrid) {
  Scene s = make_scene({-10, -10, -10}, {10, 10, 10}, 1.0);
  const Vec3 c{0.3, -1.2, 2.0};
  const double radius = 4.7;
  s.bodies.push_back(make_body("ball", SphereShape{c, radius}, 3));
  // A tilted cylinder, axis (1, 1, 1)/sqrt 3.
  const double k = 1.0 / std::sqrt(3.0);
  const Vec3 base{-6, -6, -6}, axis{k, k, k};
  s.bodies.push_back(make_body("rod", CylinderShape{base, axis, 2.5, 6.0, {}}, 4));
  const Particles p = generate_particles(s);
  std::size_t balls = 0, rods = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(x[a], -10.0);
      EXPECT_LE(x[a], 10.0);
    }
    if (p.body[i] == 0) {
      ++balls;
      EXPECT_LE(norm(x - c), radius);
    } else {
      ++rods;
      const Vec3 v = x - base;
      const double along = dot(v, axis);
      EXPECT_GE(along, 0.0);
      EXPECT_LT(along, 6.0);
      EXPECT_LE(norm(v - along * axis), 2.5 + 1e-12);
    }
  }
  // Both bodies are populated, with roughly their volumes: 10% is loose for ~10 lattice
  // spacings per radius (a tilted axis cuts the lattice irregularly at the end discs).
  const double ball_volume = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  EXPECT_NEAR(static_cast<double>(balls) / 27.0, ball_volume, 0.1 * ball_volume);
  const double rod_volume = std::numbers::pi * 2.5 * 2.5 * 6.0;
  EXPECT_NEAR(static_cast<double>(rods) / 64.0, rod_volume, 0.1 * rod_volume);
}

TEST(ParticleGeneration, BodyCrossingAFixedFaceIsAnInputErrorNamingTheFace) {
  Scene s = make_scene({0, 0, 0}, {10, 10, 10}, 1.0);
  set_face(s, Face::zmin, FaceCondition::fixed);
  s.bodies.push_back(make_body("slab", BoxShape{{2, 2, -1}, {4, 4, 3}}, 2));
  const std::string what = error_of(s);
  EXPECT_EQ(what.rfind("gen.toml:17: key 'bodies.slab.shape': the body crosses grid face zmin "
                       "(boundary \"fixed\")",
                       0),
            0u)
      << what;
}

TEST(ParticleGeneration, BodyCrossingAFreeFaceIsAlsoAnError) {
  Scene s = make_scene({0, 0, 0}, {10, 10, 10}, 1.0);
  s.bodies.push_back(make_body("ball", SphereShape{{9, 5, 5}, 2}, 2));
  EXPECT_NE(error_of(s).find("crosses grid face xmax (boundary \"free\")"), std::string::npos);
}

TEST(ParticleGeneration, BodyWithoutAnyLatticePointIsAnError) {
  Scene s = make_scene({0, 0, 0}, {10, 10, 10}, 1.0);
  // Radius 0.2 around a cell corner: the nearest lattice point (n = 1) is 0.87 away.
  s.bodies.push_back(make_body("dust", SphereShape{{5, 5, 5}, 0.2}, 1));
  EXPECT_NE(error_of(s).find("key 'bodies.dust.shape': the body has no particle"),
            std::string::npos);
}

TEST(ParticleGeneration, InitialVelocityTemperatureBodyAndMaterialAreSet) {
  Scene s = make_scene({0, 0, 0}, {10, 10, 10}, 1.0);
  core::Material hot = s.materials[0];
  hot.name = "hot";
  hot.density = 2.0e-3;
  hot.thermal.initial_temperature = 500.0;
  s.materials.push_back(hot);
  BodySpec a = make_body("a", BoxShape{{1, 1, 1}, {2, 2, 2}}, 1);
  a.velocity = {1, -2, 3};
  a.temperature = 400.0;  // overrides the material's 293
  BodySpec b = make_body("b", BoxShape{{5, 5, 5}, {6, 6, 7}}, 1);
  b.material = 1;  // takes the material's 500
  s.bodies = {a, b};
  const Particles p = generate_particles(s);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p.body[0], 0);
  EXPECT_EQ(p.material[0], 0);
  EXPECT_DOUBLE_EQ(p.velocity[0].y, -2.0);
  EXPECT_DOUBLE_EQ(p.temperature[0], 400.0);
  EXPECT_DOUBLE_EQ(p.mass[0], rho * 1.0);
  for (std::size_t i = 1; i < 3; ++i) {
    EXPECT_EQ(p.body[i], 1);
    EXPECT_EQ(p.material[i], 1);
    EXPECT_DOUBLE_EQ(p.velocity[i].x, 0.0);
    EXPECT_DOUBLE_EQ(p.temperature[i], 500.0);
    EXPECT_DOUBLE_EQ(p.mass[i], 2.0e-3);
  }
}

TEST(ParticleGeneration, PointsFileGivesOnePointPerLineWithDefaultOrGivenVolume) {
  const auto path = scratch_file(
      "# x y z [volume]\n"
      "1 1 1\n"
      "\n"
      "2.5 3.5 4.5 0.5   # a bigger point\n"
      "  9 9 9\n");
  Scene s = make_scene({0, 0, 0}, {10, 10, 10}, 1.0);
  s.bodies.push_back(make_body("cloud", PointListShape{path.string()}, 2));
  s.bodies[0].velocity = {0, 0, 5};
  const Particles p = generate_particles(s);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_DOUBLE_EQ(p.position[1].y, 3.5);
  EXPECT_DOUBLE_EQ(p.volume[0], 0.125);  // (h / n)^3
  EXPECT_DOUBLE_EQ(p.volume[1], 0.5);
  EXPECT_DOUBLE_EQ(p.mass[1], rho * 0.5);
  EXPECT_DOUBLE_EQ(p.velocity[2].z, 5.0);
  std::filesystem::remove(path);
}

TEST(ParticleGeneration, MalformedPointsLineIsAnErrorNamingTheFileAndLine) {
  const auto path = scratch_file("# header\n1 1 1\n2 2 2\n3 three 3\n");
  Scene s = make_scene({0, 0, 0}, {10, 10, 10}, 1.0);
  s.bodies.push_back(make_body("cloud", PointListShape{path.string()}, 2));
  const std::string what = error_of(s);
  EXPECT_EQ(what.rfind(path.string() + ":4: ", 0), 0u) << what;
  EXPECT_NE(what.find("malformed line"), std::string::npos) << what;
  std::filesystem::remove(path);
}

TEST(ParticleGeneration, PointsFileProblemsAreReported) {
  Scene s = make_scene({0, 0, 0}, {10, 10, 10}, 1.0);
  auto path = scratch_file("1 1 1\n5 5 11\n");
  s.bodies.push_back(make_body("cloud", PointListShape{path.string()}, 2));
  std::string what = error_of(s);
  EXPECT_EQ(what.rfind(path.string() + ":2: ", 0), 0u) << what;
  EXPECT_NE(what.find("outside the grid"), std::string::npos) << what;
  std::filesystem::remove(path);

  s.bodies[0].shape = PointListShape{"/nonexistent/points.txt"};
  what = error_of(s);
  EXPECT_NE(what.find("cannot open points file '/nonexistent/points.txt'"), std::string::npos);
}

}  // namespace
}  // namespace afemp::mpm
