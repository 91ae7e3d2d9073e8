#include "curvetet/mesh/surface_mesh.hpp"

#include <stdexcept>

namespace curvetet::mesh {

double bbox_diagonal(const std::vector<Vec3>& points) {
  if (points.empty()) return 0.0;
  Vec3 lo = points.front(), hi = points.front();
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

double mean_edge_length(const SurfaceMesh& mesh) {
  if (mesh.faces.empty()) return 0.0;
  double sum = 0;
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) sum += (mesh.vertices[f[k]] - mesh.vertices[f[(k + 1) % 3]]).norm();
  return sum / (3.0 * static_cast<double>(mesh.faces.size()));
}

SurfaceMesh to_surface_mesh(const PolygonSoup& soup) {
  SurfaceMesh m;
  m.vertices = soup.points;
  m.faces.reserve(soup.polygons.size());
  for (const auto& poly : soup.polygons) {
    if (poly.size() != 3) throw std::logic_error("to_surface_mesh: non-triangle polygon");
    m.faces.push_back({static_cast<int>(poly[0]), static_cast<int>(poly[1]), static_cast<int>(poly[2])});
  }
  return m;
}

PolygonSoup to_soup(const SurfaceMesh& mesh) {
  PolygonSoup s;
  s.points = mesh.vertices;
  s.polygons.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) s.polygons.push_back({f[0], f[1], f[2]});
  return s;
}

} // namespace curvetet::mesh
