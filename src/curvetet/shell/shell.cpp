#include "curvetet/shell/shell.hpp"

namespace curvetet::shell {

namespace {
mesh::SurfaceMesh surface_of(const std::vector<Vec3>& points, const Shell& s) {
  mesh::SurfaceMesh m;
  m.vertices = points;
  m.faces = s.faces;
  return m;
}
} // namespace

mesh::SurfaceMesh bottom_surface(const Shell& s) { return surface_of(s.bottom, s); }
mesh::SurfaceMesh middle_surface(const Shell& s) { return surface_of(s.middle, s); }
mesh::SurfaceMesh top_surface(const Shell& s) { return surface_of(s.top, s); }

} // namespace curvetet::shell
