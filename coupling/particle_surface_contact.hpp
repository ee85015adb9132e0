// Particles at the faces of a mesh (`[[contact]]` method "surface"): a body of particles and a
// body of hexahedra, deformable or rigid, meet where the particles' boundary reaches the mesh's
// boundary faces, not a cell early as in grid contact. Each particle is a slave of half width
// r = V^(1/3) / 2 at its predicted position x + dt v_p (v_p = sum N v_new, this step's grid
// velocity at it); a master face at its nodes' predicted positions x_a + dt v_a (v^{n+1/2} of
// the nodal update) holds it when the particle projects inside the face and its boundary lies
// behind it, g = n . (x_p - x_c) - r < 0 (n the face's outward normal). The pair takes the
// impulse that brings g to zero (penalty s: to (1 - s) g; a penetration already there at x^n
// recedes by a tenth a step), J n on the particle's grid nodes by their shape functions and
// -phi_a J n on the face's nodes, with the pair's inverse mass w = sum N^2 / m_I + sum phi_a^2 w_a
// (w_a a free node's 1/m, a rigid body's effective inverse mass at the node): the node-to-surface
// scheme of the mesh contacts (fem/mesh_contact.hpp; Taylor & Flanagan 1989) with the particle's
// domain as the slave, and the nodal form of a contact force on a particle (Sulsky, Chen &
// Schreyer 1994, eq 20). Projected Gauss-Seidel sweeps in the order of the particles' ids resolve
// the pairs that share nodes (J >= 0: the bodies separate freely), Coulomb friction limits the
// tangential impulse to mu J. The faces are rebuilt when elements erode or convert. On MPI ranks
// each rank finds the hits of its own particles, and every rank sweeps every rank's hits
// (mpm/contact_nodes.hpp): the mesh, on every rank, takes the same impulses everywhere.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "afemp/scene.hpp"
#include "fem/surface_faces.hpp"
#include "mpm/contact_nodes.hpp"
#include "mpm/grid_points.hpp"

namespace afemp::core {
class BackgroundGrid;
class StateArchive;
}  // namespace afemp::core

namespace afemp::fem {
class FeSolver;
}

namespace afemp::coupling {

using core::Vec3;

class ParticleSurfaceContacts final : public mpm::SurfaceContacts {
 public:
  struct Pair {
    core::ContactSpec spec;
    int particles = -1, mesh = -1;  // the particle body and the mesh body
    std::vector<char> selected;     // per scene body: the mesh body
    fem::SurfaceFaces faces;
    std::vector<Vec3> outward;                        // each face's outward area vector (this step)
    std::size_t live = static_cast<std::size_t>(-1);  // live hexahedra when the faces were made
    // This step's resultant forces on the particle body (impulse over the step) and the work
    // friction dissipated so far.
    Vec3 normal_force, tangential_force;
    double friction_work = 0.0;
  };

  ParticleSurfaceContacts(const core::Scene& scene, fem::FeSolver& fe);
  void resolve(const mpm::GridStepAccess& access) override;
  const std::vector<Pair>& pairs() const { return pairs_; }
  double friction_work() const;
  // Saves or restores the pairs' forces and friction work (coupled_state.cpp).
  void state(core::StateArchive& archive);

 private:
  // One particle held by one face this step: the particle (its id and position at the step's
  // start), the face point and normal, the impulses, and the inverse masses along the normal
  // (the pair's: the particle's sum N^2 / m_I plus the face nodes' shares; each face node's).
  struct Hit {
    std::int64_t id = 0;
    Vec3 position;
    double radius = 0.0;
    std::array<std::int32_t, 4> face{};
    std::array<double, 4> shape{};
    Vec3 normal;
    double target = 0.0, normal_impulse = 0.0;
    Vec3 tangential_impulse;
    double w = 0.0;
    std::array<double, 4> w_face{};
  };
  // The bins of the faces' grown boxes (bin_entries_ holds their faces): their bounds, edge
  // and counts.
  struct FaceBins {
    Vec3 lo, hi;
    double size = 0.0;
    std::array<std::int64_t, 3> count{};
    std::int64_t bin(const Vec3& x, int d) const;
    std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k) const;
  };
  // One pair's step: the faces and their bins, the hits, the sweeps and the forces.
  template <class Stencil>
  void resolve_pair(Pair& pair, const mpm::GridStepAccess& access);
  FaceBins bin_faces(Pair& pair, double cell);
  bool nearest_face(const Pair& pair, const FaceBins& bins, const Vec3& x, double r,
                    Hit& best) const;
  template <class Stencil>
  void find_hits(const Pair& pair, const mpm::GridStepAccess& access, const FaceBins& bins);
  void face_state(const Hit& h, double dt, Vec3& x_face, Vec3& v_face) const;
  void sweep_hits(const Pair& pair, double dt);
  void report_forces(Pair& pair, double dt) const;

  fem::FeSolver& fe_;
  std::vector<Pair> pairs_;
  // Scratch: predicted node positions, face bins, one stencil's slots and weights; the hits
  // with their grid nodes (on MPI ranks, every rank's: mpm/contact_nodes.hpp).
  std::vector<Vec3> predicted_;
  std::vector<std::array<Vec3, 2>> face_box_;  // each face's box, grown by its reach and a cell
  std::vector<double> face_reach_;
  std::vector<std::pair<std::int64_t, std::int32_t>> bin_entries_;  // (bin, face), sorted
  mpm::ContactNodes<Hit> hits_;
  std::vector<std::int64_t> slots_;
  std::vector<double> weights_;
};

}  // namespace afemp::coupling
