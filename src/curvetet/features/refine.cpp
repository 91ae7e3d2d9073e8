#include "curvetet/features/refine.hpp"

#include <algorithm>

namespace curvetet::features {

RefinedSurface refine_multi_feature_faces(const mesh::SurfaceMesh& m, const std::vector<std::array<int, 2>>& edges) {
  auto is_feature = [&](int a, int b) {
    return std::binary_search(edges.begin(), edges.end(), std::array<int, 2>{std::min(a, b), std::max(a, b)});
  };
  RefinedSurface r;
  r.mesh.vertices = m.vertices;
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    int count = 0;
    for (int k = 0; k < 3; ++k) count += is_feature(t[k], t[(k + 1) % 3]);
    if (count <= 1) {
      r.mesh.faces.push_back(t);
      r.parent_face.push_back(f);
      continue;
    }
    const int c = r.mesh.num_vertices();
    r.mesh.vertices.push_back((m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0);
    r.parent_of_new_vertex.push_back(f);
    for (int k = 0; k < 3; ++k) {
      r.mesh.faces.push_back({t[k], t[(k + 1) % 3], c});
      r.parent_face.push_back(f);
    }
  }
  return r;
}

} // namespace curvetet::features
