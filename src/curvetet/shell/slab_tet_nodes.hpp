#pragma once
// The order-P nodes of one canonical tet of a curved slab, placed exactly as
// the assembled output mesh places them (volume/assemble.cpp calls this), so
// that the shell can certify the very tets the output will hold.
//
// Slab map: x(u, v, w) = (1 - w) cap(u, v) + w M(u, v) for a bottom slab
// (cap = bottom triangle, w = 1 on the middle patch M of degree k), and
// (1 - w) M(u, v) + w cap(u, v) for a top slab. Nodes off the middle
// surface are placed on the straight tet instead where the slab map is
// degenerate or may fold although the straight prism is positive: next to
// a singular vertex (pinched pillar: det J = 0) and, with straight_parts,
// over straight parts of the middle (a flat patch, or the lateral quad over
// a straight middle edge: a bilinear quad). The second rule is per shell:
// it costs quality (a tet with straight lateral faces and a curved
// interior), so it is on only when the flat shell the curving starts from
// has a prism the slab map folds (coarsen.cpp). Each rule depends only on the node's carrier
// (corners with non-zero weight) and on data both prisms of an edge share,
// so tets sharing a node agree. Nodes on the middle are always on M.
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <array>
#include <vector>

namespace curvetet::shell {

using mesh::Vec3;

struct SlabPatch {
  int degree = 1;                     // k of the middle patch
  const Vec3* middle_nodes = nullptr; // triangle_node_count(k) nodes, corners first
  std::array<Vec3, 3> cap;            // the linear cap's corners below/above middle corners 0..2
  bool bottom = true;                 // bottom slab (cap below) or top slab
  std::array<bool, 3> pinched{};      // corner is a singular vertex (cap == middle corner)
  bool straight_parts = false;        // apply the straight-middle rule (Shell::straight_slab_parts)
};

// Which parts of the middle patch are flat (every node within 1e-12 of the
// flat triangle, relative): edge[k] = the edge opposite corner k; whole =
// all edges and the interior.
struct StraightParts {
  std::array<bool, 3> edge{};
  bool whole = false;
};
StraightParts straight_parts(const SlabPatch& patch);

// Nodes of canonical tet `tet` (its pillar must not be pinched) at `order`,
// in the internal (Gmsh) tet order.
std::vector<Vec3> slab_tet_nodes(const SlabPatch& patch, const SlabTet& tet, int order);

} // namespace curvetet::shell
