// Trusses tied into hexahedra (fem/embedded_nodes.hpp).
#include "fem/embedded_nodes.hpp"

#include <cstdio>
#include <string>

#include "afemp/errors.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "fem/mesh.hpp"
#include "fem/points_inside_mesh.hpp"

namespace afemp::fem {

using core::Vec3;

EmbeddedNodes tie_embedded_nodes(const core::Scene& scene, const FeNodes& nodes,
                                 const HexElements& hexes) {
  EmbeddedNodes t;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const core::BodySpec& body = scene.bodies[b];
    if (!core::tied_into_hexahedra(scene, body)) continue;
    std::vector<std::int32_t> own;
    std::vector<Vec3> where;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes.body[i] == static_cast<std::int32_t>(b)) {
        own.push_back(static_cast<std::int32_t>(i));
        where.push_back(nodes.position[i]);
      }
    const std::string& host_name = scene.bodies[static_cast<std::size_t>(body.bonded_to)].name;
    const std::vector<HostPoint> at = locate_points(hexes, nodes.position, body.bonded_to, where);
    for (std::size_t k = 0; k < own.size(); ++k) {
      const auto i = static_cast<std::size_t>(own[k]);
      char place[96];
      std::snprintf(place, sizeof place, " at (%.6g, %.6g, %.6g)", where[k].x, where[k].y,
                    where[k].z);
      const std::string node = "node " + std::to_string(i - static_cast<std::size_t>(own[0])) +
                               " of body \"" + body.name + "\"" + place;
      if (at[k].element < 0)
        throw core::InputError(body.where, "bodies." + body.name + ".bonded_to",
                               node + " lies outside the hexahedra of \"" + host_name +
                                   "\"; every node of a body tied into hexahedra must lie "
                                   "inside them (on their faces at most)");
      if (nodes.imposed[i])
        throw core::InputError(body.where, "bodies." + body.name + ".bonded_to",
                               "a constraint holds " + node + ", which is tied into \"" +
                                   host_name +
                                   "\" and moves with it; restrict the constraint to other "
                                   "bodies (body = ...)");
      const auto e = static_cast<std::size_t>(at[k].element);
      std::array<double, 8> w;
      for (std::size_t a = 0; a < 8; ++a)
        w[a] = 0.125 * (1.0 + kHexNatural[a][0] * at[k].xi[0]) *
               (1.0 + kHexNatural[a][1] * at[k].xi[1]) * (1.0 + kHexNatural[a][2] * at[k].xi[2]);
      t.node.push_back(own[k]);
      t.host.push_back(at[k].element);
      t.host_nodes.push_back(hexes.nodes[e]);
      t.weight.push_back(w);
    }
  }
  t.own_mass.assign(t.size(), 0.0);
  if (t.empty()) return t;
  // The ties each host node gathers, in tie order (a fixed order: the same sums at any thread
  // count).
  t.offsets.assign(nodes.size() + 1, 0);
  for (const auto& corners : t.host_nodes)
    for (std::int32_t a : corners) ++t.offsets[static_cast<std::size_t>(a) + 1];
  for (std::size_t i = 0; i < nodes.size(); ++i) t.offsets[i + 1] += t.offsets[i];
  t.ties.resize(static_cast<std::size_t>(t.offsets.back()));
  std::vector<std::int64_t> fill(t.offsets.begin(), t.offsets.end() - 1);
  for (std::size_t k = 0; k < t.size(); ++k)
    for (std::int32_t a = 0; a < 8; ++a)
      t.ties[static_cast<std::size_t>(
          fill[static_cast<std::size_t>(t.host_nodes[k][static_cast<std::size_t>(a)])]++)] = {
          static_cast<std::int32_t>(k), a};
  return t;
}

void lend_embedded_masses(EmbeddedNodes& t, FeNodes& nodes, const HexElements& hexes) {
  for (std::size_t k = 0; k < t.size(); ++k) {
    const auto s = static_cast<std::size_t>(t.node[k]);
    t.own_mass[k] = nodes.mass[s];
    if (!t.bound(k, hexes)) continue;
    for (std::size_t a = 0; a < 8; ++a)
      nodes.mass[static_cast<std::size_t>(t.host_nodes[k][a])] += t.weight[k][a] * t.own_mass[k];
    nodes.mass[s] = 0.0;
  }
}

void follow_hosts(const EmbeddedNodes& t, FeNodes& nodes, const HexElements& hexes) {
  core::parallel_chunks(t.size(), [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t k = begin; k < end; ++k) {
      if (!t.bound(k, hexes)) continue;
      Vec3 v, x;
      for (std::size_t a = 0; a < 8; ++a) {
        const auto h = static_cast<std::size_t>(t.host_nodes[k][a]);
        v += t.weight[k][a] * nodes.velocity[h];
        x += t.weight[k][a] * nodes.position[h];
      }
      const auto s = static_cast<std::size_t>(t.node[k]);
      nodes.velocity[s] = v;
      nodes.position[s] = x;
    }
  });
}

void book_embedded_bodies(const EmbeddedNodes& t, const FeNodes& nodes, const HexElements& hexes,
                          std::vector<core::BodySums>& bodies) {
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!t.bound(k, hexes)) continue;
    const double m = t.own_mass[k];
    double kinetic = 0.0;
    for (std::size_t a = 0; a < 8; ++a) {
      const Vec3& v = nodes.velocity[static_cast<std::size_t>(t.host_nodes[k][a])];
      kinetic += 0.5 * t.weight[k][a] * m * core::dot(v, v);
    }
    const Vec3 momentum = m * nodes.velocity[static_cast<std::size_t>(t.node[k])];
    core::BodySums& host =
        bodies[static_cast<std::size_t>(nodes.body[static_cast<std::size_t>(t.host_nodes[k][0])])];
    core::BodySums& own =
        bodies[static_cast<std::size_t>(nodes.body[static_cast<std::size_t>(t.node[k])])];
    host.mass -= m;
    host.momentum -= momentum;
    host.kinetic -= kinetic;
    own.mass += m;
    own.momentum += momentum;
    own.kinetic += kinetic;
  }
}

}  // namespace afemp::fem
