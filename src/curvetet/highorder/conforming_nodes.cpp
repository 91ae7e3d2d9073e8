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

// Shared by tets (C = 4) and triangles (C = 3): weights[i] are node i's
// integer barycentric weights on the element's corners.
template <int C>
ConformingNodes number_nodes(int num_vertices, const std::vector<std::array<int, C>>& elements, int order,
                             const std::vector<std::array<int, 4>>& weights) {
  const int per_element = static_cast<int>(weights.size());
  ConformingNodes out;
  out.order = order;
  out.num_nodes = num_vertices;
  out.tet_nodes.resize(elements.size() * per_element);
  // Key: the (vertex, weight) pairs with weight > 0, sorted by vertex; unused
  // slots are (-1, 0).
  using Key = std::array<std::pair<int, int>, C>;
  std::map<Key, int> ids;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (int i = 0; i < per_element; ++i) {
      Key key;
      key.fill({-1, 0});
      int used = 0, corner = -1;
      for (int k = 0; k < C; ++k)
        if (weights[i][k] > 0) {
          key[used++] = {elements[e][k], weights[i][k]};
          if (weights[i][k] == order) corner = elements[e][k];
        }
      if (corner >= 0) {
        if (corner >= num_vertices) throw std::out_of_range("number_nodes: vertex id out of range");
        out.tet_nodes[e * per_element + i] = corner;
        continue;
      }
      std::sort(key.begin(), key.begin() + used);
      auto [it, inserted] = ids.try_emplace(key, out.num_nodes);
      if (inserted) ++out.num_nodes;
      out.tet_nodes[e * per_element + i] = it->second;
    }
  }
  return out;
}

} // namespace

std::array<double, 4> tet_node_barycentric(int order, int i) {
  auto w = lattice_weights(order, i);
  return {double(w[0]) / order, double(w[1]) / order, double(w[2]) / order, double(w[3]) / order};
}

ConformingNodes number_tet_nodes(int num_vertices, const std::vector<std::array<int, 4>>& tets, int order) {
  std::vector<std::array<int, 4>> weights(tet_node_count(order));
  for (int i = 0; i < static_cast<int>(weights.size()); ++i) weights[i] = lattice_weights(order, i);
  return number_nodes<4>(num_vertices, tets, order, weights);
}

ConformingNodes number_triangle_nodes(int num_vertices, const std::vector<std::array<int, 3>>& triangles, int order) {
  std::vector<std::array<int, 4>> weights(triangle_node_count(order));
  for (int i = 0; i < static_cast<int>(weights.size()); ++i) {
    auto n = triangle_node(order, i);
    weights[i] = {order - n[0] - n[1], n[0], n[1], 0};
  }
  return number_nodes<3>(num_vertices, triangles, order, weights);
}

} // namespace curvetet::highorder
