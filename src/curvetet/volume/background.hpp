#pragma once
// Background mesh of the volume stage (paper §4.3 step 2): the Delaunay
// tetrahedralization of the offset vertices plus the corners of a box, and
// which offset triangles meet which tets (closed sets, exact).
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/volume/verify.hpp"

#include <array>
#include <vector>

namespace curvetet::volume {

struct BackgroundMesh {
  std::vector<mesh::Vec3> points;            // as given
  std::vector<std::array<int, 4>> tets;      // positive (orient3d > 0)
  // neighbours[t][k]: the tet across the face opposite corner k, -1 on the
  // hull (filled by delaunay(); computed on demand when empty).
  std::vector<std::array<int, 4>> neighbours;
};

// Outward fills: the bounding box of `around` grown on each side by
// max(margin, 1e-3) × its diagonal.
Box padded_box(const std::vector<mesh::Vec3>& around, double margin);
// Appends the points of `extra` that `pts` does not hold yet (background
// points must be distinct), in order.
void append_new_points(std::vector<mesh::Vec3>& pts, const std::vector<mesh::Vec3>& extra);
// Appends the box's 8 corners and a coarse grid inside it (smaller
// background tets meet fewer triangles), skipping points already in `pts`.
void append_box_points(const Box& box, std::vector<mesh::Vec3>& pts);

// neighbours[t][k] = the tet across the face of tets[t] opposite corner k
// (-1: none), found by hashing faces.
std::vector<std::array<int, 4>> face_neighbours(const std::vector<std::array<int, 4>>& tets);

// Which tet faces are triangles: face_of[t][k] = the triangle that is the
// face of bg.tets[t] opposite corner k, or -1; `missing` (optional) gets
// the triangles that are no face, in order. Point ids must be below
// kMaxFaceKeyId (mesh_keys.hpp).
std::vector<std::array<int, 4>> triangle_faces(const BackgroundMesh& bg, const std::vector<mesh::Tri>& triangles,
                                              std::vector<int>* missing = nullptr);

// Delaunay tetrahedralization of `points` (CGAL, exact predicates). Points
// must be pairwise distinct and not all coplanar; throws Error(internal)
// otherwise.
BackgroundMesh delaunay(const std::vector<mesh::Vec3>& points);

// For every tet, the sorted ids of the triangles (corners index bg.points)
// that may meet the closed tet: every triangle that does is listed; a few
// that do not may be (not separated by a face plane of the tet or by the
// triangle's plane; exact). Found by walking from the stars of each
// triangle's corners through face-adjacent tets that may meet it (the tets
// meeting a closed triangle are face-connected), so the cost follows the
// number of listed pairs, not of overlapping bounding boxes. With
// `interior`, the same for the triangles' relative interiors (the tets that
// meet one are face-connected too, and one holds a corner).
std::vector<std::vector<int>> triangles_meeting_tets(const BackgroundMesh& bg, const std::vector<mesh::Tri>& triangles,
                                                     bool interior = false);

} // namespace curvetet::volume
