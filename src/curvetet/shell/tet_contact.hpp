#pragma once
// Exact contact tests between an input triangle and one slab tet, shared by
// the global Section invariant (invariants.cpp) and its per-operation form
// (prism_geometry.cpp), so both apply the same rule.
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <array>

namespace curvetet::shell {

using mesh::Vec3;

// Closed triangle meets closed positive tet.
bool triangle_meets_tet(const Vec3* tri[3], const Vec3* tet[4]);

// Closed triangle meets closed positive tet outside conv(tet[i] : allowed[i])
// (one corner or one edge; with none allowed this is triangle_meets_tet).
// Conservative: "true" when the contact is not provably confined. Proofs
// are separating planes through the allowed corners (the triangle's plane,
// the tet's faces, and planes through one edge of each), exact orient3d.
bool triangle_meets_tet_outside(const Vec3* tri[3], const Vec3* tet[4], const bool allowed[4]);

// Section rule: the corners of a slab tet where an input triangle may touch
// it even though the triangle faces against the tet's pillar: the tet's
// middle-surface corners of the other two pillars (the middle surface is the
// slab's upper side in the bottom slab, its lower side in the top slab).
// Contact confined to such a corner, or to the middle edge between two, lies
// on fibres of the prism's lateral boundary (pillar i itself, or the lateral
// face over the middle edge); those fibres run through tets holding pillar i
// (or j), which test the same triangle against their own pillar, in this
// prism and in the neighbour sharing the edge. This is what lets an input
// face across a crease of 90 degrees or more touch the prism along the
// crease (paper §3.1 of Bijective Projection in a Shell: contact that cannot
// make Π non-injective).
std::array<bool, 4> section_allowed_corners(const SlabTet& tet, bool middle_is_upper);

} // namespace curvetet::shell
