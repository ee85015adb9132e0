// Adaptive conversion of hexahedra into particles (AFEMP: fem/element_retirement.cpp,
// coupling/element_conversion.cpp and coupling/coupled_model.hpp). References: conservation of mass
// and linear momentum (the particles take the mass shares and the N-weighted momentum the nodes
// lose, so both hold to round-off: 1e-12 relative), the kinetic energy the interpolation loses (the
// sum over the conversion records, booked as `converted`), and the grid domain (no element converts
// outside it). Body: a 4 mm aluminium cube of 4 x 4 x 4 hexahedra, free in space, drifting
// and spinning, with the half x > 2 squeezed along x so that only its elements compress past
// the criterion |V / V0 - 1| >= 5e-3 in the first step. Units mm, ms, g, N, MPa.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include "core/scene.hpp"
#include "coupling/coupled_model.hpp"

namespace afemp::coupling {
namespace {

using core::Vec3;

std::string cube_scene(int points, const char* element, const char* grid_max) {
  return std::string(R"([run]
end_time = 0.01

[grid]
cell = 1.0
min = [-4, -4, -4]
max = )") +
         grid_max + R"(

[materials.aluminium]
density = 2.7e-3
E = 70e3
nu = 0.3

[[bodies]]
name = "cube"
discretisation = "hexahedra"
material = "aluminium"
shape = { box = { min = [0, 0, 0], max = [4, 4, 4] } }
mesh = { divisions = [4, 4, 4] }
element = ")" +
         element + R"("
conversion = { volumetric_strain = 5e-3, points = )" +
         std::to_string(points) + R"( }
)";
}

// Drift, spin about the cube's centre, and a squeeze of the half x > 2 (50 /ms).
Vec3 start_velocity(const Vec3& x) {
  const Vec3 drift{20.0, -10.0, 5.0};
  const Vec3 omega{0.0, 0.0, 5.0};  // rad/ms
  const Vec3 r = x - Vec3{2.0, 2.0, 2.0};
  const Vec3 spin{omega.y * r.z - omega.z * r.y, omega.z * r.x - omega.x * r.z,
                  omega.x * r.y - omega.y * r.x};
  return drift + spin + Vec3{-50.0 * std::max(x.x - 2.0, 0.0), 0.0, 0.0};
}

struct Sums {
  double mass = 0.0;
  Vec3 momentum;
  double scale = 0.0;  // sum m |v|
  double kinetic = 0.0;
};

Sums sums(const CoupledModel& m) {
  Sums s;
  auto add = [&](double mass, const Vec3& v) {
    s.mass += mass;
    s.momentum += mass * v;
    s.scale += mass * core::norm(v);
    s.kinetic += 0.5 * mass * core::dot(v, v);
  };
  const auto& p = m.mpm().particles();
  for (std::size_t i = 0; i < p.size(); ++i) add(p.mass[i], p.velocity[i]);
  const auto& n = m.fe().nodes();
  for (std::size_t i = 0; i < n.size(); ++i) add(n.mass[i], n.velocity[i]);
  return s;
}

struct Case {
  int points;
  const char* element;
};

void PrintTo(const Case& c, std::ostream* out) {
  *out << c.element << ", points " << c.points;
}

class Conversion : public ::testing::TestWithParam<Case> {};

// One step converts the squeezed half (32 elements) into particles: the mass and momentum of
// nodes plus particles are those before the step to 1e-12, the particles inherit the elements'
// stress, and the converted energy is the kinetic energy the records say the nodes lost. Then
// 200 steps of the mixed body (remaining elements bonded to the particles) keep the momentum.
TEST_P(Conversion, ConservesMassAndMomentumAndBooksTheKineticEnergyItLoses) {
  const Case c = GetParam();
  const core::Scene scene =
      core::parse_scene(cube_scene(c.points, c.element, "[8, 8, 8]"), "cube.toml");
  CoupledModel model(scene);
  for (std::size_t i = 0; i < model.fe().nodes().size(); ++i)
    model.fe().mutable_nodes().velocity[i] = start_velocity(model.fe().nodes().position[i]);
  const Sums start = sums(model);
  model.step(model.stable_time_step());
  const Sums after = sums(model);
  const auto& p = model.mpm().particles();
  const std::size_t converted = p.size() / static_cast<std::size_t>(c.points * c.points * c.points);
  std::printf(
      "%s, %d per direction: %zu elements converted into %zu particles; mass %.2e, "
      "momentum %.2e (relative); converted energy %.6g uJ of kinetic %.6g\n",
      c.element, c.points, converted, p.size(), std::abs(after.mass - start.mass) / start.mass,
      core::norm(after.momentum - start.momentum) / start.scale, model.energies().converted,
      start.kinetic);
  EXPECT_EQ(converted, 32u);  // the half x > 2, and only it
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_GT(p.position[i].x, 2.0);
    EXPECT_LT(p.stress[i].xx, 0.0);  // the squeeze's compression, inherited
  }
  EXPECT_LT(std::abs(after.mass - start.mass), 1e-12 * start.mass);
  EXPECT_LT(core::norm(after.momentum - start.momentum), 1e-12 * start.scale);
  // The records' kinetic energy change is what the nodes' kinetic energy lost less what the
  // particles gained; one-point elements have one state, so nothing else changes.
  double lost = 0.0;
  for (const core::EventLog& log : model.take_events())
    if (log.file == "conversion.csv") {
      EXPECT_EQ(log.rows.size(), 32u);
      for (const std::string& row : log.rows) {
        // time,body,element,reason,particles,mass,kinetic_before,kinetic_after
        std::size_t at = 0;
        for (int k = 0; k < 6; ++k) at = row.find(',', at) + 1;
        const double before = std::stod(row.substr(at));
        const double later = std::stod(row.substr(row.find(',', at) + 1));
        lost += before - later;
        EXPECT_NE(row.find("volumetric strain"), std::string::npos) << row;
      }
    }
  EXPECT_GT(lost, 0.0);
  if (std::string(c.element) == "one-point") {
    EXPECT_NEAR(model.energies().converted, lost, 1e-12 * start.kinetic);
  }

  // The mixed body: no external force, so the momentum stays (to 1e-12 of sum m |v|).
  double drift = 0.0;
  for (int s = 0; s < 200; ++s) {
    model.step(model.stable_time_step());
    drift = std::max(drift, core::norm(sums(model).momentum - start.momentum) / start.scale);
    ASSERT_LT(std::abs(sums(model).mass - start.mass), 1e-12 * start.mass);
  }
  std::printf(
      "  after 200 more steps (t = %.4g ms, %zu particles, %zu elements): momentum "
      "drift %.2e\n",
      model.time(), model.mpm().particles().size(), model.fe().live_hexahedra(), drift);
  EXPECT_LT(drift, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(
    PointsAndElements, Conversion,
    ::testing::Values(Case{1, "one-point"}, Case{2, "one-point"}, Case{1, "full"}, Case{2, "full"}),
    [](const auto& test) {
      return std::string(test.param.element == std::string("full") ? "Full" : "OnePoint") +
             std::to_string(test.param.points);
    });

// The same cube in grid contact (CFEMP) with a block of particles it never reaches: its
// nodes are contact nodes, which the FE update moves, and after the squeeze they share the
// cube's velocity field with its particles and with the nodes bonded to them. Reference:
// conservation of linear momentum, to 1e-12 of sum m |v|, over the conversion step and 200
// more, with MUSL and USF. (A contact node's own velocity change once reached the particles'
// FLIP increment through the shared field as well: 1.4 % drift here with MUSL, 1.6 % with
// USF, 6.4 % in examples/rc_slab.)
TEST(ConversionInContact, ParticlesAndContactNodesOfOneBodyConserveMomentum) {
  for (const char* scheme : {"MUSL", "USF"}) {
    const core::Scene scene = core::parse_scene(cube_scene(2, "one-point", "[8, 8, 8]") + R"(
[mpm]
scheme = ")" + scheme + R"("

[[bodies]]
name = "block"
discretisation = "particles"
material = "aluminium"
shape = { box = { min = [-4, -4, -4], max = [-3, -3, -3] } }

[[contact]]
bodies = ["cube", "block"]
)",
                                                "cube.toml");
    CoupledModel model(scene);
    for (std::size_t i = 0; i < model.fe().nodes().size(); ++i)
      model.fe().mutable_nodes().velocity[i] = start_velocity(model.fe().nodes().position[i]);
    const Sums start = sums(model);
    const std::size_t block = model.mpm().particles().size();
    double drift = 0.0;
    for (int s = 0; s < 201; ++s) {
      model.step(model.stable_time_step());
      drift = std::max(drift, core::norm(sums(model).momentum - start.momentum) / start.scale);
    }
    std::printf(
        "%s, cube in contact: %zu particles converted, %zu elements left; momentum "
        "drift %.2e over 201 steps; contact energy %.3g\n",
        scheme, model.mpm().particles().size() - block, model.fe().live_hexahedra(), drift,
        model.energies().contact);
    EXPECT_GE(model.mpm().particles().size() - block, 16u * 8u) << scheme;  // a mixed body
    EXPECT_EQ(model.energies().contact, 0.0) << scheme;  // the block is never reached
    EXPECT_LT(drift, 1e-12) << scheme;
  }
}

// The grid covers y < 2 only: of the squeezed half, the 16 elements inside it convert and the
// 16 outside stay elements (conversion happens only where the grid is; check says so).
TEST(ConversionDomain, OnlyElementsInsideTheGridConvert) {
  const core::Scene scene = core::parse_scene(cube_scene(1, "one-point", "[8, 2, 8]"), "cube.toml");
  CoupledModel model(scene);
  EXPECT_NE(model.describe().find("32 of 64 elements lie inside now"), std::string::npos)
      << model.describe();
  for (std::size_t i = 0; i < model.fe().nodes().size(); ++i)
    model.fe().mutable_nodes().velocity[i] =
        Vec3{-50.0 * std::max(model.fe().nodes().position[i].x - 2.0, 0.0), 0.0, 0.0};
  model.step(model.stable_time_step());
  const auto& p = model.mpm().particles();
  EXPECT_EQ(p.size(), 16u);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_LT(p.position[i].y, 2.0);
  EXPECT_EQ(model.fe().live_hexahedra(), 48u);
}

// A scene whose particles all come from converted elements, with every optional particle field
// on: uGIMP (half widths), APIC (affine velocities) and principal-strain failure (the strain
// tensor, which the material's elements integrate). The particles start with none, and each
// converted one must still hold them all: the run once crashed reading arrays the start had
// left empty. Reference: a converted particle carries on from its element's strain, here the
// squeeze's closed form eps_xx = -50 /ms * dt (within 1 %: the mid-step geometry adds 25 dt
// relative), with no strain across it (|eps_yy|, |eps_zz| < 1e-3 |eps_xx|); then 50 more steps
// of the mixed body keep the mass (1e-12) and leave every particle's strain compressive. The
// half widths are uGIMP's, half the edge of the cube of each particle's volume in cells.
TEST(ConversionFields, ParticlesMadeFromElementsHoldEveryFieldTheRunKeeps) {
  std::string text = cube_scene(1, "one-point", "[8, 8, 8]");
  text.replace(text.find("[materials.aluminium]"), 21,
               "[mpm]\nshape_function = \"gimp\"\ntransfer = \"apic\"\n\n[materials.aluminium]");
  text.replace(text.find("nu = 0.3"), 8,
               "nu = 0.3\nfailure = { model = \"principal-strain\", strain = 10.0 }");
  const core::Scene scene = core::parse_scene(text, "cube.toml");
  CoupledModel model(scene);
  ASSERT_EQ(model.mpm().particles().size(), 0u);
  for (std::size_t i = 0; i < model.fe().nodes().size(); ++i)
    model.fe().mutable_nodes().velocity[i] =
        Vec3{-50.0 * std::max(model.fe().nodes().position[i].x - 2.0, 0.0), 0.0, 0.0};
  const double mass = sums(model).mass;
  const double dt = model.stable_time_step();
  model.step(dt);
  const auto& p = model.mpm().particles();
  ASSERT_EQ(p.size(), 32u);
  ASSERT_EQ(p.strain.size(), p.size());
  ASSERT_EQ(p.half_width.size(), p.size());
  ASSERT_EQ(p.affine.size(), p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_NEAR(p.strain[i].xx, -50.0 * dt, 0.01 * 50.0 * dt) << "particle " << i;
    EXPECT_LT(std::abs(p.strain[i].yy), 1e-3 * std::abs(p.strain[i].xx));
    EXPECT_LT(std::abs(p.strain[i].zz), 1e-3 * std::abs(p.strain[i].xx));
    // uGIMP's half width: half the edge of the cube of the volume, in cells of 1 mm, <= 1/2.
    EXPECT_DOUBLE_EQ(p.half_width[i], std::min(0.5, 0.5 * std::cbrt(p.volume[i])));
  }
  std::printf("converted particle 0: strain xx %.6e against -50 dt = %.6e\n", p.strain[0].xx,
              -50.0 * dt);
  for (int s = 0; s < 50; ++s) model.step(model.stable_time_step());
  EXPECT_LT(std::abs(sums(model).mass - mass), 1e-12 * mass);
  const auto& later = model.mpm().particles();
  ASSERT_EQ(later.strain.size(), later.size());
  for (std::size_t i = 0; i < later.size(); ++i) EXPECT_LT(later.strain[i].xx, 0.0);
}

// Reference: the elastic energy, internal less the plastic work and the bulk-viscous heat, is
// a positive quadratic form of the stress and cannot go below zero; once every point has left
// the grid, nothing remains to have done plastic work. The cube (J2, yield 100 MPa) is squeezed
// along x at 50 /ms, so its elements flow and convert at plastic strain 0.5 %, and it drifts at
// 1000 m/s through the outflow face x = 12. Pass: on every step elastic >= -1e-9 E0, and at the
// end no point is left and the plastic total is 0 within 1e-9 E0. The converted
// particles once left without the plastic work their elements had done (the particles did not
// carry it), and the elastic energy ended at minus that work.
TEST(ConversionOutflow, ALeavingParticleTakesItsElementsPlasticWorkWithIt) {
  const core::Scene scene = core::parse_scene(R"([run]
end_time = 0.014

[grid]
cell = 1.0
min = [-4, -4, -4]
max = [12, 8, 8]
boundary = { xmax = "outflow" }

[materials.aluminium]
density = 2.7e-3
E = 70e3
nu = 0.3
strength = { model = "j2", yield = 100, tangent_modulus = 1000 }

[[bodies]]
name = "cube"
discretisation = "hexahedra"
material = "aluminium"
shape = { box = { min = [0, 0, 0], max = [4, 4, 4] } }
mesh = { divisions = [4, 4, 4] }
conversion = { plastic_strain = 5e-3 }
)",
                                              "cube.toml");
  CoupledModel model(scene);
  for (std::size_t i = 0; i < model.fe().nodes().size(); ++i)
    model.fe().mutable_nodes().velocity[i] =
        Vec3{1000.0 - 50.0 * (model.fe().nodes().position[i].x - 2.0), 0.0, 0.0};
  const double e0 = model.energies().kinetic;
  double least_elastic = 0.0, most_plastic = 0.0;
  while (model.time() < scene.run.end_time) {
    model.step(model.stable_time_step());
    const core::Energies e = model.energies();
    least_elastic = std::min(least_elastic, e.internal - e.plastic - e.viscous);
    most_plastic = std::max(most_plastic, e.plastic);
  }
  const core::Energies e = model.energies();
  std::printf(
      "E0 %.6g; largest plastic work %.6g; least elastic %.3g; at the end %zu particles, "
      "plastic %.3g, viscous %.3g, outflow %.6g\n",
      e0, most_plastic, least_elastic, model.mpm().particles().size(), e.plastic, e.viscous,
      e.outflow);
  EXPECT_GT(most_plastic, 1e-4 * e0);  // the elements flowed before they converted
  EXPECT_GE(least_elastic, -1e-9 * e0);
  EXPECT_EQ(model.mpm().particles().size(), 0u);
  const auto& alive = model.fe().hexahedra().alive;
  EXPECT_EQ(std::count(alive.begin(), alive.end(), 1), 0);  // every element converted
  EXPECT_NEAR(e.plastic, 0.0, 1e-9 * e0);
}

}  // namespace
}  // namespace afemp::coupling
