// Node and element probes (fem/mesh_probes.hpp).
#include "fem/mesh_probes.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

namespace afemp::fem {

namespace {

// Hexahedra or trusses: what the body's elements are.
const ElementStore& elements_of(const FeSolver& fe, const core::Scene& scene, int body) {
  if (scene.bodies[static_cast<std::size_t>(body)].discretisation == core::Discretisation::trusses)
    return fe.trusses();
  return fe.hexahedra();
}

// Centroid, mean nodal velocity, point-averaged stress and plastic strain of element e.
struct ElementState {
  core::Vec3 centroid, velocity;
  core::SymTensor stress;
  double plastic_strain = 0.0;
};
template <class Elements>
ElementState element_state(const FeSolver& fe, const Elements& el, const ElementBatch& b,
                           std::size_t e) {
  ElementState s;
  constexpr int corners = Elements::corners;
  const double wn = 1.0 / corners;
  for (int a = 0; a < corners; ++a) {
    const auto n = static_cast<std::size_t>(el.nodes[e][static_cast<std::size_t>(a)]);
    s.centroid += wn * fe.nodes().position[n];
    s.velocity += wn * fe.nodes().velocity[n];
  }
  const std::size_t p0 =
      b.point_begin + (e - b.begin) * static_cast<std::size_t>(b.points_per_element);
  const double wp = 1.0 / b.points_per_element;
  for (int g = 0; g < b.points_per_element; ++g) {
    s.stress += wp * el.stress[p0 + static_cast<std::size_t>(g)];
    s.plastic_strain += wp * el.plastic_strain[p0 + static_cast<std::size_t>(g)];
  }
  return s;
}

const ElementBatch* body_batch(const ElementStore& el, int body) {
  for (const ElementBatch& b : el.batches)
    if (b.body == body) return &b;
  return nullptr;
}

}  // namespace

void MeshProbes::resolve(std::span<const core::ProbeSpec> probes, const FeSolver& fe,
                         const core::Scene& scene) {
  specs_.assign(probes.begin(), probes.end());
  target_.assign(probes.size(), 0);
  const FeNodes& nodes = fe.nodes();
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    const core::ProbeSpec& s = specs_[k];
    if (s.kind != core::ProbeKind::node && s.kind != core::ProbeKind::element) continue;
    const std::string& name = scene.bodies[static_cast<std::size_t>(s.body)].name;
    const bool node = s.kind == core::ProbeKind::node;
    const bool truss = scene.bodies[static_cast<std::size_t>(s.body)].discretisation ==
                       core::Discretisation::trusses;
    const std::string what = node ? "node" : (truss ? "truss" : "hexahedron");
    // The body's range: its nodes are contiguous (fe_model_builder.cpp), so are its elements.
    std::size_t begin = 0, count = 0;
    const ElementStore& el = elements_of(fe, scene, s.body);
    const ElementBatch* batch = body_batch(el, s.body);
    if (node) {
      const auto first = std::find(nodes.body.begin(), nodes.body.end(), s.body);
      begin = static_cast<std::size_t>(first - nodes.body.begin());
      count = static_cast<std::size_t>(std::count(nodes.body.begin(), nodes.body.end(), s.body));
    } else if (batch != nullptr) {
      begin = batch->begin;
      count = batch->end - batch->begin;
    }
    const std::string key = s.key + (node ? ".node" : ".element");
    if (count == 0)
      throw core::InputError(s.where, key + ".body",
                             "body '" + name + "' has no " + what + "s to probe");
    if (s.index >= 0) {
      if (static_cast<std::size_t>(s.index) >= count)
        throw core::InputError(s.where, key + ".index",
                               what + " " + std::to_string(s.index) + " of body '" + name +
                                   "' does not exist; its " + (node ? "nodes" : "elements") +
                                   " are 0.." + std::to_string(count - 1));
      target_[k] = begin + static_cast<std::size_t>(s.index);
      continue;
    }
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = begin; i < begin + count; ++i) {
      const core::Vec3 x = node    ? nodes.position[i]
                           : truss ? element_state(fe, fe.trusses(), *batch, i).centroid
                                   : element_state(fe, fe.hexahedra(), *batch, i).centroid;
      const double d = core::norm(x - s.near);
      if (d < best) best = d, target_[k] = i;
    }
  }
}

bool MeshProbes::reads_elements() const {
  return std::any_of(specs_.begin(), specs_.end(), [](const core::ProbeSpec& s) {
    return s.kind == core::ProbeKind::element || s.kind == core::ProbeKind::extreme;
  });
}

void MeshProbes::sample(const FeSolver& fe, std::span<double> out) const {
  const FeNodes& nodes = fe.nodes();
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    const core::ProbeSpec& s = specs_[k];
    double* v = out.data() + k * core::probe_stride;
    if (s.kind == core::ProbeKind::node) {
      const core::Vec3 &x = nodes.position[target_[k]], &u = nodes.velocity[target_[k]];
      const double row[] = {x.x, x.y, x.z, u.x, u.y, u.z};
      std::copy(std::begin(row), std::end(row), v);
    } else if (s.kind == core::ProbeKind::element) {
      auto sample_element = [&](const auto& el) {
        for (const ElementBatch& b : el.batches) {
          const std::size_t e = target_[k];
          if (b.body != s.body || e < b.begin || e >= b.end || !el.alive[e]) continue;
          const ElementState st = element_state(fe, el, b, e);
          const double row[] = {st.centroid.x,
                                st.centroid.y,
                                st.centroid.z,
                                st.velocity.x,
                                st.velocity.y,
                                st.velocity.z,
                                core::pressure(st.stress),
                                core::von_mises(st.stress),
                                st.plastic_strain};
          std::copy(std::begin(row), std::end(row), v);
        }
      };
      sample_element(fe.hexahedra());
      sample_element(fe.trusses());
    } else if (s.kind == core::ProbeKind::extreme) {
      auto scan = [&](const auto& el) {
        for (const ElementBatch& b : el.batches) {
          if (s.body >= 0 && b.body != s.body) continue;
          for (std::size_t e = b.begin; e < b.end; ++e) {
            if (!el.alive[e]) continue;
            const ElementState st = element_state(fe, el, b, e);
            if (!core::in_probe_box(s, st.centroid)) continue;
            core::merge_extreme(s,
                                core::probe_field_value(s.field, st.stress, st.plastic_strain,
                                                        st.velocity, st.centroid),
                                st.centroid, v);
          }
        }
      };
      scan(fe.hexahedra());
      scan(fe.trusses());
    }
  }
}

std::vector<core::Vec3> live_node_positions(const FeSolver& fe, int body) {
  std::vector<std::uint8_t> used(fe.nodes().size(), 0);
  auto mark = [&](const auto& el) {
    for (const ElementBatch& b : el.batches) {
      if (b.body != body) continue;
      for (std::size_t e = b.begin; e < b.end; ++e)
        if (el.alive[e])
          for (const std::int32_t n : el.nodes[e]) used[static_cast<std::size_t>(n)] = 1;
    }
  };
  mark(fe.hexahedra());
  mark(fe.trusses());
  std::vector<core::Vec3> out;
  for (std::size_t n = 0; n < used.size(); ++n)
    if (used[n]) out.push_back(fe.nodes().position[n]);
  return out;
}

}  // namespace afemp::fem
