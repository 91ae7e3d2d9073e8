#pragma once
// Attribute transfer through the map (paper §6.3-6.4), never by closest
// point. Attributes are columns of a matrix with one row per vertex/node;
// `is_label[c]` marks column c as a label (an integer id) rather than a
// quantity. A vector attribute is several quantity columns: each moves
// linearly, which is the vector's own linear transfer.
//
// input -> boundary: node j takes the attribute at φ⁻¹(node j) =
//   (input face, u, v): quantities interpolate linearly on the input face,
//   labels take the label of the face corner with the largest weight
//   (nearest-label rule).
// boundary -> input: vertex i takes the attribute at φ(vertex i) =
//   (boundary triangle, u, v): quantities interpolate with the order-P
//   Lagrange basis of the triangle (the same basis as its geometry), labels
//   take the label of the triangle's lattice node nearest to (u, v).
#include "curvetet/mesh/boundary_map.hpp"

#include <Eigen/Core>

#include <vector>

namespace curvetet::map {

// values: input vertices x columns; result: boundary nodes x columns.
Eigen::MatrixXd input_to_boundary(const mesh::BoundaryMap& map, const Eigen::MatrixXd& values,
                                  const std::vector<char>& is_label);

// values: boundary nodes x columns; result: input vertices x columns.
Eigen::MatrixXd boundary_to_input(const mesh::BoundaryMap& map, const Eigen::MatrixXd& values,
                                  const std::vector<char>& is_label);

// Point of the (curved) boundary at a map point.
mesh::Vec3 boundary_point(const mesh::BoundaryMap& map, const mesh::SurfacePoint& p);
// Point of the input surface at a map point.
mesh::Vec3 input_point(const mesh::BoundaryMap& map, const mesh::SurfacePoint& p);

// How far the map moves points (absolute units): max |x_i - φ(x_i)| over the
// input vertices (the points where the pipeline enforces ε) and max
// |n_j - φ⁻¹(n_j)| over the boundary nodes (between input vertices the
// curved surface may lie a little farther).
struct MapDistances {
  double vertex_max = 0, node_max = 0;
};
MapDistances map_distances(const mesh::BoundaryMap& map);

} // namespace curvetet::map
