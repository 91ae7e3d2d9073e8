#pragma once
// Internal: the caps (bottom and top faces) of a shell seen as one surface
// with merged vertex ids, and the exact improper-intersection rule on it
// (geometry::triangles_intersect_improperly). Used by invariants.cpp and
// cap_index.cpp.
#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/geometry/triangle_pair.hpp"
#include "curvetet/shell/shell.hpp"

#include <algorithm>
#include <array>
#include <functional>
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
  // The rule of geometry::triangles_intersect_improperly, on merged ids.
  bool intersect(int ca, int cb) const {
    if (ca % F == cb % F && all_pinched(ca % F)) return false;
    const auto a = ids(ca), b = ids(cb);
    return geometry::triangles_intersect_improperly({point(a[0]), point(a[1]), point(a[2])},
                                                    {point(b[0]), point(b[1]), point(b[2])},
                                                    geometry::shared_corners(a, b));
  }
};

// Exact decision on unique candidate cap pairs (a < b): the intersecting
// ones, sorted. Parallel; independent of the thread count. `poll`, if set,
// is called before each batch of tests and may throw to abandon them.
std::vector<std::pair<int, int>> decide_cap_pairs(const CapView& view, std::vector<std::pair<int, int>> candidates,
                                                  const std::function<void()>& poll = {});

} // namespace curvetet::shell
