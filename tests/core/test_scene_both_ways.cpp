// One scene, two ways: read from its file by the parser, and built in code from the API's
// default-constructed structs with only the keys the file states set (read here with toml++
// directly, not through the parser). Both must be the same model, field by field, and the one
// built in code must pass the check of scenes built in code (core::check_scene), so that a
// default or a range of the scene file and of the library cannot drift apart (issue 46).
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "afemp/scene.hpp"
#include "core/materials/model_parameters.hpp"
#include "core/scene.hpp"

namespace afemp::core {
namespace {

// ---------------------------------------------------------------------------------------------
// toml++ values as the API's types; a value of another type fails the test.

double num(const toml::node& n, const std::string& key) {
  if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  ADD_FAILURE() << key << ": not a number";
  return 0.0;
}

long integer(const toml::node& n, const std::string& key) {
  if (const auto* i = n.as_integer()) return static_cast<long>(i->get());
  ADD_FAILURE() << key << ": not an integer";
  return 0;
}

std::string str(const toml::node& n, const std::string& key) {
  if (const auto* s = n.as_string()) return s->get();
  ADD_FAILURE() << key << ": not a string";
  return "";
}

bool boolean(const toml::node& n, const std::string& key) {
  if (const auto* b = n.as_boolean()) return b->get();
  ADD_FAILURE() << key << ": not a boolean";
  return false;
}

Vec3 vec(const toml::node& n, const std::string& key) {
  Vec3 v;
  const auto* a = n.as_array();
  if (!a || a->size() != 3) {
    ADD_FAILURE() << key << ": not 3 numbers";
    return v;
  }
  for (int i = 0; i < 3; ++i) v[i] = num(*a->get(static_cast<std::size_t>(i)), key);
  return v;
}

// A string or an array of strings.
std::vector<std::string> strings(const toml::node& n, const std::string& key) {
  if (n.is_string()) return {str(n, key)};
  std::vector<std::string> out;
  if (const auto* a = n.as_array())
    for (const toml::node& e : *a) out.push_back(str(e, key));
  return out;
}

// A number or an array of numbers.
std::vector<double> numbers(const toml::node& n, const std::string& key) {
  if (!n.is_array()) return {num(n, key)};
  std::vector<double> out;
  for (const toml::node& e : *n.as_array()) out.push_back(num(e, key));
  return out;
}

std::vector<std::array<double, 2>> pairs(const toml::node& n, const std::string& key) {
  std::vector<std::array<double, 2>> out;
  for (const toml::node& e : *n.as_array()) {
    const auto* p = e.as_array();
    out.push_back({num(*p->get(0), key), num(*p->get(1), key)});
  }
  return out;
}

const toml::table& table(const toml::node& n, const std::string& key) {
  static const toml::table empty;
  if (const auto* t = n.as_table()) return *t;
  ADD_FAILURE() << key << ": not a table";
  return empty;
}

// The enumerator of E whose scene-file name (to_string) is `name`, among the first `count`.
template <class E>
E named(const std::string& name, int count, const std::string& key, bool ignore_case = false) {
  auto fold = [&](std::string s) {
    if (ignore_case)
      for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  for (int i = 0; i < count; ++i)
    if (fold(to_string(static_cast<E>(i))) == fold(name)) return static_cast<E>(i);
  ADD_FAILURE() << key << ": no value named " << name;
  return static_cast<E>(0);
}

void unknown(const std::string& key) {
  ADD_FAILURE() << key << ": a key this test's builder does not set; teach it the key";
}

// The entries of a table in file order (toml++ sorts them by name).
std::vector<std::pair<std::string, const toml::node*>> in_file_order(const toml::table& t) {
  std::vector<std::pair<std::string, const toml::node*>> out;
  for (auto&& [k, v] : t) out.emplace_back(std::string(k.str()), &v);
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    const auto& sa = a.second->source().begin;
    const auto& sb = b.second->source().begin;
    return sa.line != sb.line ? sa.line < sb.line : sa.column < sb.column;
  });
  return out;
}

// ---------------------------------------------------------------------------------------------
// Material models: a default-constructed model of the named alternative, with the table's keys
// set through the model's own parameter list (its parameters(): the keys and the rules that
// turn a key into a member, e.g. J2's tangent_modulus into its hardening). A key the table
// leaves out keeps the struct's default, not the parser's fallback.

class StatedKeys final : public ParameterVisitor {
 public:
  StatedKeys(const toml::table& t, const MaterialConstants& m, std::string key)
      : table_(t), material_(m), key_(std::move(key)) {}
  void required(std::string_view key, double& value, const Range&) override {
    if (const toml::node* n = table_.get(key)) {
      value = num(*n, key_ + "." + std::string(key));
      read_.emplace_back(key);
    } else {
      ADD_FAILURE() << key_ << "." << key << ": required and missing";
    }
  }
  void optional(std::string_view key, double& value, double, const Range&) override {
    if (const toml::node* n = table_.get(key)) {
      value = num(*n, key_ + "." + std::string(key));
      read_.emplace_back(key);
    }
  }
  void choice(std::string_view key, std::size_t& value, std::span<const std::string_view> allowed,
              std::optional<std::size_t>) override {
    if (const toml::node* n = table_.get(key)) {
      const std::string name = str(*n, key_ + "." + std::string(key));
      const auto it = std::find(allowed.begin(), allowed.end(), name);
      if (it == allowed.end()) ADD_FAILURE() << key_ << "." << key << ": no choice " << name;
      value = static_cast<std::size_t>(it - allowed.begin());
      read_.emplace_back(key);
    }
  }
  void require(bool, std::string_view, const std::string&) override {}
  bool has(std::string_view key) const override { return table_.contains(key); }
  bool reading() const override { return true; }
  const MaterialConstants& material() const override { return material_; }
  void check_every_key_read() const {
    for (auto&& [k, v] : table_)
      if (k.str() != "model" &&
          std::find(read_.begin(), read_.end(), std::string(k.str())) == read_.end())
        unknown(key_ + "." + std::string(k.str()));
  }

 private:
  const toml::table& table_;
  const MaterialConstants& material_;
  std::string key_;
  std::vector<std::string> read_;
};

template <class Variant>
Variant model_from(const toml::table& t, const MaterialConstants& material,
                   const std::string& key) {
  const std::string name = str(*t.get("model"), key + ".model");
  Variant out{};
  bool found = false;
  for_each_alternative<Variant>([&]<class Model>(std::size_t) {
    if constexpr (requires { Model::name; }) {
      if (found || Model::name != name) return;
      Model model{};
      StatedKeys keys(t, material, key);
      visit_parameters(model, keys);
      keys.check_every_key_read();
      out = model;
      found = true;
    }
  });
  EXPECT_TRUE(found) << key << ": no model " << name;
  return out;
}

Material material_from(const std::string& name, const toml::table& t) {
  const std::string key = "materials." + name;
  Material m;
  m.name = name;
  const toml::table *strength = nullptr, *eos = nullptr, *failure = nullptr;
  std::optional<double> shear;
  for (auto&& [k, v] : t) {
    const std::string s(k.str()), at = key + "." + s;
    if (s == "density")
      m.density = num(v, at);
    else if (s == "E")
      m.youngs_modulus = num(v, at);
    else if (s == "nu")
      m.poisson_ratio = num(v, at);
    else if (s == "G")
      shear = num(v, at);
    else if (s == "strength")
      strength = &table(v, at);
    else if (s == "eos")
      eos = &table(v, at);
    else if (s == "failure")
      failure = &table(v, at);
    else if (s == "failure_strain")
      m.failure_strain = num(v, at);
    else if (s == "specific_heat")
      m.thermal.specific_heat = num(v, at);
    else if (s == "taylor_quinney")
      m.thermal.taylor_quinney = num(v, at);
    else if (s == "temperature")
      m.thermal.initial_temperature = num(v, at);
    else if (s == "pressure_cutoff")
      m.pressure_cutoff = num(v, at);
    else if (s == "burn") {
      ProgrammedBurn b;
      for (auto&& [bk, bv] : table(v, at)) {
        const std::string bs(bk.str());
        if (bs == "D")
          b.detonation_velocity = num(bv, at + ".D");
        else if (bs == "pcj")
          b.cj_pressure = num(bv, at + ".pcj");
        else if (bs == "mode") {
          const std::string mode = str(bv, at + ".mode");
          b.lighting_time = mode != "volumetric";
          b.volumetric = mode != "lighting-time";
        } else
          unknown(at + "." + bs);
      }
      m.burn = b;
    } else
      unknown(at);
  }
  // A program that gives G (a strength model with its own pressure law) takes the bulk
  // modulus from that law, as docs/scene-format.md says.
  const auto constants = [&] {
    return MaterialConstants{m.density, m.youngs_modulus, m.bulk_modulus()};
  };
  if (eos) m.eos = model_from<EquationOfState>(*eos, constants(), key + ".eos");
  if (shear)
    std::visit(
        [&](const auto& law) {
          if constexpr (requires { law.elastic_modulus(); })
            m.set_shear_and_bulk_modulus(*shear, law.elastic_modulus());
          else
            ADD_FAILURE() << key << ": G without a pressure law of the strength model";
        },
        m.eos);
  if (eos && shear) m.eos = model_from<EquationOfState>(*eos, constants(), key + ".eos");
  if (strength) m.strength = model_from<StrengthModel>(*strength, constants(), key + ".strength");
  if (failure) m.failure = model_from<FailureModel>(*failure, constants(), key + ".failure");
  return m;
}

// ---------------------------------------------------------------------------------------------
// The scene, table by table.

class Builder {
 public:
  Builder(const toml::table& root, std::string path) : root_(root), path_(std::move(path)) {}

  Scene build() {
    Scene s;
    for (auto&& [k, v] : root_) {
      const std::string key(k.str());
      if (key == "run" || key == "reference" || key == "grid" || key == "mpm" ||
          key == "materials" || key == "bodies")
        continue;  // in the order their references need, below
      if (key != "constraints" && key != "walls" && key != "contact" && key != "detonations" &&
          key != "probes" && key != "absorbing" && key != "phases")
        unknown(key);
    }
    if (const toml::node* g = root_.get("grid")) grid(table(*g, "grid"), s);
    if (const toml::node* m = root_.get("mpm")) mpm(table(*m, "mpm"), s.mpm);
    for (const auto& [name, t] : in_file_order(table(*root_.get("materials"), "materials"))) {
      materials_[name] = static_cast<int>(s.materials.size());
      s.materials.push_back(material_from(name, table(*t, "materials." + name)));
    }
    const toml::array& bodies = *root_.get("bodies")->as_array();
    for (const toml::node& b : bodies) s.bodies.push_back(body_shape_and_keys(table(b, "bodies")));
    for (std::size_t i = 0; i < bodies.size(); ++i)
      body_references(table(*bodies.get(i), "bodies"), s, s.bodies[i]);
    run(table(*root_.get("run"), "run"), s);
    if (const toml::node* m = root_.get("mpm")) splitting_bodies(table(*m, "mpm"), s);
    each("constraints", [&](const toml::table& t) { s.constraints.push_back(constraint(t, s)); });
    each("absorbing", [&](const toml::table& t) { s.absorbing.push_back(absorbing(t, s)); });
    each("walls", [&](const toml::table& t) { s.walls.push_back(wall(t, s)); });
    each("contact", [&](const toml::table& t) { s.contacts.push_back(contact(t, s)); });
    each("detonations", [&](const toml::table& t) { s.detonations.push_back(detonation(t)); });
    if (const toml::node* r = root_.get("reference")) reference(table(*r, "reference"), s);
    each("probes", [&](const toml::table& t) { s.probes.push_back(probe(t, s)); });
    each("phases", [&](const toml::table& t) { s.phases.push_back(phase(t, s)); });
    return s;
  }

 private:
  template <class F>
  void each(const char* key, F f) {
    if (const toml::node* n = root_.get(key))
      for (const toml::node& t : *n->as_array()) f(table(t, key));
  }

  int body_named(const Scene& s, const std::string& name) const {
    for (std::size_t b = 0; b < s.bodies.size(); ++b)
      if (s.bodies[b].name == name) return static_cast<int>(b);
    ADD_FAILURE() << "no body " << name;
    return -1;
  }

  // A file a scene names, as a program gives it: the path relative to the scene's folder.
  std::string beside_scene(const std::string& file) const {
    return (std::filesystem::path(path_).parent_path() / file).lexically_normal().string();
  }

  void run(const toml::table& t, Scene& s) {
    RunSettings& r = s.run;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "run." + key;
      if (key == "title")
        r.title = str(v, at);
      else if (key == "end_time")
        r.end_time = num(v, at);
      else if (key == "time_step_factor")
        r.time_step_factor = num(v, at);
      else if (key == "element_time_step_factor")
        r.element_time_step_factor = num(v, at);
      else if (key == "time_step")
        r.fixed_time_step = num(v, at);
      else if (key == "max_steps")
        r.max_steps = integer(v, at);
      else if (key == "output_every")
        r.output_every = num(v, at);
      else if (key == "history_every")
        r.history_every = integer(v, at);
      else if (key == "history_interval")
        r.history_interval = num(v, at);
      else if (key == "output_times")
        r.output_times = numbers(v, at);
      else if (key == "energy_error_limit")
        r.energy_error_limit = num(v, at);
      else if (key == "output_strain")
        r.output_strain = boolean(v, at);
      else if (key == "gravity")
        r.gravity = vec(v, at);
      else if (key == "units")
        r.units = str(v, at);
      else if (key == "quiet")
        r.quiet = strings(v, at);
      else if (key == "checkpoint_every")
        r.checkpoint_every = num(v, at);
      else if (key == "checkpoint_wall_every")
        r.checkpoint_wall_every = num(v, at);
      else if (key == "checkpoint_keep")
        r.checkpoint_keep = static_cast<int>(integer(v, at));
      else if (key == "reproducible")
        r.reproducible = boolean(v, at);
      else if (key == "terminate") {
        RunSettings::Termination term;
        const toml::table& tt = table(v, at);
        term.body = body_named(s, str(*tt.get("body"), at + ".body"));
        term.travel = num(*tt.get("travel"), at + ".travel");
        r.terminate = term;
      } else
        unknown(at);
    }
  }

  void grid(const toml::table& t, Scene& s) {
    s.has_grid = true;
    GridSettings& g = s.mpm.grid;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "grid." + key;
      if (key == "cell")
        g.cell = num(v, at);
      else if (key == "min")
        g.min = vec(v, at);
      else if (key == "max")
        g.max = vec(v, at);
      else if (key == "boundary") {
        for (auto&& [fk, fv] : table(v, at))
          g.faces[static_cast<std::size_t>(named<Face>(std::string(fk.str()), 6, at))] =
              named<FaceCondition>(str(fv, at), 6, at);
      } else if (key == "far_field") {
        FarField far;
        for (auto&& [fk, fv] : table(v, at)) {
          const std::string f(fk.str());
          if (f == "centre")
            far.centre = vec(fv, at + ".centre");
          else if (f == "pressure")
            far.pressure = num(fv, at + ".pressure");
          else if (f == "stress")
            far.absolute_stress = str(fv, at + ".stress") == "absolute";
          else
            unknown(at + "." + f);
        }
        g.far_field = far;
      } else if (key == "axisymmetric") {
        g.axisymmetric = boolean(v, at);
      } else
        unknown(at);
    }
    if (g.axisymmetric) make_axisymmetric(g);
  }

  void mpm(const toml::table& t, MpmSettings& m) {
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "mpm." + key;
      if (key == "scheme")
        m.scheme = named<UpdateScheme>(str(v, at), 4, at, true);
      else if (key == "shape_function")
        m.shape = named<ShapeFunction>(str(v, at), 2, at);
      else if (key == "transfer")
        m.transfer = named<Transfer>(str(v, at), 2, at);
      else if (key == "flip")
        m.flip = num(v, at);
      else if (key == "jaumann")
        m.jaumann = boolean(v, at);
      else if (key == "splitting") {
        SplittingSettings split;
        for (auto&& [sk, sv] : table(v, at)) {
          const std::string f(sk.str());
          if (f == "alpha")
            split.alpha = num(sv, at + ".alpha");
          else if (f == "max_particles")
            split.max_particles = static_cast<std::size_t>(integer(sv, at + ".max_particles"));
          else if (f == "axes") {
            split.axes = {false, false, false};
            for (const std::string& a : strings(sv, at + ".axes"))
              split.axes[static_cast<std::size_t>(a[0] - 'x')] = true;
          } else if (f != "bodies")  // once the bodies are known
            unknown(at + "." + f);
        }
        m.splitting = split;
      } else
        unknown(at);
    }
  }

  void splitting_bodies(const toml::table& t, Scene& s) {
    if (const toml::node* split = t.get("splitting"))
      if (const toml::node* b = table(*split, "mpm.splitting").get("bodies"))
        for (const std::string& name : strings(*b, "mpm.splitting.bodies"))
          s.mpm.splitting->bodies.push_back(body_named(s, name));
  }

  static Shape shape(const toml::table& t, const std::string& at, const Builder& self) {
    const auto first = t.begin();
    const std::string k(first->first.str());
    const toml::node& node = first->second;
    const toml::table& s = table(node, at + "." + k);
    const auto get = [&](const char* key) -> const toml::node& { return *s.get(key); };
    const auto stated = [&](std::initializer_list<std::string_view> keys) {
      for (auto&& [sk, sv] : s)
        if (std::find(keys.begin(), keys.end(), sk.str()) == keys.end())
          unknown(at + "." + k + "." + std::string(sk.str()));
    };
    if (k == "box") {
      stated({"min", "max"});
      return BoxShape{vec(get("min"), at), vec(get("max"), at)};
    }
    if (k == "cylinder" || k == "cone") {
      stated({"base", "axis", "radius", "length", "nose", "top_radius", "wall"});
      CylinderShape c;
      c.base = vec(get("base"), at);
      if (s.contains("axis")) c.axis = vec(get("axis"), at);
      c.radius = num(get("radius"), at);
      c.length = num(get("length"), at);
      if (s.contains("top_radius")) c.top_radius = num(get("top_radius"), at);
      if (s.contains("wall")) c.wall = num(get("wall"), at);
      if (s.contains("nose")) {
        const toml::table& n = table(get("nose"), at + ".nose");
        c.nose.crh = num(*n.get("crh"), at + ".nose.crh");
        if (n.contains("meplat")) c.nose.meplat = num(*n.get("meplat"), at + ".nose.meplat");
      }
      return c;
    }
    if (k == "sphere") {
      stated({"centre", "radius"});
      return SphereShape{vec(get("centre"), at), num(get("radius"), at)};
    }
    if (k == "points") {
      stated({"file"});
      PointListShape p;
      p.path = self.beside_scene(str(get("file"), at));
      return p;
    }
    if (k == "mesh") {
      stated({"file", "parts", "scale", "translate"});
      MeshFileShape m;
      m.path = self.beside_scene(str(get("file"), at));
      if (s.contains("parts")) m.parts = strings(get("parts"), at);
      if (s.contains("scale")) m.scale = num(get("scale"), at);
      if (s.contains("translate")) m.translate = vec(get("translate"), at);
      return m;
    }
    if (k == "line") {
      stated({"from", "to"});
      return LineShape{vec(get("from"), at), vec(get("to"), at)};
    }
    if (k == "rebar") {
      stated({"min", "max", "normal", "position", "spacing", "diameter", "cover"});
      RebarShape r;
      r.min = vec(get("min"), at);
      r.max = vec(get("max"), at);
      r.normal_axis = str(get("normal"), at)[0] - 'x';
      r.positions = numbers(get("position"), at);
      r.spacing = num(get("spacing"), at);
      r.diameter = num(get("diameter"), at);
      r.cover = num(get("cover"), at);
      return r;
    }
    unknown(at + "." + k);
    return BoxShape{};
  }

  static void mesh(const toml::table& t, const std::string& at, MeshDensity& m) {
    for (auto&& [k, v] : t) {
      const std::string key(k.str());
      if (key == "size")
        m.size = num(v, at);
      else if (key == "divisions")
        for (std::size_t i = 0; i < 3; ++i)
          m.divisions[i] = static_cast<int>(integer(*v.as_array()->get(i), at));
      else if (key == "x" || key == "y" || key == "z")
        m.graded[static_cast<std::size_t>(key[0] - 'x')] = pairs(v, at);
      else if (key == "core")
        m.core = static_cast<int>(integer(v, at));
      else if (key == "ring")
        m.ring = static_cast<int>(integer(v, at));
      else if (key == "axial")
        m.axial = static_cast<int>(integer(v, at));
      else if (key == "sectors")
        m.sectors = static_cast<int>(integer(v, at));
      else if (key == "across")
        m.divisions[0] = static_cast<int>(integer(v, at));
      else if (key == "segments")
        m.segments = static_cast<int>(integer(v, at));
      else
        unknown(at + "." + key);
    }
  }

  // The body's own keys; the bodies it names are resolved once all are known.
  BodySpec body_shape_and_keys(const toml::table& t) {
    BodySpec b;
    b.name = str(*t.get("name"), "bodies.name");
    const std::string pre = "bodies." + b.name;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = pre + "." + key;
      if (key == "name" || key == "outside" || key == "bonded_to" || key == "overlap_allowed")
        continue;
      else if (key == "material")
        b.material = materials_.at(str(v, at));
      else if (key == "discretisation")
        b.discretisation = named<Discretisation>(str(v, at), 3, at);
      else if (key == "shape")
        b.shape = shape(table(v, at), at, *this);
      else if (key == "particles_per_cell")
        b.particles_per_cell = static_cast<int>(integer(v, at));
      else if (key == "layout")
        b.layout = str(v, at) == "shells" ? BodySpec::Layout::shells : BodySpec::Layout::lattice;
      else if (key == "mesh")
        mesh(table(v, at), at, b.mesh);
      else if (key == "element")
        b.element = named<HexFormulation>(str(v, at), 2, at);
      else if (key == "hourglass") {
        for (auto&& [hk, hv] : table(v, at)) {
          if (hk.str() == "form")
            b.hourglass.form = named<HourglassForm>(str(hv, at), 3, at);
          else if (hk.str() == "coefficient")
            b.hourglass.coefficient = num(hv, at);
          else
            unknown(at + "." + std::string(hk.str()));
        }
      } else if (key == "bulk_viscosity") {
        BulkViscositySettings q;
        for (auto&& [qk, qv] : table(v, at)) {
          if (qk.str() == "linear")
            q.linear = num(qv, at);
          else if (qk.str() == "quadratic")
            q.quadratic = num(qv, at);
          else
            unknown(at + "." + std::string(qk.str()));
        }
        b.bulk_viscosity = q;
      } else if (key == "erosion") {
        ErosionSettings e;
        for (auto&& [ek, ev] : table(v, at)) {
          const std::string f(ek.str());
          if (f == "plastic_strain")
            e.plastic_strain = num(ev, at);
          else if (f == "material_failure")
            e.material_failure = boolean(ev, at);
          else if (f == "volume_ratio")
            e.volume_ratio = num(ev, at);
          else if (f == "time_step")
            e.time_step = num(ev, at);
          else
            unknown(at + "." + f);
        }
        b.erosion = e;
      } else if (key == "conversion") {
        ConversionSettings c;
        for (auto&& [ck, cv] : table(v, at)) {
          const std::string f(ck.str());
          if (f == "plastic_strain")
            c.plastic_strain = num(cv, at);
          else if (f == "volumetric_strain")
            c.volumetric_strain = num(cv, at);
          else if (f == "jacobian_ratio")
            c.jacobian_ratio = num(cv, at);
          else if (f == "negative_jacobian")
            c.negative_jacobian = boolean(cv, at);
          else if (f == "time_step_fraction")
            c.time_step_fraction = num(cv, at);
          else if (f == "damage")
            c.damage = num(cv, at);
          else if (f == "points")
            c.points = static_cast<int>(integer(cv, at));
          else
            unknown(at + "." + f);
        }
        b.conversion = c;
      } else if (key == "rigid") {
        if (v.is_boolean()) {
          if (boolean(v, at)) b.rigid = RigidSettings{};
        } else {
          RigidSettings r;
          static const char* dof[6] = {"x", "y", "z", "rx", "ry", "rz"};
          for (const std::string& c : strings(*table(v, at).get("fixed"), at))
            for (std::size_t d = 0; d < 6; ++d)
              if (c == "all" || c == dof[d]) r.fixed[d] = true;
          b.rigid = r;
        }
      } else if (key == "area")
        b.area = num(v, at);
      else if (key == "prestress")
        b.prestress = num(v, at);
      else if (key == "velocity")
        b.velocity = vec(v, at);
      else if (key == "temperature")
        b.temperature = num(v, at);
      else if (key == "internal_energy")
        b.internal_energy = num(v, at);
      else if (key == "pressure")
        b.pressure = num(v, at);
      else if (key == "initial_stress") {
        GeostaticStress g;
        for (auto&& [gk, gv] : table(v, at)) {
          const std::string f(gk.str());
          if (f == "K0")
            g.k0 = num(gv, at + ".K0");
          else if (f == "surface")
            g.surface = num(gv, at + ".surface");
          else if (f != "model")
            unknown(at + "." + f);
        }
        b.initial_stress = g;
      } else
        unknown(at);
    }
    return b;
  }

  void body_references(const toml::table& t, const Scene& s, BodySpec& b) {
    if (const toml::node* n = t.get("outside"))
      for (const std::string& name : strings(*n, "outside"))
        b.outside.push_back(body_named(s, name));
    if (const toml::node* n = t.get("bonded_to")) b.bonded_to = body_named(s, str(*n, "bonded_to"));
    if (const toml::node* n = t.get("overlap_allowed"))
      for (const std::string& name : strings(*n, "overlap_allowed"))
        b.overlap_allowed.push_back(body_named(s, name));
  }

  NodeSelector selector(const toml::table& t, const std::string& at) {
    NodeSelector n;
    for (auto&& [k, v] : t) {
      const std::string key(k.str());
      if (key == "set") {
        n.kind = NodeSelector::Kind::set;
        n.set = str(v, at);
      } else if (key == "box") {
        n.kind = NodeSelector::Kind::box;
        n.min = vec(*table(v, at).get("min"), at);
        n.max = vec(*table(v, at).get("max"), at);
      } else if (key == "plane") {
        n.kind = NodeSelector::Kind::plane;
        for (auto&& [pk, pv] : table(v, at)) {
          if (pk.str() == "point")
            n.point = vec(pv, at);
          else if (pk.str() == "normal")
            n.normal = vec(pv, at);
          else if (pk.str() == "tolerance")
            n.tolerance = num(pv, at);
          else
            unknown(at + ".plane." + std::string(pk.str()));
        }
      } else
        unknown(at + "." + key);
    }
    return n;
  }

  static void components(const toml::node& n, std::array<bool, 3>& c, const std::string& at) {
    for (const std::string& name : strings(n, at)) {
      if (name == "all")
        c = {true, true, true};
      else
        c[static_cast<std::size_t>(name[0] - 'x')] = true;
    }
  }

  ConstraintSpec constraint(const toml::table& t, const Scene& s) {
    ConstraintSpec c;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "constraints." + key;
      if (key == "nodes")
        c.nodes = selector(table(v, at), at);
      else if (key == "body")
        c.body = body_named(s, str(v, at));
      else if (key == "fixed")
        components(v, c.components, at);
      else if (key == "velocity") {
        c.velocity = vec(v, at);
        if (!t.contains("components")) c.components = {true, true, true};
      } else if (key == "components")
        components(v, c.components, at);
      else if (key == "curve")
        c.curve = pairs(v, at);
      else
        unknown(at);
    }
    return c;
  }

  AbsorbingSpec absorbing(const toml::table& t, const Scene& s) {
    AbsorbingSpec a;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "absorbing." + key;
      if (key == "nodes")
        a.nodes = selector(table(v, at), at);
      else if (key == "body")
        a.body = body_named(s, str(v, at));
      else
        unknown(at);
    }
    return a;
  }

  PhaseSpec phase(const toml::table& t, const Scene& s) {
    PhaseSpec p;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "phases." + key;
      if (key == "kind")
        p.kind = named<PhaseKind>(str(v, at), 4, at);
      else if (key == "end_time")
        p.end_time = num(v, at);
      else if (key == "load_steps")
        p.load_steps = static_cast<int>(integer(v, at));
      else if (key == "max_iterations")
        p.max_iterations = static_cast<int>(integer(v, at));
      else if (key == "tolerance")
        p.tolerance = num(v, at);
      else if (key == "gravity")
        p.gravity = vec(v, at);
      else if (key == "bodies")
        for (const std::string& name : strings(v, at)) p.bodies.push_back(body_named(s, name));
      else if (key == "damping_factor")
        p.damping_factor = num(v, at);
      else if (key == "check_every")
        p.check_every = integer(v, at);
      else if (key == "time_step_factor")
        p.relaxation_step_factor = num(v, at);
      else if (key == "time_step")
        p.time_step = num(v, at);
      else if (key == "alpha")
        p.alpha = num(v, at);
      else
        unknown(at);
    }
    return p;
  }

  WallSpec wall(const toml::table& t, const Scene& s) {
    WallSpec w;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "walls." + key;
      if (key == "point")
        w.point = vec(v, at);
      else if (key == "normal")
        w.normal = vec(v, at);
      else if (key == "velocity")
        w.velocity = vec(v, at);
      else if (key == "friction")
        w.friction = num(v, at);
      else if (key == "bodies")
        for (const std::string& name : strings(v, at)) w.bodies.push_back(body_named(s, name));
      else
        unknown(at);
    }
    return w;
  }

  ContactSpec contact(const toml::table& t, const Scene& s) {
    ContactSpec c;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "contact." + key;
      if (key == "bodies") {
        const std::vector<std::string> names = strings(v, at);
        c.bodies = {body_named(s, names.front()), body_named(s, names.back())};
      } else if (key == "method")
        c.method = named<ContactMethod>(str(v, at), 4, at);
      else if (key == "friction")
        c.friction = num(v, at);
      else if (key == "distance_factor")
        c.distance_factor = num(v, at);
      else if (key == "penalty")
        c.penalty = num(v, at);
      else if (key == "name")
        c.name = str(v, at);
      else
        unknown(at);
    }
    // The one default that depends on the pair: meshes meet by penalty contact unless the
    // scene says otherwise (docs/scene-format.md). ContactSpec's own default is grid contact,
    // which check_scene refuses between meshes, so a program is told rather than misled.
    const auto mesh = [&](int b) {
      return s.bodies[static_cast<std::size_t>(b)].discretisation != Discretisation::particles;
    };
    if (!t.contains("method") && mesh(c.bodies[0]) && mesh(c.bodies[1]))
      c.method = ContactMethod::penalty;
    return c;
  }

  DetonationSpec detonation(const toml::table& t) {
    DetonationSpec d;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "detonations." + key;
      if (key == "point")
        d.point = vec(v, at);
      else if (key == "plane") {
        d.kind = DetonationSpec::Kind::plane;
        d.point = vec(*table(v, at).get("point"), at);
        d.normal = vec(*table(v, at).get("normal"), at);
      } else if (key == "line") {
        d.kind = DetonationSpec::Kind::line;
        d.point = vec(*table(v, at).get("from"), at);
        d.end = vec(*table(v, at).get("to"), at);
      } else if (key == "time")
        d.time = num(v, at);
      else if (key == "shadow")
        d.shadow = boolean(v, at);
      else
        unknown(at);
    }
    return d;
  }

  VelocityReference velocity_reference(const toml::table& t, const Scene& s) {
    VelocityReference r;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "reference.velocity." + key;
      if (key == "body")
        r.body = body_named(s, str(v, at));
      else if (key == "component") {
        const std::string c = str(v, at);
        r.component = c == "magnitude" ? -1 : c[0] - 'x';
      } else if (key == "value")
        r.value = num(v, at);
      else if (key == "tolerance")
        r.tolerance = num(v, at);
      else
        unknown(at);
    }
    return r;
  }

  void reference(const toml::table& t, Scene& s) {
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "reference." + key;
      if (key == "taylor") {
        TaylorReference ref;
        for (auto&& [tk, tv] : table(v, at)) {
          const std::string f(tk.str());
          if (f == "L")
            ref.length = num(tv, at);
          else if (f == "D")
            ref.impact_diameter = num(tv, at);
          else if (f == "W")
            ref.bulge_diameter = num(tv, at);
          else if (f == "tolerance")
            ref.tolerance = num(tv, at);
          else
            unknown(at + "." + f);
        }
        s.taylor_reference = ref;
      } else if (key == "velocity") {
        if (v.is_table())
          s.velocity_references.push_back(velocity_reference(table(v, at), s));
        else
          for (const toml::node& e : *v.as_array())
            s.velocity_references.push_back(velocity_reference(table(e, at), s));
      } else if (key == "energy")
        s.energy_tolerance = num(*table(v, at).get("tolerance"), at);
      else
        unknown(at);
    }
  }

  ProbeSpec probe(const toml::table& t, const Scene& s) {
    ProbeSpec p;
    for (auto&& [k, v] : t) {
      const std::string key(k.str()), at = "probes." + key;
      if (key == "name")
        p.name = str(v, at);
      else if (key == "interval")
        p.interval = num(v, at);
      else if (key == "mean_velocity") {
        p.kind = ProbeKind::mean_velocity;
        p.body = body_named(s, str(v, at));
      } else if (key == "force") {
        p.kind = ProbeKind::force;
        p.target = str(v, at);
      } else if (key == "extreme") {
        p.kind = ProbeKind::extreme;
        for (auto&& [ek, ev] : table(v, at)) {
          const std::string f(ek.str());
          if (f == "field")
            p.field = named<ProbeField>(str(ev, at), 10, at);
          else if (f == "of")
            p.maximum = str(ev, at) == "max";
          else if (f == "body")
            p.body = body_named(s, str(ev, at));
          else if (f == "box") {
            p.box_min = vec(*table(ev, at).get("min"), at);
            p.box_max = vec(*table(ev, at).get("max"), at);
          } else
            unknown(at + "." + f);
        }
      } else if (key == "particle" || key == "node" || key == "element") {
        p.kind = named<ProbeKind>(key, 3, at);
        for (auto&& [pk, pv] : table(v, at)) {
          const std::string f(pk.str());
          if (f == "body")
            p.body = body_named(s, str(pv, at));
          else if (f == "index")
            p.index = integer(pv, at);
          else if (f == "near")
            p.near = vec(pv, at);
          else
            unknown(at + "." + f);
        }
      } else
        unknown(at);
    }
    return p;
  }

  const toml::table& root_;
  std::string path_;
  std::map<std::string, int> materials_;
};

// ---------------------------------------------------------------------------------------------
// Field-by-field comparison. Where an object sits in the file (where, material_where,
// grid_where, the probe's key) and the file's text and path are not the model, and not
// compared.

#define SAME(field) EXPECT_EQ(a.field, b.field) << at << "." #field

void same_vec(const Vec3& a, const Vec3& b, const std::string& at) {
  EXPECT_EQ(a.x, b.x) << at << ".x";
  EXPECT_EQ(a.y, b.y) << at << ".y";
  EXPECT_EQ(a.z, b.z) << at << ".z";
}

// A model's parameters, by key, as its parameters() lists them (and its reference density).
class Recorded final : public ParameterVisitor {
 public:
  explicit Recorded(const MaterialConstants& m) : material_(m) {}
  void required(std::string_view key, double& value, const Range&) override {
    values.emplace_back(key, value);
  }
  void optional(std::string_view key, double& value, double, const Range&) override {
    values.emplace_back(key, value);
  }
  void choice(std::string_view key, std::size_t& value, std::span<const std::string_view>,
              std::optional<std::size_t>) override {
    values.emplace_back(key, static_cast<double>(value));
  }
  void require(bool, std::string_view, const std::string&) override {}
  bool has(std::string_view) const override { return true; }
  bool reading() const override { return false; }
  const MaterialConstants& material() const override { return material_; }
  std::vector<std::pair<std::string, double>> values;

 private:
  const MaterialConstants& material_;
};

template <class Variant>
void same_model(const Variant& a, const Variant& b, const MaterialConstants& m,
                const std::string& at) {
  ASSERT_EQ(a.index(), b.index()) << at << ": " << model_name(a) << " against " << model_name(b);
  std::visit(
      [&](const auto& ma) {
        using M = std::decay_t<decltype(ma)>;
        M ca = ma, cb = std::get<M>(b);
        Recorded ra(m), rb(m);
        visit_parameters(ca, ra);
        visit_parameters(cb, rb);
        EXPECT_EQ(ra.values, rb.values) << at << " (" << model_name(a) << ")";
        if constexpr (requires { ca.rho0; }) {
          EXPECT_EQ(ca.rho0, cb.rho0) << at << ".rho0";
        }
      },
      a);
}

void same_material(const Material& a, const Material& b, const std::string& at) {
  SAME(name);
  SAME(density);
  SAME(youngs_modulus);
  SAME(poisson_ratio);
  SAME(thermal.specific_heat);
  SAME(thermal.taylor_quinney);
  SAME(thermal.initial_temperature);
  SAME(failure_strain);
  SAME(pressure_cutoff);
  ASSERT_EQ(a.burn.has_value(), b.burn.has_value()) << at << ".burn";
  if (a.burn) {
    SAME(burn->detonation_velocity);
    SAME(burn->cj_pressure);
    SAME(burn->lighting_time);
    SAME(burn->volumetric);
  }
  const MaterialConstants m{a.density, a.youngs_modulus, a.bulk_modulus()};
  same_model(a.strength, b.strength, m, at + ".strength");
  same_model(a.eos, b.eos, m, at + ".eos");
  same_model(a.failure, b.failure, m, at + ".failure");
}

void same_shape(const Shape& sa, const Shape& sb, const std::string& at) {
  ASSERT_EQ(sa.index(), sb.index()) << at;
  if (const auto* box = std::get_if<BoxShape>(&sa)) {
    const auto& a = *box;
    const auto& b = std::get<BoxShape>(sb);
    same_vec(a.min, b.min, at + ".min");
    same_vec(a.max, b.max, at + ".max");
  } else if (const auto* cyl = std::get_if<CylinderShape>(&sa)) {
    const auto& a = *cyl;
    const auto& b = std::get<CylinderShape>(sb);
    same_vec(a.base, b.base, at + ".base");
    same_vec(a.axis, b.axis, at + ".axis");
    EXPECT_EQ(a.radius, b.radius) << at;
    EXPECT_EQ(a.length, b.length) << at;
    EXPECT_EQ(a.nose.crh, b.nose.crh) << at;
    EXPECT_EQ(a.nose.meplat, b.nose.meplat) << at;
    EXPECT_EQ(a.top_radius, b.top_radius) << at;
    EXPECT_EQ(a.wall, b.wall) << at;
  } else if (const auto* sphere = std::get_if<SphereShape>(&sa)) {
    const auto& a = *sphere;
    const auto& b = std::get<SphereShape>(sb);
    same_vec(a.centre, b.centre, at + ".centre");
    EXPECT_EQ(a.radius, b.radius) << at;
  } else if (const auto* points = std::get_if<PointListShape>(&sa)) {
    EXPECT_EQ(points->path, std::get<PointListShape>(sb).path) << at;
  } else if (const auto* mesh = std::get_if<MeshFileShape>(&sa)) {
    const auto& a = *mesh;
    const auto& b = std::get<MeshFileShape>(sb);
    EXPECT_EQ(a.path, b.path) << at;
    EXPECT_EQ(a.parts, b.parts) << at;
    EXPECT_EQ(a.scale, b.scale) << at;
    same_vec(a.translate, b.translate, at + ".translate");
  } else if (const auto* line = std::get_if<LineShape>(&sa)) {
    const auto& a = *line;
    const auto& b = std::get<LineShape>(sb);
    same_vec(a.from, b.from, at + ".from");
    same_vec(a.to, b.to, at + ".to");
  } else if (const auto* rebar = std::get_if<RebarShape>(&sa)) {
    const auto& a = *rebar;
    const auto& b = std::get<RebarShape>(sb);
    same_vec(a.min, b.min, at + ".min");
    same_vec(a.max, b.max, at + ".max");
    EXPECT_EQ(a.normal_axis, b.normal_axis) << at;
    EXPECT_EQ(a.positions, b.positions) << at;
    EXPECT_EQ(a.spacing, b.spacing) << at;
    EXPECT_EQ(a.diameter, b.diameter) << at;
    EXPECT_EQ(a.cover, b.cover) << at;
  }
}

void same_body(const BodySpec& a, const BodySpec& b, const std::string& at) {
  SAME(name);
  SAME(material);
  SAME(discretisation);
  same_shape(a.shape, b.shape, at + ".shape");
  SAME(particles_per_cell);
  SAME(layout);
  SAME(mesh.divisions);
  SAME(mesh.core);
  SAME(mesh.ring);
  SAME(mesh.axial);
  SAME(mesh.sectors);
  SAME(mesh.segments);
  SAME(mesh.size);
  SAME(mesh.graded);
  SAME(element);
  SAME(hourglass.form);
  SAME(hourglass.coefficient);
  ASSERT_EQ(a.bulk_viscosity.has_value(), b.bulk_viscosity.has_value()) << at;
  if (a.bulk_viscosity) {
    SAME(bulk_viscosity->linear);
    SAME(bulk_viscosity->quadratic);
  }
  ASSERT_EQ(a.erosion.has_value(), b.erosion.has_value()) << at;
  if (a.erosion) {
    SAME(erosion->plastic_strain);
    SAME(erosion->material_failure);
    SAME(erosion->volume_ratio);
    SAME(erosion->time_step);
  }
  ASSERT_EQ(a.conversion.has_value(), b.conversion.has_value()) << at;
  if (a.conversion) {
    SAME(conversion->plastic_strain);
    SAME(conversion->volumetric_strain);
    SAME(conversion->jacobian_ratio);
    SAME(conversion->negative_jacobian);
    SAME(conversion->time_step_fraction);
    SAME(conversion->damage);
    SAME(conversion->points);
  }
  ASSERT_EQ(a.rigid.has_value(), b.rigid.has_value()) << at;
  if (a.rigid) {
    SAME(rigid->fixed);
  }
  SAME(area);
  SAME(prestress);
  SAME(bonded_to);
  SAME(outside);
  SAME(overlap_allowed);
  same_vec(a.velocity, b.velocity, at + ".velocity");
  SAME(temperature);
  SAME(internal_energy);
  SAME(pressure);
  ASSERT_EQ(a.initial_stress.has_value(), b.initial_stress.has_value()) << at;
  if (a.initial_stress) {
    SAME(initial_stress->surface);
    SAME(initial_stress->k0);
  }
}

void same_selector(const NodeSelector& a, const NodeSelector& b, const std::string& at) {
  SAME(kind);
  same_vec(a.min, b.min, at + ".min");
  same_vec(a.max, b.max, at + ".max");
  same_vec(a.point, b.point, at + ".point");
  same_vec(a.normal, b.normal, at + ".normal");
  SAME(tolerance);
  SAME(set);
}

void same_scene(const Scene& a, const Scene& b) {
  {
    const std::string at = "run";
    SAME(run.title);
    SAME(run.end_time);
    SAME(run.time_step_factor);
    SAME(run.element_time_step_factor);
    SAME(run.fixed_time_step);
    SAME(run.max_steps);
    SAME(run.output_every);
    SAME(run.history_every);
    SAME(run.history_interval);
    SAME(run.output_times);
    SAME(run.energy_error_limit);
    SAME(run.output_strain);
    same_vec(a.run.gravity, b.run.gravity, "run.gravity");
    ASSERT_EQ(a.run.terminate.has_value(), b.run.terminate.has_value());
    if (a.run.terminate) {
      SAME(run.terminate->body);
      SAME(run.terminate->travel);
    }
    SAME(run.units);
    SAME(run.quiet);
    SAME(run.checkpoint_every);
    SAME(run.checkpoint_wall_every);
    SAME(run.checkpoint_keep);
    SAME(run.reproducible);
  }
  {
    const std::string at = "grid, mpm";
    SAME(has_grid);
    SAME(mpm.scheme);
    SAME(mpm.shape);
    SAME(mpm.transfer);
    SAME(mpm.flip);
    SAME(mpm.jaumann);
    ASSERT_EQ(a.mpm.splitting.has_value(), b.mpm.splitting.has_value());
    if (a.mpm.splitting) {
      SAME(mpm.splitting->alpha);
      SAME(mpm.splitting->max_particles);
      SAME(mpm.splitting->bodies);
      SAME(mpm.splitting->axes);
    }
    SAME(mpm.grid.cell);
    same_vec(a.mpm.grid.min, b.mpm.grid.min, "grid.min");
    same_vec(a.mpm.grid.max, b.mpm.grid.max, "grid.max");
    SAME(mpm.grid.faces);
    SAME(mpm.grid.axisymmetric);
    ASSERT_EQ(a.mpm.grid.far_field.has_value(), b.mpm.grid.far_field.has_value());
    if (a.mpm.grid.far_field) {
      same_vec(a.mpm.grid.far_field->centre, b.mpm.grid.far_field->centre, "far_field.centre");
      SAME(mpm.grid.far_field->pressure);
      SAME(mpm.grid.far_field->absolute_stress);
    }
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t m = 0; m < a.materials.size(); ++m)
    same_material(a.materials[m], b.materials[m], "materials." + a.materials[m].name);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i)
    same_body(a.bodies[i], b.bodies[i], "bodies." + a.bodies[i].name);
  ASSERT_EQ(a.constraints.size(), b.constraints.size());
  for (std::size_t k = 0; k < a.constraints.size(); ++k) {
    const ConstraintSpec &ca = a.constraints[k], &cb = b.constraints[k];
    const std::string at = "constraints[" + std::to_string(k) + "]";
    same_selector(ca.nodes, cb.nodes, at + ".nodes");
    EXPECT_EQ(ca.body, cb.body) << at;
    EXPECT_EQ(ca.components, cb.components) << at;
    same_vec(ca.velocity, cb.velocity, at + ".velocity");
    EXPECT_EQ(ca.curve, cb.curve) << at;
  }
  ASSERT_EQ(a.absorbing.size(), b.absorbing.size());
  for (std::size_t k = 0; k < a.absorbing.size(); ++k) {
    const std::string at = "absorbing[" + std::to_string(k) + "]";
    same_selector(a.absorbing[k].nodes, b.absorbing[k].nodes, at);
    EXPECT_EQ(a.absorbing[k].body, b.absorbing[k].body) << at;
  }
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t k = 0; k < a.walls.size(); ++k) {
    const WallSpec &wa = a.walls[k], &wb = b.walls[k];
    const std::string at = "walls[" + std::to_string(k) + "]";
    same_vec(wa.point, wb.point, at + ".point");
    same_vec(wa.normal, wb.normal, at + ".normal");
    same_vec(wa.velocity, wb.velocity, at + ".velocity");
    EXPECT_EQ(wa.friction, wb.friction) << at;
    EXPECT_EQ(wa.bodies, wb.bodies) << at;
  }
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  for (std::size_t k = 0; k < a.contacts.size(); ++k) {
    const ContactSpec &ca = a.contacts[k], &cb = b.contacts[k];
    const std::string at = "contact[" + std::to_string(k) + "]";
    EXPECT_EQ(ca.bodies, cb.bodies) << at;
    EXPECT_EQ(ca.method, cb.method) << at;
    EXPECT_EQ(ca.friction, cb.friction) << at;
    EXPECT_EQ(ca.distance_factor, cb.distance_factor) << at;
    EXPECT_EQ(ca.penalty, cb.penalty) << at;
    EXPECT_EQ(ca.name, cb.name) << at;
  }
  ASSERT_EQ(a.detonations.size(), b.detonations.size());
  for (std::size_t k = 0; k < a.detonations.size(); ++k) {
    const DetonationSpec &da = a.detonations[k], &db = b.detonations[k];
    const std::string at = "detonations[" + std::to_string(k) + "]";
    EXPECT_EQ(da.kind, db.kind) << at;
    same_vec(da.point, db.point, at + ".point");
    same_vec(da.normal, db.normal, at + ".normal");
    same_vec(da.end, db.end, at + ".end");
    EXPECT_EQ(da.time, db.time) << at;
    EXPECT_EQ(da.shadow, db.shadow) << at;
  }
  {
    const std::string at = "reference";
    ASSERT_EQ(a.taylor_reference.has_value(), b.taylor_reference.has_value());
    if (a.taylor_reference) {
      SAME(taylor_reference->length);
      SAME(taylor_reference->impact_diameter);
      SAME(taylor_reference->bulge_diameter);
      SAME(taylor_reference->tolerance);
    }
    SAME(energy_tolerance);
    ASSERT_EQ(a.velocity_references.size(), b.velocity_references.size());
    for (std::size_t k = 0; k < a.velocity_references.size(); ++k) {
      SAME(velocity_references[k].body);
      SAME(velocity_references[k].component);
      SAME(velocity_references[k].value);
      SAME(velocity_references[k].tolerance);
    }
  }
  ASSERT_EQ(a.phases.size(), b.phases.size());
  for (std::size_t k = 0; k < a.phases.size(); ++k) {
    const std::string at = "phases[" + std::to_string(k) + "]";
    SAME(phases[k].kind);
    SAME(phases[k].end_time);
    SAME(phases[k].load_steps);
    SAME(phases[k].max_iterations);
    SAME(phases[k].tolerance);
    ASSERT_EQ(a.phases[k].gravity.has_value(), b.phases[k].gravity.has_value()) << at;
    if (a.phases[k].gravity) same_vec(*a.phases[k].gravity, *b.phases[k].gravity, at + ".gravity");
    SAME(phases[k].bodies);
    SAME(phases[k].damping_factor);
    SAME(phases[k].check_every);
    SAME(phases[k].relaxation_step_factor);
    SAME(phases[k].time_step);
    SAME(phases[k].alpha);
  }
  ASSERT_EQ(a.probes.size(), b.probes.size());
  for (std::size_t k = 0; k < a.probes.size(); ++k) {
    const ProbeSpec &pa = a.probes[k], &pb = b.probes[k];
    const std::string at = "probes." + pa.name;
    EXPECT_EQ(pa.name, pb.name) << at;
    EXPECT_EQ(pa.kind, pb.kind) << at;
    EXPECT_EQ(pa.body, pb.body) << at;
    EXPECT_EQ(pa.index, pb.index) << at;
    same_vec(pa.near, pb.near, at + ".near");
    EXPECT_EQ(pa.field, pb.field) << at;
    EXPECT_EQ(pa.target, pb.target) << at;
    EXPECT_EQ(pa.maximum, pb.maximum) << at;
    same_vec(pa.box_min, pb.box_min, at + ".box_min");
    same_vec(pa.box_max, pb.box_max, at + ".box_max");
    EXPECT_EQ(pa.interval, pb.interval) << at;
  }
}

#undef SAME

// The scene of `text` both ways: parsed, and built in code, checked as Simulation checks it.
void expect_same_both_ways(const std::string& text, const std::string& path) {
  SCOPED_TRACE(path);
  const Scene parsed = parse_scene(text, path);
  Scene built = Builder(toml::parse(text, path), path).build();
  EXPECT_NO_THROW(check_scene(built));
  same_scene(parsed, built);
}

std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Reference: every example scene (examples/*/*.toml) is the same model built in code from the
// API's defaults and the keys its file states.
TEST(SceneBothWays, EveryExampleBuiltInCodeIsTheModelItsFileReads) {
  std::vector<std::filesystem::path> scenes;
  for (const auto& folder :
       std::filesystem::directory_iterator(std::string(AFEMP_SOURCE_DIR) + "/examples"))
    if (folder.is_directory())
      for (const auto& f : std::filesystem::directory_iterator(folder.path()))
        if (f.path().extension() == ".toml") scenes.push_back(f.path());
  std::sort(scenes.begin(), scenes.end());
  ASSERT_GE(scenes.size(), 16u);
  for (const std::filesystem::path& p : scenes) expect_same_both_ways(file_text(p), p.string());
}

// Reference: tables given with few or none of their keys, which the examples do not show, are
// the same model both ways: an FE scene (hourglass forms without their coefficient, erosion,
// bulk viscosity and contact without keys, a truss line, a plane without its tolerance) and a
// particle scene (splitting and a far field without their keys, a cone).
// Reference: [[phases]] (a static phase with and without its keys, a relaxation phase, the
// last phase's end left to [run]) and a prestressed tendon are the same model both ways.
TEST(SceneBothWays, PhasesAndPrestressAreTheSameModelBothWays) {
  const std::string base =
      "[run]\nend_time = 2\ngravity = [0, 0, -9.81e-3]\n"
      "[materials.steel]\ndensity = 7.85e-3\nE = 2.0e5\nnu = 0.3\n"
      "[[bodies]]\nname = \"beam\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "element = \"full\"\nshape = { box = { min = [0, 0, 0], max = [1, 1, 4] } }\n"
      "mesh = { size = 1 }\n"
      "[[bodies]]\nname = \"tendon\"\ndiscretisation = \"trusses\"\nmaterial = \"steel\"\n"
      "shape = { line = { from = [0, 0, 5], to = [0, 0, 9] } }\nmesh = { segments = 4 }\n"
      "area = 0.1\nprestress = 500\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
      "fixed = [\"all\"]\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 5], normal = [0, 0, 1] } }\n"
      "fixed = [\"all\"]\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 9], normal = [0, 0, 1] } }\n"
      "fixed = [\"all\"]\n";
  expect_same_both_ways(base +
                            "[[phases]]\nkind = \"static\"\nend_time = 1\nbodies = [\"beam\"]\n"
                            "[[phases]]\nkind = \"explicit\"\n",
                        "static_defaults.toml");
  expect_same_both_ways(base +
                            "[[phases]]\nkind = \"static\"\nend_time = 1\nbodies = [\"beam\"]\n"
                            "load_steps = 4\nmax_iterations = 12\ntolerance = 1e-9\n"
                            "gravity = [0, 0, -1]\n"
                            "[[phases]]\nkind = \"explicit\"\nend_time = 2\n",
                        "static_keys.toml");
  expect_same_both_ways(base +
                            "[[phases]]\nkind = \"relaxation\"\nend_time = 1\n"
                            "[[phases]]\nkind = \"explicit\"\n",
                        "relaxation_defaults.toml");
  expect_same_both_ways(base +
                            "[[phases]]\nkind = \"relaxation\"\nend_time = 1\ntolerance = 1e-4\n"
                            "damping_factor = 0.99\ncheck_every = 100\ntime_step_factor = 0.5\n"
                            "[[phases]]\nkind = \"explicit\"\n",
                        "relaxation_keys.toml");
  expect_same_both_ways(base +
                            "[[phases]]\nkind = \"implicit\"\nend_time = 1\ntime_step = 0.1\n"
                            "bodies = [\"beam\"]\n[[phases]]\nkind = \"explicit\"\n",
                        "implicit_defaults.toml");
  expect_same_both_ways(base +
                            "[[phases]]\nkind = \"implicit\"\nend_time = 1\ntime_step = 0.1\n"
                            "alpha = -0.1\nmax_iterations = 12\ntolerance = 1e-9\n"
                            "gravity = [0, 0, -1]\nbodies = [\"beam\"]\n"
                            "[[phases]]\nkind = \"explicit\"\n",
                        "implicit_keys.toml");
}

TEST(SceneBothWays, TablesLeftAtTheirDefaultsAreTheSameModelBothWays) {
  const std::string steel =
      "[materials.steel]\ndensity = 7.85e-3\nE = 2.0e5\nnu = 0.3\n"
      "strength = { model = \"johnson-cook\", A = 350, B = 275, n = 0.36 }\n";
  expect_same_both_ways(
      "[run]\nend_time = 0.01\n" + steel +
          "[[bodies]]\nname = \"stiff\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
          "shape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }\nmesh = { size = 0.5 }\n"
          "hourglass = { form = \"stiffness\" }\nerosion = { plastic_strain = 2 }\n"
          "bulk_viscosity = {}\n"
          "[[bodies]]\nname = \"bending\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
          "shape = { box = { min = [0, 0, 2], max = [1, 1, 3] } }\nmesh = { size = 0.5 }\n"
          "hourglass = { form = \"assumed_strain\" }\nerosion = {}\n"
          "[[bodies]]\nname = \"bar\"\ndiscretisation = \"trusses\"\nmaterial = \"steel\"\n"
          "shape = { line = { from = [0, 0, 4], to = [1, 0, 4] } }\nmesh = { segments = 2 }\n"
          "area = 0.1\n"
          "[[contact]]\nbodies = [\"stiff\", \"bending\"]\n"
          "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
          "fixed = [\"z\"]\n[[walls]]\npoint = [0, 0, -1]\nnormal = [0, 0, 1]\n",
      "defaults_fe.toml");
  expect_same_both_ways(
      "[run]\nend_time = 0.01\n[grid]\ncell = 0.5\nmin = [0, 0, 0]\nmax = [4, 4, 4]\n"
      "boundary = { xmax = \"absorbing\" }\nfar_field = { centre = [0, 0, 0] }\n"
      "[mpm]\nsplitting = {}\n" +
          steel +
          "[[bodies]]\nname = \"cone\"\nmaterial = \"steel\"\n"
          "shape = { cone = { base = [2, 2, 1], radius = 1, top_radius = 0, length = 2 } }\n",
      "defaults_mpm.toml");
}

// Reference: every table of a scene built in code passes the check as default-constructed,
// with only its required fields set (issue 46: a table's defaults are the scene file's, and the
// file accepts a table without its optional keys): the run, the grid, splitting, a body of
// each discretisation with its hourglass, bulk viscosity, erosion, conversion and rigid
// settings, contacts, a wall and a constraint; and a far field.
TEST(SceneCheck, DefaultConstructedTablesPassTheCheck) {
  Scene s;
  s.run.end_time = 1.0;
  s.has_grid = true;
  s.mpm.grid.cell = 1.0;
  s.mpm.grid.max = {8, 8, 8};
  s.mpm.splitting = SplittingSettings{};
  Material steel;
  steel.name = "steel";
  steel.density = 7.85e-3;
  steel.youngs_modulus = 2.0e5;
  steel.poisson_ratio = 0.3;
  s.materials = {steel};
  const auto body = [&](const char* name, Discretisation d, Shape shape) {
    BodySpec b;
    b.name = name;
    b.material = 0;
    b.discretisation = d;
    b.shape = std::move(shape);
    b.mesh.size = 1.0;
    s.bodies.push_back(b);
    return &s.bodies.back();
  };
  body("ball", Discretisation::particles, SphereShape{{4, 4, 6}, 1.0})->bulk_viscosity =
      BulkViscositySettings{};
  {
    BodySpec* plate = body("plate", Discretisation::hexahedra, BoxShape{{1, 1, 2}, {7, 7, 3}});
    plate->hourglass = HourglassSettings{};
    plate->bulk_viscosity = BulkViscositySettings{};
    plate->erosion = ErosionSettings{};
  }
  body("block", Discretisation::hexahedra, BoxShape{{1, 1, 0}, {2, 2, 1}})->conversion =
      ConversionSettings{};
  body("anvil", Discretisation::hexahedra, BoxShape{{5, 5, 0}, {6, 6, 1}})->rigid = RigidSettings{};
  body("bar", Discretisation::trusses, LineShape{{0, 0, 4}, {1, 0, 4}})->area = 1.0;
  ContactSpec grid;
  grid.bodies = {0, 1};
  ContactSpec penalty;
  penalty.bodies = {1, 3};
  penalty.method = ContactMethod::penalty;
  s.contacts = {grid, penalty};
  WallSpec wall;
  wall.normal = {0, 0, 1};
  s.walls = {wall};
  ConstraintSpec held;
  held.components = {true, true, true};
  s.constraints = {held};
  EXPECT_NO_THROW(check_scene(s));

  Scene fluid;
  fluid.run.end_time = 1.0;
  fluid.has_grid = true;
  fluid.mpm.grid = s.mpm.grid;
  fluid.mpm.grid.faces[1] = FaceCondition::absorbing;
  fluid.mpm.grid.far_field = FarField{};
  fluid.materials = {steel};
  fluid.bodies = {s.bodies.front()};
  EXPECT_NO_THROW(check_scene(fluid));
}

}  // namespace
}  // namespace afemp::core
