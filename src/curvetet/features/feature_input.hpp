#pragma once
// User-given features and constraint points (0-based indices into the input
// surface), as read from the JSON feature file or detected by angle.
#include "curvetet/mesh/edge_topology.hpp"
#include "curvetet/mesh/surface_mesh.hpp"

#include <array>
#include <vector>

namespace curvetet::features {

// Points on the input surface where the distance bound is enforced in
// addition to (or instead of) the input vertices: face f, barycentric (a,b,c)
// with a,b,c >= 0 and a+b+c = 1 (renormalized after validation).
struct ConstraintPoints {
  std::vector<int> faces;
  std::vector<std::array<double, 3>> barycentric;
};

struct FeatureInput {
  std::vector<std::array<int, 2>> edges; // each a mesh edge, stored with [0] < [1]
  std::vector<int> corners;
  ConstraintPoints points;

  bool empty() const { return edges.empty() && corners.empty() && points.faces.empty(); }
};

// Throws Error(InputDefect::bad_features) naming every invalid entry (up to
// a few ids per kind): edges that are not mesh edges, indices out of range,
// barycentrics negative or not summing to 1 (within 1e-9: JSON decimals
// cannot sum to exactly 1), faces/barycentric count mismatch.
// Normalizes edges to [min, max], sorts and dedups edges and corners, and
// divides each barycentric triple by its sum.
void validate_and_normalize(FeatureInput& features, const mesh::SurfaceMesh& mesh, const mesh::EdgeTopology& topo);

} // namespace curvetet::features
