// Contact between meshes (LS-DYNA *CONTACT_(ERODING_)SURFACE_TO_SURFACE, Abaqus/Explicit's
// surface-to-surface contact), node-to-face in both directions. The penalty acts on the
// penetration predicted at the end of the step (the predictor-corrector of Taylor & Flanagan
// 1989, "The PRONTO 3D contact algorithm", Sandia; Belytschko, Liu & Moran 2000, §10.5): with
// the velocities v^{n+1/2} of the nodal update, the positions x^{n+1} = x^n + dt v; a slave node
// behind a master face there (its closest-point projection on the bilinear face, the gap
// g = n . (x_s - x_c) < 0) gets the impulse P n, the face's nodes -N_a P n, with
// P = s (-g) / (dt w), w = 1/m_s + sum N_a^2 / m_a the pair's inverse mass: a penalty spring of
// stiffness k = s / (w dt^2) (LS-DYNA's SOFT=1 form, the nodal masses over the step squared)
// on the predicted penetration. s = 1 closes it within the step (kinematic contact); below 1
// the remainder is taken over the next steps. Being a velocity correction that takes out at
// most the penetration predicted for the step (and a tenth of one already there), not a spring
// the step must resolve, it is stable for s in (0, 1] at any step. The pairs share nodes, so the
// impulses are found by projected Gauss-Seidel sweeps in slave order (the total normal impulse of a
// pair stays >= 0: surfaces separate freely), with Coulomb friction limiting the tangential impulse
// to mu P. A slave keeps the face it met last while that face still holds it (a node that entered a
// thin plate is pushed back out of the side it came in by). The faces are found through bins whose
// cost grows with the surface (a face in every bin its box, grown by its reach and a margin of a
// quarter face, touches; a slave in its own bin), remade only when a face node has moved by the
// margin. The surfaces are rebuilt from the live elements whenever elements erode or convert
// (eroding contact). The surfaces come from the element sets (element_set.hpp): the boundary
// faces of the kinds with faces, the live elements' nodes of those without (slaves only).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "afemp/scene.hpp"

namespace afemp::fem {

using core::Vec3;
struct FeNodes;    // fe_solver.hpp
class ElementSet;  // element_set.hpp

// One direction of a contact: slave nodes against master faces.
struct ContactPass {
  std::vector<std::int32_t> slaves;
  // The slaves' own boundary faces (bodies of a kind with faces; outward): a face holds a slave
  // only when the two surfaces face each other (the slave's normal, the area-weighted mean of its
  // faces', against the face's), so a node on an edge is not caught by the side face it
  // slides along.
  std::vector<std::array<std::int32_t, 4>> slave_faces;
  std::vector<Vec3> slave_normal;  // per FE node, this step's (unnormalised)
  // Per slave (in `slaves` order): its own faces (CSR into slave_faces), for the normals.
  std::vector<std::int32_t> slave_face_offsets, slave_face_list;
  std::vector<std::array<std::int32_t, 4>> faces;    // master faces, node order outward
  std::vector<std::int32_t> face_set, face_element;  // the element of each face, in its set
  std::vector<double> reach;      // the largest penetration the face holds a node at
  bool slaves_first_body = true;  // the slaves are nodes of the contact's first body
  // Per FE node (sized on the first build): the face it met last (-1: none).
  std::vector<std::int32_t> last_face;
  // Bins of the current step (CSR of face indices per bin).
  Vec3 bin_min;
  double bin_size = 0.0;
  std::array<std::int64_t, 3> bin_count{0, 0, 0};
  std::vector<std::int64_t> bin_offsets;
  std::vector<std::int32_t> bin_faces;
  std::vector<std::array<Vec3, 2>> face_box;  // each face's box grown by its reach and margin
  // The bins hold while no face node has moved more than `margin` since they were made (the
  // boxes are grown by it): the face nodes and their positions then.
  double margin = 0.0;
  std::vector<std::int32_t> face_nodes;
  std::vector<Vec3> binned_position;
  bool binned = false;
};

// A slave node behind a master face at the predicted positions, and the impulses the
// Gauss-Seidel sweeps give the pair.
struct ContactHit {
  std::int32_t slave = 0;
  std::array<std::int32_t, 4> face{};  // the master face's nodes
  std::array<double, 4> shape{};       // their shape functions at the projection
  Vec3 normal;                         // the face's outward unit normal there
  double normal_impulse = 0.0;         // P >= 0, on the slave along the normal
  double target = 0.0;                 // the predicted gap the sweeps aim at, (1 - s) g0
  Vec3 tangential_impulse;             // on the slave, |T| <= mu P
  bool first_body = true;              // the slave is a node of the contact's first body
};

struct MeshContact {
  core::ContactSpec spec;
  std::vector<ContactPass> passes;  // 1 (self-contact, or trusses against hexahedra) or 2
  std::vector<ContactHit> hits;     // this step's, pass by pass in slave order
  // This step's resultant normal and tangential forces on the first body (impulse over the
  // step; self-contact: on the slave nodes), and the work friction dissipated so far.
  Vec3 normal_force, tangential_force;
  // The sums of the pairs' force magnitudes (what a self-contact transmits: its resultant on
  // the body is zero).
  double normal_sum = 0.0, tangential_sum = 0.0;
  double friction_work = 0.0;
  std::vector<std::vector<ContactHit>> thread_hits;
};

// The contact of spec between the meshes, its surfaces from the live elements.
MeshContact make_mesh_contact(const core::ContactSpec& spec, const core::Scene& scene,
                              std::span<ElementSet* const> sets, const FeNodes& nodes);
// Rebuilds the slave lists and master faces from the live elements (after erosion or
// conversion); a slave's last face follows it to the rebuilt list where the face is still there.
void rebuild_surfaces(MeshContact& c, const core::Scene& scene, std::span<ElementSet* const> sets,
                      const FeNodes& nodes);
// Finds this step's hits at the predicted positions x (per FE node): c.hits.
void find_contacts(MeshContact& c, const FeNodes& nodes, std::span<ElementSet* const> sets,
                   const std::vector<Vec3>& x);

}  // namespace afemp::fem
