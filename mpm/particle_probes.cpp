// Particle probes (mpm/particle_probes.hpp).
#include "mpm/particle_probes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace afemp::mpm {

void ParticleProbes::resolve(std::span<const core::ProbeSpec> probes, const Particles& p,
                             const core::Scene& scene) {
  specs_.assign(probes.begin(), probes.end());
  id_.assign(probes.size(), -1);
  slot_.assign(probes.size(), 0);
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    const core::ProbeSpec& s = specs_[k];
    if (s.kind != core::ProbeKind::particle) continue;
    // The body's particles in the order they were made: by id.
    std::vector<std::pair<std::int32_t, std::size_t>> ids;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body[i] == s.body) ids.emplace_back(p.id[i], i);
    std::sort(ids.begin(), ids.end());
    const std::string& name = scene.bodies[static_cast<std::size_t>(s.body)].name;
    if (s.index >= 0) {
      if (static_cast<std::size_t>(s.index) >= ids.size())
        throw core::InputError(s.where, s.key + ".particle.index",
                               "particle " + std::to_string(s.index) + " of body '" + name +
                                   "' does not exist; its particles are 0.." +
                                   std::to_string(static_cast<long>(ids.size()) - 1));
      id_[k] = ids[static_cast<std::size_t>(s.index)].first;
      slot_[k] = ids[static_cast<std::size_t>(s.index)].second;
      continue;
    }
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [id, i] : ids) {  // the first of equally near ones by id
      const double d = core::norm(p.position[i] - s.near);
      if (d < best) best = d, id_[k] = id, slot_[k] = i;
    }
    if (id_[k] < 0)
      throw core::InputError(s.where, s.key + ".particle.body",
                             "body '" + name + "' has no particles to probe");
  }
}

void ParticleProbes::sample(const Particles& p, std::span<double> out) const {
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    const core::ProbeSpec& s = specs_[k];
    double* v = out.data() + k * core::probe_stride;
    if (s.kind == core::ProbeKind::particle) {
      std::size_t i = slot_[k];
      if (i >= p.size() || p.id[i] != id_[k]) {  // moved by a reordering: find it again
        i = static_cast<std::size_t>(std::find(p.id.begin(), p.id.end(), id_[k]) - p.id.begin());
        slot_[k] = i;
      }
      if (i >= p.size()) {  // the particle left through an outflow face: nothing to read
        std::fill(v, v + core::probe_stride, std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      const core::Vec3 &x = p.position[i], &u = p.velocity[i];
      const double row[] = {x.x,
                            x.y,
                            x.z,
                            u.x,
                            u.y,
                            u.z,
                            core::pressure(p.stress[i]),
                            core::von_mises(p.stress[i]),
                            p.plastic_strain[i]};
      std::copy(std::begin(row), std::end(row), v);
    } else if (s.kind == core::ProbeKind::extreme) {
      for (std::size_t i = 0; i < p.size(); ++i) {
        if ((s.body >= 0 && p.body[i] != s.body) || !core::in_probe_box(s, p.position[i])) continue;
        core::merge_extreme(s,
                            core::probe_field_value(s.field, p.stress[i], p.plastic_strain[i],
                                                    p.velocity[i], p.position[i]),
                            p.position[i], v);
      }
    }
  }
}

void ParticleProbes::merge_ranks(std::span<const double> all, std::span<double> out) const {
  const std::size_t width = out.size();
  const std::size_t ranks = width > 0 ? all.size() / width : 0;
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    const core::ProbeSpec& s = specs_[k];
    if (s.kind != core::ProbeKind::particle && s.kind != core::ProbeKind::extreme) continue;
    double* v = out.data() + k * core::probe_stride;
    std::fill(v, v + core::probe_stride, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t r = 0; r < ranks; ++r) {
      const double* w = all.data() + r * width + k * core::probe_stride;
      if (std::isnan(w[0])) continue;  // not this rank's particle; no point of it in the box
      if (s.kind == core::ProbeKind::particle) {
        std::copy(w, w + core::probe_stride, v);
        break;
      }
      core::merge_extreme(s, w[0], core::Vec3{w[1], w[2], w[3]}, v);
    }
  }
}

}  // namespace afemp::mpm
