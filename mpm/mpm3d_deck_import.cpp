// MPM3D and MPM3D-F90 decks into afemp scenes (mpm/mpm3d_deck_import.hpp). The deck is a list
// of keywords, each known by its first four letters in any case, followed by numbers that may
// run over lines; '!' starts a comment (Ma 2005, appendix A; MPM3D-F90's FFI.f90 and
// DataIn.f90). Particles are written as point lists with each particle's volume (its mass
// over the density), so that every generator gives exactly the particles MPM3D would make.
#include "mpm/mpm3d_deck_import.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <vector>

#include "afemp/tensor.hpp"
#include "core/decks/deck_units.hpp"
#include "core/decks/scene_text.hpp"
#include "core/source_text.hpp"

namespace afemp::mpm {

namespace {

namespace dim = core::dimension;

struct Token {
  std::string_view text;
  std::size_t line;  // index in the SourceText
};

// The deck's words line by line, read as FFI.f90 reads them: a number may be on a later line
// than its keyword, but some keywords take "the rest of the line".
class Words {
 public:
  explicit Words(const core::SourceText& src) : src_(src) {
    for (std::size_t i = 0; i < src.size(); ++i) {
      std::string_view line = src.line(i);
      line = line.substr(0, line.find('!'));
      std::size_t pos = 0;
      while (pos < line.size()) {
        while (pos < line.size() && is_separator(line[pos])) ++pos;
        const std::size_t start = pos;
        while (pos < line.size() && !is_separator(line[pos])) ++pos;
        if (pos > start) tokens_.push_back({line.substr(start, pos - start), i});
      }
    }
  }

  bool done() const { return next_ == tokens_.size(); }
  // The line of the last word read (or of the next one before any).
  core::SourceLocation at() const {
    const std::size_t i = next_ == 0 ? 0 : next_ - 1;
    return src_.at(tokens_.empty() ? 0 : tokens_[std::min(i, tokens_.size() - 1)].line);
  }
  std::string_view peek() const { return done() ? std::string_view{} : tokens_[next_].text; }

  std::string_view word(const std::string& key, const std::string& what) {
    if (done()) throw core::InputError(at(), key, "the deck ends where " + what + " should follow");
    return tokens_[next_++].text;
  }
  double real(const std::string& key, const std::string& what) {
    const std::string_view w = word(key, what);
    return core::to_real(w, at(), key, what);
  }
  long integer(const std::string& key, const std::string& what) {
    const std::string_view w = word(key, what);
    return static_cast<long>(core::to_integer(w, at(), key, what));
  }
  // The words left on the current line (all of them when at a line's start).
  std::vector<std::string_view> rest_of_line() {
    std::vector<std::string_view> out;
    if (done()) return out;
    const std::size_t line = next_ > 0 ? tokens_[next_ - 1].line : tokens_[next_].line;
    while (next_ < tokens_.size() && tokens_[next_].line == line)
      out.push_back(tokens_[next_++].text);
    return out;
  }

 private:
  static bool is_separator(char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r'; }

  const core::SourceText& src_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
};

// MPM3D keywords compare their first four letters, case-insensitively.
std::string key_of(std::string_view word) {
  std::string k(word.substr(0, 4));
  for (char& c : k) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return k;
}

struct Material {
  long id = 0;
  std::string type;  // the deck's four letters
  core::SourceLocation at;
  double density = 0, E = 0, nu = 0;
  std::string strength;  // the scene's inline table
  double specific_heat = 0, temperature = -1, failure_strain = 0;
  std::string eos;
  double e0 = 0;  // EOS initial internal energy per unit volume (deck units)
  // hiex: its detonation velocity and the JWL constants of its seos (scene units: A, B, E0
  // pressures, then R1, R2, omega), which give the Chapman-Jouguet pressure the burn needs.
  double detonation_speed = 0;
  std::optional<std::array<double, 6>> jwl;
  // null: its bulk modulus (scene units), the wave speed MPM3D-F90 runs its EOS with.
  double bulk_modulus = 0;
};

// The Chapman-Jouguet state of JWL products detonated from rest at the reference density
// (Fickett & Davis, Detonation, 1979, section 2A): on the products' Hugoniot,
// E = E0 + p (1 - V) / 2 with p = f(V) + omega E / V (E per unit reference volume, V = rho0 /
// rho), the CJ point is where the Rayleigh line's slope rho0 D^2 = p / (1 - V) is least. The
// pressure there, for the burn's Wilkins term; the search runs over 0.3 <= V <= 0.99 (the CJ
// volume of every explosive afemp's docs list is 0.7-0.8).
double cj_pressure(const std::array<double, 6>& jwl) {
  const auto [a, b, e0, r1, r2, omega] = jwl;
  const auto hugoniot = [&](double v) {
    const double f = a * (1.0 - omega / (r1 * v)) * std::exp(-r1 * v) +
                     b * (1.0 - omega / (r2 * v)) * std::exp(-r2 * v);
    const double e = (e0 + 0.5 * f * (1.0 - v)) / (1.0 - 0.5 * omega * (1.0 - v) / v);
    return f + omega * e / v;
  };
  const auto slope = [&](double v) { return hugoniot(v) / (1.0 - v); };
  double lo = 0.3, hi = 0.99;
  for (int i = 0; i < 200; ++i) {  // golden-section search of the least slope
    const double m1 = hi - 0.618033988749895 * (hi - lo), m2 = lo + 0.618033988749895 * (hi - lo);
    if (slope(m1) < slope(m2))
      hi = m2;
    else
      lo = m1;
  }
  return hugoniot(0.5 * (lo + hi));
}

struct Point {
  core::Vec3 x;
  double mass;
};

struct Body {
  long component = 0;
  long material = 0;
  core::SourceLocation at;
  std::vector<Point> points;
  std::optional<core::Vec3> velocity;
  std::optional<core::Vec3> gravity;
};

class Mpm3dImport {
 public:
  Mpm3dImport(const std::string& text, const std::string& deck_path, const std::string& scene_path,
              const core::DeckImportOptions& options)
      : src_(text, deck_path),
        words_(src_),
        deck_path_(deck_path),
        scene_stem_(std::filesystem::path(scene_path).stem().string()),
        units_(options.units, {deck_path, 0}),
        options_(options) {}

  core::DeckImport run() {
    read();
    check_counts();
    core::DeckImport out;
    std::string body = scene(out.files);  // may add notes
    core::refuse_untranslated(notes_, options_);
    body.insert(body.find('\n') + 1, core::untranslated_run_key(notes_));
    out.notes = notes_;
    out.units = units_.description();
    out.scene = core::imported_scene_header(deck_path_, core::DeckFormat::mpm3d,
                                            units_.description(), notes_) +
                "\n" + body;
    return out;
  }

 private:
  void note(const std::string& key, const std::string& what, bool approximated) {
    notes_.push_back({words_.at(), key, what, approximated});
  }
  // Not translated, and the run differs for it (an initial condition, a load, damping): the
  // import stops unless DeckImportOptions::allow_untranslated.
  void changes_run(const std::string& key, const std::string& what) {
    notes_.push_back({words_.at(), key, what, false, true});
  }

  void read() {
    while (!words_.done()) {
      const std::string_view word = words_.word("", "a keyword");
      const std::string k = key_of(word);
      key_ = std::string(word);
      if (k == "endi") break;
      keyword(k);
    }
  }

  double length() { return units_(words_.real(key_, "a length"), dim::length); }

  void keyword(const std::string& k) {
    if (k == "mpm3") {
      std::string t;
      for (std::string_view w : words_.rest_of_line()) t += (t.empty() ? "" : " ") + std::string(w);
      while (t.starts_with('*') || t.starts_with(' ')) t.erase(0, 1);
      title_ = t;
    } else if (k == "nbmp") {
      nbmp_ = words_.integer(key_, "the number of particles");
    } else if (k == "nmat") {
      nmat_ = words_.integer(key_, "the number of materials");
    } else if (k == "nbbo") {
      nbbo_ = words_.integer(key_, "the number of bodies");
    } else if (k == "nbco" || k == "ncom") {
      words_.integer(key_, "the number of components");  // bodies carry their component
    } else if (k == "ppc") {
      ppc_ = words_.integer(key_, "the particles per cell");
    } else if (k == "nbgn") {
      words_.integer(key_, "the number of grid nodes");  // follows from spx, spy, spz, dcell
    } else if (k == "endt") {
      end_time_ = units_(words_.real(key_, "the end time"), dim::time);
    } else if (k == "dt") {
      time_step_ = units_(words_.real(key_, "the time step"), dim::time);
    } else if (k == "tste") {
      steps_ = words_.integer(key_, "the number of steps");
    } else if (k == "oste") {
      output_steps_ = words_.integer(key_, "the steps between outputs");
    } else if (k == "outt") {
      output_every_ = units_(words_.real(key_, "the output interval"), dim::time);
    } else if (k == "rptt") {
      words_.real(key_, "the report interval");
      note(key_, "the report interval (afemp's progress line reports every 10 s)", false);
    } else if (k == "grid") {
      for (int a = 0; a < 3; ++a) {
        span_min_[a] = length();
        span_max_[a] = length();
      }
    } else if (k == "spx" || k == "spy" || k == "spz") {
      const int a = k[2] - 'x';
      span_min_[a] = length();
      span_max_[a] = length();
    } else if (k == "dcel") {
      cell_ = length();
    } else if (k == "dtsc") {
      dtscale_ = words_.real(key_, "the time-step scale");
      dtscale_at_ = words_.at();
    } else if (k == "fixe") {
      for (int f = 0; f < 6; ++f) {
        const long c = words_.integer(key_, "a face condition (0 free, 1 fixed, 2 symmetric)");
        if (c < 0 || c > 2)
          throw core::InputError(
              words_.at(), key_,
              "face conditions are 0 (free), 1 (fixed) or 2 (symmetric), found " +
                  std::to_string(c));
        faces_[f] = static_cast<int>(c);
      }
    } else if (k == "mate") {
      read_materials();
    } else if (k == "seos") {
      read_eos();
    } else if (k == "part") {
      read_particles();
    } else if (k == "musl" || k == "usf" || k == "usl") {
      if (on_off()) {
        scheme_ = k == "musl" ? "MUSL" : k == "usf" ? "USF" : "USL";
        scheme_set_ = true;
      }
    } else if (k == "jaum") {
      jaumann_ = on_off();
    } else if (k == "gimp") {
      shape_ = "gimp";
      note(key_, "GIMP is written as afemp's uGIMP (the particle's cube kept at its initial size)",
           true);
    } else if (k == "bimp") {
      // MPM3D-F90's NShape_Bspline: the quadratic B-spline, 27 nodes.
      shape_ = "bspline2";
      note(key_,
           "B-spline MPM is written as afemp's quadratic B-spline (MPM3D-F90's is quadratic too, "
           "centred half a cell off its nodes; afemp's is centred on them and modified at the "
           "grid's faces)",
           true);
    } else if (k == "bulk") {
      bulk_ = std::array<double, 2>{words_.real(key_, "the quadratic coefficient"),
                                    words_.real(key_, "the linear coefficient")};
    } else if (k == "velo") {
      read_velocities();
    } else if (k == "load") {
      read_loads();
    } else if (k == "cont") {
      read_contact();
    } else if (k == "outr" || k == "curv" || k == "curx" || k == "pt2d" || k == "tecp" ||
               k == "para") {
      words_.rest_of_line();
      note(key_,
           "output option (afemp writes every field to fields.xmf and energies to history.csv; "
           "time histories are [[probes]])",
           false);
    } else if (k == "deto") {
      core::Vec3 x;
      x.x = length();
      x.y = length();
      x.z = length();
      detonations_.push_back({x, words_.at()});
    } else if (k == "sgmp" || k == "smoo" || k == "tlmp" || k == "uvfp") {
      // A different discretisation of the same physics: run with afemp's own, noted.
      note(key_,
           "an MPM3D-F90 scheme the import does not translate (staggered-grid, smoothed-stress, "
           "total-Lagrangian or mixed MPM): the deck runs with the scene's shape function and "
           "the updated-Lagrangian form (docs/import.md)",
           true);
    } else if (k == "drda") {
      changes_run(key_, "dynamic relaxation (damping to a static solution) is not part of afemp");
    } else if (k == "qulo" || k == "damp") {
      if (words_.real(key_, "its value") != 0.0)
        changes_run(key_, "quasi-static loading and damping are not part of afemp");
      else
        note(key_, "zero, as afemp runs", false);
    } else {
      throw core::InputError(
          words_.at(), key_,
          "unknown MPM3D keyword; known: mpm3d, nbmp, nmat, nbco, nbbo, ppc, "
          "nbgn, endtime, dt, tstep, ostep, outtime, rpttime, grid, spx, spy, "
          "spz, dcell, dtscale, fixed, material, seos, particle, musl, usf, usl, "
          "jaum, gimp, bulk, velo, load, contact, outres, curv, curx, pt2d, "
          "tecp, para, deto, drda, bimp, sgmp, smoo, TLmp, UVFp, QuLo, Damp, "
          "endi");
    }
  }

  bool on_off() {
    const std::string v = key_of(words_.word(key_, "on or off"));
    if (v == "on") return true;
    if (v == "off") return false;
    throw core::InputError(words_.at(), key_, "expected on or off, found '" + v + "'");
  }

  // Material records "id type values..." until the one numbered nmat (DataIn.f90's
  // SetMaterial), each on its own line.
  void read_materials() {
    if (nmat_ <= 0)
      throw core::InputError(words_.at(), key_, "nmat must come before the materials");
    long id = 0;
    while (id < nmat_) {
      id = words_.integer(key_, "a material number");
      if (id <= 0 || id > nmat_)
        throw core::InputError(words_.at(), key_,
                               "material number " + std::to_string(id) +
                                   ": allowed 1 to nmat = " + std::to_string(nmat_));
      Material m;
      m.id = id;
      m.type = key_of(words_.word(key_, "a material type"));
      m.at = words_.at();
      std::vector<double> v;
      for (std::string_view w : words_.rest_of_line())
        v.push_back(core::to_real(w, m.at, key_, "a value of material " + std::to_string(id)));
      material(m, v);
      materials_[id] = m;
    }
  }

  // One material line into the scene's terms (the values as DataIn.f90 reads them).
  void material(Material& m, const std::vector<double>& v) {
    const auto want = [&](std::initializer_list<std::size_t> counts, const char* fields) {
      if (std::find(counts.begin(), counts.end(), v.size()) == counts.end())
        throw core::InputError(m.at, key_,
                               "material " + std::to_string(m.id) + " (" + m.type + ") takes " +
                                   fields + "; found " + std::to_string(v.size()) + " values");
    };
    const auto stress = [&](double s) { return core::toml_number(units_(s, dim::stress)); };
    if (m.type == "elas")
      want({3}, "density, E, nu");
    else if (m.type == "pla1")
      want({4}, "density, E, nu, yield");
    else if (m.type == "pla2")
      want({5}, "density, E, nu, yield, tangent modulus");
    else if (m.type == "sjc")
      want({8}, "density, E, nu, A, B, n, C, epso");
    else if (m.type == "sjcf")
      want({9}, "density, E, nu, A, B, n, C, epso, epf");
    else if (m.type == "john")
      want({7, 12},
           "density, E, nu, A, B, n, C (MPM3D 2005) or those and m, room and melt "
           "temperature, specific heat, epso (MPM3D-F90)");
    else if (m.type == "jcf")
      want({13},
           "density, E, nu, A, B, n, C, m, room and melt temperature, specific heat, epso, "
           "epf");
    else if (m.type == "hiex")
      want({2}, "density, detonation velocity D");
    else if (m.type == "null")
      want({3}, "density, bulk modulus, viscosity");
    else if (m.type == "dpm")
      want({7}, "density, E, nu, q_fai, k_fai, q_psi, ten_f");
    else if (m.type == "neoh")
      want({3}, "density, E, nu");
    else
      throw core::InputError(m.at, key_,
                             "material type '" + m.type +
                                 "' has no afemp counterpart; translated: elas, pla1, pla2, "
                                 "john, sjc, sjcf, jcf, hiex, null, dpm, neoh");
    if (m.type == "hiex" || m.type == "null") {
      // No strength (DataIn.f90's SetMaterial; Constitution.f90's M3DM6 and M3DM7): the EOS
      // of its seos gives the pressure.
      m.density = units_(v[0], dim::density);
      m.strength = "{ model = \"fluid\" }";
      if (m.type == "hiex") {
        m.detonation_speed = units_(v[1], dim::velocity);
      } else {
        m.bulk_modulus = units_(v[1], dim::stress);
        if (v[2] != 0.0)
          notes_.push_back({m.at, key_,
                            "material " + std::to_string(m.id) + " (null): its viscosity " +
                                core::toml_number(v[2]) +
                                " is left out (afemp's fluid carries no shear stress)",
                            true});
      }
      return;
    }
    m.density = units_(v[0], dim::density);
    m.E = units_(v[1], dim::stress);
    m.nu = v[2];
    if (m.type == "elas") {
      m.strength = "{ model = \"elastic\" }";
    } else if (m.type == "neoh") {
      // Constitution.f90's M3DM10 and M3DM11: sigma = (mu (B - I) + lambda ln J I) / J, the
      // neo-Hookean solid's log form.
      m.strength = "{ model = \"neo-hookean\", form = \"log\" }";
    } else if (m.type == "dpm") {
      // Constitution.f90's M3DM9 (no EOS): the cone's constants as they are; its tension
      // cutoff min(ten_f, k_fai / q_fai), 0 without friction. Left out at or beyond the apex,
      // which is then afemp's default (the apex computed again after the unit conversion).
      const double q = v[3], k = v[4], tension = v[6];
      m.strength = "{ model = \"drucker-prager\", q_phi = " + core::toml_number(q) +
                   ", k_phi = " + stress(k) + ", q_psi = " + core::toml_number(v[5]);
      if (q == 0.0)
        m.strength += ", tension_cutoff = 0";
      else if (tension < k / q)
        m.strength += ", tension_cutoff = " + stress(tension);
      m.strength += " }";
    } else if (m.type == "pla1" || m.type == "pla2") {
      m.strength = "{ model = \"j2\", yield = " + stress(v[3]);
      if (m.type == "pla2") m.strength += ", tangent_modulus = " + stress(v[4]);
      m.strength += " }";
    } else {
      const bool thermal = v.size() >= 12;
      m.strength = "{ model = \"johnson-cook\", A = " + stress(v[3]) + ", B = " + stress(v[4]) +
                   ", n = " + core::toml_number(v[5]) + ", C = " + core::toml_number(v[6]);
      if (thermal) {
        m.strength += ", m = " + core::toml_number(v[7]) +
                      ", room_temperature = " + core::toml_number(v[8]) +
                      ", melt_temperature = " + core::toml_number(v[9]);
        m.specific_heat = units_(v[10], dim::specific_energy);
        m.temperature = v[8];
      }
      const std::size_t epso = thermal ? 11 : 7;
      if (epso < v.size())
        m.strength += ", reference_strain_rate = " + core::toml_number(units_(v[epso], dim::rate));
      m.strength += " }";
      if (m.type == "sjcf" || m.type == "jcf") {
        m.failure_strain = v.back();
        notes_.push_back({m.at, key_,
                          "material " + std::to_string(m.id) + " (" + m.type +
                              "): failure at epf is afemp's plastic-strain failure (a failed "
                              "point keeps compression, loses shear and tension)",
                          true});
      }
    }
  }

  // "seos set type values": 1 linear polynomial (C0..C6, E0), 2 Mie-Grueneisen (c0, lambda,
  // gamma0, E0); MPM3D 2005 wrote type 1 with c0, lambda, gamma0 for the Grueneisen form.
  void read_eos() {
    const long set = words_.integer(key_, "the material number");
    const long type = words_.integer(key_, "the EOS type");
    const core::SourceLocation at = words_.at();
    const auto it = materials_.find(set);
    if (it == materials_.end())
      throw core::InputError(
          at, key_,
          "material " + std::to_string(set) + " is not defined (seos comes after material)");
    std::vector<double> v;
    for (std::string_view w : words_.rest_of_line())
      v.push_back(core::to_real(w, at, key_, "an EOS value"));
    Material& m = it->second;
    if (m.type == "dpm")
      throw core::InputError(at, key_,
                             "material " + std::to_string(set) +
                                 " (dpm): MPM3D's Drucker-Prager runs without an EOS (its "
                                 "pressure is linear elastic, Constitution.f90's M3DM9); remove "
                                 "this seos");
    const auto speed = [&](double c) { return core::toml_number(units_(c, dim::velocity)); };
    const bool special = m.type == "hiex" || m.type == "null";
    if (!special && ((type == 2 && v.size() == 4) || (type == 1 && v.size() == 3))) {
      m.eos = "{ model = \"mie-gruneisen\", c0 = " + speed(v[0]) +
              ", s = " + core::toml_number(v[1]) + ", gamma0 = " + core::toml_number(v[2]) + " }";
      if (v.size() == 4) m.e0 = v[3];
    } else if (!special && type == 1 && v.size() == 8) {
      m.eos = "{ model = \"linear-polynomial\"";
      for (int i = 0; i < 7; ++i)
        m.eos += ", C" + std::to_string(i) + " = " + core::toml_number(units_(v[i], dim::stress));
      m.eos += " }";
      m.e0 = v[7];
    } else if (type == 3 && v.size() == 6 && m.type == "hiex") {
      // A, B, R1, R2, omega, E0 (DataIn.f90's SetEos); E0 is per unit volume, as afemp's.
      const auto stress = [&](double x) { return units_(x, dim::stress); };
      m.jwl = {stress(v[0]), stress(v[1]), stress(v[5]), v[2], v[3], v[4]};
      m.eos = "{ model = \"jwl\", A = " + core::toml_number((*m.jwl)[0]) +
              ", B = " + core::toml_number((*m.jwl)[1]) + ", R1 = " + core::toml_number(v[2]) +
              ", R2 = " + core::toml_number(v[3]) + ", omega = " + core::toml_number(v[4]) +
              ", E0 = " + core::toml_number((*m.jwl)[2]) + " }";
    } else if (type == 4 && v.size() == 1 && m.type == "null") {
      // p = c^2 (rho - rho0), afemp's linear EOS with K = rho0 c^2; MPM3D-F90 replaces the c
      // given by the null material's own sqrt(K / rho0) (DataIn.f90's Initial), so K it is.
      m.eos = "{ model = \"linear\", bulk_modulus = " + core::toml_number(m.bulk_modulus) + " }";
      notes_.push_back({at, key_,
                        "material " + std::to_string(set) +
                            " (null): the weakly compressible EOS runs with the material's wave "
                            "speed sqrt(K / density), as MPM3D-F90 runs it, not the c given",
                        true});
    } else if (special || type == 3 || type == 4) {
      throw core::InputError(
          at, key_,
          "material " + std::to_string(set) + " (" + m.type + ") with EOS type " +
              std::to_string(type) + " and " + std::to_string(v.size()) +
              " values; translated: hiex with 3 (JWL: A, B, R1, R2, omega, E0), null with 4 "
              "(weakly compressible: c; MPM3D-F90 overwrites the first constant of the other "
              "types with the null material's wave speed, so they do not run as written), "
              "other materials with 1 (linear polynomial: C0..C6, E0) or 2 (Grueneisen: c0, "
              "lambda, gamma0, E0)");
    } else {
      throw core::InputError(at, key_,
                             "EOS type " + std::to_string(type) + " with " +
                                 std::to_string(v.size()) +
                                 " values; allowed: 1 with C0..C6, E0 (8 values), 2 with c0, "
                                 "lambda, gamma0, E0 (4 values)");
    }
  }

  long material_id(const std::string& what) {
    const long id = words_.integer(key_, what);
    if (materials_.find(id) == materials_.end())
      throw core::InputError(words_.at(), key_,
                             "material " + std::to_string(id) +
                                 " is not defined; define it under "
                                 "'material' (nmat " +
                                 std::to_string(nmat_) + ") before the particles");
    return id;
  }

  // A particle set's size before it is made (the lattice it scans, an upper bound): far past
  // the nbmp the deck declares (MPM3D allocates that many; the exact count is checked once all
  // are made), or past 2e7 in any case (nbmp itself may be absurd), it is refused. Found by
  // fuzzing: a block of 4294967296 x 4 x 2 took minutes and then all the memory.
  void expect_particles(double count) {
    double made = 0.0;
    for (const Body& b : bodies_) made += static_cast<double>(b.points.size());
    const double limit = std::min(nbmp_ > 0 ? 4.0 * static_cast<double>(nbmp_) + 1e4 : 2e7, 2e7);
    if (!(count >= 0.0) || made + count > limit)
      throw core::InputError(
          words_.at(), key_,
          "this particle set scans " + core::readable_count(count) + " lattice sites; with the " +
              core::readable_count(made) + " particles before it that is far more than " +
              (nbmp_ > 0 && 4.0 * static_cast<double>(nbmp_) + 1e4 < 2e7
                   ? "nbmp = " + std::to_string(nbmp_) + " declares"
                   : std::string("an imported deck may make (2e7; its point list would take "
                                 "gigabytes)")));
  }

  Body& new_body(long component, long material) {
    Body& b = bodies_.emplace_back();
    b.component = component;
    b.material = material;
    b.at = words_.at();
    return b;
  }

  // DataIn.f90's SetParticle: the generators place particles at the centres of a lattice of
  // spacing dp, each of mass density * dp^3.
  void read_particles() {
    const std::string option = key_of(words_.peek());
    if (!option.empty() && (std::isdigit(static_cast<unsigned char>(option[0])) != 0)) {
      read_particle_table();
      return;
    }
    words_.word(key_, "point, block, sphere, blod or cicl");
    const long component = words_.integer(key_, "the component number");
    if (option == "poin") {
      const long count = words_.integer(key_, "the number of particles");
      expect_particles(static_cast<double>(count));
      Body* body = nullptr;
      for (long p = 0; p < count; ++p) {
        words_.integer(key_, "a particle id");
        const long mat = material_id("the material of a particle");
        if (body == nullptr) body = &new_body(component, mat);
        if (mat != body->material)
          throw core::InputError(words_.at(), key_,
                                 "particles of one point list share one material (MPM3D gives the "
                                 "list the last one's); split the list");
        const double mass = units_(words_.real(key_, "the particle mass"), dim::mass);
        const double x = length(), y = length(), z = length();
        body->points.push_back({{x, y, z}, mass});
      }
      return;
    }
    if (option != "bloc" && option != "sphe" && option != "blod" && option != "cicl")
      throw core::InputError(words_.at(), key_,
                             "particle option '" + option +
                                 "'; allowed: point, block, sphere, "
                                 "blod, cicl");
    Body& body = new_body(component, material_id("the material"));
    const double density = units_(words_.real(key_, "the density"), dim::density);
    const double dp = length();
    const double mass = density * dp * dp * dp;
    const core::Vec3 o{length(), length(), length()};
    const auto add = [&](double x, double y, double z) {
      body.points.push_back({{x, y, z}, mass});
    };
    if (option == "bloc" || option == "blod") {
      const long nx = words_.integer(key_, "nx"), ny = words_.integer(key_, "ny"),
                 nz = words_.integer(key_, "nz");
      // Each count at least 1 (fuzzing found 0 x 4 x 2e18: no particle, and the outer loops
      // ran for ever).
      if (nx < 1 || ny < 1 || nz < 1)
        throw core::InputError(words_.at(), key_,
                               "a block needs nx, ny and nz of at least 1; got " +
                                   std::to_string(nx) + " x " + std::to_string(ny) + " x " +
                                   std::to_string(nz));
      expect_particles(static_cast<double>(nx) * static_cast<double>(ny) * static_cast<double>(nz));
      core::Vec3 hole{};
      double r2 = -1.0;
      if (option == "blod") {
        hole = {length(), length(), length()};
        const double nr =
            static_cast<double>(words_.integer(key_, "the hole's radius in spacings"));
        r2 = nr * dp * nr * dp;
      }
      for (long iz = 0; iz < nz; ++iz)
        for (long iy = 0; iy < ny; ++iy)
          for (long ix = 0; ix < nx; ++ix) {
            const double x = o.x + (ix + 0.5) * dp, y = o.y + (iy + 0.5) * dp,
                         z = o.z + (iz + 0.5) * dp;
            if ((x - hole.x) * (x - hole.x) + (y - hole.y) * (y - hole.y) >= r2) add(x, y, z);
          }
      return;
    }
    // sphere and cicl (a disc one particle thick): nR spacings of radius about the origin.
    const double radius = words_.real(key_, "the radius in spacings");
    // The lattice it scans: (2n)^3, (2n)^2 for a disc.
    const double side = 2.0 * std::floor(std::abs(radius));
    expect_particles(!std::isfinite(radius) ? -1.0
                     : option == "sphe"     ? side * side * side
                                            : side * side);
    const long n = static_cast<long>(radius);
    const double r2 = (n * dp) * (n * dp);
    for (long ix = 1 - n; ix <= n; ++ix)
      for (long iy = 1 - n; iy <= n; ++iy)
        for (long iz = option == "sphe" ? 1 - n : 0; iz <= (option == "sphe" ? n : 0); ++iz) {
          const double x = (ix - 0.5) * dp + o.x, y = (iy - 0.5) * dp + o.y;
          const double z = option == "sphe" ? (iz - 0.5) * dp + o.z : o.z + 0.5 * dp;
          const double dz = option == "sphe" ? z - o.z : 0.0;
          if ((x - o.x) * (x - o.x) + (y - o.y) * (y - o.y) + dz * dz < r2) add(x, y, z);
        }
  }

  // MPM3D 2005 (appendix A): "particle" then nbmp rows "id material component x y z", each
  // particle of volume dcell^3 / ppc; a body per component.
  void read_particle_table() {
    if (nbmp_ <= 0)
      throw core::InputError(words_.at(), key_, "nbmp must come before the particles");
    if (cell_ <= 0.0 || ppc_ <= 0)
      throw core::InputError(words_.at(), key_,
                             "a particle table (id, material, component, x, y, z) needs dcell and "
                             "ppc before it: the particles' volume is dcell^3 / ppc");
    std::map<long, std::size_t> body_of;
    for (long p = 0; p < nbmp_; ++p) {
      words_.integer(key_, "a particle id");
      const long mat = material_id("the material of a particle");
      const long comp = words_.integer(key_, "the component of a particle");
      const double x = length(), y = length(), z = length();
      auto it = body_of.find(comp);
      if (it == body_of.end()) {
        new_body(comp, mat);
        it = body_of.emplace(comp, bodies_.size() - 1).first;
      }
      Body& b = bodies_[it->second];
      if (b.material != mat)
        throw core::InputError(words_.at(), key_,
                               "the particles of component " + std::to_string(comp) +
                                   " have different materials; afemp gives a body one material");
      const double volume = cell_ * cell_ * cell_ / static_cast<double>(ppc_);
      b.points.push_back({{x, y, z}, materials_[mat].density * volume});
    }
  }

  Body& body_numbered(long n, const char* by) {
    if (n < 1 || n > static_cast<long>(bodies_.size()))
      throw core::InputError(words_.at(), key_,
                             std::string(by) + " " + std::to_string(n) +
                                 " is not defined; bodies 1 to " + std::to_string(bodies_.size()) +
                                 " (in the order of the particle sets)");
    return bodies_[static_cast<std::size_t>(n - 1)];
  }

  core::Vec3 velocity() {
    const double x = words_.real(key_, "vx"), y = words_.real(key_, "vy"),
                 z = words_.real(key_, "vz");
    return {units_(x, dim::velocity), units_(y, dim::velocity), units_(z, dim::velocity)};
  }

  // "velo" ... "endv": by body (MPM3D-F90), by component (MPM3D 2005) or by particle.
  void read_velocities() {
    while (true) {
      const std::string k = key_of(words_.word(key_, "body, comp, node or endv"));
      if (k == "endv") return;
      if (k == "body") {
        Body& b = body_numbered(words_.integer(key_, "the body number"), "body");
        b.velocity = velocity();
      } else if (k == "comp") {
        const long comp = words_.integer(key_, "the component number");
        const core::Vec3 v = velocity();
        bool found = false;
        for (Body& b : bodies_)
          if (b.component == comp) {
            b.velocity = v;
            found = true;
          }
        if (!found)
          throw core::InputError(words_.at(), key_,
                                 "component " + std::to_string(comp) + " has no particles");
      } else if (k == "node") {
        const long p = words_.integer(key_, "the particle number");
        velocity();
        changes_run(key_, "the initial velocity of particle " + std::to_string(p) +
                              " alone (afemp gives a body one initial velocity)");
      } else if (k == "ksin" || k == "nuli" || k == "vsin") {
        words_.rest_of_line();
        changes_run(key_, "a velocity profile built into MPM3D-F90 for one test case");
      } else {
        throw core::InputError(words_.at(), key_,
                               "'" + k + "' in velo; allowed: body, comp, node, endv");
      }
    }
  }

  // "load" ... "endl": gravity per body; forces on particles or bodies are not translated.
  void read_loads() {
    while (true) {
      const std::string k = key_of(words_.word(key_, "grav, body, part or endl"));
      if (k == "endl") return;
      if (k == "grav") {
        Body& b = body_numbered(words_.integer(key_, "the body number"), "body");
        const double x = words_.real(key_, "gx"), y = words_.real(key_, "gy"),
                     z = words_.real(key_, "gz");
        b.gravity = core::Vec3{units_(x, dim::acceleration), units_(y, dim::acceleration),
                               units_(z, dim::acceleration)};
      } else if (k == "body" || k == "part") {
        words_.integer(key_, "the number");
        for (int a = 0; a < 3; ++a) words_.real(key_, "a force component");
        changes_run(key_, "a constant force on a " +
                              std::string(k == "body" ? "body" : "particle") +
                              " (afemp's scenes take gravity, not point forces)");
      } else {
        throw core::InputError(words_.at(), key_,
                               "'" + k + "' in load; allowed: grav, body, part, endl");
      }
    }
  }

  // "contact lagr friction normal" (MPM3D-F90) or "cont on|off" (MPM3D 2005).
  void read_contact() {
    const std::string k = key_of(words_.word(key_, "lagr, others, on or off"));
    if (k == "off") return;
    contact_ = true;
    contact_at_ = words_.at();
    if (k == "on") return;
    if (k != "lagr" && k != "othe")
      throw core::InputError(words_.at(), key_, "'" + k + "'; allowed: lagr, others, on, off");
    friction_ = words_.real(key_, "the friction coefficient");
    words_.integer(key_, "the normal's method");
    note(key_,
         "Bardenhagen's grid contact is written as afemp's (Lian et al. 2013, eqs 37-42: "
         "collinear normals, the distance criterion)",
         true);
  }

  void check_counts() {
    std::size_t particles = 0;
    for (const Body& b : bodies_) particles += b.points.size();
    if (bodies_.empty())
      throw core::InputError({deck_path_, 0}, "particle", "the deck defines no particles");
    if (nbmp_ > 0 && static_cast<std::size_t>(nbmp_) != particles)
      throw core::InputError({deck_path_, 0}, "nbmp",
                             "nbmp is " + std::to_string(nbmp_) + " but the particle sets make " +
                                 std::to_string(particles) + " particles");
    if (nbbo_ > 0 && static_cast<std::size_t>(nbbo_) != bodies_.size())
      throw core::InputError({deck_path_, 0}, "nbbo",
                             "nbbo is " + std::to_string(nbbo_) + " but the deck has " +
                                 std::to_string(bodies_.size()) + " particle sets");
    if (cell_ <= 0.0)
      throw core::InputError({deck_path_, 0}, "dcell", "the deck gives no cell size (dcell)");
    for (int a = 0; a < 3; ++a)
      if (!(span_max_[a] > span_min_[a]))
        throw core::InputError(
            {deck_path_, 0}, std::string("sp") + char('x' + a),
            "the grid's extent along " + std::string(1, char('x' + a)) + " is missing or empty");
  }

  std::string scene(std::vector<core::DeckFile>& files) {
    std::string s = "[run]\n";
    if (!title_.empty()) s += "title = " + core::toml_string(title_) + "\n";
    if (!units_.scene_units().empty())
      s += "units = " + core::toml_string(units_.scene_units()) + "\n";
    double end_time = end_time_;
    if (time_step_ > 0.0 && steps_ > 0 && end_time <= 0.0)
      end_time = time_step_ * static_cast<double>(steps_);
    if (end_time <= 0.0)
      throw core::InputError({deck_path_, 0}, "endtime",
                             "the deck gives no end time (endtime, or dt and tstep)");
    s += "end_time = " + core::toml_number(end_time) + "\n";
    double output = output_every_;
    if (output <= 0.0 && output_steps_ > 0 && time_step_ > 0.0)
      output = time_step_ * static_cast<double>(output_steps_);
    s += "output_every = " + core::toml_number(output > 0.0 ? output : end_time) + "\n";
    if (time_step_ > 0.0) {
      s += "time_step = " + core::toml_number(time_step_) + "\n";
    } else {
      double f = dtscale_;
      if (f > 1.0) {
        notes_.push_back(
            {dtscale_at_, "dtscale",
             "dtscale " + core::toml_number(f) + " is above afemp's largest factor 1; written as 1",
             true});
        f = 1.0;
      }
      s += "time_step_factor = " + core::toml_number(f) +
           (dtscale_at_.line == 0 ? "  # MPM3D-F90's default dtscale" : "") + "\n";
    }
    // One gravity for the scene: the bodies' own, when they agree.
    std::optional<core::Vec3> gravity;
    for (const Body& b : bodies_)
      if (b.gravity) {
        if (gravity && (gravity->x != b.gravity->x || gravity->y != b.gravity->y ||
                        gravity->z != b.gravity->z))
          notes_.push_back(
              {b.at, "load grav",
               "bodies with different gravity: afemp's scene has one; the first is written", true});
        if (!gravity) gravity = b.gravity;
      }
    if (gravity) {
      s += "gravity = " + core::toml_vec3(gravity->x, gravity->y, gravity->z) + "\n";
      for (const Body& b : bodies_)
        if (!b.gravity) {
          notes_.push_back({b.at, "load grav",
                            "gravity acts on every body in afemp, on some bodies in the deck",
                            true});
          break;
        }
    }

    static constexpr std::array<const char*, 6> face_names{"xmin", "xmax", "ymin",
                                                           "ymax", "zmin", "zmax"};
    // A free face lets a particle leave the grid, and MPM3D-F90 skips it from then on
    // (update_step.f90: "out of the computational region"): afemp's outflow face.
    static constexpr std::array<const char*, 3> conditions{"outflow", "fixed", "symmetric"};
    s += "\n[grid]\ncell = " + core::toml_number(cell_) +
         "\nmin = " + core::toml_vec3(span_min_[0], span_min_[1], span_min_[2]) +
         "\nmax = " + core::toml_vec3(span_max_[0], span_max_[1], span_max_[2]) + "\n";
    std::string faces;
    for (int f = 0; f < 6; ++f)
      faces += std::string(faces.empty() ? "" : ", ") + face_names[f] + " = \"" +
               conditions[faces_[f]] + "\"";
    if (!faces.empty()) s += "boundary = { " + faces + " }\n";

    if (contact_ && bodies_.size() > 1 && scheme_ == "USL") {
      notes_.push_back({contact_at_, "contact",
                        "afemp's grid contact needs MUSL or USF (with USL it loses most of the "
                        "energy); the deck's USL is written as MUSL",
                        true});
      scheme_ = "MUSL";
      scheme_set_ = true;
    }
    s += "\n[mpm]\nscheme = \"" + scheme_ + "\"" + (scheme_set_ ? "" : "  # MPM3D's default") +
         "\njaumann = " + (jaumann_ ? "true" : "false") + "\n";
    if (!shape_.empty()) s += "shape_function = \"" + shape_ + "\"\n";

    std::set<long> used;
    for (const Body& b : bodies_) used.insert(b.material);
    for (const auto& [id, m] : materials_) {
      if (used.count(id) == 0) {
        notes_.push_back(
            {m.at, "material",
             "material " + std::to_string(id) + " is used by no particle set and is left out",
             false});
        continue;
      }
      s += "\n[materials.material" + std::to_string(id) + "]  # " + m.type + "\n";
      s += "density = " + core::toml_number(m.density) + "\n";
      if (m.E > 0.0)
        s += "E = " + core::toml_number(m.E) + "\nnu = " + core::toml_number(m.nu) + "\n";
      s += "strength = " + m.strength + "\n";
      if (m.type == "hiex" && !m.jwl)
        throw core::InputError(m.at, "material",
                               "material " + std::to_string(id) +
                                   " (hiex) has no EOS: give it its products' JWL with "
                                   "'seos " +
                                   std::to_string(id) + " 3 A B R1 R2 omega E0'");
      if (m.type == "null" && m.eos.empty())
        throw core::InputError(m.at, "material",
                               "material " + std::to_string(id) +
                                   " (null) has no EOS (MPM3D-F90 stops there too): give it "
                                   "'seos " +
                                   std::to_string(id) + " 4 c'");
      if (!m.eos.empty()) s += "eos = " + m.eos + "\n";
      if (m.jwl) {
        // MPM3D-F90 burns a particle whole once the front from the nearest detonation point
        // reaches it (Constitution.f90's M3DM6): afemp's lighting-time burn, which spreads it
        // over 1.5 cells. The CJ pressure is the JWL's own (it serves the volumetric burn only).
        const double pcj = cj_pressure(*m.jwl);
        const double rho_d2 = m.density * m.detonation_speed * m.detonation_speed;
        if (!(pcj > 0.0 && pcj < rho_d2))
          throw core::InputError(
              m.at, "material",
              "material " + std::to_string(id) + " (hiex): its JWL's Chapman-Jouguet pressure " +
                  core::toml_number(pcj) + " is not between 0 and density D^2 = " +
                  core::toml_number(rho_d2) + ": the JWL constants and D do not belong together");
        s += "burn = { D = " + core::toml_number(m.detonation_speed) +
             ", pcj = " + core::toml_number(pcj) +
             ", mode = \"lighting-time\" }  # pcj: the JWL's Chapman-Jouguet point\n";
        notes_.push_back({m.at, "material",
                          "material " + std::to_string(id) +
                              " (hiex): MPM3D-F90 burns a particle whole when the front reaches "
                              "it; afemp's lighting-time burn spreads that over 1.5 cells",
                          true});
      }
      if (m.specific_heat > 0.0)
        s += "specific_heat = " + core::toml_number(m.specific_heat) + "\n";
      if (m.temperature >= 0.0) s += "temperature = " + core::toml_number(m.temperature) + "\n";
      if (m.failure_strain > 0.0)
        s += "failure = { model = \"plastic-strain\", strain = " +
             core::toml_number(m.failure_strain) + " }\n";
    }

    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const Body& b = bodies_[i];
      const Material& m = materials_.at(b.material);
      const std::string name = "body" + std::to_string(i + 1);
      const std::string file = scene_stem_ + "." + name + ".txt";
      std::string points = "# " + name + " of " + deck_path_ + " (component " +
                           std::to_string(b.component) + "): x y z volume\n";
      char line[128];
      for (const Point& p : b.points) {
        std::snprintf(line, sizeof line, "%.9g %.9g %.9g %.9g\n", p.x.x, p.x.y, p.x.z,
                      p.mass / m.density);
        points += line;
      }
      files.push_back({file, std::move(points)});
      s += "\n[[bodies]]\nname = \"" + name + "\"  # component " + std::to_string(b.component) +
           ", " + std::to_string(b.points.size()) + " particles\nmaterial = \"material" +
           std::to_string(b.material) +
           "\"\nshape = { points = { file = " + core::toml_string(file) + " } }\n";
      if (b.velocity)
        s += "velocity = " + core::toml_vec3(b.velocity->x, b.velocity->y, b.velocity->z) + "\n";
      if (m.e0 != 0.0 && !m.jwl)
        s += "internal_energy = " + core::toml_number(units_(m.e0, dim::stress) / m.density) +
             "  # E0 / density\n";
      if (bulk_)
        s += "bulk_viscosity = { quadratic = " + core::toml_number((*bulk_)[0]) +
             ", linear = " + core::toml_number((*bulk_)[1]) + " }\n";
      // Without `contact` MPM3D maps every body to the grid's one velocity field, so bodies
      // that meet weld: meant, as the overlap check is told.
      if (!contact_ && bodies_.size() > 1) {
        std::string others;
        for (std::size_t j = 0; j < bodies_.size(); ++j)
          if (j != i)
            others +=
                std::string(others.empty() ? "" : ", ") + "\"body" + std::to_string(j + 1) + "\"";
        s += "overlap_allowed = [" + others +
             "]  # one velocity field without contact, as in MPM3D\n";
      }
    }

    if (contact_) {
      if (bodies_.size() < 2)
        notes_.push_back(
            {contact_at_, "contact", "contact with one body has nothing to act on", false});
      for (std::size_t i = 0; i < bodies_.size(); ++i)
        for (std::size_t j = i + 1; j < bodies_.size(); ++j)
          s += "\n[[contact]]\nbodies = [\"body" + std::to_string(i + 1) + "\", \"body" +
               std::to_string(j + 1) + "\"]\nfriction = " + core::toml_number(friction_) + "\n";
    }

    // DataIn.f90's Initial lights each particle at its least distance to a detonation point
    // over D; with none, an explosive never burns.
    bool explosive = false;
    for (long id : used) explosive = explosive || materials_.at(id).jwl.has_value();
    if (explosive && detonations_.empty())
      throw core::InputError({deck_path_, 0}, "deto",
                             "the deck has a hiex material and no detonation point: MPM3D-F90 "
                             "would never light it; give one with 'deto x y z'");
    for (const Detonation& d : detonations_) {
      if (!explosive) {
        notes_.push_back({d.at, "deto",
                          "no particle is of a hiex material: the detonation "
                          "point has nothing to light and is left out",
                          false});
        continue;
      }
      s += "\n[[detonations]]\npoint = " + core::toml_vec3(d.x.x, d.x.y, d.x.z) + "\n";
    }
    return s;
  }

  core::SourceText src_;
  Words words_;
  std::string deck_path_, scene_stem_;
  core::UnitConversion units_;
  core::DeckImportOptions options_;
  std::string key_;
  std::vector<core::DeckNote> notes_;

  std::string title_;
  long nbmp_ = 0, nmat_ = 0, nbbo_ = 0, ppc_ = 0, steps_ = 0, output_steps_ = 0;
  double end_time_ = 0, time_step_ = 0, output_every_ = 0, cell_ = 0;
  double dtscale_ = 0.9;  // MPM3D-F90's default
  core::SourceLocation dtscale_at_{};
  std::array<double, 3> span_min_{}, span_max_{};
  std::array<int, 6> faces_{};
  std::string scheme_ = "USL";  // neither MUSL nor USF: MPM3D updates the stress last
  bool scheme_set_ = false;
  bool jaumann_ = true, contact_ = false;
  std::string shape_;  // "gimp" or "bspline2" (bimp): the shape function written; empty: linear
  double friction_ = 0.0;
  core::SourceLocation contact_at_{};
  std::optional<std::array<double, 2>> bulk_;
  std::map<long, Material> materials_;
  std::vector<Body> bodies_;
  struct Detonation {
    core::Vec3 x;
    core::SourceLocation at;
  };
  std::vector<Detonation> detonations_;
};

}  // namespace

core::DeckImport import_mpm3d_deck(const std::string& text, const std::string& deck_path,
                                   const std::string& scene_path,
                                   const core::DeckImportOptions& options) {
  return Mpm3dImport(text, deck_path, scene_path, options).run();
}

}  // namespace afemp::mpm
