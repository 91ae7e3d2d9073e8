#include "curvetet/features/detect.hpp"

#include <cmath>
#include <numbers>

namespace curvetet::features {

std::vector<std::array<int, 2>> detect_feature_edges(const mesh::SurfaceMesh& m, const mesh::EdgeTopology& topo,
                                                     double angle_degrees) {
  auto normal = [&](int f) {
    const auto& t = m.faces[f];
    return (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).normalized();
  };
  const double cos_limit = std::cos(angle_degrees * std::numbers::pi / 180.0);
  std::vector<std::array<int, 2>> out;
  for (int e = 0; e < topo.num_edges(); ++e) {
    if (topo.num_faces_of(e) != 2) continue;
    double c = normal(topo.faces_of(e)[0]).dot(normal(topo.faces_of(e)[1]));
    if (c < cos_limit) out.push_back(topo.edges[e]);
  }
  return out; // topo.edges is sorted, so is out
}

} // namespace curvetet::features
