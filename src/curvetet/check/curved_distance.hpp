#pragma once
// Distance from points to the curved boundary of a TetMesh, measured on the
// curved triangles themselves (not on a flat approximation, whose chords can
// lie farther from a point than the surface does).
//
// For each query, the closest point of the linearization gives a start
// (u, v) on its curved triangle; projected Gauss-Newton steps move it toward
// a closest point of that triangle. The result is |q - S(u, v)| at the best
// (u, v) reached: the distance to an actual point of the curved boundary,
// hence never below the true distance (up to the rounding of S). Plain
// double: it decides the verifier's distance bound conservatively.
#include "curvetet/check/boundary_linearization.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <vector>

namespace curvetet::check {

// `lin` = linearize_boundary(mesh, s) for any s >= 1.
std::vector<double> distances_to_curved_boundary(const mesh::TetMesh& mesh, const BoundaryLinearization& lin,
                                                 const std::vector<mesh::Vec3>& queries);

} // namespace curvetet::check
