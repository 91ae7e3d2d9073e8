#include "curvetet/check/self_intersection.hpp"

#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/geometry/triangle_pair.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace curvetet::check {

bool faces_intersect(const mesh::SurfaceMesh& m, int f, int g) {
  const auto& a = m.faces[f];
  const auto& b = m.faces[g];
  const auto& P = m.vertices;
  return geometry::triangles_intersect_improperly({P[a[0]], P[a[1]], P[a[2]]}, {P[b[0]], P[b[1]], P[b[2]]},
                                                  geometry::shared_corners(a, b));
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
