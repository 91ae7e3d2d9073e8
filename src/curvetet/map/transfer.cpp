#include "curvetet/map/transfer.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/node_ordering.hpp"

#include <fmt/format.h>

#include <limits>

namespace curvetet::map {
namespace {

void check_shape(const Eigen::MatrixXd& values, std::size_t rows, const std::vector<char>& is_label, const char* what) {
  if (static_cast<std::size_t>(values.rows()) != rows)
    throw Error(ExitCode::usage, fmt::format("transfer: {} has {} rows, the map expects {}", what, values.rows(), rows));
  if (is_label.size() != static_cast<std::size_t>(values.cols()))
    throw Error(ExitCode::usage, "transfer: one label flag per column expected");
}

} // namespace

Eigen::MatrixXd input_to_boundary(const mesh::BoundaryMap& m, const Eigen::MatrixXd& values,
                                  const std::vector<char>& is_label) {
  check_shape(values, m.input.vertices.size(), is_label, "the input attribute table");
  Eigen::MatrixXd out(m.nodes.size(), values.cols());
  for (std::size_t j = 0; j < m.nodes.size(); ++j) {
    const auto& p = m.node_to_input[j];
    const auto& f = m.input.faces[p.face];
    const double w[3] = {1 - p.u - p.v, p.u, p.v};
    const int nearest = w[0] >= w[1] && w[0] >= w[2] ? 0 : w[1] >= w[2] ? 1 : 2;
    for (Eigen::Index c = 0; c < values.cols(); ++c)
      out(j, c) = is_label[c] ? values(f[nearest], c)
                              : w[0] * values(f[0], c) + w[1] * values(f[1], c) + w[2] * values(f[2], c);
  }
  return out;
}

Eigen::MatrixXd boundary_to_input(const mesh::BoundaryMap& m, const Eigen::MatrixXd& values,
                                  const std::vector<char>& is_label) {
  check_shape(values, m.nodes.size(), is_label, "the boundary attribute table");
  const int P = m.order, per = m.triangle_nodes();
  Eigen::MatrixXd out(m.input.vertices.size(), values.cols());
  for (std::size_t i = 0; i < m.input.vertices.size(); ++i) {
    const auto& p = m.vertex_to_boundary[i];
    const int* tri = m.triangle(p.face);
    const double xi[2] = {p.u, p.v};
    const Eigen::VectorXd N = highorder::lagrange_basis(2, P, xi);
    int nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < per; ++k) {
      const auto q = highorder::triangle_node(P, k);
      const double du = p.u - double(q[0]) / P, dv = p.v - double(q[1]) / P;
      if (du * du + dv * dv < best) best = du * du + dv * dv, nearest = k;
    }
    for (Eigen::Index c = 0; c < values.cols(); ++c) {
      if (is_label[c]) {
        out(i, c) = values(tri[nearest], c);
        continue;
      }
      double sum = 0;
      for (int k = 0; k < per; ++k) sum += N[k] * values(tri[k], c);
      out(i, c) = sum;
    }
  }
  return out;
}

mesh::Vec3 boundary_point(const mesh::BoundaryMap& m, const mesh::SurfacePoint& p) {
  const double xi[2] = {p.u, p.v};
  const Eigen::VectorXd N = highorder::lagrange_basis(2, m.order, xi);
  const int* tri = m.triangle(p.face);
  mesh::Vec3 x = mesh::Vec3::Zero();
  for (int k = 0; k < m.triangle_nodes(); ++k) x += N[k] * m.nodes[tri[k]];
  return x;
}

mesh::Vec3 input_point(const mesh::BoundaryMap& m, const mesh::SurfacePoint& p) {
  const auto& f = m.input.faces[p.face];
  return (1 - p.u - p.v) * m.input.vertices[f[0]] + p.u * m.input.vertices[f[1]] + p.v * m.input.vertices[f[2]];
}

MapDistances map_distances(const mesh::BoundaryMap& m) {
  MapDistances d;
  for (std::size_t i = 0; i < m.vertex_to_boundary.size(); ++i)
    d.vertex_max = std::max(d.vertex_max, (m.input.vertices[i] - boundary_point(m, m.vertex_to_boundary[i])).norm());
  for (std::size_t j = 0; j < m.node_to_input.size(); ++j)
    d.node_max = std::max(d.node_max, (m.nodes[j] - input_point(m, m.node_to_input[j])).norm());
  return d;
}

} // namespace curvetet::map
