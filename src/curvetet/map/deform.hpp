#pragma once
// Paper §6.4 "fast animation": deform the coarse mesh, then carry its
// displacement to the dense input through the map. The dense vertex i moves
// by the boundary displacement interpolated at φ(vertex i) with the
// triangle's order-P basis (map/transfer.hpp), so the dense surface rides on
// the curved coarse boundary.
#include "curvetet/mesh/boundary_map.hpp"

#include <vector>

namespace curvetet::map {

// A smooth prescribed deformation: a twist of `radians` in total about the
// line through the box centre along `axis` (0, 1, 2 = x, y, z), the angle
// growing linearly along the axis from -radians/2 at the low end of
// [low, high] to +radians/2 at the high end.
struct Twist {
  int axis = 2;
  double radians = 0;
  mesh::Vec3 centre = mesh::Vec3::Zero();
  double low = 0, high = 1;
};

// Twist about the longest axis of the box of `points`.
Twist twist_for(const std::vector<mesh::Vec3>& points, double radians);
mesh::Vec3 displacement(const Twist& t, const mesh::Vec3& x);

// Deformed input vertices: vertex i + the node displacement field
// (one per boundary node) carried through φ.
std::vector<mesh::Vec3> carry_to_input(const mesh::BoundaryMap& map, const std::vector<mesh::Vec3>& node_displacement);

} // namespace curvetet::map
