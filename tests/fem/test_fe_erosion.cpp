// Element erosion (fem/erosion.cpp, the criteria in fem/hexahedron_update.cpp): a J2-plastic
// bar hitting a rigid wall loses the elements that pass the erosion plastic strain; the records
// in erosion.csv, the energy balance (eroded energy booked) and the node masses are checked, and
// an inverted element stops a run without erosion and erodes with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "analysis/reference_checks.hpp"
#include "core/output/history.hpp"
#include "core/scene.hpp"
#include "fem/fe_model.hpp"
#include "scratch_dir.hpp"

namespace afemp::fem {
namespace {

// A steel bar 1 x 1 x 4 mm along z (4 x 4 x 16 one-point hexahedra of 0.25 mm) with J2
// plasticity (yield 300 MPa, no hardening) whose elements erode at an equivalent plastic strain
// of 0.3, held at z = 0 and pulled at 20 m/s at z = 4 (a slow pull: no impulsive wall or
// start-up losses hide the erosion booking in the balance).
// The J2 steel (yield 300 MPa, no hardening) of the erosion scenes.
const std::string kSteel = R"(
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
strength = { model = "j2", yield = 300 }
)";

const std::string kPulledBar = "[run]\nend_time = 0.025\nhistory_every = 1\n" + kSteel + R"(
[[bodies]]
name = "bar"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [1, 1, 4] } }
mesh = { size = 0.25 }
erosion = { plastic_strain = 0.3 }
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }
fixed = ["all"]
[[constraints]]
nodes = { plane = { point = [0, 0, 4], normal = [0, 0, 1] } }
velocity = [0, 0, 20]
)";

std::vector<std::vector<std::string>> read_rows(const std::string& path, std::string& header) {
  std::ifstream in(path);
  std::getline(in, header);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

// Reference: erosion removes an element with its internal energy and the kinetic energy of the
// node mass that leaves with it, both booked as eroded energy, so the energy balance still
// closes: the balance error changes by less than 0.1 % of the work done across the erosion and
// ends below 0.5 % (without the booking it would miss the eroded energy, about 20 % of the work
// done here; the first steps of the pull, with almost no energy in the bar yet, are not
// compared). The node masses are recomputed from the
// live elements: sum of live node masses = sum of live element masses (1e-12). Each record
// (time,kind,id,body,reason,energy,mass) accounts for its share: the rows' energies add up to
// the eroded energy and a hexahedron's mass is rho h^3 (CSV precision, 1e-9). The summary
// warns of the eroded elements (their count) and of the mass that left with them, eroded
// rho h^3 (to the 6 digits it prints).
TEST(Erosion, ErodedElementsAreRecordedAndTheEnergyBalanceCloses) {
  test::ScratchDir dir;
  const core::Scene scene = core::parse_scene(kPulledBar, "bar.toml");
  FeModel model(scene);
  core::RunOptions options;
  options.output_directory = dir.str();
  options.write_fields = false;
  const core::RunSummary s = analysis::run(model, scene, options);

  const FeSolver& solver = model.solver();
  const HexElements& h = solver.hexahedra();
  std::size_t eroded = 0;
  for (std::size_t e = 0; e < h.size(); ++e) {
    if (h.alive[e]) continue;
    ++eroded;
    EXPECT_GE(h.plastic_strain[e], 0.3) << "hexahedron " << e << " eroded below the criterion";
  }
  ASSERT_GT(eroded, 0u) << "the impact must erode some elements";
  EXPECT_LT(eroded, h.size());

  std::string header;
  const auto rows = read_rows(dir.file("erosion.csv"), header);
  EXPECT_EQ(header, "time,kind,id,body,reason,energy,mass");
  const double element_mass = 7.85e-3 * 0.25 * 0.25 * 0.25;
  std::size_t hex_rows = 0;
  double energy = 0.0, previous_time = 0.0;
  for (const auto& r : rows) {
    ASSERT_EQ(r.size(), 7u);
    const double time = std::strtod(r[0].c_str(), nullptr);
    EXPECT_GE(time, previous_time);
    EXPECT_LE(time, s.time);
    previous_time = time;
    EXPECT_EQ(r[3], "bar");
    if (r[1] == "hexahedron") {
      energy += std::strtod(r[5].c_str(), nullptr);
      ++hex_rows;
      EXPECT_EQ(r[4], "plastic strain");
      EXPECT_NEAR(std::strtod(r[6].c_str(), nullptr), element_mass, 1e-9 * element_mass);
    } else {
      EXPECT_EQ(r[1], "node");
      EXPECT_EQ(r[4], "no element left");
      EXPECT_GE(std::strtod(r[5].c_str(), nullptr), 0.0);  // reported, counted in its elements
      EXPECT_GT(std::strtod(r[6].c_str(), nullptr), 0.0);
    }
  }
  EXPECT_EQ(hex_rows, eroded);
  EXPECT_NEAR(energy, s.final.eroded, 1e-9 * s.final.eroded);
  EXPECT_GT(s.final.eroded, 0.1 * s.final.external_work);
  EXPECT_LT(std::abs(s.energy_error), 0.005);
  const core::CsvTable history = core::read_csv(dir.file("history.csv"));
  const double first_erosion = std::strtod(rows.at(0)[0].c_str(), nullptr);
  double before = 0.0;
  for (const auto& row : history.rows)
    if (row[history.column("time")] < first_erosion) before = row[history.column("energy_error")];
  EXPECT_NEAR(history.rows.back()[history.column("energy_error")], before, 1e-3);

  double node_mass = 0.0, element_total = 0.0;
  for (double m : solver.nodes().mass) node_mass += m;
  for (std::size_t e = 0; e < h.size(); ++e)
    if (h.alive[e]) element_total += h.mass[e];
  EXPECT_NEAR(node_mass, element_total, 1e-12 * element_total);
  EXPECT_NEAR(element_total, (h.size() - eroded) * element_mass, 1e-9 * element_total);

  const std::string count = std::to_string(eroded) + " of " + std::to_string(h.size()) +
                            " elements of body \"bar\" eroded";
  EXPECT_EQ(std::count_if(s.warnings.begin(), s.warnings.end(),
                          [&](const std::string& w) { return w.rfind(count, 0) == 0; }),
            1)
      << count;
  double lost = 0.0, initial = 0.0;
  for (const std::string& w : s.warnings) {
    if (w.find("with eroded elements") == std::string::npos) continue;
    ASSERT_EQ(std::sscanf(w.c_str(), "%*f %% of the initial mass left the model (%lf of %lf)",
                          &lost, &initial),
              2)
        << w;
  }
  EXPECT_NEAR(lost, static_cast<double>(eroded) * element_mass, 1e-5 * lost);
  EXPECT_NEAR(initial, static_cast<double>(h.size()) * element_mass, 1e-5 * initial);
  std::printf(
      "erosion: %zu of %zu hexahedra eroded, %zu records, eroded energy %.4g of the "
      "work %.4g done on the bar, energy-balance error %.3f %% before the erosion, "
      "%.3f %% at the end\n",
      eroded, h.size(), rows.size(), s.final.eroded, s.final.external_work, 100.0 * before,
      100.0 * s.energy_error);
}

// What the live hexahedra of a steel body (E = 200 GPa, nu = 0.3, one point each) hold after a
// run: their strain energy sum V (s:s / 4G + p^2 / 2K) from the stresses, their own plastic work
// and viscous heat tallies (where kept), and how many eroded.
struct LiveTotals {
  double strain_energy = 0.0, plastic = 0.0, viscous = 0.0;
  std::size_t eroded = 0;
};

// The elastic column of the history's last row.
double history_elastic_last(const std::string& path) {
  const core::CsvTable h = core::read_csv(path);
  return h.rows.back()[h.column("elastic")];
}

LiveTotals live_totals(const HexElements& h) {
  const double E = 200e3, nu = 0.3, G = E / (2 * (1 + nu)), K = E / (3 * (1 - 2 * nu));
  LiveTotals t;
  for (std::size_t e = 0; e < h.size(); ++e) {
    if (!h.alive[e]) {
      ++t.eroded;
      continue;
    }
    const core::SymTensor& sigma = h.stress[e];  // one point per element
    const core::SymTensor dev = sigma.deviator();
    const double p = -sigma.trace() / 3.0;
    t.strain_energy += h.volume[e] * (core::double_dot(dev, dev) / (4 * G) + p * p / (2 * K));
    if (!h.plastic_heat.empty()) t.plastic += h.point_mass[e] * h.plastic_heat[e];
    if (!h.viscous_heat.empty()) t.viscous += h.point_mass[e] * h.viscous_heat[e];
  }
  return t;
}

// Reference: after erosion the history's elastic column (internal - plastic - viscous) is the
// strain energy of the live elements, sum V (s:s / 4G + p^2 / 2K) from their stresses (J2 with
// the bulk modulus: the internal energy is that plus the plastic work and the bulk-viscous heat,
// to the trapezoidal rule's error). The column is the difference of two totals about 600 times
// larger here (the bar has necked and broken: plastic work 82, live strain energy 0.14), each
// integrated to about 0.1 %: pass within 0.2 % of the internal energy of that strain energy at
// the end, and never below -0.2 % of it. Before the eroded elements' plastic work left the
// plastic total, the column ended at -22.4 (27 % of the internal energy).
TEST(Erosion, TheElasticColumnIsTheLiveElementsStrainEnergyAfterErosion) {
  test::ScratchDir dir;
  const core::Scene scene = core::parse_scene(kPulledBar, "bar.toml");
  FeModel model(scene);
  core::RunOptions options;
  options.output_directory = dir.str();
  options.write_fields = false;
  const core::RunSummary s = analysis::run(model, scene, options);
  ASSERT_EQ(model.solver().hexahedra().plastic_heat.size(), model.solver().hexahedra().size());
  const LiveTotals live = live_totals(model.solver().hexahedra());
  const double strain_energy = live.strain_energy;
  const std::size_t eroded = live.eroded;
  ASSERT_GT(eroded, 0u);
  // The plastic column is the live points' own plastic work (what the column relies on).
  EXPECT_NEAR(s.final.plastic, live.plastic, 1e-9 * s.final.plastic);
  EXPECT_GT(history_elastic_last(dir.file("history.csv")), 0.0);
  const core::CsvTable history = core::read_csv(dir.file("history.csv"));
  double lowest = 0.0;
  for (const auto& row : history.rows) lowest = std::min(lowest, row[history.column("elastic")]);
  const double elastic = history.rows.back()[history.column("elastic")];
  std::printf(
      "after erosion of %zu hexahedra: elastic column %.5g, live strain energy %.5g "
      "(difference %.2g of the internal energy %.5g), plastic %.5g, eroded %.5g, lowest "
      "elastic %.3g\n",
      eroded, elastic, strain_energy, (elastic - strain_energy) / s.final.internal,
      s.final.internal, s.final.plastic, s.final.eroded, lowest);
  EXPECT_NEAR(elastic, strain_energy, 2e-3 * s.final.internal);
  EXPECT_GE(lowest, -2e-3 * s.final.internal);
}

// A steel plate 10 x 4 x 1 mm (20 x 8 x 2 hexahedra of 0.5 mm; J2, yield 300 MPa, erosion at
// a plastic strain of 0.1) whose half x < 5 is stretched evenly along x: the node planes x = 0,
// 1, 2, 3 and 4 move at -20, -16, -12, -8 and -4 m/s, x = 5 is held, the other half is free.
// The stretched half erodes at about t = 0.021 ms. Reference: each history column's own
// balance, from the live elements and the records, once half the plate is gone: eroded = the
// records' energies (erosion.csv, to CSV precision); plastic = sum over live points of m w_p and
// viscous = sum m q_heat (their own tallies, 1e-9); elastic = internal - plastic - viscous = the
// live elements' strain energy sum V (s:s / 4G + p^2 / 2K) (0.5 % of the internal energy: the
// internal energy's trapezoidal rule against the stresses' closed form) and never below -0.5 %
// of it on any row; and the energy balance (the held and moved planes' work is external work)
// closes to 0.5 %.
TEST(Erosion, HalfAPlateErodedLeavesEveryHistoryColumnBalanced) {
  test::ScratchDir dir;
  std::string text = "[run]\nend_time = 0.03\nhistory_every = 1\n" + kSteel + R"(
[[bodies]]
name = "plate"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [10, 4, 1] } }
mesh = { size = 0.5 }
erosion = { plastic_strain = 0.1 }
[[constraints]]
nodes = { plane = { point = [5, 0, 0], normal = [1, 0, 0] } }
fixed = ["x"]
)";
  for (int k = 0; k < 5; ++k)
    text += "[[constraints]]\nnodes = { plane = { point = [" + std::to_string(k) +
            ", 0, 0], normal = [1, 0, 0] } }\nvelocity = [" + std::to_string(-20 + 4 * k) +
            ", 0, 0]\n";
  const core::Scene scene = core::parse_scene(text, "plate.toml");
  FeModel model(scene);
  core::RunOptions options;
  options.output_directory = dir.str();
  options.write_fields = false;
  const core::RunSummary s = analysis::run(model, scene, options);
  const HexElements& h = model.solver().hexahedra();
  ASSERT_EQ(h.plastic_heat.size(), h.size());
  const LiveTotals live = live_totals(h);
  const double strain_energy = live.strain_energy, plastic = live.plastic, viscous = live.viscous;
  const std::size_t eroded = live.eroded;
  std::string header;
  double recorded = 0.0;
  for (const auto& r : read_rows(dir.file("erosion.csv"), header))
    if (r[1] == "hexahedron") recorded += std::strtod(r[5].c_str(), nullptr);
  const core::CsvTable history = core::read_csv(dir.file("history.csv"));
  double lowest = 0.0;
  for (const auto& row : history.rows) lowest = std::min(lowest, row[history.column("elastic")]);
  const auto& last = history.rows.back();
  const double elastic = last[history.column("elastic")];
  const core::Energies& f = s.final;
  std::printf(
      "half a plate: %zu of %zu hexahedra eroded; eroded %.6g (records %.6g), plastic "
      "%.6g (live %.6g), viscous %.6g (live %.6g), elastic %.6g (strain energy %.6g), "
      "lowest elastic %.3g, internal %.6g; energy balance %.3g %%\n",
      eroded, h.size(), f.eroded, recorded, f.plastic, plastic, f.viscous, viscous, elastic,
      strain_energy, lowest, f.internal, 100.0 * s.energy_error);
  EXPECT_GT(eroded, 0.4 * static_cast<double>(h.size()));
  EXPECT_LT(eroded, 0.6 * static_cast<double>(h.size()));
  EXPECT_NEAR(f.eroded, recorded, 1e-9 * f.eroded);
  EXPECT_NEAR(f.plastic, plastic, 1e-9 * f.plastic);
  EXPECT_NEAR(f.viscous, viscous, 1e-9 * std::max(f.viscous, 1e-30));
  EXPECT_NEAR(elastic, strain_energy, 5e-3 * f.internal);
  EXPECT_GE(lowest, -5e-3 * f.internal);
  EXPECT_LT(std::abs(s.energy_error), 5e-3);
}

// Two elastic hexahedra side by side along x; `erosion` is added to the body.
core::Scene pair_scene(const std::string& erosion) {
  return core::parse_scene(
      "[run]\nend_time = 1.0\n[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
      "[[bodies]]\nname = \"pair\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [0, 0, 0], max = [2, 1, 1] } }\nmesh = { divisions = [2, 1, 1] }\n" +
          erosion,
      "pair.toml");
}

// Moves the face x = 0 of the first hexahedron to x = 1.5, through its opposite face, in one
// step: the element turns inside out.
void invert_first(FeSolver& solver, double dt) {
  FeNodes& n = solver.mutable_nodes();
  for (std::size_t i = 0; i < n.size(); ++i)
    if (n.position[i].x == 0.0) n.velocity[i].x = 1.5 / dt;
}

// Reference: an inverted element has no meaningful strain; without erosion the run must stop
// with core::SimulationError naming the element ("hexahedron 0 of body pair") and the field
// 'jacobian'.
TEST(Erosion, InvertedElementWithoutErosionStopsTheRunNamingItAndTheJacobian) {
  const core::Scene scene = pair_scene("");
  FeSolver solver(scene);
  const double dt = solver.stable_time_step();
  invert_first(solver, dt);
  try {
    solver.step(dt);
    FAIL() << "expected a SimulationError";
  } catch (const core::SimulationError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("hexahedron 0 of body pair"), std::string::npos) << what;
    EXPECT_NE(what.find("field 'jacobian'"), std::string::npos) << what;
    EXPECT_EQ(e.step(), 1);
  }
}

// Reference: with any erosion criterion on the body, the inverted element erodes instead: it is
// dead, recorded with the reason "negative Jacobian", its four nodes that no other element holds
// drop out (their records carry no energy or mass: the element's does), and the run goes on.
// The kinetic energy those nodes carried is booked as eroded and is the element record's
// energy, so the total energy is unchanged by the step (1e-9 relative).
TEST(Erosion, InvertedElementWithErosionErodesInsteadOfStopping) {
  const core::Scene scene = pair_scene("erosion = { plastic_strain = 0.5 }\n");
  FeSolver solver(scene);
  const double dt = solver.stable_time_step();
  invert_first(solver, dt);
  const core::Energies before = solver.energies();
  ASSERT_NO_THROW(solver.step(dt));
  const core::Energies after = solver.energies();
  EXPECT_EQ(solver.hexahedra().alive[0], 0);
  EXPECT_EQ(solver.hexahedra().alive[1], 1);
  const std::vector<ErosionEvent> events = solver.take_erosion_events();
  ASSERT_EQ(events.size(), 5u);  // the element and its 4 free nodes
  EXPECT_STREQ(events[0].kind, "hexahedron");
  EXPECT_EQ(events[0].id, 0);
  EXPECT_EQ(events[0].reason, "negative Jacobian");
  double node_kinetic = 0.0, node_mass = 0.0;
  for (std::size_t k = 1; k < events.size(); ++k) {
    EXPECT_STREQ(events[k].kind, "node");
    node_kinetic += events[k].energy;
    node_mass += events[k].mass;
  }
  // The dropped nodes report the mass and kinetic energy they leave with: all of the element's
  // kinetic energy and half its mass (the other four nodes keep their other elements).
  EXPECT_NEAR(node_kinetic, before.kinetic, 1e-12 * before.kinetic);
  EXPECT_NEAR(node_mass, 0.5 * solver.hexahedra().mass[0], 1e-12 * solver.hexahedra().mass[0]);
  // All the kinetic energy was in the four moved nodes, half the element's mass.
  EXPECT_NEAR(events[0].energy, before.kinetic, 1e-12 * before.kinetic);
  EXPECT_EQ(events[0].mass, solver.hexahedra().mass[0]);
  EXPECT_NEAR(after.eroded, events[0].energy, 1e-12 * before.kinetic);
  EXPECT_NEAR(after.total(), before.total(), 1e-9 * before.total());
  EXPECT_NO_THROW(solver.step(solver.stable_time_step()));
}

}  // namespace
}  // namespace afemp::fem
