#pragma once
// The one rule for "do two triangles of a surface intersect improperly",
// used by the input checks (check::self_intersections), the shell's cap
// invariants and its star checks. Exact.
//
// Two closed, non-degenerate triangles that share `shared.count` corners
// (a[shared.a[i]] is the same vertex as b[shared.b[i]]) intersect improperly
// when
//  - they share no corner and meet at all;
//  - they share one corner v and meet anywhere else: decided as "the edge
//    opposite v in one meets the other" (either way round), which is exact
//    and complete because both are convex and contain v;
//  - they share an edge and are coplanar with their third corners on the
//    same side of it (they overlap: a fold of zero dihedral angle);
//  - they share all three corners (the same triangle twice).
#include "curvetet/geometry/predicates.hpp"

#include <array>

namespace curvetet::geometry {

struct SharedCorners {
  int count = 0;
  int a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
};

// Corners with equal ids (any integer id type).
template <class Id>
SharedCorners shared_corners(const std::array<Id, 3>& a_ids, const std::array<Id, 3>& b_ids) {
  SharedCorners s;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a_ids[i] == b_ids[j]) {
        s.a[s.count] = i;
        s.b[s.count] = j;
        ++s.count;
      }
  return s;
}

bool triangles_intersect_improperly(const std::array<Point3, 3>& a, const std::array<Point3, 3>& b,
                                    const SharedCorners& shared);

} // namespace curvetet::geometry
