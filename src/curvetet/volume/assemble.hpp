#pragma once
// Assembly of the output mesh (paper §4.3; DESIGN.md §1 volume::assemble):
// the linear fill inside the shell's bottom surface B, plus every bottom slab
// (B -> curved middle V) cut into 3 tets by the canonical split, all raised to
// order P with shared (conforming) high-order nodes. The boundary of the
// result is the curved middle surface.
//
// Optionally (`--fill all`) an exterior region too: a linear fill between the
// shell's top surface T and a box, plus every top slab (curved middle V -> T)
// cut the same way, tagged kExteriorTag. The middle surface is then an
// interface between the two regions (still listed as the "boundary"
// triangles, oriented outward from the domain); the box faces are listed
// with kBoxTag. Bottom and top slabs go through one code path: a slab has a
// linear cap (B or T) on one side of the curved middle.
//
// With a flat middle (degree 1) slab tets are the straight canonical tets
// (positive by the shell's invariant 1). With a curved middle they are the
// images of reference-slab tets under the curved slab map
//   x(u, v, w) = (1 - w) B_f(u, v) + w M_f(u, v),
// B_f the flat bottom triangle, M_f the degree-k middle patch (Lagrange nodes
// in internal order). Restricted to a tet this map has total degree k + 1, so
// with P = k + 1 (or more) the order-P Lagrange tet reproduces it exactly at
// every point, not just at the nodes. A slab tet whose pillar is pinched
// (singular vertex: bottom = middle) has no volume and is left out; the
// pinched vertex's bottom and middle are one mesh vertex. The slab map is
// degenerate on a pinched pillar, so off the middle surface the nodes around
// a pinched vertex are placed on straight simplices (assemble.cpp).
// Positivity is not assumed here: the caller certifies the result.
#include "curvetet/mesh/linear_tet_mesh.hpp"
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <vector>

namespace curvetet::volume {

// What the assembly needs from the (coarsened, curved) shell.
struct CurvedMiddle {
  std::vector<mesh::Vec3> bottom;      // per shell vertex
  std::vector<mesh::Tri> faces;        // shared by bottom and middle
  std::vector<char> singular;          // per shell vertex: bottom == middle (== top)
  std::vector<mesh::Vec3> top;         // per shell vertex; only read with an exterior fill
  int degree = 1;                      // k of the middle patches
  std::vector<std::vector<mesh::Vec3>> middle_nodes; // per face: triangle_node_count(k) nodes, corners first
  bool straight_slab_parts = false;    // shell::Shell::straight_slab_parts
};

struct AssemblyStats {
  int fill_tets = 0, slab_tets = 0, pinched_slab_tets = 0, boundary_triangles = 0; // interior region
  int exterior_fill_tets = 0, top_slab_tets = 0, box_triangles = 0;                  // exterior region
  double max_shared_node_mismatch = 0; // |difference| of a shared node computed from two tets
};

// `fill` tetrahedralizes the inside of the bottom surface: its vertices
// [0, bottom.size()) are the bottom vertices (same ids), its boundary faces
// are exactly `faces`. Result: order `order` (>= degree + 1 for an exact
// representation), tets tagged kDomainTag, boundary = the middle surface
// tagged kBoundaryTag, default physical groups set.
// `exterior` (optional) tetrahedralizes the region between the top surface
// and a box: its vertices [0, top.size()) are the top vertices (same ids),
// its boundary faces are the reversed `faces` plus the box (as
// volume::fill_layered with OffsetSide::outward gives). Its tets get
// kExteriorTag, the box faces kBoxTag (mesh::set_exterior_groups).
mesh::TetMesh assemble_curved_mesh(const CurvedMiddle& shell, const mesh::LinearTetMesh& fill, int order,
                                   AssemblyStats* stats = nullptr, const mesh::LinearTetMesh* exterior = nullptr);

} // namespace curvetet::volume
