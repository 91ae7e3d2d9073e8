#pragma once
// INTERNAL to volume/*.cpp. A tetrahedralization of the inside of a closed
// oriented surface with no new point, by peeling tets off it (an advancing
// front): for cavity pieces that have no kernel point (cavity_fill.hpp),
// where no cone can fill them, and too thin for any interior point to be
// represented (a solid 1e-17 thick beside needle triangles, as in
// thingi10k_44901).
//
// Each step adds one tet T = (face of the front, a front vertex) such that
//  - T is exactly positive and lies on the inner side of every front face
//    it shares (those leave the front; T's other faces join it, reversed);
//  - no front vertex other than T's lies in closed T, and no face of T
//    meets a front face other than in their shared corners
//    (geometry::triangles_intersect_improperly, exact).
// So T lies inside the region the front bounds, and the tets and the front
// always form a proper complex; an empty front means the tets
// tetrahedralize the inside exactly. Ears (T with two or more faces on the
// front) are preferred, best shape first. A depth-first search that tries
// the two best fitting tets at each step, within a budget of steps: it may
// get stuck (some polyhedra have no such tetrahedralization at all); it then
// starts again with another order of candidates, up to `attempts` orders.
#include "curvetet/mesh/surface_mesh.hpp"

#include <array>
#include <vector>

namespace curvetet::volume {

struct Peeled {
  std::vector<std::array<int, 4>> tets; // positive (orient3d > 0)
  std::vector<mesh::Tri> rest;          // the front where it got stuck (empty: done)
};

// `faces` (ids into p) bound a region on their positive side (orient3d of a
// face and a point just inside is +1). One attempt that peels it all, or
// every attempt (each after `budget` steps, or stuck everywhere), with the
// deepest state it reached, fewest faces left first: the rest bounds what is
// left of the region, for the caller to fill otherwise (a cone from a
// kernel point).
std::vector<Peeled> peel_tetrahedralize(const std::vector<mesh::Vec3>& p, const std::vector<mesh::Tri>& faces,
                                        long budget, int attempts);

} // namespace curvetet::volume
