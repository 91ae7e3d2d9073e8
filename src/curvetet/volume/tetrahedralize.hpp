#pragma once
// `curvetet tetrahedralize`: boundary-preserving tetrahedralization of a
// closed surface (issue 6). Each side is filled by fill_direct() (the
// Delaunay tetrahedralization of the surface's vertices, flips and interior
// cones for the triangles it lacks) when that succeeds and its result
// verifies, else by fill_layered() on the offset of the shell's one-sided
// extrusion (shell::extrude_one_sided).
//
// Output: vertices [0, n) are the surface's vertices bit for bit; tag 1 = the
// interior (bounded exactly by the surface faces), tag 2 = with `exterior`,
// the region between the surface and a box (bounded by the reversed surface
// faces and the box). verify_tet_mesh() has been run on each part; a layered
// fill that fails it throws Error(internal).
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/mesh/linear_tet_mesh.hpp"
#include "curvetet/volume/fill.hpp"
#include "curvetet/volume/verify.hpp"

namespace curvetet::volume {

struct TetrahedralizeOptions {
  bool exterior = false;
  bool direct = true;             // try fill_direct() before the layered fill
  double layer_thickness = 0.01; // target pillar length, × bbox diagonal
  FillOptions fill;              // fill.box_margin: box margin, × diagonal
};

struct TetrahedralizeResult {
  mesh::LinearTetMesh mesh;
  FillStats interior, exterior;
  TetMeshCheck interior_check, exterior_check;
  int singular_inward = 0, singular_outward = 0;
  double seconds_extrusion = 0;
};

TetrahedralizeResult tetrahedralize(const mesh::SurfaceMesh& surface, const TetrahedralizeOptions& options = {});

} // namespace curvetet::volume
