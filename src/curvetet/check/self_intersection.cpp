#include "curvetet/check/self_intersection.hpp"

#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/geometry/predicates.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace curvetet::check {

using geometry::Point3;

bool faces_intersect(const mesh::SurfaceMesh& m, int f, int g) {
  const auto& a = m.faces[f];
  const auto& b = m.faces[g];
  const auto& P = m.vertices;
  // Shared corners: position in a of each shared vertex, and in b.
  int shared = 0, ia[3], ib[3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) {
        ia[shared] = i;
        ib[shared] = j;
        ++shared;
      }
  if (shared == 0) return geometry::triangles_intersect(P[a[0]], P[a[1]], P[a[2]], P[b[0]], P[b[1]], P[b[2]]);
  if (shared == 1) {
    const int i = ia[0], j = ib[0];
    const Point3 &v = P[a[i]], &a1 = P[a[(i + 1) % 3]], &a2 = P[a[(i + 2) % 3]];
    const Point3 &b1 = P[b[(j + 1) % 3]], &b2 = P[b[(j + 2) % 3]];
    // B strictly on one side of A's plane except at v (or vice versa): they
    // meet only at v. Cheap, and decides most neighbouring pairs.
    const int s1 = geometry::orient3d(v, a1, a2, b1), s2 = geometry::orient3d(v, a1, a2, b2);
    if (s1 == s2 && s1 != 0) return false;
    const int r1 = geometry::orient3d(v, b1, b2, a1), r2 = geometry::orient3d(v, b1, b2, a2);
    if (r1 == r2 && r1 != 0) return false;
    if (s1 == 0 && s2 == 0) // coplanar: decide in 2D
      return geometry::coplanar_segment_triangle_intersect(a1, a2, v, b1, b2) ||
             geometry::coplanar_segment_triangle_intersect(b1, b2, v, a1, a2);
    return geometry::segment_triangle_intersect(a1, a2, v, b1, b2) ||
           geometry::segment_triangle_intersect(b1, b2, v, a1, a2);
  }
  if (shared == 2) {
    const int u = a[ia[0]], v = a[ia[1]];
    const int pa = a[3 - ia[0] - ia[1]], pb = b[3 - ib[0] - ib[1]];
    if (geometry::orient3d(P[u], P[v], P[pa], P[pb]) != 0) return false;
    return geometry::coplanar_orientation(P[u], P[v], P[pa], P[pb]) > 0;
  }
  return true; // same three vertices: a duplicate face covers the same area
}

std::vector<std::pair<int, int>> self_intersections(const mesh::SurfaceMesh& m, const std::vector<bool>& skip) {
  std::vector<int> ids;
  std::vector<geometry::Box3> boxes;
  for (int f = 0; f < m.num_faces(); ++f) {
    if (!skip.empty() && skip[f]) continue;
    const auto& t = m.faces[f];
    ids.push_back(f);
    boxes.push_back(geometry::bounding_box(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]));
  }
  auto candidates = geometry::overlapping_pairs(boxes);
  std::vector<char> hit(candidates.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 256), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k)
      hit[k] = faces_intersect(m, ids[candidates[k].first], ids[candidates[k].second]);
  });
  std::vector<std::pair<int, int>> out;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    if (hit[k]) out.emplace_back(ids[candidates[k].first], ids[candidates[k].second]);
  std::sort(out.begin(), out.end()); // candidates come in no particular order
  return out;
}

} // namespace curvetet::check
