#pragma once
// INTERNAL to volume/*.cpp. The tets on one side of a closed surface, taken
// from a tetrahedralization of its vertices (plus, outward, the box points)
// that has most of its triangles as faces, for fill_direct()
// (direct_fill.hpp). The triangles it lacks are recovered with interior
// Steiner points, never on the surface:
//  - every tet that may meet the relative interior of a missing triangle is
//    removed (exact separation tests, conservative); the union of those is
//    the cavity, and every missing triangle lies inside it;
//  - the other tets cross no triangle: each keeps its winding number, found
//    by crossing faces from the hull;
//  - the wanted side of the cavity is bounded by the faces it shares with
//    kept tets of that side and by surface triangles. Each closed piece of
//    that boundary is coned from one Steiner point that sees every face of
//    the piece (a point of its kernel, the Chebyshev centre found by an exact
//    LP), checked by exact orient3d on the rounded point;
//  - a piece without one grows: the kept tets behind the faces that hide its
//    centre join the cavity (two growth orders are tried, see side_tets).
// A cone over a closed surface from a point that sees every face strictly
// tetrahedralizes its inside exactly once, so the result is exact.
#include "curvetet/volume/background.hpp"

#include <optional>

namespace curvetet::volume {

struct SideTets {
  std::vector<mesh::Vec3> steiner;       // point ids bg.points.size() + i
  std::vector<std::array<int, 4>> tets;  // positive; ids into bg.points, then steiner
};

// face_of[t][k]: the surface triangle that is the face of bg.tets[t]
// opposite corner k, or -1; `missing`: the triangles that are no face.
// nullopt when a piece of the cavity has no kernel point (or its boundary is
// not a closed oriented surface); the caller then takes the layered path.
std::optional<SideTets> side_tets(const BackgroundMesh& bg, const std::vector<mesh::Tri>& surface,
                                  const std::vector<std::array<int, 4>>& face_of, const std::vector<int>& missing,
                                  bool inside);

} // namespace curvetet::volume
