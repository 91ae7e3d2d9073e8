#pragma once
// INTERNAL to volume/*.cpp. Step 2-3 of paper §4.3: exact insertion of a
// closed triangle surface into a background tet mesh by binary space
// partitioning (TetWild §3.1), then keeping one side of it.
//
// A surface triangle that is a face of the background is only labelled.
// Every tet is cut by the planes of the other surface triangles meeting it (and,
// where two adjacent triangles are coplanar, by a plane through their shared
// edge, so no cell face straddles two triangles). Cuts act on a conforming
// polyhedral complex: splitting an edge or a face updates every cell sharing
// it, so cells stay face-to-face across tets. All coordinates are rational.
// Afterwards each cell face lying in a surface triangle is known; cells get a
// winding number by crossing those faces (+1 when going against the
// triangle's normal); the cells of the wanted region are tetrahedralized:
// polygonal faces by a fan from a vertex or ear clipping (once, shared by
// both cells), cells by a cone from one of their vertices, or from a new
// centroid where no vertex can cone them (a cell that is a tet stays one).
// Exact predicates run on homogeneous integer points (homogeneous.hpp).
#include "curvetet/volume/background.hpp"
#include "curvetet/volume/exact_mesh.hpp"

#include <vector>

namespace curvetet::volume::exact {

struct InsertedSurface {
  Vertices vertices;                         // first bg.points.size() are the background points
  std::vector<std::array<int, 4>> tets;      // positive, region kept
  // refined[t]: triangles tiling surface triangle t (unoriented).
  std::vector<std::vector<std::array<int, 3>>> refined;
  std::size_t num_cells = 0, num_cuts = 0;
};

// keep_winding: 1 keeps the inside of the (outward oriented) surface, 0 the
// outside within the background's convex hull (the hull may touch the surface).
InsertedSurface insert_surface(const BackgroundMesh& bg, const std::vector<mesh::Tri>& triangles, int keep_winding);

} // namespace curvetet::volume::exact
