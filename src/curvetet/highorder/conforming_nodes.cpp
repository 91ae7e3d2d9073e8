#include "curvetet/highorder/conforming_nodes.hpp"

#include "curvetet/highorder/node_ordering.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace curvetet::highorder {
namespace {

// Weights over the 4 corners of internal node i (sum = order).
std::array<int, 4> lattice_weights(int order, int i) {
  auto n = tet_node(order, i);
  return {order - n[0] - n[1] - n[2], n[0], n[1], n[2]};
}

} // namespace

std::array<double, 4> tet_node_barycentric(int order, int i) {
  auto w = lattice_weights(order, i);
  return {double(w[0]) / order, double(w[1]) / order, double(w[2]) / order, double(w[3]) / order};
}

ConformingNodes number_tet_nodes(int num_vertices, const std::vector<std::array<int, 4>>& tets, int order) {
  const int per_tet = tet_node_count(order);
  std::vector<std::array<int, 4>> weights(per_tet);
  for (int i = 0; i < per_tet; ++i) weights[i] = lattice_weights(order, i);

  ConformingNodes out;
  out.order = order;
  out.num_nodes = num_vertices;
  out.tet_nodes.resize(tets.size() * per_tet);
  // Key: up to four (vertex, weight) pairs with weight > 0, sorted by vertex;
  // unused slots are (-1, 0).
  using Key = std::array<std::pair<int, int>, 4>;
  std::map<Key, int> ids;
  for (std::size_t t = 0; t < tets.size(); ++t) {
    for (int i = 0; i < per_tet; ++i) {
      Key key;
      key.fill({-1, 0});
      int used = 0, corner = -1;
      for (int k = 0; k < 4; ++k)
        if (weights[i][k] > 0) {
          key[used++] = {tets[t][k], weights[i][k]};
          if (weights[i][k] == order) corner = tets[t][k];
        }
      if (corner >= 0) {
        if (corner >= num_vertices) throw std::out_of_range("number_tet_nodes: vertex id out of range");
        out.tet_nodes[t * per_tet + i] = corner;
        continue;
      }
      std::sort(key.begin(), key.begin() + used);
      auto [it, inserted] = ids.try_emplace(key, out.num_nodes);
      if (inserted) ++out.num_nodes;
      out.tet_nodes[t * per_tet + i] = it->second;
    }
  }
  return out;
}

} // namespace curvetet::highorder
