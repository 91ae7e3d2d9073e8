#include "curvetet/shell/shell.hpp"

#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"

namespace curvetet::shell {

namespace {
mesh::SurfaceMesh surface_of(const std::vector<Vec3>& points, const Shell& s) {
  mesh::SurfaceMesh m;
  m.vertices = points;
  m.faces = s.faces;
  return m;
}
} // namespace

Vec3 middle_point(const Shell& s, const MapPoint& p) {
  if (!s.middle_nodes.empty())
    return highorder::triangle_point(s.middle_degree, s.middle_nodes[p.prism].data(), Eigen::Vector2d(p.u, p.v));
  const Tri& t = s.faces[p.prism];
  return (1 - p.u - p.v) * s.middle[t[0]] + p.u * s.middle[t[1]] + p.v * s.middle[t[2]];
}

std::vector<Vec3> flat_triangle_nodes(const std::array<Vec3, 3>& corners, int degree) {
  const int n = highorder::triangle_node_count(degree);
  std::vector<Vec3> nodes(n);
  for (int i = 0; i < n; ++i) {
    const auto l = highorder::triangle_node(degree, i);
    const double u = double(l[0]) / degree, v = double(l[1]) / degree;
    nodes[i] = (1 - u - v) * corners[0] + u * corners[1] + v * corners[2];
  }
  for (int k = 0; k < 3; ++k) nodes[k] = corners[k]; // bit-exact corners
  return nodes;
}

void set_flat_middle(Shell& s, int degree) {
  s.middle_degree = degree;
  s.middle_nodes.clear();
  if (degree <= 1) return;
  s.middle_nodes.reserve(s.faces.size());
  for (const auto& f : s.faces) s.middle_nodes.push_back(flat_triangle_nodes({s.middle[f[0]], s.middle[f[1]], s.middle[f[2]]}, degree));
}

mesh::SurfaceMesh bottom_surface(const Shell& s) { return surface_of(s.bottom, s); }
mesh::SurfaceMesh middle_surface(const Shell& s) { return surface_of(s.middle, s); }
mesh::SurfaceMesh top_surface(const Shell& s) { return surface_of(s.top, s); }

} // namespace curvetet::shell
