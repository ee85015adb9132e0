// LS-DYNA keyword decks into afemp scenes (fem/lsdyna_deck_import.hpp). The mesh keywords are
// read by fem/lsdyna_reader.cpp when the scene runs; here every other keyword is translated,
// approximated with a note, listed as not translated, or refused: a keyword outside the subset
// that changes the run (anything but output and data only other keywords use) stops the import
// unless DeckImportOptions::allow_untranslated. Card layouts follow the LS-DYNA Keyword User's
// Manual (R13): Vol. I for *PART, *SECTION_SOLID, *SECTION_BEAM, *HOURGLASS, *INITIAL_VELOCITY,
// *INITIAL_VELOCITY_NODE, *INITIAL_VELOCITY_GENERATION, *CONTACT (the AUTOMATIC and ERODING
// forms), *SET_PART_LIST, *SET_NODE_LIST, *RIGIDWALL_PLANAR, *CONTROL_TERMINATION,
// *CONTROL_TIMESTEP, *CONTROL_HOURGLASS, *CONTROL_BULK_VISCOSITY, *CONTROL_SOLID,
// *CONTROL_CONTACT, *PART_CONTACT, *DATABASE_BINARY_D3PLOT, *DEFINE_CURVE,
// *BOUNDARY_PRESCRIBED_MOTION; Vol. II
// for *MAT_ELASTIC (001), *MAT_PLASTIC_KINEMATIC (003), *MAT_JOHNSON_COOK (015), *MAT_RIGID (020),
// *MAT_MOONEY-RIVLIN_RUBBER (027), *MAT_JOHNSON_HOLMQUIST_CONCRETE (111), *MAT_ADD_EROSION,
// *EOS_LINEAR_POLYNOMIAL (001) and *EOS_GRUNEISEN (004).
#include "fem/lsdyna_deck_import.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "core/decks/deck_units.hpp"
#include "core/decks/scene_text.hpp"
#include "core/nearly_incompressible.hpp"
#include "fem/lsdyna_keywords.hpp"
#include "fem/mesh_import.hpp"

namespace afemp::fem {

namespace {

namespace dim = core::dimension;

// Read by the mesh reader when the scene runs.
const std::set<std::string> kMeshKeywords = {"NODE",
                                             "ELEMENT_SOLID",
                                             "ELEMENT_BEAM",
                                             "SET_NODE_LIST",
                                             "SET_NODE_LIST_TITLE",
                                             "BOUNDARY_SPC_SET",
                                             "BOUNDARY_SPC_NODE"};

// Keywords outside the subset that leave the run as it is: output, and data that only other
// keywords use (a material, section or EOS no part names; curves, sets, boxes), whose users
// are translated or listed themselves. Every other keyword outside the subset changes the run.
bool leaves_the_run(const std::string& name) {
  static const std::vector<std::string> prefixes = {"DATABASE_",
                                                    "CONTROL_OUTPUT",
                                                    "CONTROL_ENERGY",
                                                    "CONTROL_CPU",
                                                    "CONTROL_PARALLEL",
                                                    "CONTROL_MPP",
                                                    "CONTROL_REPORT",
                                                    "TITLE",
                                                    "COMMENT",
                                                    "DEFINE_CURVE",
                                                    "DEFINE_TABLE",
                                                    "DEFINE_COORDINATE",
                                                    "DEFINE_BOX",
                                                    "DEFINE_VECTOR",
                                                    "SET_",
                                                    "EOS_",
                                                    "SECTION_",
                                                    "MAT_"};
  if (name.starts_with("MAT_ADD_")) return false;
  return std::any_of(prefixes.begin(), prefixes.end(),
                     [&](const std::string& p) { return name.starts_with(p); });
}

struct Material {
  std::string kind;  // "elastic", "plastic-kinematic", "johnson-cook", "mooney-rivlin", "hjc",
                     // "rigid"
  core::SourceLocation at;
  std::string keyword;
  double density = 0;
  std::string body;             // the material table's lines, EOS excepted
  double G = 0, E = 0, nu = 0;  // G: for E and nu when a Johnson-Cook card leaves them blank
  std::string rigid;            // *MAT_RIGID: the bodies' `rigid = ...`
};

// What erodes the elements of a material's bodies: *MAT_ADD_EROSION's criteria, and a failure
// at which the material's own card deletes the element (MAT_003 FS, MAT_015 damage).
struct Erosion {
  double plastic_strain = 0;  // 0: off
  double volume_ratio = 0;    // 0: off
  bool material_failure = false;
};

struct Eos {
  std::string table;
  double bulk_modulus = 0;         // C1 of the linear polynomial
  double sound_speed_squared = 0;  // c0^2 of Gruneisen: the bulk modulus is rho0 c0^2
  double e0 = 0;                   // initial internal energy per unit reference volume (converted)
};

struct Hourglass {
  std::string hourglass;  // the body's `hourglass = ...`, empty for the default
  std::string bulk_viscosity;
};

// A contact between parts (*CONTACT_...): the parts of its two surfaces, or of its one surface
// (single surface: every pair, and each part with itself).
struct Contact {
  core::SourceLocation at;
  std::string keyword;
  std::vector<std::int64_t> slave, master;
  bool single = false;
  double friction = 0;
  bool part_friction = false;  // FS = -1: the parts' *PART_CONTACT coefficients, times fsf
  double fsf = 1;
};

// Coulomb friction as LS-DYNA's mu = FD + (FS - FD) exp(-DC |v_rel|) written with one
// coefficient: FS itself when DC is 0, else FD (the fast-sliding value).
struct Friction {
  double fs = 0, fd = 0, dc = 0;
  double coefficient() const { return dc > 0.0 ? fd : fs; }
};

// The contact keywords translated, without their _ID or _TITLE option.
const std::set<std::string> kContacts = {
    "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", "CONTACT_AUTOMATIC_NODES_TO_SURFACE",
    "CONTACT_AUTOMATIC_SINGLE_SURFACE",     "CONTACT_ERODING_SURFACE_TO_SURFACE",
    "CONTACT_ERODING_NODES_TO_SURFACE",     "CONTACT_ERODING_SINGLE_SURFACE"};

// A translated contact keyword's name without its _ID / _TITLE option, or "".
std::string contact_base(const std::string& name) {
  for (const char* option : {"", "_ID", "_TITLE"})
    for (const std::string& c : kContacts)
      if (name == c + option) return c;
  return "";
}

// A velocity given to nodes: a node set's (nsid > 0), every node's (nsid 0) or listed nodes'.
struct NodeVelocity {
  core::Vec3 v;
  core::SourceLocation at;
  std::string keyword;
  std::int64_t nsid;
  std::vector<std::int64_t> nodes;
};

// *DEFINE_CURVE: its points (abscissa scaled and offset, converted as a time; ordinates scaled
// and offset, a factor) and whether a translated keyword uses it.
struct Curve {
  core::SourceLocation at;
  std::vector<std::pair<double, double>> points;
  bool used = false;
};

// *BOUNDARY_PRESCRIBED_MOTION_SET: a velocity SF x curve(t) on one component of a node set.
struct PrescribedMotion {
  core::SourceLocation at;
  std::int64_t nsid = 0, curve = 0;
  int component = 0;  // 0, 1, 2: x, y, z
  double velocity = 0;
};

struct Wall {
  core::Vec3 point, normal;
  double friction = 0;
};

class LsDynaImport {
 public:
  LsDynaImport(const std::string& text, const std::string& deck_path, const std::string& scene_path,
               const core::DeckImportOptions& options)
      : deck_(LsDynaDeck::parse(text, deck_path)),
        deck_path_(deck_path),
        scene_path_(scene_path),
        units_(options.units, {deck_path, 0}),
        options_(options) {}

  core::DeckImport run() {
    for (const LsDynaKeyword& k : deck_.keywords()) {
      key_ = "*" + k.name;
      keyword(k);
    }
    const MeshData mesh = lsdyna_mesh(deck_);
    resolve_node_velocities(mesh);
    std::string body = scene(mesh);
    core::refuse_untranslated(notes_, options_);
    body.insert(body.find('\n') + 1, core::untranslated_run_key(notes_));
    core::DeckImport out;
    out.notes = notes_;
    out.units = units_.description();
    out.scene = core::imported_scene_header(deck_path_, core::DeckFormat::lsdyna,
                                            units_.description(), notes_) +
                "\n" + body;
    return out;
  }

 private:
  void note(const core::SourceLocation& at, const std::string& what, bool approximated) {
    notes_.push_back({at, key_, what, approximated});
  }
  // Not translated, and the run differs for it: refused unless allow_untranslated.
  void changes_run(const core::SourceLocation& at, const std::string& what) {
    notes_.push_back({at, key_, what, false, true});
  }

  // The cards holding data: a _TITLE keyword's first card is its title.
  static std::vector<LsDynaCard> data_cards(const LsDynaKeyword& k) {
    std::vector<LsDynaCard> cards = k.cards;
    if (k.name.ends_with("_TITLE") && !cards.empty()) cards.erase(cards.begin());
    return cards;
  }

  // Card i of the keyword's data as fields; a card left out reads as blank (defaults).
  std::vector<std::string_view> card(const std::vector<LsDynaCard>& cards, std::size_t i) const {
    return i < cards.size() ? card_fields(cards[i], kStandardColumns)
                            : std::vector<std::string_view>{};
  }
  const LsDynaCard& card_at(const LsDynaKeyword& k, const std::vector<LsDynaCard>& cards,
                            std::size_t i) const {
    if (cards.empty()) throw core::InputError(k.at(), key_, "the keyword has no card");
    return cards[std::min(i, cards.size() - 1)];
  }
  double real(const LsDynaKeyword& k, const std::vector<LsDynaCard>& cards, std::size_t c,
              std::size_t i, const std::string& what, core::Dimension d = dim::none) const {
    return units_(card_real(card(cards, c), i, card_at(k, cards, c), key_, what), d);
  }
  std::int64_t integer(const LsDynaKeyword& k, const std::vector<LsDynaCard>& cards, std::size_t c,
                       std::size_t i, const std::string& what) const {
    return card_integer(card(cards, c), i, card_at(k, cards, c), key_, what);
  }

  static bool is(const std::string& name, std::initializer_list<const char*> names) {
    for (const char* n : names)
      if (name == n || name == std::string(n) + "_TITLE") return true;
    return false;
  }

  void keyword(const LsDynaKeyword& k) {
    const std::string& n = k.name;
    if (n == "SET_NODE_LIST" || n == "SET_NODE_LIST_TITLE") node_sets_.push_back(lsdyna_id_list(k));
    if (is(n, {"SET_PART", "SET_PART_LIST"})) {
      part_sets_.push_back(lsdyna_id_list(k));
      return;
    }
    if (const std::string base = contact_base(n); !base.empty()) {
      contact(k, base);
      return;
    }
    if (n == "KEYWORD" || kMeshKeywords.count(n) != 0) return;
    if (n == "TITLE") {
      if (!k.cards.empty()) title_ = std::string(core::trim(k.cards.front().text));
    } else if (n == "PART" || n == "PART_CONTACT") {
      for (LsDynaPart& p : lsdyna_parts(k)) {
        if (p.extra)
          note(p.card.at(), "GRAV, ADPOPT and TMID of part " + std::to_string(p.id), false);
        if (p.contact_extra)
          note(p.card.at(), "VC, OPTT, SFT and SSF of part " + std::to_string(p.id), false);
        parts_[p.id] = std::move(p);
      }
    } else if (is(n, {"SECTION_SOLID"})) {
      section_solid(k);
    } else if (is(n, {"SECTION_BEAM"})) {
      section_beam(k);
    } else if (is(n, {"MAT_RIGID", "MAT_020"})) {
      mat_rigid(k);
    } else if (is(n, {"MAT_ELASTIC", "MAT_001"})) {
      mat_elastic(k);
    } else if (is(n, {"MAT_PLASTIC_KINEMATIC", "MAT_003"})) {
      mat_plastic_kinematic(k);
    } else if (is(n, {"MAT_MOONEY-RIVLIN_RUBBER", "MAT_027"})) {
      mat_mooney_rivlin(k);
    } else if (is(n, {"MAT_JOHNSON_COOK", "MAT_015"})) {
      mat_johnson_cook(k);
    } else if (is(n, {"MAT_ADD_EROSION"})) {
      mat_add_erosion(k);
    } else if (is(n, {"MAT_JOHNSON_HOLMQUIST_CONCRETE", "MAT_111"})) {
      mat_hjc(k);
    } else if (is(n, {"EOS_GRUNEISEN", "EOS_004"})) {
      eos_gruneisen(k);
    } else if (is(n, {"EOS_LINEAR_POLYNOMIAL", "EOS_001"})) {
      eos_linear_polynomial(k);
    } else if (n == "HOURGLASS" || n == "HOURGLASS_TITLE") {
      hourglass(k);
    } else if (n == "CONTROL_HOURGLASS") {
      control_hourglass(k);
    } else if (n == "CONTROL_BULK_VISCOSITY") {
      control_bulk_viscosity(k);
    } else if (n == "CONTROL_SOLID") {
      control_solid(k);
    } else if (n == "CONTROL_CONTACT") {
      control_contact(k);
    } else if (n == "INITIAL_VELOCITY_GENERATION") {
      initial_velocity(k);
    } else if (n == "INITIAL_VELOCITY") {
      initial_velocity_set(k);
    } else if (n == "INITIAL_VELOCITY_NODE") {
      initial_velocity_node(k);
    } else if (is(n, {"DEFINE_CURVE"})) {
      define_curve(k);
    } else if (n == "BOUNDARY_PRESCRIBED_MOTION_SET") {
      prescribed_motion(k);
    } else if (n == "RIGIDWALL_PLANAR") {
      rigid_wall(k);
    } else if (n == "CONTROL_TERMINATION") {
      const auto c = data_cards(k);
      end_time_ = real(k, c, 0, 0, "ENDTIM", dim::time);
      max_steps_ = integer(k, c, 0, 1, "ENDCYC");
      bool other = false;
      for (std::size_t i = 2; i < 5; ++i)
        other = other || real(k, c, 0, i, "DTMIN, ENDENG or ENDMAS") != 0.0;
      if (other) note(k.at(), "DTMIN, ENDENG and ENDMAS (afemp stops at ENDTIM or ENDCYC)", false);
    } else if (n == "CONTROL_TIMESTEP") {
      const auto c = data_cards(k);
      tssfac_ = real(k, c, 0, 1, "TSSFAC");
      if (real(k, c, 0, 0, "DTINIT") != 0.0 || real(k, c, 0, 4, "DT2MS") != 0.0 ||
          integer(k, c, 0, 5, "LCTM") != 0)
        note(k.at(),
             "DTINIT, DT2MS (mass scaling) and LCTM: afemp takes the stable step times TSSFAC",
             false);
    } else if (n == "DATABASE_BINARY_D3PLOT") {
      const auto c = data_cards(k);
      output_every_ = real(k, c, 0, 0, "DT", dim::time);
      note(k.at(), "written as afemp's fields.xmf + fields.h5 every DT (not a d3plot file)", true);
    } else if (leaves_the_run(n)) {
      note(k.at(), "outside the subset afemp imports (docs/import.md)", false);
    } else {
      changes_run(k.at(), "outside the subset afemp imports (docs/import.md)");
    }
  }

  void section_solid(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (c[i].blank()) continue;
      const std::int64_t id = integer(k, c, i, 0, "SECID");
      std::int64_t elform = integer(k, c, i, 1, "ELFORM");
      if (elform == 0) elform = 1;
      if (elform != 1 && elform != 2)
        throw core::InputError(c[i].at(), key_,
                               "ELFORM " + std::to_string(elform) +
                                   " has no afemp element; allowed: 1 (one-point, hourglass "
                                   "control) and 2 (fully integrated, written as afemp's 2x2x2 "
                                   "B-bar element)");
      if (elform == 2)
        note(c[i].at(),
             "ELFORM 2 (selectively reduced) is afemp's fully integrated B-bar hexahedron", true);
      solid_elform_[id] = elform;
    }
  }

  void section_beam(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    const std::int64_t id = integer(k, c, 0, 0, "SECID");
    const std::int64_t elform = integer(k, c, 0, 1, "ELFORM");
    if (elform != 3)
      note(c.front().at(),
           "beam section " + std::to_string(id) + " (ELFORM " + std::to_string(elform) +
               ") is read as trusses: axial force only, no bending",
           true);
  }

  Material& new_material(const LsDynaKeyword& k, const std::vector<LsDynaCard>& c,
                         const std::string& kind) {
    const std::int64_t id = integer(k, c, 0, 0, "MID");
    if (materials_.count(id) != 0)
      throw core::InputError(k.at(), key_,
                             "material " + std::to_string(id) + " is already defined");
    Material& m = materials_[id];
    m.kind = kind;
    m.at = k.at();
    m.keyword = key_;
    m.density = real(k, c, 0, 1, "RO", dim::density);
    return m;
  }

  std::string num(double v) const { return core::toml_number(v); }

  // MID RO E PR DA DB K
  void mat_elastic(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    Material& m = new_material(k, c, "elastic");
    m.E = real(k, c, 0, 2, "E", dim::stress);
    m.nu = real(k, c, 0, 3, "PR");
    m.body = "strength = { model = \"elastic\" }\n";
    if (real(k, c, 0, 4, "DA") != 0.0 || real(k, c, 0, 5, "DB") != 0.0)
      note(k.at(), "DA and DB (axial and bending damping of beams)", false);
  }

  // MID RO PR A B REF / SGL SW ST LCID (Vol. II, *MAT_MOONEY-RIVLIN_RUBBER): afemp's
  // Mooney-Rivlin solid with C10 = A, C01 = B and the same small-strain moduli, G = 2 (A + B) and
  // PR, so E = 4 (A + B) (1 + PR). LS-DYNA's volumetric terms, C (III^-2 - 1) + D (III - 1)^2
  // with C and D fixed by A, B and PR, become K / 2 (J - 1)^2 with K from E and PR: the same
  // bulk modulus at small strain (approximated).
  void mat_mooney_rivlin(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    Material& m = new_material(k, c, "mooney-rivlin");
    m.nu = real(k, c, 0, 2, "PR");
    const double a = real(k, c, 0, 3, "A", dim::stress), b = real(k, c, 0, 4, "B", dim::stress);
    if (real(k, c, 0, 5, "REF") != 0.0)
      throw core::InputError(card_at(k, c, 0).at(), key_,
                             "REF " + num(real(k, c, 0, 5, "REF")) +
                                 ": allowed 0; the reference geometry of "
                                 "*INITIAL_FOAM_REFERENCE_GEOMETRY is not translated");
    if (a <= 0.0 || b < 0.0)
      throw core::InputError(
          card_at(k, c, 0).at(), key_,
          "A " + num(a) + ", B " + num(b) +
              ": allowed A > 0 and B >= 0 (afemp's C10 and C01); the fit of A and B to a "
              "uniaxial test curve (A = B = 0 with SGL, SW, ST and LCID) is not translated");
    if (m.nu <= 0.0 || m.nu >= 0.5)
      throw core::InputError(card_at(k, c, 0).at(), key_,
                             "PR " + num(m.nu) +
                                 ": allowed 0 < PR < 0.5 (0.49 to 0.499 "
                                 "is usual for rubber)");
    m.E = 4.0 * (a + b) * (1.0 + m.nu);
    m.body =
        "strength = { model = \"mooney-rivlin\", C10 = " + num(a) + ", C01 = " + num(b) + " }\n";
    note(k.at(),
         "the volumetric energy C (III^-2 - 1) + D (III - 1)^2 as K / 2 (J - 1)^2, K from "
         "G = 2 (A + B) and PR: the same at small strain",
         true);
  }

  // MID RO E PR N COUPLE M ALIAS / CMO CON1 CON2 / LCO or A1 A2 A3 V1 V2 V3 (Vol. II, *MAT_RIGID):
  // afemp's rigid body, its global constraints (CMO 1) as the fixed components.
  void mat_rigid(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    Material& m = new_material(k, c, "rigid");
    m.E = real(k, c, 0, 2, "E", dim::stress);
    m.nu = real(k, c, 0, 3, "PR");
    m.body = "strength = { model = \"elastic\" }\n";
    if (real(k, c, 0, 4, "N") != 0.0 || real(k, c, 0, 5, "COUPLE") != 0.0 ||
        real(k, c, 0, 6, "M") != 0.0)
      note(k.at(), "N, COUPLE, M (coupling with MADYMO or CAL3D)", false);
    const std::int64_t cmo = integer(k, c, 1, 0, "CMO");
    const std::int64_t con1 = integer(k, c, 1, 1, "CON1"), con2 = integer(k, c, 1, 2, "CON2");
    const bool global = cmo == 1 && con1 >= 0 && con1 <= 7 && con2 >= 0 && con2 <= 7;
    if (cmo != 0 && !global)
      throw core::InputError(
          card_at(k, c, 1).at(), key_,
          "CMO " + std::to_string(cmo) + " with CON1 " + std::to_string(con1) + ", CON2 " +
              std::to_string(con2) +
              ": allowed CMO 0 (free) and 1 (global constraints, CON1 and "
              "CON2 from 0 to 7); local constraints (CMO -1) are not translated");
    // CON1 / CON2: 0 free, 1 x, 2 y, 3 z, 4 x and y, 5 y and z, 6 z and x, 7 all three.
    static const char* const axes[8] = {"", "x", "y", "z", "xy", "yz", "zx", "xyz"};
    std::string fixed;
    if (cmo == 1) {
      for (const char* a = axes[con1]; *a != '\0'; ++a)
        fixed += (fixed.empty() ? "\"" : ", \"") + std::string(1, *a) + "\"";
      for (const char* a = axes[con2]; *a != '\0'; ++a)
        fixed += (fixed.empty() ? "\"r" : ", \"r") + std::string(1, *a) + "\"";
    }
    m.rigid = fixed.empty() ? "true" : "{ fixed = [" + fixed + "] }";
  }

  // MID RO E PR SIGY ETAN BETA / SRC SRP FS VP
  void mat_plastic_kinematic(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    Material& m = new_material(k, c, "plastic-kinematic");
    m.E = real(k, c, 0, 2, "E", dim::stress);
    m.nu = real(k, c, 0, 3, "PR");
    const double etan = real(k, c, 0, 5, "ETAN", dim::stress);
    const double beta = real(k, c, 0, 6, "BETA");
    m.body = "strength = { model = \"j2\", yield = " + num(real(k, c, 0, 4, "SIGY", dim::stress)) +
             ", tangent_modulus = " + num(etan) + " }\n";
    if (beta != 1.0 && etan > 0.0)
      note(k.at(),
           "BETA = " + num(beta) + ": kinematic hardening is written as isotropic (BETA = 1)",
           true);
    if (real(k, c, 1, 0, "SRC", dim::rate) != 0.0)
      note(k.at(), "SRC and SRP (Cowper-Symonds rate factor): afemp's j2 is rate-independent",
           false);
    // LS-DYNA deletes the element whose effective plastic strain reaches FS.
    if (const double fs = real(k, c, 1, 2, "FS"); fs > 0.0) {
      m.body += "failure_strain = " + num(fs) + "\n";
      material_erosion_[integer(k, c, 0, 0, "MID")].material_failure = true;
    }
  }

  // MID RO G E PR DTF VP RATEOP / A B N C M TM TR EPSO / CP PC SPALL IT D1 D2 D3 D4 /
  // D5 C2/P/XNP EROD EFMIN NUMINT
  void mat_johnson_cook(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    Material& m = new_material(k, c, "johnson-cook");
    const std::int64_t mid = integer(k, c, 0, 0, "MID");
    m.G = real(k, c, 0, 2, "G", dim::stress);
    m.E = real(k, c, 0, 3, "E", dim::stress);
    m.nu = real(k, c, 0, 4, "PR");
    const double tm = real(k, c, 1, 5, "TM"), tr = real(k, c, 1, 6, "TR");
    const double epso = real(k, c, 1, 7, "EPSO", dim::rate);
    const double mexp = real(k, c, 1, 4, "M");
    std::string s =
        "strength = { model = \"johnson-cook\", A = " + num(real(k, c, 1, 0, "A", dim::stress)) +
        ", B = " + num(real(k, c, 1, 1, "B", dim::stress)) + ", n = " + num(real(k, c, 1, 2, "N")) +
        ", C = " + num(real(k, c, 1, 3, "C"));
    if (epso > 0.0) s += ", reference_strain_rate = " + num(epso);
    if (mexp > 0.0)
      s += ", m = " + num(mexp) + ", room_temperature = " + num(tr) +
           ", melt_temperature = " + num(tm);
    m.body = s + " }\n";
    if (const double cp = real(k, c, 2, 0, "CP", dim::specific_energy); cp > 0.0)
      m.body += "specific_heat = " + num(cp) + "\n";
    if (tr > 0.0) m.body += "temperature = " + num(tr) + "\n";
    std::array<double, 5> d{};
    for (std::size_t i = 0; i < 4; ++i) d[i] = real(k, c, 2, 4 + i, "D" + std::to_string(i + 1));
    d[4] = real(k, c, 3, 0, "D5");
    const double pc = real(k, c, 2, 1, "PC", dim::stress);
    const double spall = real(k, c, 2, 2, "SPALL");
    if (std::any_of(d.begin(), d.end(), [](double v) { return v != 0.0; })) {
      m.body += "failure = { model = \"johnson-cook\", D1 = " + num(d[0]) + ", D2 = " + num(d[1]) +
                ", D3 = " + num(d[2]) + ", D4 = " + num(d[3]) + ", D5 = " + num(d[4]);
      if (epso > 0.0) m.body += ", reference_strain_rate = " + num(epso);
      if (tm > 0.0) m.body += ", room_temperature = " + num(tr) + ", melt_temperature = " + num(tm);
      m.body += " }\n";
      // SPALL 1 limits the pressure at PC: afemp's pressure cutoff, beside the damage.
      if (pc < 0.0 && spall == 1.0)
        m.body += "pressure_cutoff = " + num(pc) + "\n";
      else if (pc < 0.0)
        note(k.at(),
             "PC with SPALL " + num(spall) +
                 " (spall failure) beside the Johnson-Cook damage: afemp takes one failure model",
             false);
      // EROD 0 (the default): LS-DYNA deletes the element whose damage reaches 1.
      if (real(k, c, 3, 2, "EROD") == 0.0) material_erosion_[mid].material_failure = true;
    } else if (pc < 0.0) {
      const bool principal = spall == 2.0;
      m.body += std::string("failure = { model = \"spall\", ") +
                (principal ? "principal_stress" : "pressure") + " = " + num(-pc) + " }\n";
      note(k.at(),
           "PC with SPALL " + num(spall) + " is afemp's instantaneous spall failure (" +
               (principal ? "largest principal stress" : "-p") + " beyond -PC)",
           true);
    }
    if (real(k, c, 0, 6, "VP") != 0.0 || real(k, c, 0, 5, "DTF") != 0.0)
      note(k.at(), "DTF and VP (afemp's Johnson-Cook is rate-dependent through C)", false);
  }

  // MID EXCL MXPRES MNEPS EFFEPS VOLEPS NUMFIP NCS / MNPRES SIGP1 SIGVM MXEPS EPSSH SIGTH
  // IMPULSE FAILTM / further cards (damage, forming limits): a field equal to EXCL is off, as is
  // a blank or 0 one. EFFEPS and a compressive VOLEPS have afemp counterparts; the rest refused.
  void mat_add_erosion(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    const std::int64_t mid = integer(k, c, 0, 0, "MID");
    const double excl = real(k, c, 0, 1, "EXCL");
    const auto on = [&](double v) { return v != 0.0 && v != excl; };
    const char* const card1[] = {"MID", "EXCL", "MXPRES", "MNEPS", "EFFEPS", "VOLEPS"};
    const char* const card2[] = {"MNPRES", "SIGP1", "SIGVM",   "MXEPS",
                                 "EPSSH",  "SIGTH", "IMPULSE", "FAILTM"};
    std::vector<std::pair<std::size_t, std::size_t>> refused = {{0, 2}, {0, 3}};
    for (std::size_t i = 0; i < 8; ++i) refused.emplace_back(1, i);
    for (const auto& [card, i] : refused)
      if (on(real(k, c, card, i, card == 0 ? card1[i] : card2[i])))
        throw core::InputError(card_at(k, c, card).at(), key_,
                               std::string(card == 0 ? card1[i] : card2[i]) +
                                   " has no afemp erosion criterion; allowed: EFFEPS (as the "
                                   "plastic strain) and VOLEPS < 0 (as the volume ratio)");
    for (std::size_t card = 2; card < c.size(); ++card)
      for (std::size_t i = 0; i < 8; ++i)
        if (real(k, c, card, i, "a field of card " + std::to_string(card + 1)) != 0.0)
          throw core::InputError(c[card].at(), key_,
                                 "card " + std::to_string(card + 1) +
                                     " (damage and forming-limit criteria) has no afemp "
                                     "counterpart; allowed: EFFEPS and VOLEPS < 0 on card 1");
    Erosion& e = add_erosion_[mid];
    e = {};
    const double effeps = real(k, c, 0, 4, "EFFEPS"), voleps = real(k, c, 0, 5, "VOLEPS");
    if (on(effeps)) {
      e.plastic_strain = effeps;
      note(k.at(),
           "EFFEPS (LS-DYNA's effective strain, summed from the deviatoric strain increments) "
           "as the erosion's plastic strain: they differ by the elastic strain",
           true);
    }
    if (on(voleps)) {
      if (voleps > 0.0)
        throw core::InputError(card_at(k, c, 0).at(), key_,
                               "VOLEPS > 0 (erosion in volumetric tension) has no afemp "
                               "criterion; allowed: VOLEPS < 0, as the volume ratio 1 + VOLEPS");
      if (voleps <= -1.0)
        throw core::InputError(card_at(k, c, 0).at(), key_,
                               "VOLEPS must lie above -1 (a volume ratio 1 + VOLEPS above 0)");
      e.volume_ratio = 1.0 + voleps;
    }
    const std::int64_t numfip = integer(k, c, 0, 6, "NUMFIP");
    if (numfip > 1)
      note(k.at(),
           "NUMFIP " + std::to_string(numfip) +
               ": afemp erodes an element when one point "
               "reaches a criterion",
           true);
    if (integer(k, c, 0, 7, "NCS") > 1 && on(effeps) && on(voleps))
      throw core::InputError(card_at(k, c, 0).at(), key_,
                             "NCS > 1 (several criteria met together) has no afemp counterpart: "
                             "afemp erodes at the first criterion met");
    if (!on(effeps) && !on(voleps))
      note(k.at(), "no criterion afemp has is set: nothing erodes", false);
  }

  // MID RO G A B C N FC / T EPS0 EFMIN SFMAX PC UC PL UL / D1 D2 K1 K2 K3 FS
  void mat_hjc(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    Material& m = new_material(k, c, "hjc");
    const auto st = [&](std::size_t card, std::size_t i, const char* what) {
      return num(real(k, c, card, i, what, dim::stress));
    };
    const auto nd = [&](std::size_t card, std::size_t i, const char* what) {
      return num(real(k, c, card, i, what));
    };
    m.body = "G = " + st(0, 2, "G") +
             "\nstrength = { model = \"holmquist-johnson-cook\", A = " + nd(0, 3, "A") +
             ", B = " + nd(0, 4, "B") + ", C = " + nd(0, 5, "C") + ", N = " + nd(0, 6, "N") +
             ", fc = " + st(0, 7, "FC") + ", T = " + st(1, 0, "T") +
             ", reference_strain_rate = " + num(real(k, c, 1, 1, "EPS0", dim::rate)) +
             ", EFMIN = " + nd(1, 2, "EFMIN") + ", SFMAX = " + nd(1, 3, "SFMAX") +
             ", D1 = " + nd(2, 0, "D1") + ", D2 = " + nd(2, 1, "D2") +
             " }\neos = { model = \"hjc-compaction\", PC = " + st(1, 4, "PC") +
             ", muc = " + nd(1, 5, "UC") + ", PL = " + st(1, 6, "PL") +
             ", mul = " + nd(1, 7, "UL") + ", K1 = " + st(2, 2, "K1") + ", K2 = " + st(2, 3, "K2") +
             ", K3 = " + st(2, 4, "K3") + " }\n";
    if (real(k, c, 2, 5, "FS") != 0.0)
      note(k.at(),
           "FS (failure type): afemp's HJC carries its damage to D = 1 and does not erode on it",
           false);
  }

  // EOSID C S1 S2 S3 GAMAO A E0 / V0
  void eos_gruneisen(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    const std::int64_t id = integer(k, c, 0, 0, "EOSID");
    const double c0 = real(k, c, 0, 1, "C", dim::velocity);
    Eos& e = new_eos(k, id);
    e.table = "{ model = \"mie-gruneisen\", c0 = " + num(c0) +
              ", s = " + num(real(k, c, 0, 2, "S1")) +
              ", gamma0 = " + num(real(k, c, 0, 5, "GAMAO")) + " }";
    e.e0 = real(k, c, 0, 7, "E0", dim::stress);
    e.sound_speed_squared = c0 * c0;
    if (real(k, c, 0, 3, "S2") != 0.0 || real(k, c, 0, 4, "S3") != 0.0)
      note(k.at(), "S2 and S3: afemp's Hugoniot is linear in u_p (S1 only)", false);
    if (real(k, c, 0, 6, "A") != 0.0)
      note(k.at(), "A (first-order volume correction to GAMAO)", false);
    if (const double v0 = real(k, c, 1, 0, "V0"); v0 != 0.0 && v0 != 1.0)
      note(k.at(), "V0 = " + num(v0) + ": afemp starts at the reference density", false);
    note(k.at(),
         "the Hugoniot pressure is afemp's cubic expansion in mu (Ma 2005, eq 2-25), 1.4 % "
         "below LS-DYNA's rational form at mu = 0.4; in tension p = rho0 c0^2 mu",
         true);
  }

  // EOSID C0 C1 C2 C3 C4 C5 C6 / E0 V0
  void eos_linear_polynomial(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    const std::int64_t id = integer(k, c, 0, 0, "EOSID");
    Eos& e = new_eos(k, id);
    e.table = "{ model = \"linear-polynomial\"";
    for (std::size_t i = 0; i < 7; ++i) {
      const std::string name = std::string("C") + std::to_string(i);
      e.table +=
          ", " + name + " = " + num(real(k, c, 0, 1 + i, name, i < 4 ? dim::stress : dim::none));
    }
    e.table += " }";
    e.bulk_modulus = real(k, c, 0, 2, "C1", dim::stress);
    e.e0 = real(k, c, 1, 0, "E0", dim::stress);
    if (const double v0 = real(k, c, 1, 1, "V0"); v0 != 0.0 && v0 != 1.0)
      note(k.at(), "V0 = " + num(v0) + ": afemp starts at the reference density", false);
  }

  Eos& new_eos(const LsDynaKeyword& k, std::int64_t id) {
    if (eos_.count(id) != 0)
      throw core::InputError(k.at(), key_, "EOS " + std::to_string(id) + " is already defined");
    return eos_[id];
  }

  // HGID IHQ QM IBQ Q1 Q2 QB/VDC QW
  void hourglass(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    const std::int64_t id = integer(k, c, 0, 0, "HGID");
    Hourglass h;
    h.hourglass = hourglass_form(k, c, integer(k, c, 0, 1, "IHQ"), real(k, c, 0, 2, "QM"), "QM");
    const double q1 = real(k, c, 0, 4, "Q1"), q2 = real(k, c, 0, 5, "Q2");
    if (q1 != 0.0 || q2 != 0.0) h.bulk_viscosity = bulk_viscosity(q1, q2);
    hourglass_[id] = h;
  }

  // *CONTROL_HOURGLASS (IHQ QH): the form of the parts that name no *HOURGLASS.
  void control_hourglass(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    const std::int64_t ihq = integer(k, c, 0, 0, "IHQ");
    default_hourglass_ = hourglass_form(k, c, ihq != 0 ? ihq : 1, real(k, c, 0, 1, "QH"), "QH");
  }

  // *CONTROL_BULK_VISCOSITY (Q1 Q2 TYPE BTYPE): the bulk viscosity of the parts whose
  // *HOURGLASS gives none. TYPE -1 and -2 add it to shells, which afemp does not have; BTYPE
  // is the beams' (afemp's trusses carry none).
  void control_bulk_viscosity(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    default_bulk_viscosity_ = bulk_viscosity(real(k, c, 0, 0, "Q1"), real(k, c, 0, 1, "Q2"));
    if (integer(k, c, 0, 3, "BTYPE") != 0)
      note(k.at(), "BTYPE (bulk viscosity in beams: afemp's trusses carry none)", false);
  }

  // *CONTROL_SOLID: what it sets concerns tetrahedra, pentahedra, cohesive elements, implicit
  // element matrices and output, none of which afemp's hexahedra and trusses have, except
  // ESORT (degenerate hexahedra get a wedge or tetrahedron formulation in LS-DYNA) and PSFAIL
  // (solids erode at a principal stress).
  void control_solid(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    if (integer(k, c, 0, 4, "PSFAIL") != 0)
      changes_run(k.at(), "PSFAIL (solids of a part set erode at a principal stress)");
    if (integer(k, c, 0, 0, "ESORT") != 0)
      note(k.at(),
           "ESORT: degenerate hexahedra (wedges, tetrahedra with repeated nodes) stay one-point "
           "hexahedra in afemp",
           true);
    bool other = false;
    for (std::size_t i : {1, 2, 3, 5, 6, 7})
      other = other || real(k, c, 0, i, "FMATRX, NIPTETS, SWLOCL, T10JTOL, ICOH or TET13K") != 0.0;
    if (other || c.size() > 1)
      note(k.at(),
           "FMATRX, NIPTETS, SWLOCL, T10JTOL, ICOH, TET13K and the PM cards (tetrahedra, "
           "cohesive and implicit elements, output)",
           false);
  }

  // *CONTROL_CONTACT: SLSFAC scales LS-DYNA's penalty stiffness, which afemp's penalty
  // contact has not (it takes out each step's predicted penetration); SFRIC, DFRIC and EDC
  // are the friction of the parts a contact with FS = -1 takes where *PART_CONTACT gives none.
  void control_contact(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    if (real(k, c, 0, 0, "SLSFAC") != 0.0)
      note(k.at(),
           "SLSFAC (penalty stiffness scale): afemp's penalty contact takes out each step's "
           "predicted penetration",
           true);
    bool other = false;
    for (std::size_t i = 1; i < 8; ++i)
      other = other ||
              real(k, c, 0, i, "RWPNAL, ISLCHK, SHLTHK, PENOPT, THKCHG, ORIEN or ENMASS") != 0.0;
    if (other)
      note(k.at(),
           "RWPNAL, ISLCHK, SHLTHK, PENOPT, THKCHG, ORIEN and ENMASS (afemp's contact checks "
           "and orients surfaces itself; an eroded element's nodes leave the contact)",
           true);
    control_friction_ = {real(k, c, 2, 0, "SFRIC"), real(k, c, 2, 1, "DFRIC"),
                         real(k, c, 2, 2, "EDC", core::Dimension{-1, 1, 0})};
    if (real(k, c, 2, 3, "VFC") != 0.0) note(k.at(), "VFC (viscous friction)", false);
    if ((c.size() > 1 && !c[1].blank()) || c.size() > 3)
      note(k.at(), "the cards after the first and third (contact search and output options)",
           false);
  }

  std::string one_coefficient(const Friction& f) const {
    return "FS, FD, DC: afemp's Coulomb friction is one coefficient; written as FD = " + num(f.fd) +
           " (LS-DYNA's at fast sliding) times FSF";
  }

  // A part's friction for a contact with FS = -1: its *PART_CONTACT card, where that gives FS,
  // else *CONTROL_CONTACT's SFRIC, DFRIC and EDC (LS-DYNA's defaults for *PART_CONTACT).
  Friction part_friction(std::int64_t label) const {
    const auto p = parts_.find(label);
    if (p != parts_.end() && p->second.has_contact && p->second.fs != 0.0)
      return {p->second.fs, p->second.fd, p->second.dc};
    return control_friction_;
  }

  // The friction of a contact between parts a and b (b the master's, or the other of a
  // single surface's pair).
  double pair_friction(const Contact& ct, std::int64_t a, std::int64_t b) {
    if (!ct.part_friction) return ct.friction;
    const Friction fa = part_friction(a), fb = part_friction(b);
    if (fa.coefficient() != fb.coefficient())
      notes_.push_back({ct.at, ct.keyword,
                        "FS -1 with parts " + std::to_string(a) + " and " + std::to_string(b) +
                            " of different friction: afemp takes one coefficient per pair, " +
                            (ct.single ? "the later part's" : "the master's") + " (part " +
                            std::to_string(b) + "; LS-DYNA takes the segment's part's)",
                        true});
    if (fb.dc > 0.0 && fb.fd != fb.fs)
      notes_.push_back({ct.at, ct.keyword, one_coefficient(fb), true});
    return ct.fsf * fb.coefficient();
  }

  std::string bulk_viscosity(double q1, double q2) const {
    // Blank fields are LS-DYNA's defaults, which are afemp's too.
    return "{ quadratic = " + num(q1 != 0.0 ? q1 : 1.5) +
           ", linear = " + num(q2 != 0.0 ? q2 : 0.06) + " }";
  }

  // The hourglass table of LS-DYNA's type ihq with coefficient qm (`field` names it).
  std::string hourglass_form(const LsDynaKeyword& k, const std::vector<LsDynaCard>& c,
                             std::int64_t ihq, double qm, const std::string& field) {
    std::string form;
    if (ihq >= 0 && ihq <= 3) {
      form = "viscous";
      if (ihq == 1 || ihq == 2)
        note(k.at(),
             "IHQ " + std::to_string(ihq) + " is written as afemp's viscous form (LS-DYNA type 3)",
             true);
    } else if (ihq == 4 || ihq == 5) {
      form = "stiffness";
      if (ihq == 4)
        note(k.at(), "IHQ 4 is written as afemp's stiffness form (LS-DYNA type 5)", true);
    } else if (ihq == 6) {
      form = "assumed_strain";
    } else {
      throw core::InputError(card_at(k, c, 0).at(), key_,
                             "IHQ " + std::to_string(ihq) +
                                 " has no afemp form; allowed: 0-3 (viscous), "
                                 "4-5 (stiffness), 6 (assumed strain)");
    }
    // A blank coefficient is LS-DYNA's 0.1 for every form (afemp's stiffness default is 0.05).
    const double wanted = qm > 0.0 ? qm : 0.1;
    const double largest = form == "assumed_strain" ? 1.0 : 0.5;
    if (wanted > largest)
      note(k.at(),
           field + " " + num(wanted) + " is above afemp's largest " + num(largest) + " for the " +
               form + " form; written as " + num(largest),
           true);
    return "{ form = \"" + form + "\", coefficient = " + num(std::min(wanted, largest)) + " }";
  }

  // ID STYP OMEGA VX VY VZ IVATN ICID / XC YC ZC NX NY NZ PHASE IRIGID
  void initial_velocity(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    for (std::size_t i = 0; i < c.size(); i += 2) {
      const std::int64_t id = integer(k, c, i, 0, "ID");
      const std::int64_t styp = integer(k, c, i, 1, "STYP");
      const core::Vec3 v{real(k, c, i, 3, "VX", dim::velocity),
                         real(k, c, i, 4, "VY", dim::velocity),
                         real(k, c, i, 5, "VZ", dim::velocity)};
      if (real(k, c, i, 2, "OMEGA", dim::rate) != 0.0)
        changes_run(c[i].at(),
                    "OMEGA (an initial rotation): afemp gives a body one translational velocity");
      if (styp != 2) {
        changes_run(c[i].at(), "STYP " + std::to_string(styp) +
                                   " (a part set or node set): only STYP 2 (a part) is translated");
        continue;
      }
      velocity_[id] = {v, c[i].at()};  // id 0: every part
    }
  }

  // The parts a contact surface names: SSTYP / MSTYP 3 a part, 2 a part set (*SET_PART_LIST);
  // a single surface with SSID 0 (or SSTYP 5) covers every part. Parts as ids (a part set as
  // -SID, every part as 0), resolved once the deck has been read.
  std::vector<std::int64_t> contact_parts(const LsDynaCard& card, std::int64_t id,
                                          std::int64_t type, bool single, const char* which) const {
    if (type == 5 || (single && id == 0)) return {0};  // every part
    if ((type == 3 || type == 2) && id <= 0)
      throw core::InputError(
          card.at(), key_,
          std::string(which) + " " + std::to_string(type) + " needs a part or part set id above 0");
    if (type == 3) return {id};
    if (type == 2) return {-id};  // a part set, looked up once the deck has been read
    throw core::InputError(card.at(), key_,
                           std::string(which) + " " + std::to_string(type) +
                               ": afemp's contact is between whole bodies; allowed: 3 (a part), 2 "
                               "(a part set, *SET_PART_LIST), 5 (every part)");
  }

  // SSID MSID SSTYP MSTYP SBOXID MBOXID SPR MPR / FS FD DC VC VDC PENCHK BT DT /
  // SFS SFM SST MST SFST SFMT FSF VSF [/ ISYM EROSOP IADJ for _ERODING_] (Vol. I, *CONTACT)
  void contact(const LsDynaKeyword& k, const std::string& base) {
    std::vector<LsDynaCard> c = k.cards;
    if (k.name != base && !c.empty()) c.erase(c.begin());  // the _ID / _TITLE card
    const bool single = base.ends_with("SINGLE_SURFACE");
    const bool eroding = base.starts_with("CONTACT_ERODING");
    Contact ct;
    ct.at = k.at();
    ct.keyword = key_;
    ct.single = single;
    const LsDynaCard& c1 = card_at(k, c, 0);
    ct.slave = contact_parts(c1, integer(k, c, 0, 0, "SSID"), integer(k, c, 0, 2, "SSTYP"), single,
                             "SSTYP");
    if (!single)
      ct.master = contact_parts(c1, integer(k, c, 0, 1, "MSID"), integer(k, c, 0, 3, "MSTYP"),
                                false, "MSTYP");
    if (integer(k, c, 0, 4, "SBOXID") != 0 || integer(k, c, 0, 5, "MBOXID") != 0)
      throw core::InputError(c1.at(), key_,
                             "SBOXID and MBOXID (only the segments in a box) are not translated: "
                             "afemp's contact is between whole bodies");
    const Friction f{real(k, c, 1, 0, "FS"), real(k, c, 1, 1, "FD"),
                     real(k, c, 1, 2, "DC", core::Dimension{-1, 1, 0})};  // DC per velocity
    ct.fsf = real(k, c, 2, 6, "FSF");
    if (ct.fsf == 0.0) ct.fsf = 1.0;
    if (f.fs == -1.0) {
      ct.part_friction = true;
    } else if (f.fs < 0.0) {
      throw core::InputError(card_at(k, c, 1).at(), key_,
                             "FS " + num(f.fs) +
                                 " (friction from a table) is not translated; allowed: FS >= 0, "
                                 "or -1 (the parts' *PART_CONTACT coefficients)");
    } else {
      ct.friction = ct.fsf * f.coefficient();
      if (f.dc > 0.0 && f.fd != f.fs) note(k.at(), one_coefficient(f), true);
    }
    if (real(k, c, 1, 3, "VC") != 0.0 || real(k, c, 1, 4, "VDC") != 0.0 ||
        integer(k, c, 1, 5, "PENCHK") != 0)
      note(k.at(), "VC (a cap on the friction force), VDC (contact damping) and PENCHK", false);
    const double bt = real(k, c, 1, 6, "BT", dim::time), dt = real(k, c, 1, 7, "DT", dim::time);
    if (bt > 0.0 || (dt != 0.0 && dt < 1e20))
      changes_run(k.at(), "BT, DT (a contact born or dying during the run)");
    for (std::size_t i = 2; i < 6; ++i)
      if (real(k, c, 2, i, "SST, MST, SFST or SFMT") != 0.0) {
        note(k.at(), "SST, MST, SFST, SFMT (shell thicknesses: afemp's contact takes solids)",
             false);
        break;
      }
    if (real(k, c, 2, 7, "VSF") != 0.0) note(k.at(), "VSF (scale on VDC)", false);
    note(k.at(),
         "afemp's penalty contact (method \"penalty\", penalty = 1) takes out each step's "
         "predicted penetration (LS-DYNA's SOFT = 1 form); SFS and SFM have no counterpart",
         true);
    if (base.find("NODES_TO_SURFACE") != std::string::npos)
      note(k.at(),
           "afemp's contact is surface to surface: the master's nodes are held off the "
           "slave surface too",
           true);
    if (!eroding)
      note(k.at(),
           "afemp's contact rebuilds its surfaces from the live elements when elements erode "
           "(as *CONTACT_ERODING_...)",
           true);
    else if (integer(k, c, 3, 0, "ISYM") != 0 || integer(k, c, 3, 2, "IADJ") != 0)
      note(k.at(), "ISYM and IADJ", false);
    contacts_.push_back(std::move(ct));
  }

  // A node velocity's rotational components and local system: afemp's bodies start with one
  // translational velocity each.
  void refuse_rotation(const LsDynaKeyword& k, const std::vector<LsDynaCard>& c, std::size_t card,
                       std::size_t first, std::int64_t icid) const {
    for (std::size_t i = first; i < first + 3; ++i)
      if (real(k, c, card, i, "VXR, VYR or VZR", dim::rate) != 0.0)
        throw core::InputError(card_at(k, c, card).at(), key_,
                               "VXR, VYR, VZR (a rotational velocity) must be 0: afemp's "
                               "hexahedra and truss nodes have no rotations");
    if (icid != 0)
      throw core::InputError(card_at(k, c, card).at(), key_,
                             "ICID " + std::to_string(icid) +
                                 ": a local coordinate system is not translated; give the "
                                 "velocity in the global system");
  }

  // NSID NSIDEX BOXID IRIGID ICID / VX VY VZ VXR VYR VZR (Vol. I, *INITIAL_VELOCITY)
  void initial_velocity_set(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    if (integer(k, c, 0, 1, "NSIDEX") != 0 || integer(k, c, 0, 2, "BOXID") != 0)
      throw core::InputError(card_at(k, c, 0).at(), key_,
                             "NSIDEX and BOXID (nodes exempted, or only those in a box) are not "
                             "translated: afemp gives whole bodies one velocity; give the "
                             "velocity to a node set holding exactly the parts' nodes");
    if (integer(k, c, 0, 3, "IRIGID") != 0)
      note(k.at(), "IRIGID (velocities of rigid bodies' inertia cards)", false);
    refuse_rotation(k, c, 1, 3, integer(k, c, 0, 4, "ICID"));
    NodeVelocity v{{real(k, c, 1, 0, "VX", dim::velocity), real(k, c, 1, 1, "VY", dim::velocity),
                    real(k, c, 1, 2, "VZ", dim::velocity)},
                   card_at(k, c, 1).at(),
                   key_,
                   integer(k, c, 0, 0, "NSID"),
                   {}};
    node_velocities_.push_back(std::move(v));
  }

  // NID VX VY VZ VXR VYR VZR ICID, a card per node (Vol. I, *INITIAL_VELOCITY_NODE)
  void initial_velocity_node(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (c[i].blank()) continue;
      refuse_rotation(k, c, i, 4, integer(k, c, i, 7, "ICID"));
      const std::int64_t nid = integer(k, c, i, 0, "NID");
      node_velocities_.push_back(
          {{real(k, c, i, 1, "VX", dim::velocity), real(k, c, i, 2, "VY", dim::velocity),
            real(k, c, i, 3, "VZ", dim::velocity)},
           c[i].at(),
           key_,
           -1,
           {nid}});
    }
  }

  // The node velocities of *INITIAL_VELOCITY and *INITIAL_VELOCITY_NODE as bodies' velocities:
  // later cards override earlier ones node by node (as LS-DYNA reads them), and every part
  // must then have one velocity on all its nodes, or none on any.
  void resolve_node_velocities(const MeshData& mesh) {
    if (node_velocities_.empty()) return;
    std::map<std::int64_t, std::int32_t> index;
    for (std::size_t i = 0; i < mesh.node_labels.size(); ++i)
      index[mesh.node_labels[i]] = static_cast<std::int32_t>(i);
    std::vector<const NodeVelocity*> given(mesh.nodes.size(), nullptr);
    for (const NodeVelocity& v : node_velocities_) {
      if (v.nsid == 0) {
        std::fill(given.begin(), given.end(), &v);
        continue;
      }
      std::vector<std::int64_t> nodes = v.nodes;
      if (v.nsid > 0) {
        const auto set = std::find_if(node_sets_.begin(), node_sets_.end(),
                                      [&](const LsDynaIdList& l) { return l.id == v.nsid; });
        if (set == node_sets_.end())
          throw core::InputError(
              v.at, v.keyword,
              "NSID " + std::to_string(v.nsid) + " names no node set (*SET_NODE_LIST)");
        for (const auto& id : set->ids) nodes.push_back(id.first);
      }
      for (const std::int64_t label : nodes) {
        const auto i = index.find(label);
        if (i == index.end())
          throw core::InputError(v.at, v.keyword,
                                 "node " + std::to_string(label) + " is not defined (*NODE)");
        given[static_cast<std::size_t>(i->second)] = &v;
      }
    }
    std::vector<std::vector<std::int32_t>> part_nodes(mesh.part_names.size());
    for (std::size_t e = 0; e < mesh.hexahedra.size(); ++e)
      for (const std::int32_t n : mesh.hexahedra[e])
        part_nodes[static_cast<std::size_t>(mesh.hexahedron_part[e])].push_back(n);
    for (std::size_t e = 0; e < mesh.lines.size(); ++e)
      for (const std::int32_t n : mesh.lines[e])
        part_nodes[static_cast<std::size_t>(mesh.line_part[e])].push_back(n);
    for (std::size_t p = 0; p < part_nodes.size() && p < mesh.part_labels.size(); ++p) {
      std::vector<std::int32_t>& nodes = part_nodes[p];
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      const NodeVelocity* first = nullptr;
      std::size_t count = 0;
      for (const std::int32_t n : nodes) {
        const NodeVelocity* v = given[static_cast<std::size_t>(n)];
        if (v == nullptr) continue;
        ++count;
        if (first == nullptr) first = v;
        if (v->v.x != first->v.x || v->v.y != first->v.y || v->v.z != first->v.z)
          throw core::InputError(v->at, v->keyword,
                                 "part " + std::to_string(mesh.part_labels[p]) + " ('" +
                                     mesh.part_names[p] +
                                     "') would start with two velocities (this one and that of " +
                                     first->keyword + " at line " + std::to_string(first->at.line) +
                                     "): afemp gives a body one initial velocity");
      }
      if (first == nullptr) continue;
      if (count != nodes.size())
        throw core::InputError(
            first->at, first->keyword,
            "the nodes given hold " + std::to_string(count) + " of the " +
                std::to_string(nodes.size()) + " nodes of part " +
                std::to_string(mesh.part_labels[p]) + " ('" + mesh.part_names[p] +
                "'): afemp gives a body one initial velocity, so the velocity must be given to "
                "every node of a part or to none");
      node_velocity_part_[mesh.part_labels[p]] = {first->v, first->at};
    }
  }

  // LCID SIDR SFA SFO OFFA OFFO DATTYP / A1 O1 (two 20-column fields) ... (Vol. I, *DEFINE_CURVE)
  void define_curve(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    const std::int64_t id = integer(k, c, 0, 0, "LCID");
    const double sfa = real(k, c, 0, 2, "SFA"), sfo = real(k, c, 0, 3, "SFO");
    const double offa = real(k, c, 0, 4, "OFFA"), offo = real(k, c, 0, 5, "OFFO");
    if (integer(k, c, 0, 6, "DATTYP") != 0)
      throw core::InputError(card_at(k, c, 0).at(), key_,
                             "DATTYP != 0: only a curve of time against a value is translated");
    Curve curve{k.at(), {}, false};
    constexpr std::array<std::size_t, 2> columns{20, 20};
    for (std::size_t i = 1; i < c.size(); ++i) {
      if (c[i].blank()) continue;
      const auto f = card_fields(c[i], columns);
      const double a = card_real(f, 0, c[i], key_, "A"), o = card_real(f, 1, c[i], key_, "O");
      curve.points.emplace_back(units_((sfa != 0.0 ? sfa : 1.0) * a + offa, dim::time),
                                (sfo != 0.0 ? sfo : 1.0) * o + offo);
      const auto n = curve.points.size();
      if (curve.points.back().first < 0.0 ||
          (n > 1 && !(curve.points[n - 1].first > curve.points[n - 2].first)))
        throw core::InputError(c[i].at(), key_,
                               "the times must start at 0 or later and increase (afemp's "
                               "constraint curves)");
    }
    if (curve.points.empty()) throw core::InputError(k.at(), key_, "the curve has no points");
    if (!curves_.emplace(id, std::move(curve)).second)
      throw core::InputError(k.at(), key_, "curve " + std::to_string(id) + " is already defined");
  }

  // NSID DOF VAD LCID SF VID DEATH BIRTH, a card each (Vol. I, *BOUNDARY_PRESCRIBED_MOTION): a
  // velocity (VAD 0) along x, y or z (DOF 1-3) becomes a [[constraints]] velocity with the
  // curve as its history.
  void prescribed_motion(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (c[i].blank()) continue;
      const std::int64_t dof = integer(k, c, i, 1, "DOF"), vad = integer(k, c, i, 2, "VAD");
      if (dof < 1 || dof > 3)
        throw core::InputError(c[i].at(), key_,
                               "DOF " + std::to_string(dof) +
                                   ": allowed 1, 2, 3 (x, y, z); afemp's constraints hold "
                                   "translations along the axes");
      if (vad != 0)
        throw core::InputError(
            c[i].at(), key_,
            "VAD " + std::to_string(vad) + ": allowed 0 (a velocity); afemp prescribes velocities");
      const double death = real(k, c, i, 6, "DEATH", dim::time);
      if (real(k, c, i, 7, "BIRTH", dim::time) != 0.0 || (death != 0.0 && death < 1e20))
        throw core::InputError(c[i].at(), key_,
                               "BIRTH and DEATH are not translated: give the velocity's "
                               "history in the curve instead");
      const double sf = real(k, c, i, 4, "SF");
      PrescribedMotion m;
      m.at = c[i].at();
      m.nsid = integer(k, c, i, 0, "NSID");
      m.curve = integer(k, c, i, 3, "LCID");
      m.component = static_cast<int>(dof - 1);
      m.velocity = units_(sf != 0.0 ? sf : 1.0, dim::velocity);
      motions_.push_back(m);
    }
    note(k.at(),
         "afemp holds the curve's first value before its first time and its last after its last",
         true);
  }

  // The [[constraints]] of the prescribed motions, and the notes of curves nothing used.
  std::string motion_tables() {
    std::string s;
    for (const PrescribedMotion& m : motions_) {
      const auto set = std::find_if(node_sets_.begin(), node_sets_.end(),
                                    [&](const LsDynaIdList& l) { return l.id == m.nsid; });
      if (set == node_sets_.end())
        throw core::InputError(
            m.at, "*BOUNDARY_PRESCRIBED_MOTION_SET",
            "NSID " + std::to_string(m.nsid) + " names no node set (*SET_NODE_LIST)");
      const auto curve = curves_.find(m.curve);
      if (curve == curves_.end())
        throw core::InputError(
            m.at, "*BOUNDARY_PRESCRIBED_MOTION_SET",
            "LCID " + std::to_string(m.curve) + " names no curve (*DEFINE_CURVE)");
      curve->second.used = true;
      core::Vec3 v{0, 0, 0};
      (m.component == 0 ? v.x : m.component == 1 ? v.y : v.z) = m.velocity;
      std::string points;
      for (const auto& [t, f] : curve->second.points)
        points += (points.empty() ? "[" : ", [") + num(t) + ", " + num(f) + "]";
      s += "\n[[constraints]]  # *BOUNDARY_PRESCRIBED_MOTION_SET at line " +
           std::to_string(m.at.line) + "\nnodes = { set = " +
           core::toml_string(set->title.empty() ? "set " + std::to_string(set->id) : set->title) +
           " }\nvelocity = " + core::toml_vec3(v.x, v.y, v.z) + "\ncomponents = [\"" +
           std::string(1, "xyz"[m.component]) + "\"]\ncurve = [" + points + "]\n";
    }
    for (const auto& [id, curve] : curves_)
      if (!curve.used)
        notes_.push_back({curve.at, "*DEFINE_CURVE",
                          "curve " + std::to_string(id) + " is used by no translated keyword",
                          false});
    return s;
  }

  // NSID NSIDEX BOXID OFFSET BIRTH DEATH RWKSF / XT YT ZT XH YH ZH FRIC WVEL
  void rigid_wall(const LsDynaKeyword& k) {
    const auto c = data_cards(k);
    Wall w;
    w.point = {real(k, c, 1, 0, "XT", dim::length), real(k, c, 1, 1, "YT", dim::length),
               real(k, c, 1, 2, "ZT", dim::length)};
    const core::Vec3 head{real(k, c, 1, 3, "XH", dim::length), real(k, c, 1, 4, "YH", dim::length),
                          real(k, c, 1, 5, "ZH", dim::length)};
    w.normal = {head.x - w.point.x, head.y - w.point.y, head.z - w.point.z};
    if (w.normal.x == 0.0 && w.normal.y == 0.0 && w.normal.z == 0.0)
      throw core::InputError(card_at(k, c, 1).at(), key_,
                             "the head (XH, YH, ZH) equals the tail: no normal");
    w.friction = real(k, c, 1, 6, "FRIC");
    if (integer(k, c, 0, 0, "NSID") != 0 || integer(k, c, 0, 1, "NSIDEX") != 0 ||
        integer(k, c, 0, 2, "BOXID") != 0)
      note(k.at(), "NSID, NSIDEX and BOXID: the wall acts on every node of every mesh body", true);
    if (real(k, c, 0, 3, "OFFSET") != 0.0 || real(k, c, 0, 4, "BIRTH") != 0.0 ||
        real(k, c, 0, 5, "DEATH") != 0.0 || real(k, c, 1, 7, "WVEL") != 0.0)
      changes_run(k.at(), "OFFSET, BIRTH, DEATH and WVEL");
    if (w.friction >= 1.0)
      note(k.at(), "FRIC >= 1 (no sliding) is written as Coulomb friction " + num(w.friction),
           true);
    walls_.push_back(w);
  }

  // The body's `erosion`: the union of its material's criteria.
  std::string erosion_table(const LsDynaPart& part) const {
    Erosion e;
    if (const auto m = material_erosion_.find(part.material); m != material_erosion_.end())
      e = m->second;
    if (const auto a = add_erosion_.find(part.material); a != add_erosion_.end()) {
      e.plastic_strain = a->second.plastic_strain;
      e.volume_ratio = a->second.volume_ratio;
    }
    std::string s;
    if (e.plastic_strain > 0.0) s += "plastic_strain = " + num(e.plastic_strain);
    if (e.volume_ratio > 0.0)
      s += (s.empty() ? "" : ", ") + std::string("volume_ratio = ") + num(e.volume_ratio);
    if (e.material_failure) s += (s.empty() ? "" : ", ") + std::string("material_failure = true");
    return s.empty() ? s : "erosion = { " + s + " }\n";
  }

  std::string material_name(std::int64_t mid, std::int64_t eosid) const {
    return "mat" + std::to_string(mid) + (eosid != 0 ? "_eos" + std::to_string(eosid) : "");
  }

  // The material table of a part's MID with its EOSID.
  std::string material_table(const LsDynaPart& p) {
    const auto m = materials_.find(p.material);
    if (m == materials_.end())
      throw core::InputError(
          p.card.at(), "*PART",
          "part " + std::to_string(p.id) + " names material " + std::to_string(p.material) +
              ", which is not defined; translated materials: *MAT_ELASTIC, "
              "*MAT_PLASTIC_KINEMATIC, *MAT_JOHNSON_COOK, *MAT_MOONEY-RIVLIN_RUBBER, "
              "*MAT_JOHNSON_HOLMQUIST_CONCRETE, *MAT_RIGID");
    const Material& mat = m->second;
    const Eos* eos = nullptr;
    if (p.eos != 0) {
      const auto e = eos_.find(p.eos);
      if (e == eos_.end())
        throw core::InputError(
            p.card.at(), "*PART",
            "part " + std::to_string(p.id) + " names EOS " + std::to_string(p.eos) +
                ", which is not defined; translated: *EOS_GRUNEISEN, *EOS_LINEAR_POLYNOMIAL");
      eos = &e->second;
    }
    std::string s = "density = " + num(mat.density) + "\n";
    if (mat.kind == "hjc") {
      if (eos != nullptr)
        notes_.push_back({p.card.at(), "*PART",
                          "EOS " + std::to_string(p.eos) + " of part " + std::to_string(p.id) +
                              ": *MAT_JOHNSON_HOLMQUIST_CONCRETE has its own compaction EOS",
                          false});
      return s + mat.body;
    }
    if (mat.kind == "mooney-rivlin" && eos != nullptr)
      throw core::InputError(p.card.at(), "*PART",
                             "part " + std::to_string(p.id) + " gives EOS " +
                                 std::to_string(p.eos) +
                                 " to *MAT_MOONEY-RIVLIN_RUBBER, whose pressure is its own: "
                                 "allowed EOSID 0");
    double E = mat.E, nu = mat.nu;
    if (mat.kind == "johnson-cook") {
      if (eos == nullptr)
        throw core::InputError(
            p.card.at(), "*PART",
            "part " + std::to_string(p.id) + ": *MAT_JOHNSON_COOK needs an EOS (EOSID)");
      const double K =
          eos->bulk_modulus > 0.0 ? eos->bulk_modulus : mat.density * eos->sound_speed_squared;
      if (E <= 0.0 || nu <= 0.0) {
        if (mat.G <= 0.0 || K <= 0.0)
          throw core::InputError(mat.at, mat.keyword,
                                 "G and a bulk modulus from the EOS are needed for E and nu");
        E = 9.0 * K * mat.G / (3.0 * K + mat.G);
        nu = (3.0 * K - 2.0 * mat.G) / (2.0 * (3.0 * K + mat.G));
        notes_.push_back({mat.at, mat.keyword,
                          "E and PR (blank) follow from G and the EOS's bulk modulus " + num(K),
                          true});
      } else if (mat.G > 0.0 && std::abs(E / (2.0 * (1.0 + nu)) - mat.G) > 0.01 * mat.G) {
        notes_.push_back({mat.at, mat.keyword,
                          "G differs from E / (2 (1 + PR)) by more than 1 %; afemp uses E and PR",
                          true});
      }
    }
    s += "E = " + num(E) + "\nnu = " + num(nu) + "\n" + mat.body;
    if (eos != nullptr) s += "eos = " + eos->table + "\n";
    return s;
  }

  // A contact surface's parts as indices into mesh.part_names: a part set named before it was
  // defined is looked up now; 0 stands for every part.
  std::vector<std::size_t> contact_bodies(const Contact& ct, const std::vector<std::int64_t>& ids,
                                          const MeshData& mesh) const {
    std::vector<std::int64_t> parts;
    for (const std::int64_t id : ids) {
      if (id == 0) {
        parts = mesh.part_labels;
        break;
      }
      if (id > 0) {
        parts.push_back(id);
        continue;
      }
      const auto set = std::find_if(part_sets_.begin(), part_sets_.end(),
                                    [&](const LsDynaIdList& l) { return l.id == -id; });
      if (set == part_sets_.end())
        throw core::InputError(
            ct.at, ct.keyword,
            "part set " + std::to_string(-id) + " is not defined (*SET_PART_LIST)");
      for (const auto& p : set->ids) parts.push_back(p.first);
    }
    std::vector<std::size_t> out;
    for (const std::int64_t id : parts) {
      const auto p = std::find(mesh.part_labels.begin(), mesh.part_labels.end(), id);
      if (p == mesh.part_labels.end())
        throw core::InputError(ct.at, ct.keyword,
                               "part " + std::to_string(id) + " has no elements");
      const auto i = static_cast<std::size_t>(p - mesh.part_labels.begin());
      if (std::find(out.begin(), out.end(), i) == out.end()) out.push_back(i);
    }
    return out;
  }

  bool rigid_part(std::int64_t label) const {
    const auto p = parts_.find(label);
    if (p == parts_.end()) return false;
    const auto m = materials_.find(p->second.material);
    return m != materials_.end() && !m->second.rigid.empty();
  }

  // The [[contact]] tables: each pair of bodies once (the first contact naming it sets its
  // friction), a body with itself as afemp's self-contact.
  std::string contact_tables(const MeshData& mesh) {
    std::vector<bool> hexahedra(mesh.part_names.size(), false);
    for (const std::int32_t p : mesh.hexahedron_part) hexahedra[static_cast<std::size_t>(p)] = true;
    std::map<std::pair<std::size_t, std::size_t>, std::pair<const Contact*, double>> written;
    std::string s;
    for (const Contact& ct : contacts_) {
      const std::vector<std::size_t> a = contact_bodies(ct, ct.slave, mesh);
      const std::vector<std::size_t> b = ct.single ? a : contact_bodies(ct, ct.master, mesh);
      for (const std::size_t i : a)
        for (const std::size_t j : b) {
          if (ct.single && j < i) continue;
          const auto pair = std::minmax(i, j);
          if (!hexahedra[i] && !hexahedra[j]) {
            if (i == j) continue;  // trusses have no surface of their own
            throw core::InputError(ct.at, ct.keyword,
                                   "parts '" + mesh.part_names[i] + "' and '" + mesh.part_names[j] +
                                       "' are both trusses: afemp's contact needs a surface of "
                                       "hexahedra");
          }
          if (i == j && (!hexahedra[i] || rigid_part(mesh.part_labels[i]))) continue;
          const double friction = pair_friction(ct, mesh.part_labels[i], mesh.part_labels[j]);
          const auto [it, added] = written.emplace(pair, std::pair{&ct, friction});
          if (!added) {
            if (it->second.first != &ct && it->second.second != friction)
              notes_.push_back({ct.at, ct.keyword,
                                "'" + mesh.part_names[i] + "' and '" + mesh.part_names[j] +
                                    "' are already in contact (line " +
                                    std::to_string(it->second.first->at.line) +
                                    "): afemp takes one contact per pair, with that friction",
                                true});
            continue;
          }
          s += "\n[[contact]]  # " + ct.keyword + " at line " + std::to_string(ct.at.line) +
               "\nbodies = [" + core::toml_string(mesh.part_names[pair.first]) +
               (i == j ? "" : ", " + core::toml_string(mesh.part_names[pair.second])) +
               "]\nmethod = \"penalty\"\n";
          if (friction > 0.0) s += "friction = " + num(friction) + "\n";
        }
    }
    return s;
  }

  std::string scene(const MeshData& mesh) {
    std::string s = "[run]\n";
    if (!title_.empty()) s += "title = " + core::toml_string(title_) + "\n";
    if (!units_.scene_units().empty())
      s += "units = " + core::toml_string(units_.scene_units()) + "\n";
    if (end_time_ <= 0.0)
      throw core::InputError(
          {deck_path_, 0}, "*CONTROL_TERMINATION",
          "the deck gives no end time: ENDTIM of *CONTROL_TERMINATION is needed");
    s += "end_time = " + num(end_time_) + "\n";
    if (output_every_ > 0.0) s += "output_every = " + num(output_every_) + "\n";
    // A nearly incompressible solid rings beyond LS-DYNA's step rule in afemp's hexahedra
    // (core/nearly_incompressible.hpp): its factor is held to the one they need.
    namespace ni = core::nearly_incompressible;
    double factor = tssfac_ > 0.0 ? std::min(tssfac_, 1.0) : 0.0;
    const Material* nearly_incompressible = nullptr;
    for (const std::int64_t label : mesh.part_labels)
      if (const auto p = parts_.find(label); p != parts_.end())
        if (const auto m = materials_.find(p->second.material);
            m != materials_.end() && m->second.kind != "rigid" &&
            m->second.nu > ni::poisson_ratio &&
            (nearly_incompressible == nullptr || m->second.nu > nearly_incompressible->nu))
          nearly_incompressible = &m->second;
    if (nearly_incompressible != nullptr && (factor == 0.0 || factor > ni::element_step_factor)) {
      notes_.push_back({nearly_incompressible->at, nearly_incompressible->keyword,
                        "PR " + num(nearly_incompressible->nu) + ": element_time_step_factor " +
                            num(ni::element_step_factor) + " in place of TSSFAC " +
                            num(factor > 0.0 ? factor : 0.9) +
                            " (afemp's hexahedra of a nearly incompressible solid ring at "
                            "LS-DYNA's usual factor)",
                        true});
      factor = ni::element_step_factor;
    }
    if (factor > 0.0) s += "element_time_step_factor = " + num(factor) + "\n";
    if (max_steps_ > 0) s += "max_steps = " + std::to_string(max_steps_) + "\n";

    // A material table for each (MID, EOSID) the parts use.
    std::set<std::pair<std::int64_t, std::int64_t>> written;
    std::string materials;
    for (const std::int64_t label : mesh.part_labels) {
      const auto p = parts_.find(label);
      if (p == parts_.end()) continue;
      const auto key = std::make_pair(p->second.material, p->second.eos);
      if (!written.insert(key).second) continue;
      const std::string table = material_table(p->second);  // refuses an undefined MID first
      materials += "\n[materials." + material_name(key.first, key.second) + "]  # " +
                   materials_.at(key.first).keyword + "\n" + table;
    }
    for (const auto& entry : materials_) {
      const std::int64_t mid = entry.first;  // (a structured binding: clang 14 cannot capture it)
      if (std::none_of(written.begin(), written.end(),
                       [&](const auto& w) { return w.first == mid; }))
        notes_.push_back({entry.second.at, entry.second.keyword,
                          "material " + std::to_string(mid) + " is used by no part with elements",
                          false});
    }
    s += materials;

    const std::filesystem::path scene_dir = std::filesystem::absolute(scene_path_).parent_path();
    const std::string mesh_file = std::filesystem::absolute(deck_path_)
                                      .lexically_normal()
                                      .lexically_relative(scene_dir)
                                      .generic_string();
    const double scale = units_(1.0, dim::length);
    for (std::size_t i = 0; i < mesh.part_names.size(); ++i) {
      const std::int64_t label = mesh.part_labels[i];
      const auto p = parts_.find(label);
      if (p == parts_.end())
        throw core::InputError(
            {deck_path_, 0}, "*PART",
            "elements name part " + std::to_string(label) + ", which no *PART defines");
      const LsDynaPart& part = p->second;
      const bool hexahedra = std::find(mesh.hexahedron_part.begin(), mesh.hexahedron_part.end(),
                                       static_cast<std::int32_t>(i)) != mesh.hexahedron_part.end();
      if (!hexahedra && scale != 1.0)
        throw core::InputError(
            part.card.at(), "--units",
            "part " + std::to_string(label) +
                " has beams, whose section areas are "
                "read from the deck unconverted; import this deck without --units");
      s += "\n[[bodies]]\nname = " + core::toml_string(mesh.part_names[i]) + "  # *PART " +
           std::to_string(label) + "\ndiscretisation = \"" + (hexahedra ? "hexahedra" : "trusses") +
           "\"\nmaterial = \"" + material_name(part.material, part.eos) +
           "\"\nshape = { mesh = { file = " + core::toml_string(mesh_file) + ", parts = [" +
           core::toml_string(mesh.part_names[i]) + "]" +
           (scale != 1.0 ? ", scale = " + num(scale) : "") + " } }\n";
      const auto mat = materials_.find(part.material);
      const bool rigid = mat != materials_.end() && !mat->second.rigid.empty();
      if (rigid) {
        if (!hexahedra)
          throw core::InputError(part.card.at(), "*PART",
                                 "part " + std::to_string(label) +
                                     " of beams names *MAT_RIGID: afemp's rigid bodies are "
                                     "made of hexahedra");
        s += "rigid = " + mat->second.rigid + "\n";
      }
      if (hexahedra && !rigid) {
        const auto sec = solid_elform_.find(part.section);
        if (sec == solid_elform_.end())
          throw core::InputError(
              part.card.at(), "*PART",
              "part " + std::to_string(label) + " of solid elements names section " +
                  std::to_string(part.section) + ", which no *SECTION_SOLID defines");
        if (sec->second == 2) s += "element = \"full\"\n";
      }
      if (!rigid) {
        // A part naming no *HOURGLASS, or one without Q1 and Q2, takes *CONTROL_HOURGLASS's
        // form and *CONTROL_BULK_VISCOSITY's coefficients.
        Hourglass h{default_hourglass_, hexahedra ? default_bulk_viscosity_ : ""};
        if (part.hourglass != 0) {
          const auto named = hourglass_.find(part.hourglass);
          if (named == hourglass_.end())
            throw core::InputError(part.card.at(), "*PART",
                                   "part " + std::to_string(label) + " names hourglass " +
                                       std::to_string(part.hourglass) +
                                       ", which no *HOURGLASS defines");
          h.hourglass = named->second.hourglass;
          if (!named->second.bulk_viscosity.empty())
            h.bulk_viscosity = named->second.bulk_viscosity;
        }
        if (hexahedra && solid_elform_[part.section] == 1 && !h.hourglass.empty())
          s += "hourglass = " + h.hourglass + "\n";
        if (!h.bulk_viscosity.empty()) s += "bulk_viscosity = " + h.bulk_viscosity + "\n";
      }
      const auto v = velocity_.count(label) != 0 ? velocity_.find(label) : velocity_.find(0);
      const auto nv = node_velocity_part_.find(label);
      if (v != velocity_.end() && nv != node_velocity_part_.end()) {
        const core::Vec3 &a = v->second.first, &b = nv->second.first;
        if (a.x != b.x || a.y != b.y || a.z != b.z)
          throw core::InputError(nv->second.second, "*INITIAL_VELOCITY",
                                 "part " + std::to_string(label) +
                                     " is given another velocity by "
                                     "*INITIAL_VELOCITY_GENERATION at line " +
                                     std::to_string(v->second.second.line) +
                                     ": afemp gives a body one initial velocity");
      }
      if (v != velocity_.end()) {
        const core::Vec3& u = v->second.first;
        s += "velocity = " + core::toml_vec3(u.x, u.y, u.z) + "\n";
      } else if (nv != node_velocity_part_.end()) {
        const core::Vec3& u = nv->second.first;
        s += "velocity = " + core::toml_vec3(u.x, u.y, u.z) + "\n";
      }
      s += erosion_table(part);
      if (const auto e = eos_.find(part.eos);
          part.eos != 0 && e != eos_.end() && e->second.e0 != 0.0)
        s += "internal_energy = " + num(e->second.e0 / materials_.at(part.material).density) +
             "  # E0 / RO\n";
    }
    for (const auto& [label, v] : velocity_) {
      if (label == 0 || std::find(mesh.part_labels.begin(), mesh.part_labels.end(), label) !=
                            mesh.part_labels.end())
        continue;
      core::DeckNote n;
      n.at = v.second;
      n.keyword = "*INITIAL_VELOCITY_GENERATION";
      n.what = "part " + std::to_string(label) + " has no elements";
      notes_.push_back(std::move(n));
    }
    s += contact_tables(mesh);
    s += motion_tables();
    for (const Wall& w : walls_) {
      s += "\n[[walls]]\npoint = " + core::toml_vec3(w.point.x, w.point.y, w.point.z) +
           "\nnormal = " + core::toml_vec3(w.normal.x, w.normal.y, w.normal.z) + "\n";
      if (w.friction > 0.0) s += "friction = " + num(w.friction) + "\n";
    }
    return s;
  }

  LsDynaDeck deck_;
  std::string deck_path_, scene_path_;
  core::UnitConversion units_;
  core::DeckImportOptions options_;
  std::string key_;
  std::vector<core::DeckNote> notes_;

  std::string title_;
  double end_time_ = 0, output_every_ = 0, tssfac_ = 0;
  std::int64_t max_steps_ = 0;
  std::map<std::int64_t, LsDynaPart> parts_;
  std::map<std::int64_t, std::int64_t> solid_elform_;
  std::map<std::int64_t, Material> materials_;
  std::map<std::int64_t, Erosion> material_erosion_;  // by MID: the material card's own
  std::map<std::int64_t, Erosion> add_erosion_;       // by MID: *MAT_ADD_EROSION
  std::map<std::int64_t, Eos> eos_;
  std::map<std::int64_t, Hourglass> hourglass_;
  std::string default_hourglass_, default_bulk_viscosity_;  // *CONTROL_HOURGLASS, _BULK_VISCOSITY
  Friction control_friction_;                               // *CONTROL_CONTACT
  std::map<std::int64_t, std::pair<core::Vec3, core::SourceLocation>> velocity_;
  std::vector<LsDynaIdList> node_sets_;
  std::vector<LsDynaIdList> part_sets_;
  std::vector<Contact> contacts_;
  std::map<std::int64_t, Curve> curves_;
  std::vector<PrescribedMotion> motions_;
  std::vector<NodeVelocity> node_velocities_;
  // A part's velocity from its nodes' (*INITIAL_VELOCITY, *INITIAL_VELOCITY_NODE).
  std::map<std::int64_t, std::pair<core::Vec3, core::SourceLocation>> node_velocity_part_;
  std::vector<Wall> walls_;
};

}  // namespace

core::DeckImport import_lsdyna_deck(const std::string& text, const std::string& deck_path,
                                    const std::string& scene_path,
                                    const core::DeckImportOptions& options) {
  return LsDynaImport(text, deck_path, scene_path, options).run();
}

}  // namespace afemp::fem
