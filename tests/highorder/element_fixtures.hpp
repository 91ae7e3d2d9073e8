#pragma once
// Elements built in code for the highorder tests.
#include "curvetet/highorder/node_ordering.hpp"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

namespace curvetet::highorder::testing {

// Nodes of an order-P tet whose geometry is phi(straight tet v0..v3).
inline std::vector<Eigen::Vector3d> mapped_tet(int order, const std::array<Eigen::Vector3d, 4>& v,
                                               const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& phi) {
  std::vector<Eigen::Vector3d> nodes;
  for (int i = 0; i < tet_node_count(order); ++i) {
    auto p = tet_node(order, i);
    const double u = double(p[0]) / order, s = double(p[1]) / order, w = double(p[2]) / order;
    nodes.push_back(phi((1 - u - s - w) * v[0] + u * v[1] + s * v[2] + w * v[3]));
  }
  return nodes;
}

inline std::array<Eigen::Vector3d, 4> unit_tet() {
  return {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1)};
}

inline std::vector<Eigen::Vector3d> straight_tet(int order, const std::array<Eigen::Vector3d, 4>& v = unit_tet()) {
  return mapped_tet(order, v, [](const Eigen::Vector3d& x) { return x; });
}

// A smooth near-identity bend: small enough to keep det J > 0.
inline Eigen::Vector3d gentle_bend(const Eigen::Vector3d& x) {
  return x + 0.08 * Eigen::Vector3d(std::sin(2 * x.y()), std::sin(2 * x.z() + 1), std::cos(2 * x.x()) - 1);
}

} // namespace curvetet::highorder::testing
