#pragma once
// INTERNAL to volume/*.cpp. The centre of the largest ball inside an
// intersection of half-spaces {x : n_i · x >= b_i} (unit n_i) and a box, by
// a small revised simplex in doubles. It only proposes a point: whoever uses
// it checks it exactly (the Delaunay fill's cone apexes are checked by
// orient3d against every face), and falls back to the exact LP when it does
// not pass.
#include "curvetet/mesh/surface_mesh.hpp"

#include <optional>
#include <vector>

namespace curvetet::volume {

struct HalfSpace {
  mesh::Vec3 normal; // unit
  double offset;     // the half-space is normal · x >= offset
};

struct Centre {
  mesh::Vec3 point;
  double radius; // negative when the half-spaces have no common interior
};

// nullopt when the simplex does not settle (degenerate or ill-conditioned
// input): the caller then asks the exact LP.
std::optional<Centre> chebyshev_centre(const std::vector<HalfSpace>& halves, const mesh::Vec3& box_lo,
                                       const mesh::Vec3& box_hi);

} // namespace curvetet::volume
