#include "curvetet/volume/background.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/geometry/predicates.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/intersections.h>

#include <algorithm>

namespace curvetet::volume {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;
K::Point_3 cg(const mesh::Vec3& p) { return {p.x(), p.y(), p.z()}; }
// Conservative: false only when a plane of the tet's faces or the
// triangle's plane separates them (exact orient3d); callers accept extra
// pairs (they only cost a later exact test).
bool may_meet(const std::vector<mesh::Vec3>& p, const std::array<int, 4>& t, const mesh::Tri& f) {
  for (int k = 0; k < 4; ++k) {
    const int a = t[(k + 1) % 4], b = t[(k + 2) % 4], c = t[(k + 3) % 4];
    const int inner = geometry::orient3d(p[a], p[b], p[c], p[t[k]]);
    bool all_out = true;
    for (int x : f)
      if (x == a || x == b || x == c || geometry::orient3d(p[a], p[b], p[c], p[x]) != -inner) { // inside or on
        all_out = false;
        break;
      }
    if (all_out) return false;
  }
  int pos = 0, neg = 0;
  for (int x : t) {
    if (x == f[0] || x == f[1] || x == f[2]) continue; // on the plane
    const int s = geometry::orient3d(p[f[0]], p[f[1]], p[f[2]], p[x]);
    pos += s > 0;
    neg += s < 0;
  }
  return !(pos == 4 || neg == 4);
}

} // namespace

BackgroundMesh delaunay(const std::vector<mesh::Vec3>& points) {
  std::vector<std::pair<K::Point_3, int>> input;
  input.reserve(points.size());
  for (int i = 0; i < static_cast<int>(points.size()); ++i) input.emplace_back(cg(points[i]), i);
  Delaunay dt(input.begin(), input.end());
  if (dt.number_of_vertices() != points.size())
    throw Error(ExitCode::internal, "volume: background points are not pairwise distinct");
  if (dt.dimension() != 3) throw Error(ExitCode::internal, "volume: background points are coplanar");
  BackgroundMesh bg;
  bg.points = points;
  bg.tets.reserve(dt.number_of_finite_cells());
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c)
    bg.tets.push_back({c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()});
  return bg;
}

std::vector<std::vector<int>> triangles_meeting_tets(const BackgroundMesh& bg, const std::vector<mesh::Tri>& triangles) {
  const auto& p = bg.points;
  std::vector<geometry::Box3> tet_boxes, tri_boxes;
  tet_boxes.reserve(bg.tets.size());
  for (const auto& t : bg.tets) {
    auto b = geometry::bounding_box(p[t[0]], p[t[1]], p[t[2]]);
    b.min = b.min.cwiseMin(p[t[3]]);
    b.max = b.max.cwiseMax(p[t[3]]);
    tet_boxes.push_back(b);
  }
  tri_boxes.reserve(triangles.size());
  for (const auto& t : triangles) tri_boxes.push_back(geometry::bounding_box(p[t[0]], p[t[1]], p[t[2]]));
  std::vector<std::vector<int>> out(bg.tets.size());
  for (auto [i, j] : geometry::overlapping_pairs(tet_boxes, tri_boxes)) {
    const auto& t = bg.tets[i];
    const auto& f = triangles[j];
    if (may_meet(p, t, f)) out[i].push_back(j);
  }
  for (auto& l : out) std::sort(l.begin(), l.end());
  return out;
}

} // namespace curvetet::volume
