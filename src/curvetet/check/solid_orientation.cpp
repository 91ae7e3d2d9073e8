#include "curvetet/check/solid_orientation.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <functional>
#include <stdexcept>

namespace curvetet::check {

std::vector<ComponentOrientation> solid_orientation(const mesh::SurfaceMesh& m) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SM = CGAL::Surface_mesh<K::Point_3>;
  namespace PMP = CGAL::Polygon_mesh_processing;

  SM sm;
  std::vector<SM::Vertex_index> vid;
  vid.reserve(m.vertices.size());
  for (const auto& p : m.vertices) vid.push_back(sm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
  for (const auto& f : m.faces)
    if (sm.add_face(vid[f[0]], vid[f[1]], vid[f[2]]) == SM::null_face())
      throw std::logic_error("solid_orientation: mesh is not an oriented manifold");
  // Isolated vertices would trip CGAL's closedness precondition.
  for (auto v : sm.vertices())
    if (sm.is_isolated(v)) sm.remove_vertex(v);

  auto volume_map = sm.add_property_map<SM::Face_index, std::size_t>("f:volume", 0).first;
  auto cc_map = sm.add_property_map<SM::Face_index, std::size_t>("f:cc", 0).first;
  std::vector<std::size_t> nesting;
  std::vector<bool> outward;
  PMP::volume_connected_components(sm, volume_map,
                                   CGAL::parameters::face_connected_component_map(cc_map)
                                       .nesting_levels(std::ref(nesting))
                                       .is_cc_outward_oriented(std::ref(outward)));

  // Surface_mesh faces are numbered in insertion order = our face ids.
  std::vector<ComponentOrientation> out(nesting.size(), ComponentOrientation{-1, 0, true});
  for (auto f : sm.faces()) {
    auto cc = cc_map[f];
    auto& c = out[cc];
    if (c.first_face < 0) c = {static_cast<int>(f.idx()), static_cast<int>(nesting[cc]), bool(outward[cc])};
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first_face < y.first_face; });
  return out;
}

} // namespace curvetet::check
