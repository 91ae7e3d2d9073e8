#pragma once
// Internal: the caps (bottom and top faces) of a shell seen as one surface
// with merged vertex ids, and the exact improper-intersection rule on it
// (the rule of check::faces_intersect). Used by invariants.cpp and
// cap_index.cpp.
#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/shell/shell.hpp"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace curvetet::shell {

// Exact segment/triangle test with cheap exact rejections first: disjoint
// boxes, or both segment ends strictly on one side of the triangle's plane
// (two filtered orient3d). Only the rest goes to the general predicate.
inline bool segment_meets_triangle(const Vec3& s0, const Vec3& s1, const Vec3& t0, const Vec3& t1, const Vec3& t2) {
  for (int k = 0; k < 3; ++k) {
    const double slo = std::min(s0[k], s1[k]), shi = std::max(s0[k], s1[k]);
    const double tlo = std::min({t0[k], t1[k], t2[k]}), thi = std::max({t0[k], t1[k], t2[k]});
    if (shi < tlo || thi < slo) return false;
  }
  const int o0 = geometry::orient3d(t0, t1, t2, s0);
  if (o0 != 0 && o0 == geometry::orient3d(t0, t1, t2, s1)) return false;
  return geometry::segment_triangle_intersect(s0, s1, t0, t1, t2);
}

// Exact triangle/triangle test with the same kind of rejection: all corners
// of one strictly on one side of the other's plane.
inline bool triangles_meet(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                           const Vec3& b2) {
  auto one_side = [](const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& q0, const Vec3& q1, const Vec3& q2) {
    const int o = geometry::orient3d(p0, p1, p2, q0);
    return o != 0 && o == geometry::orient3d(p0, p1, p2, q1) && o == geometry::orient3d(p0, p1, p2, q2);
  };
  if (one_side(a0, a1, a2, b0, b1, b2) || one_side(b0, b1, b2, a0, a1, a2)) return false;
  return geometry::triangles_intersect(a0, a1, a2, b0, b1, b2);
}

// Merged vertex id of a cap corner: bottom v -> v; top v -> v when
// B[v] == T[v] (the pillar is pinched), else n + v.
struct CapView {
  const Shell& s;
  int F, n;
  std::array<int, 3> ids(int cap) const {
    const Tri& t = s.faces[cap % F];
    std::array<int, 3> out;
    for (int k = 0; k < 3; ++k) out[k] = cap < F || s.bottom[t[k]] == s.top[t[k]] ? t[k] : n + t[k];
    return out;
  }
  const Vec3& point(int id) const { return id < n ? s.bottom[id] : s.top[id - n]; }
  geometry::Box3 box(int cap) const {
    const auto i = ids(cap);
    return geometry::bounding_box(point(i[0]), point(i[1]), point(i[2]));
  }
  bool all_pinched(int f) const {
    const Tri& t = s.faces[f];
    return s.bottom[t[0]] == s.top[t[0]] && s.bottom[t[1]] == s.top[t[1]] && s.bottom[t[2]] == s.top[t[2]];
  }
  // Same rule as check::faces_intersect, on merged ids.
  bool intersect(int ca, int cb) const {
    if (ca % F == cb % F && all_pinched(ca % F)) return false;
    const auto a = ids(ca), b = ids(cb);
    int shared = 0, ia[3], ib[3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (a[i] == b[j]) {
          ia[shared] = i;
          ib[shared] = j;
          ++shared;
        }
    auto P = [&](int id) -> const Vec3& { return point(id); };
    if (shared == 0) return triangles_meet(P(a[0]), P(a[1]), P(a[2]), P(b[0]), P(b[1]), P(b[2]));
    if (shared == 1) {
      const int i = ia[0], j = ib[0];
      return segment_meets_triangle(P(a[(i + 1) % 3]), P(a[(i + 2) % 3]), P(b[0]), P(b[1]), P(b[2])) ||
             segment_meets_triangle(P(b[(j + 1) % 3]), P(b[(j + 2) % 3]), P(a[0]), P(a[1]), P(a[2]));
    }
    if (shared == 2) {
      const int u = a[ia[0]], v = a[ia[1]];
      const int pa = a[3 - ia[0] - ia[1]], pb = b[3 - ib[0] - ib[1]];
      if (geometry::orient3d(P(u), P(v), P(pa), P(pb)) != 0) return false;
      return geometry::coplanar_orientation(P(u), P(v), P(pa), P(pb)) > 0;
    }
    return true;
  }
};

// Exact decision on unique candidate cap pairs (a < b): the intersecting
// ones, sorted. Parallel; independent of the thread count.
std::vector<std::pair<int, int>> decide_cap_pairs(const CapView& view, std::vector<std::pair<int, int>> candidates);

} // namespace curvetet::shell
