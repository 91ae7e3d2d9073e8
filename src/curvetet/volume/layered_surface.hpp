#pragma once
// The input of the volume stage: a closed surface plus one offset position per
// vertex (paper §4.3 step 1; produced by the shell's one-sided extrusion).
//
// Contract (checked exactly by layer_tets(), an error otherwise):
//  - surface: closed, oriented, intersection-free (check::preconditions).
//  - offset[v]: the end of v's pillar, or exactly surface.vertices[v] where
//    the pillar is pinched (singular vertex). The offset surface (same faces,
//    offset positions) does not self-intersect and, apart from pinched
//    vertices, does not touch the surface.
//  - every layer prism (face f, its offset) cut into 3 tets by the shell's
//    split below has positive tets, except tets that contain a pinched
//    pillar (they are degenerate and dropped).
// side = inward: the offset lies behind the faces (filling the interior);
// side = outward: in front of them (filling the exterior).
#include "curvetet/mesh/surface_mesh.hpp"

#include <array>
#include <vector>

namespace curvetet::volume {

enum class OffsetSide { inward, outward };

struct LayeredSurface {
  mesh::SurfaceMesh surface;
  std::vector<mesh::Vec3> offset; // size surface.num_vertices()
  OffsetSide side = OffsetSide::inward;

  bool pinched(int v) const { return offset[v] == surface.vertices[v]; }
};

// A layer tet on "layer vertex" ids: v in [0, n) is surface vertex v, n + v is
// the offset of v (use `v` itself when pinched; see layer_vertex()).
using LayerTet = std::array<int, 4>;

// Layer vertex id of the offset end of v's pillar (v itself when pinched).
inline int offset_id(const LayeredSurface& s, int v) { return s.pinched(v) ? v : s.surface.num_vertices() + v; }

// The 3 tets of each prism, positively oriented, degenerate ones dropped.
// The split is the shell's slab split, shell::canonical_split (one rule for
// the whole code base), with the slab's lower corners on the side the face's
// normal points away from: the offset for inward, the surface for outward.
// It depends on global vertex ids only, so neighbouring prisms agree on their
// shared quads.
// Throws Error(internal) naming the face if a tet is not positive (the offset
// breaks the contract).
// face_of (optional) receives the face of each tet.
std::vector<LayerTet> layer_tets(const LayeredSurface& s, std::vector<int>* face_of = nullptr);

} // namespace curvetet::volume
