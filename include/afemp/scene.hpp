// The scene: everything a run needs, as plain data with defaults a newcomer would pick
// (docs/scene-format.md names each key). The scene-file parser fills it, and so may a program
// through the library (afemp/simulation.hpp checks it as the parser does). Units are the
// scene's own consistent set.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "afemp/errors.hpp"
#include "afemp/material.hpp"
#include "afemp/ogive_nose.hpp"
#include "afemp/probes.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

/// MPM update scheme: stress update before or after the grid update, or both (modified USL).
/// Lian et al. 2013, eqs 25-27; USAVG: half the strain increment from the start velocity before
/// the forces, half from the remapped end velocity after (Wallstedt & Guilkey 2008).
enum class UpdateScheme { USF, USL, MUSL, USAVG };
/// Particle-grid weights: the trilinear hat of the node (Ma 2005, eq 2-5); uGIMP, the hat
/// averaged over the particle's cubic domain (Bardenhagen & Kober 2004), smooth across cells;
/// the quadratic and cubic B-splines (Steffen, Kirby & Berzins 2008), modified at the grid's
/// faces; CPDI, the hat averaged over a domain that deforms with the material: a parallelepiped
/// following the deformation gradient (cpdi1, Sadeghirad, Brannon & Burghardt 2011) or a
/// hexahedron whose corners are tracked (cpdi2, Sadeghirad, Brannon & Guilkey 2013).
enum class ShapeFunction { linear, gimp, bspline2, bspline3, cpdi1, cpdi2 };
/// How velocity travels between particles and grid: the FLIP/PIC blend, or the affine PIC of
/// Jiang et al. 2015 (particles carry an affine velocity C_p; P2G maps v_p + C_p (x_I - x_p)).
enum class Transfer { flip, apic };
/// Where the MPM's weights live: updated-Lagrangian, at the particles' current positions (the
/// default); total-Lagrangian (de Vaucorbeil, Nguyen & Hutchinson 2020), at their reference
/// positions, computed from those alone, with gradients mapped to the current configuration by
/// each particle's deformation gradient.
enum class Formulation { updated_lagrangian, total_lagrangian };
/// Where the particles' pressure comes from: each point's own volumetric law, or the mixed
/// displacement-pressure projection of the total-Lagrangian MPM (Zhang et al. 2022).
enum class PressureField { standard, mixed };
/// free: nothing; fixed: all velocity components zero (the material sticks);
/// symmetric: normal component zero (a symmetry plane; tension is carried across it);
/// wall: a rigid frictionless wall the material may not cross but may leave (the normal
/// component is zeroed only at nodes whose updated velocity points into the wall);
/// outflow: nothing imposed, and a particle that leaves the grid through the face takes no
/// further part in the run (its mass, momentum and energy are booked in Energies::outflow*).
/// Through the other faces a particle leaving the grid stops the run;
/// absorbing: a viscous boundary (Lysmer & Kuhlemeyer 1969) for a body that continues beyond
/// the face: tractions -rho c_L v_n and -rho c_S v_t let waves leave instead of reflecting.
enum class FaceCondition { free, fixed, symmetric, wall, outflow, absorbing };
/// The six faces of the grid domain, in the order of GridSettings::faces.
enum class Face { xmin = 0, xmax, ymin, ymax, zmin, zmax };

/// The scene file's names of the enumerations above.
const char* to_string(UpdateScheme s);
const char* to_string(ShapeFunction s);
const char* to_string(Transfer t);
const char* to_string(Formulation f);
const char* to_string(PressureField p);
const char* to_string(FaceCondition c);
const char* to_string(Face f);

/// The [run] section: end time, time-step factors, output and history intervals, guards.
struct RunSettings {
  std::string title{};                    ///< printed with the run
  double end_time = 0.0;                  ///< required
  double time_step_factor = 0.3;          ///< Courant safety factor on the grid's stable step
  double element_time_step_factor = 0.9;  ///< on the elements' critical step (LS-DYNA's TSSFAC)
  double fixed_time_step = 0.0;           ///< > 0: use this step instead of the stable one
  long max_steps = 0;                     ///< > 0: stop after this many steps
  double output_every = 0.0;  ///< simulated time between field outputs; 0: final state only
  long history_every = 10;    ///< steps between history rows
  /// > 0: simulated time between history rows instead (a row at the first step end at or past
  /// each multiple); 0: history_every steps.
  double history_interval = 0.0;
  /// Times of field frames (increasing, in (0, end_time]), besides output_every's: a frame at
  /// the first step end at or past each.
  std::vector<double> output_times{};
  /// > 0: stop the run as unstable once |energy-balance error| exceeds this at a history row
  /// (energy created or destroyed beyond any physical account); 0: no such guard.
  double energy_error_limit = 1.0;
  bool output_strain = false;  ///< integrate and write each particle's strain tensor
  Vec3 gravity{};              ///< body force per unit mass
  /// Stop before end_time once a body's centre of mass has moved `travel` from where it started
  /// (LS-DYNA's *TERMINATION_BODY): a perforation run ends when the projectile is through.
  struct Termination {
    int body = -1;
    double travel = 0.0;
  };
  std::optional<Termination> terminate{};
  /// The unit system the scene's numbers are in, for plausibility warnings
  /// (core/plausibility.hpp): "mm-ms-g" (mm, ms, g, N, MPa), "SI", or empty (each material is
  /// then tried against the unit systems a scene may be in).
  std::string units{};
  /// Keys whose plausibility warnings are silenced (dotted, as the warning names them).
  std::vector<std::string> quiet{};
  /// What the deck an imported scene came from holds that changes the run and was not
  /// translated (`afemp import --allow-untranslated`, docs/import.md), one "FILE:LINE: KEYWORD:
  /// ..." line each: `afemp check` and `afemp run` repeat them as warnings.
  std::vector<std::string> untranslated{};
  SourceLocation untranslated_where{};  ///< the key's line (messages)
  /// Checkpoints (docs/restart.md): every checkpoint_every of simulated time (0: none) and every
  /// checkpoint_wall_every seconds of wall time (0: none), keeping the newest checkpoint_keep.
  double checkpoint_every = 0.0;
  double checkpoint_wall_every = 1800.0;
  int checkpoint_keep = 2;
  /// Sums that do not depend on their order (docs/parallel.md, "Determinism"): the grid's nodal
  /// sums in 128-bit fixed point, the energies and forces exact, so that a run gives the same
  /// bits on any number of MPI ranks and threads (core/exact_sum.hpp). Scenes of particles or of
  /// meshes (core/reproducible_refusals.hpp says what is refused).
  bool reproducible = false;
  SourceLocation reproducible_where{};  ///< the key's line (messages)
};

/// What lies beyond the absorbing faces of a grid (mpm/absorbing_faces.hpp): an unbounded fluid
/// at a hydrostatic pressure, into which waves and flow leave as spherical ones from a centre
/// (Geers's doubly asymptotic approximation, exact for a source at the centre: it keeps the
/// outer fluid's added mass, which a pulsating bubble feels, as well as its radiation damping).
struct FarField {
  Vec3 centre{};          ///< where the outgoing waves come from (an explosion's centre)
  double pressure = 0.0;  ///< the ambient pressure held beyond the faces (depth: rho g z + p_atm)
  /// How the ambient pressure enters the internal force (mpm/absorbing_faces.hpp):
  /// gauge: the stress relative to it, sigma + p I (a gas near the ambient; a void reads as
  /// the ambient); absolute: the stress itself, with the ambient as a static traction on the
  /// faces (a gas far below the ambient, as an explosion bubble near its largest; a void
  /// reads as vacuum; prestressed bodies need two or more particles per cell direction).
  bool absolute_stress = false;
};

/// The [grid] section: the background grid of cubic cells and its face conditions.
struct GridSettings {
  double cell = 0.0;  ///< cell edge length h (cubic cells)
  Vec3 min{}, max{};  ///< the domain; grid nodes sit at min + i h
  std::array<FaceCondition, 6> faces{FaceCondition::free, FaceCondition::free, FaceCondition::free,
                                     FaceCondition::free, FaceCondition::free, FaceCondition::free};
  /// Set: the absorbing faces open onto an unbounded fluid (FarField); unset: plane-wave
  /// (Lysmer-Kuhlemeyer) faces at zero pressure.
  std::optional<FarField> far_field{};
  /// Axisymmetric about the z axis (mpm/axisymmetric.hpp): x is the radius r >= 0, the
  /// particles lie in the r-z plane y = 0 and each stands for its ring (volume and mass
  /// 2 pi r A); the grid is one cell thick across it (y from -h/2 to h/2, both faces
  /// symmetric) and its x = 0 face, the axis, symmetric.
  bool axisymmetric = false;
  /// Whether some face has condition c.
  bool has_face(FaceCondition c) const {
    for (FaceCondition f : faces)
      if (f == c) return true;
    return false;
  }
};

/// Makes `grid` the axisymmetric grid its cell and its r-z extent (min.x = 0 to max.x, min.z
/// to max.z) describe: `axisymmetric` set, y from -cell/2 to cell/2, the faces xmin (the
/// axis), ymin and ymax symmetric. The parser does this for `axisymmetric = true`; a scene
/// built in code calls it once cell, min and max are set.
inline void make_axisymmetric(GridSettings& grid) {
  grid.axisymmetric = true;
  grid.min.y = -0.5 * grid.cell;
  grid.max.y = 0.5 * grid.cell;
  grid.faces[static_cast<std::size_t>(Face::xmin)] = FaceCondition::symmetric;
  grid.faces[static_cast<std::size_t>(Face::ymin)] = FaceCondition::symmetric;
  grid.faces[static_cast<std::size_t>(Face::ymax)] = FaceCondition::symmetric;
}

/// Adaptive multi-axis particle splitting (the 2020 Journal of Harbin Engineering University
/// paper on MPM for explosion and impact, eqs 14-17): a particle whose length along an axis
/// reaches 2 alpha l0 (l0 its initial length there) splits into two halves along that axis, on
/// every axis that meets it in the same step (2, 4 or 8 particles: the seven 3-D patterns).
struct SplittingSettings {
  double alpha = 0.9;                    ///< split factor, in (0.5, 1.5]
  std::size_t max_particles = 10000000;  ///< a split that would exceed it stops the run
  std::vector<int> bodies{};             ///< the particle bodies that split (indices); empty: all
  std::array<bool, 3> axes{true, true, true};  ///< the axes (x, y, z) a particle may split along
};

/// The [mpm] section: scheme, shape function, transfer, splitting, and the grid.
struct MpmSettings {
  UpdateScheme scheme = UpdateScheme::MUSL;     ///< USF, USL or MUSL
  ShapeFunction shape = ShapeFunction::linear;  ///< particle-grid weights
  Transfer transfer = Transfer::flip;           ///< FLIP/PIC blend or APIC
  double flip = 1.0;    ///< velocity update blend (transfer flip): 1 pure FLIP, 0 pure PIC
  bool jaumann = true;  ///< objective (Jaumann) stress rate
  Formulation formulation = Formulation::updated_lagrangian;  ///< where the weights live
  PressureField pressure = PressureField::standard;           ///< point-wise or mixed u-p pressure
  std::optional<SplittingSettings> splitting{};  ///< adaptive particle splitting; none: off
  GridSettings grid{};                           ///< the background grid
};

/// An axis-aligned box, corners min and max.
struct BoxShape {
  Vec3 min{}, max{};  ///< opposite corners
};
/// A cylinder from its base disc along its axis, optionally with an ogive nose at the far end.
struct CylinderShape {
  Vec3 base{};         ///< centre of the base disc
  Vec3 axis{0, 0, 1};  ///< direction, normalised by the parser
  double radius = 0.0;
  double length = 0.0;  ///< overall, the nose included
  OgiveNose nose{};     ///< at the far end (base + length axis); crh 0: a flat end
  /// A cone or frustum (the scene's `cone`, particles only): the radius at the far end, the
  /// radius falling linearly from `radius` at the base; < 0: a cylinder.
  double top_radius = -1.0;
  /// A cone's wall thickness normal to its surface (a conical liner, open at the base, solid
  /// near the apex); 0: a solid cone.
  double wall = 0.0;
};
/// A sphere (particles, or hexahedra: fem/mesh_generation.hpp's blended cubed sphere).
struct SphereShape {
  Vec3 centre{};        ///< centre
  double radius = 0.0;  ///< radius
};
/// Particles at given points: read from a plain-text file (one "x y z [volume]" per line, '#'
/// comments; the path resolved relative to the scene file), or, from a program, the arrays
/// `points` and `volumes` (empty volumes: (cell / particles_per_cell)^3 each).
struct PointListShape {
  std::string path{};             ///< empty: the arrays
  std::vector<Vec3> points{};     ///< particle positions
  std::vector<double> volumes{};  ///< one volume per point, or empty
};
/// A mesh given as arrays (a program's own mesh): nodes, 8-node hexahedra and 2-node trusses
/// by 0-based node index, and named node sets for constraints (`set` selectors). Hexahedron
/// node order: nodes 0-3 round the face zeta = -1, 4-7 round zeta = +1 (LS-DYNA, Abaqus C3D8).
struct MeshArrays {
  std::vector<Vec3> nodes{};                             ///< node positions
  std::vector<std::array<std::int32_t, 8>> hexahedra{};  ///< 8 node indices each
  std::vector<std::array<std::int32_t, 2>> trusses{};    ///< 2 node indices each
  std::vector<double> truss_areas{};  ///< one per truss, or empty: the body's area
  struct NodeSet {
    std::string name{};
    std::vector<std::int32_t> nodes{};
  };
  std::vector<NodeSet> node_sets;  ///< named sets for constraints (NodeSelector::set)
};
/// A mesh read from a file (Gmsh .msh 4.1, Abaqus .inp, LS-DYNA keyword), path resolved
/// relative to the scene file, or given as arrays; `parts` selects parts by name (empty: all).
struct MeshFileShape {
  std::string path{};                ///< empty: the arrays
  MeshArrays arrays{};               ///< the mesh itself, when path is empty
  std::vector<std::string> parts{};  ///< parts to take from a file (empty: all)
  double scale = 1.0;                ///< coordinates are multiplied by scale, then translated
  Vec3 translate{};                  ///< added after scaling
};
/// A straight truss bar.
struct LineShape {
  Vec3 from{}, to{};  ///< end points
};
/// A rebar mat: straight bars both ways in the plane normal to `normal_axis` at `position`,
/// spanning the box [min, max] less the cover (fem/mesh_generation.hpp).
struct RebarShape {
  Vec3 min{}, max{};
  int normal_axis = 2;
  std::vector<double> positions;  ///< one mat (layer) per plane position along normal_axis
  double spacing = 0.0, diameter = 0.0, cover = 0.0;
};
/// Where a body's material is: a shape the body is filled with or a mesh it is made of.
using Shape = std::variant<BoxShape, CylinderShape, SphereShape, PointListShape, MeshFileShape,
                           LineShape, RebarShape>;

/// What a body is made of.
enum class Discretisation { particles, hexahedra, trusses };
enum class HexFormulation { one_point, full };  ///< FB hourglass-controlled | 2x2x2 B-bar
/// FB viscous (LS-DYNA type 3) | FB stiffness (type 5) | assumed strain (type 6, Belytschko &
/// Bindeman ASQBI): fem/hourglass.hpp, fem/hourglass_assumed_strain.hpp
enum class HourglassForm { viscous, stiffness, assumed_strain };
/// The scene file's names of the enumerations above.
const char* to_string(Discretisation d);
const char* to_string(HexFormulation f);
const char* to_string(HourglassForm f);

/// How finely a generated mesh divides its shape. `size` (a target edge length) fills what is
/// not given explicitly.
struct MeshDensity {
  std::array<int, 3> divisions{0, 0, 0};  ///< box: elements along x, y, z; sphere: [0] across
  int core = 0, ring = 0, axial = 0;      ///< cylinder O-grid (fem/mesh_generation.hpp)
  int sectors = 4;                        ///< cylinder, sphere: 1 quarter, 2 half, 4 full
  int segments = 0;                       ///< line: trusses along the bar
  double size = 0.0;                      ///< target element edge / truss length
  /// box: a graded axis, as [end, elements] segments from the box's min to its max (the
  /// last end is the max), each divided evenly; empty: the axis takes divisions or size.
  std::array<std::vector<std::array<double, 2>>, 3> graded{};
};

/// Hourglass control of one-point hexahedra: form and coefficient.
struct HourglassSettings {
  HourglassForm form = HourglassForm::viscous;  ///< viscous, stiffness or assumed strain
  /// Q_hg, or the assumed strain form's scale on its stiffness; unset: the form's default, as
  /// in the scene file.
  std::optional<double> coefficient{};
  /// 0.1 viscous (LS-DYNA's QM), 0.05 stiffness (types 4 and 5), 1 assumed strain (the form
  /// has no free coefficient, only this scale).
  static constexpr double default_coefficient(HourglassForm f) {
    return f == HourglassForm::viscous ? 0.1 : f == HourglassForm::stiffness ? 0.05 : 1.0;
  }
  /// The coefficient in effect: the one given, else the form's default.
  double effective_coefficient() const { return coefficient.value_or(default_coefficient(form)); }
};

/// Linear and quadratic artificial bulk viscosity (LS-DYNA's Q2 = 0.06, Q1 = 1.5).
struct BulkViscositySettings {
  double linear = 0.06;    ///< Q1 on the sound speed term
  double quadratic = 1.5;  ///< Q2 on the velocity-jump term
};

/// Erosion criteria of a body's elements; 0 / false switches a criterion off. With erosion on,
/// an element whose Jacobian turns non-positive erodes instead of stopping the run.
struct ErosionSettings {
  double plastic_strain = 0.0;    ///< equivalent plastic strain at which an element erodes
  bool material_failure = false;  ///< erode at the material's failure_strain
  double volume_ratio = 0.0;      ///< erode when V / V0 falls below this
  double time_step = 0.0;         ///< erode when the element's critical step falls below this
};

/// Adaptive conversion of a body's hexahedra into particles (AFEMP, Lian et al. 2013, §2.6): an
/// element inside the grid domain that meets any criterion becomes points x points x points
/// particles; 0 / false switches a criterion off.
struct ConversionSettings {
  double plastic_strain = 0.0;     ///< equivalent plastic strain of any integration point
  double volumetric_strain = 0.0;  ///< |V / V0 - 1|
  double jacobian_ratio = 0.0;     ///< smallest scaled corner Jacobian (1 for a box) below this
  bool negative_jacobian = true;   ///< an element that inverts converts instead of stopping
  double time_step_fraction =
      0.0;              ///< critical step below this fraction of h / c (material at rest)
  double damage = 0.0;  ///< scalar damage of any integration point
  int points = 1;       ///< particles per direction: 1 or 2
};

/// A rigid body of hexahedra (LS-DYNA *MAT_RIGID): its elements carry no stress; it moves
/// with 6 degrees of freedom, its mass, centre of mass and inertia summed from its elements'
/// lumped node masses (fem/rigid_body.cpp). Fixed components keep their initial value: the
/// body's `velocity` for translations (zero: an anvil; non-zero: a die at constant speed), zero
/// for rotations.
struct RigidSettings {
  std::array<bool, 6> fixed{false, false, false, false, false, false};  ///< x y z rx ry rz
};

/// A body at rest under gravity (soil): at depth d below its free surface, along the gravity g,
/// the vertical stress is sigma_v = -rho |g| d and the horizontal ones K0 sigma_v
/// (core/materials/initial_pressure.hpp, geostatic_stress).
struct GeostaticStress {
  double surface = 0.0;  ///< the free surface's height along -g (its z when g points along -z)
  double k0 = 0.0;       ///< the coefficient of earth pressure at rest, sigma_h / sigma_v
};

/// One [[bodies]] entry: material (index into Scene::materials), discretisation, shape, and the
/// settings of that discretisation; initial velocity, temperature and internal energy.
struct BodySpec {
  std::string name{};                                         ///< unique in the scene
  int material = -1;                                          ///< index into Scene::materials
  Discretisation discretisation = Discretisation::particles;  ///< particles, hexahedra or trusses
  Shape shape{};                                              ///< where the body's material is
  int particles_per_cell = 2;                                 ///< per direction (particles)
  /// Particles of a sphere: on the grid's lattice (a staircase surface), or in shells that
  /// follow the sphere (mpm/sphere_shells.hpp), one particle per cell of a cubed-sphere grid.
  enum class Layout { lattice, shells };
  Layout layout = Layout::lattice;
  /// Meshes (hexahedra, trusses).
  MeshDensity mesh{};  ///< how finely a generated mesh divides the shape
  HexFormulation element = HexFormulation::one_point;  ///< one-point or fully integrated
  HourglassSettings hourglass{};                       ///< one-point hexahedra
  /// Unset: on (LS-DYNA's defaults) for hexahedra and for particles whose material has an
  /// equation of state, off otherwise (core::bulk_viscosity_of).
  std::optional<BulkViscositySettings> bulk_viscosity{};
  std::optional<ErosionSettings> erosion{};        ///< set: the elements may erode
  std::optional<ConversionSettings> conversion{};  ///< hexahedra
  std::optional<RigidSettings> rigid{};            ///< set: a rigid body (hexahedra)
  double area = 0.0;  ///< truss cross-section where the mesh gives none
  /// Trusses: the initial axial stress (tension positive) of a prestressed tendon or rebar,
  /// with its elastic energy; it acts from the start (a relaxation phase brings what the body is
  /// bonded to into equilibrium with it).
  double prestress = 0.0;
  /// Bonded coupling (HFEMP, Lian et al. 2013, §2.6): the particle body whose velocity field this
  /// mesh body's nodes join; they move with the grid solution (perfect bond). Trusses may name a
  /// body of hexahedra instead: their nodes are tied into its elements (rebar in solid elements,
  /// LS-DYNA's *CONSTRAINED_BEAM_IN_SOLID). -1: not bonded.
  int bonded_to = -1;
  /// Particles: none is placed inside the shapes of these bodies (water around a charge).
  std::vector<int> outside{};
  /// Bodies this one is meant to overlap with no contact between them (indices into
  /// Scene::bodies): neither the warning before the run nor the run's check for bodies that
  /// come to overlap names the pair (core/contact_warnings.hpp).
  std::vector<int> overlap_allowed{};
  Vec3 velocity{};                      ///< initial velocity
  std::optional<double> temperature{};  ///< initial temperature; default the material's
  /// Initial specific internal energy e0 (per unit mass; J/kg = mm^2/ms^2): with an EOS that
  /// depends on e it is an initial pressure (a hot or pressurised body, a gas charge), like
  /// LS-DYNA's E0 on the EOS card (which is per unit reference volume, rho0 e0).
  double internal_energy = 0.0;
  /// Particles: an initial pressure (water at depth): the particles start at the density at
  /// which the material's EOS gives it (core/materials/initial_pressure.hpp), with stress -p I.
  std::optional<double> pressure{};
  /// Particles and hexahedra: a geostatic initial stress (needs gravity).
  std::optional<GeostaticStress> initial_stress{};
  SourceLocation where{};  ///< the [[bodies]] table, for messages
};

/// Reference values a run compares its result with at the end (Ma 2005, eq 2-42).
struct TaylorReference {
  double length = 0.0, impact_diameter = 0.0, bulge_diameter = 0.0;  ///< L, D, W
  double tolerance = 0.0;  ///< allowed mean error; 0: report only
};

/// A body's mean velocity at the end of the run (a projectile's residual velocity, a bar's
/// rebound) against a reference value: error |v - value| / |value|.
struct VelocityReference {
  int body = -1;
  int component = -1;      ///< 0, 1, 2 for x, y, z; -1 for the magnitude
  double value = 0.0;      ///< != 0
  double tolerance = 0.0;  ///< allowed error; 0: report only
  SourceLocation where{};
};

/// Which mesh nodes a constraint holds: inside a box, on a plane (within tolerance), or a
/// node set named by an imported mesh.
struct NodeSelector {
  enum class Kind { box, plane, set } kind = Kind::box;
  Vec3 min{}, max{};        ///< box
  Vec3 point, normal;       ///< plane (normal unit)
  double tolerance = 1e-6;  ///< plane: largest distance of a selected node
  std::string set{};        ///< set
};

/// Fixed or prescribed-velocity nodes (FE bodies).
struct ConstraintSpec {
  NodeSelector nodes{};
  int body = -1;  ///< restrict to one body; -1: every mesh body
  std::array<bool, 3> components{false, false, false};  ///< which components are imposed
  Vec3 velocity;  ///< the imposed value (0 for fixed components)
  /// A velocity's history: (time, factor) points, times increasing; the imposed value at t is
  /// velocity times the factor interpolated linearly (the first factor before the first point,
  /// the last after the last). Empty: constant.
  std::vector<std::array<double, 2>> curve{};
  SourceLocation where{};
};

/// The factor of a constraint's curve at time t (1 without a curve).
inline double curve_factor(const std::vector<std::array<double, 2>>& curve, double t) {
  if (curve.empty()) return 1.0;
  if (t <= curve.front()[0]) return curve.front()[1];
  for (std::size_t k = 1; k < curve.size(); ++k)
    if (t <= curve[k][0]) {
      const double w = (t - curve[k - 1][0]) / (curve[k][0] - curve[k - 1][0]);
      return curve[k - 1][1] + w * (curve[k][1] - curve[k - 1][1]);
    }
  return curve.back()[1];
}

/// A load on one body ([[loads]], core/scene_parser.cpp). On hexahedra, a dead surface
/// traction on the boundary faces whose four nodes `region` holds (LS-DYNA's *LOAD_SEGMENT_SET
/// with a traction vector, Abaqus's *DSLOAD TRVEC), given per unit initial area or as a total
/// force spread over the faces' area, and handed to the nodes by the faces' bilinear shape
/// functions (fem/surface_loads.cpp). On particles, a total force shared among the particles
/// of the body that start inside `region` (a box) in proportion to their mass, as Uintah's and
/// CB-Geo's particle loads do (mpm/particle_loads.cpp): a particle carries no surface area of
/// its own, so only the total is exact. Its work is booked as external work.
struct LoadSpec {
  int body = -1;  ///< the loaded body (hexahedra or particles)
  /// Hexahedra: the loaded faces' nodes (box, plane or set); particles: a box.
  NodeSelector region{};
  bool traction = true;  ///< value is a traction (per unit initial area), else a total force
  Vec3 value{};
  /// The load's history: value times the factor interpolated linearly at each step's start
  /// time (curve_factor); empty: constant.
  std::vector<std::array<double, 2>> curve{};
  SourceLocation where{};
};

/// An absorbing (non-reflecting) boundary on mesh nodes: the viscous boundary of Lysmer &
/// Kuhlemeyer (1969), LS-DYNA's *BOUNDARY_NON_REFLECTING, on the boundary faces of hexahedra
/// whose four nodes the selector holds (fem/absorbing_boundary.cpp).
struct AbsorbingSpec {
  NodeSelector nodes{};
  int body = -1;  ///< restrict to one body; -1: every hexahedron body
  SourceLocation where{};
};

/// A rigid planar wall for FE nodes (LS-DYNA *RIGIDWALL_PLANAR): nodes stay on the side the
/// normal points to; the wall may move at a constant velocity; Coulomb friction.
struct WallSpec {
  Vec3 point{}, normal{}, velocity{};
  double friction = 0.0;
  std::vector<int> bodies{};  ///< empty: every mesh body
  SourceLocation where{};
};

/// How a contact acts.
/// grid: grid contact between two bodies, at least one of particles (Lian et al. 2013, eqs
/// 37-42): each body named in a contact gets its own velocity field on the grid (a mesh body's
/// nodes map into theirs: contact coupling, CFEMP); where two fields meet at a node and
/// approach, a normal correction makes their normal velocities equal, Coulomb friction limits
/// the tangential one, and they may separate.
/// penalty: between meshes (fem/mesh_contact.cpp): node-to-surface penalty contact in both
/// directions (surface to surface), the stiffness scaled by the nodal mass and the step
/// (LS-DYNA's SOFT=1), with Coulomb friction; one body named twice is its self-contact.
/// weld: two particle bodies meant to share one velocity field where they meet (stick, no
/// separation): nothing is added, and `afemp check` and `run` do not warn about the pair.
/// surface: a body of particles and a body of hexahedra (deformable or rigid) meet where the
/// particles' boundary reaches the mesh's faces (coupling/particle_surface_contact.cpp).
enum class ContactMethod { grid, penalty, weld, surface };
const char* to_string(ContactMethod m);

struct ContactSpec {
  std::array<int, 2> bodies{-1, -1};  ///< indices into Scene::bodies (equal: self-contact)
  ContactMethod method = ContactMethod::grid;
  double friction = 0.0;         ///< Coulomb coefficient
  double distance_factor = 0.5;  ///< grid: lambda of eq 42, contact once the gap <= lambda h
  /// penalty and surface: the fraction of the predicted penetration one step takes out,
  /// 0 < s <= 1 (1 closes it within the step; a velocity correction, stable for any s). The
  /// scene file's default is this one (core/scene_parser.cpp reads it from here).
  double penalty = 1.0;
  /// The prefix of its history columns NAME.fx ...; empty: "BODY1-BODY2" ("BODY-self"), as in
  /// the scene file.
  std::string name{};
  SourceLocation where{};
};

/// A detonation that lights the high explosives (programmed burn, afemp/material.hpp): a
/// point, a plane (points on either side light at their distance from it) or a line segment,
/// at a time. A point lights at min over detonations of (time + distance / D); the distance is
/// the straight line, or with `shadow` the shortest path that stays in the explosive (around
/// inert bodies and voids: core/detonation_paths.hpp).
struct DetonationSpec {
  enum class Kind { point, plane, line };
  Kind kind = Kind::point;
  Vec3 point{};   ///< the point; a point of the plane; the segment's start
  Vec3 normal{};  ///< plane: unit normal
  Vec3 end{};     ///< line: the segment's end
  double time = 0.0;
  bool shadow = false;  ///< the wave travels through explosive only (Huygens), not straight
  SourceLocation where{};
};

/// What a [[phases]] entry computes (docs/scene-format.md, "Phases").
/// static: the equilibrium of the loads at the phase's end (an implicit Newton solve of the
/// meshes, fem/static_phase.hpp), reached in load steps; relaxation: the same state reached by
/// dynamic relaxation (LS-DYNA's *CONTROL_DYNAMIC_RELAXATION, core/dynamic_relaxation.hpp), the
/// explicit model damped to rest under the scene's loads, for what the static solve cannot take
/// (particles, coupling, contact, any material); explicit: the explicit dynamics of the whole
/// scene, as a scene without phases runs.
enum class PhaseKind { static_load, implicit_dynamics, relaxation, explicit_dynamics };
const char* to_string(PhaseKind k);

/// One [[phases]] entry. The phases run in order on one clock: each from the end of the one
/// before (the first from 0) to its end_time; the last ends at [run] end_time. Static and
/// implicit phases may come anywhere, each from the state the phase before leaves; a
/// relaxation phase comes first only (core/phases.cpp says why).
struct PhaseSpec {
  PhaseKind kind = PhaseKind::explicit_dynamics;
  double end_time = 0.0;  ///< the last phase may leave it at 0: [run] end_time
  /// static: the loads reach their full value in load_steps equal steps (after another phase,
  /// from the state's own internal forces), each solved by Newton to |r| <= tolerance x the
  /// force scale in at most max_iterations iterations (implicit: per time step).
  int load_steps = 10;
  int max_iterations = 25;
  /// static and implicit: the residual's (default 1e-8); relaxation: DRTOL, the kinetic
  /// energy's fraction of its peak at convergence (default 1e-3). 0: the kind's default
  /// (phase_tolerance).
  double tolerance = 0.0;
  /// implicit: the longest time step (the phase is cut into equal steps no longer) and HHT's
  /// alpha in [-1/3, 0] (0: Newmark's trapezoidal rule, no numerical damping).
  double time_step = 0.0;
  double alpha = 0.0;
  /// relaxation: DRFCTR, the factor on every velocity after every step; NRCYCK, the steps
  /// between convergence checks; TSSFDR, the factor on the explicit model's stable step.
  double damping_factor = 0.995;
  long check_every = 250;
  double relaxation_step_factor = 1.0;
  /// static and implicit: the phase's gravity; unset: [run] gravity.
  std::optional<Vec3> gravity{};
  /// static and implicit: the mesh bodies it solves (indices into Scene::bodies); empty: every
  /// deformable mesh body not bonded to particles. The others are held where they are.
  std::vector<int> bodies{};
  SourceLocation where{};
};

/// Everything a run needs. Bodies, constraints, walls, contacts and references refer to materials
/// and bodies by index into the vectors here.
struct Scene {
  std::string path{};  ///< the scene file, as given
  /// The scene's TOML text as read (a checkpoint keeps it: a restart compares the scene with
  /// it); empty for scenes built in code.
  std::string source{};
  RunSettings run{};
  bool has_grid = false;  ///< a [grid] section: needed by particle bodies
  MpmSettings mpm{};
  std::vector<Material> materials{};
  /// Where each [materials.NAME] table is (messages; empty for scenes built in code).
  std::vector<SourceLocation> material_where{};
  SourceLocation grid_where{};  ///< the [grid] table
  std::vector<BodySpec> bodies{};
  std::vector<ConstraintSpec> constraints{};
  std::vector<AbsorbingSpec> absorbing{};  ///< [[absorbing]]: non-reflecting mesh boundaries
  std::vector<LoadSpec> loads{};           ///< [[loads]]: tractions and forces on bodies
  std::vector<WallSpec> walls{};
  std::vector<ContactSpec> contacts{};
  std::vector<DetonationSpec> detonations{};  ///< [[detonations]]: what lights the explosives
  std::optional<TaylorReference> taylor_reference{};
  std::vector<VelocityReference> velocity_references{};
  double energy_tolerance = 0.0;    ///< > 0: the largest |energy-balance error| allowed
  std::vector<ProbeSpec> probes{};  ///< [[probes]], in file order
  /// [[phases]], in order; empty: one explicit phase to [run] end_time.
  std::vector<PhaseSpec> phases{};
};

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::BodySpec;
using core::BoxShape;
using core::BulkViscositySettings;
using core::ConstraintSpec;
using core::ContactMethod;
using core::ContactSpec;
using core::ConversionSettings;
using core::CylinderShape;
using core::DetonationSpec;
using core::Discretisation;
using core::ErosionSettings;
using core::Face;
using core::FaceCondition;
using core::Formulation;
using core::GeostaticStress;
using core::GridSettings;
using core::HexFormulation;
using core::HourglassForm;
using core::HourglassSettings;
using core::LineShape;
using core::LoadSpec;
using core::MeshArrays;
using core::MeshDensity;
using core::MeshFileShape;
using core::MpmSettings;
using core::NodeSelector;
using core::PhaseKind;
using core::PhaseSpec;
using core::PointListShape;
using core::PressureField;
using core::RebarShape;
using core::RigidSettings;
using core::RunSettings;
using core::Scene;
using core::Shape;
using core::ShapeFunction;
using core::SphereShape;
using core::TaylorReference;
using core::to_string;
using core::Transfer;
using core::UpdateScheme;
using core::VelocityReference;
using core::WallSpec;
}  // namespace afemp
