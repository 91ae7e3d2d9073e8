#pragma once
// Tetrahedra of a slab (one half of a prism), as local corner indices:
// 0, 1, 2 = lower corners of the face's corners 0, 1, 2; 3, 4, 5 = the upper
// corners above them (corner k+3 is above k; pillar k joins k and k+3).
//
// Reference slab: lower corner k at (r_k, 0), upper at (r_k, 1) in (u, v, w)
// with r_0 = (0,0), r_1 = (1,0), r_2 = (0,1). Every tet listed here is
// oriented so that it is positive (orient3d > 0) on the reference slab, i.e.
// on any right prism over a counter-clockwise triangle with upper above.
#include <array>

namespace curvetet::shell {

struct SlabTet {
  std::array<int, 4> corners; // local corners, positively ordered
  int pillar;                 // the one pillar (0..2) it contains
};

// The 12 distinct tets of the 6 ways to cut a slab into 3 tets (every 4-subset
// of the 6 corners holding exactly one whole pillar). Prism positivity
// requires all of them positive (DESIGN.md §2 item 1).
const std::array<SlabTet, 12>& all_slab_tets();

// The one fixed 3-tet split used by the projection, decided from the global
// vertex ids of the face's corners: the quad over edge (i, j) is cut by the
// diagonal from the lower corner of the smaller id to the upper corner of the
// larger one, so the two prisms sharing the quad cut it the same way.
// Precondition: the three ids are distinct.
std::array<SlabTet, 3> canonical_split(const std::array<int, 3>& global_ids);

// Reference (u, v, w) coordinates of local corner c (0..5).
std::array<double, 3> reference_corner(int c);

} // namespace curvetet::shell
