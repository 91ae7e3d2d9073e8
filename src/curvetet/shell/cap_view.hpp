#pragma once
// Internal: the caps (bottom and top faces) of a shell seen as one surface
// with merged vertex ids, and the exact improper-intersection rule on it
// (the rule of check::faces_intersect). Used by invariants.cpp and
// cap_index.cpp.
#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/shell/shell.hpp"

#include <array>
#include <utility>
#include <vector>

namespace curvetet::shell {

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
    if (shared == 0) return geometry::triangles_intersect(P(a[0]), P(a[1]), P(a[2]), P(b[0]), P(b[1]), P(b[2]));
    if (shared == 1) {
      const int i = ia[0], j = ib[0];
      return geometry::segment_triangle_intersect(P(a[(i + 1) % 3]), P(a[(i + 2) % 3]), P(b[0]), P(b[1]), P(b[2])) ||
             geometry::segment_triangle_intersect(P(b[(j + 1) % 3]), P(b[(j + 2) % 3]), P(a[0]), P(a[1]), P(a[2]));
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
