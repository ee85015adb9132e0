// Meshes and materials shared by the static-solve tests (header only; not a test file itself):
// steel (elastic, J2, Johnson-Cook), the quarter ring of the thick cylinder and the Lame
// solution it is checked against.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include "afemp/material.hpp"
#include "fem/mesh.hpp"
#include "fem/mesh_generation.hpp"
#include "fem/static_solve.hpp"

namespace afemp::fem::test {

inline core::Material steel() {
  core::Material m;
  m.name = "steel";
  m.density = 7.85e-3;
  m.youngs_modulus = 200e3;  // MPa
  m.poisson_ratio = 0.3;
  return m;
}

inline core::Material j2_steel(double hardening) {
  core::Material m = steel();
  m.strength = core::J2Plasticity{250.0, hardening};  // yield 250 MPa, plastic modulus H
  return m;
}

// Johnson-Cook with thermal softening at 600 K (T* = 0.204, 1 - T*^m = 0.806), the rate term
// present (C > 0) but frozen at its quasi-static factor 1 by the static update.
inline core::Material jc_steel() {
  core::Material m = steel();
  m.name = "jc-steel";
  core::JohnsonCook jc;
  jc.A = 300.0;
  jc.B = 500.0;
  jc.n = 0.3;
  jc.C = 0.014;
  jc.m = 1.03;
  jc.melt_temperature = 1800.0;
  m.strength = jc;
  m.thermal.initial_temperature = 600.0;
  return m;
}

// The quarter ring a <= r <= b, 0 <= theta <= 90 degrees, 0 <= z <= thickness: a box in
// (r, theta, z) of n_r x n_theta x 1 elements mapped to (r cos theta, r sin theta, z), so that
// its nodes lie on the circles. Node sets as box_mesh's: "xmin" the bore, "xmax" the outside,
// "ymin" the cut y = 0, "ymax" the cut x = 0.
inline MeshData quarter_ring(double a, double b, double thickness, int n_r, int n_theta) {
  MeshData mesh = box_mesh(core::BoxShape{{a, 0.0, 0.0}, {b, 0.5 * std::numbers::pi, thickness}},
                           {n_r, n_theta, 1});
  for (core::Vec3& p : mesh.nodes) p = {p.x * std::cos(p.y), p.x * std::sin(p.y), p.z};
  mesh.part_names[0] = "ring";
  return mesh;
}

inline const std::vector<std::int32_t>& node_set(const MeshData& mesh, const char* name) {
  for (const NamedSet& s : mesh.node_sets)
    if (s.name == name) return s.members;
  throw std::invalid_argument(name);
}

// Plane strain (every u_z = 0) and symmetry (u_y = 0 on y = 0, u_x = 0 on x = 0) of the ring,
// with pressure p on its bore.
inline StaticProblem pressurised_ring(const MeshData& ring, const core::Material& material,
                                      double p) {
  StaticProblem problem;
  problem.mesh = &ring;
  problem.materials = {material};
  for (std::size_t n = 0; n < ring.nodes.size(); ++n)
    problem.prescribed.push_back({static_cast<std::int32_t>(n), 2, 0.0});
  for (std::int32_t n : node_set(ring, "ymin")) problem.prescribed.push_back({n, 1, 0.0});
  for (std::int32_t n : node_set(ring, "ymax")) problem.prescribed.push_back({n, 0, 0.0});
  for (const auto& face : faces_on_nodes(ring, node_set(ring, "xmin")))
    problem.pressures.push_back({face, p});
  return problem;
}

// The position of Gauss point g (at kHexNatural[g] / sqrt 3) of hexahedron e.
inline core::Vec3 gauss_point(const MeshData& mesh, std::size_t e, int g) {
  const double r = 1.0 / std::sqrt(3.0);
  core::Vec3 x;
  for (int a = 0; a < 8; ++a) {
    double n = 0.125;
    for (int i = 0; i < 3; ++i) n *= 1.0 + kHexNatural[a][i] * kHexNatural[g][i] * r;
    x += n * mesh.nodes[mesh.hexahedra[e][a]];
  }
  return x;
}

// Radial and hoop stress at (x, y) from the Cartesian components.
struct Polar {
  double radial, hoop;
};
inline Polar polar(const core::SymTensor& s, const core::Vec3& x) {
  const double r = std::hypot(x.x, x.y), c = x.x / r, sn = x.y / r;
  return {s.xx * c * c + s.yy * sn * sn + 2.0 * s.xy * c * sn,
          s.xx * sn * sn + s.yy * c * c - 2.0 * s.xy * c * sn};
}

// The cantilever of the static tests: a steel beam 10 x 1 x 1 of n_x x n x n hexahedra
// (`formulations`: one per part, or none for B-bar), its root face x = 0 held as beam theory
// clamps it (u_x = 0 over the face, u_y = 0 only on the line y = h/2, u_z = 0 only on z = h/2),
// a shear force P = 10 along z spread over the end face's nodes. Its end face's mean deflection,
// and the Timoshenko beam's, delta = P L^3 / (3 E I) + P L / (kappa G A) with
// kappa = 10 (1 + nu) / (12 + 11 nu) (Cowper 1966, rectangle), in its two parts.
struct Cantilever {
  double deflection, bending, shear;
  double error() const { return deflection / (bending + shear) - 1.0; }
};
inline Cantilever cantilever(int n_x, int n, std::vector<HexahedronFormulation> formulations = {}) {
  const double length = 10.0, h = 1.0, force = 10.0;
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {length, h, h}}, {n_x, n, n});
  mesh.part_names[0] = "beam";
  const core::Material m = steel();
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m};
  problem.hexahedra = std::move(formulations);
  for (std::int32_t node : node_set(mesh, "xmin")) {
    problem.prescribed.push_back({node, 0, 0.0});
    if (std::abs(mesh.nodes[node].y - 0.5 * h) < 1e-9) problem.prescribed.push_back({node, 1, 0.0});
    if (std::abs(mesh.nodes[node].z - 0.5 * h) < 1e-9) problem.prescribed.push_back({node, 2, 0.0});
  }
  problem.nodal_forces.assign(mesh.nodes.size(), core::Vec3{});
  const auto faces = faces_on_nodes(mesh, node_set(mesh, "xmax"));
  for (const auto& face : faces)
    for (std::int32_t node : face) problem.nodal_forces[node].z += force / (4.0 * faces.size());
  const StaticResult r = solve_static(problem);
  const std::vector<std::int32_t>& tip = node_set(mesh, "xmax");
  double deflection = 0.0;
  for (std::int32_t node : tip) deflection += r.displacement[node].z;
  deflection /= static_cast<double>(tip.size());
  const double nu = m.poisson_ratio, inertia = h * h * h * h / 12.0;
  const double kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
  return {deflection, force * length * length * length / (3.0 * m.youngs_modulus * inertia),
          force * length / (kappa * m.shear_modulus() * h * h)};
}

}  // namespace afemp::fem::test
