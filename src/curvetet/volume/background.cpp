#include "curvetet/volume/background.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/volume/mesh_keys.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <set>
#include <unordered_map>

namespace curvetet::volume {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Cb = CGAL::Triangulation_cell_base_with_info_3<int, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, CGAL::Delaunay_triangulation_cell_base_3<K, Cb>>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;
K::Point_3 cg(const mesh::Vec3& p) { return {p.x(), p.y(), p.z()}; }
// Conservative: false only when a plane of the tet's faces or the
// triangle's plane separates them (exact orient3d); callers accept extra
// pairs (they only cost a later exact test). With `interior`, "meet" means
// meeting the triangle's relative interior: a plane that the two only share
// corners of the triangle in (one of them, or an edge) also separates them.
bool may_meet(const std::vector<mesh::Vec3>& p, const std::array<int, 4>& t, const mesh::Tri& f, bool interior) {
  auto is_corner = [&](int x) { return x == f[0] || x == f[1] || x == f[2]; };
  for (int k = 0; k < 4; ++k) {
    const int a = t[(k + 1) % 4], b = t[(k + 2) % 4], c = t[(k + 3) % 4];
    const int inner = geometry::orient3d(p[a], p[b], p[c], p[t[k]]);
    int out = 0, on = 0;
    for (int x : f) {
      const int s = x == a || x == b || x == c ? 0 : geometry::orient3d(p[a], p[b], p[c], p[x]);
      out += s == -inner;
      on += s == 0;
    }
    if (out == 3 || (interior && out > 0 && out + on == 3)) return false;
  }
  int pos = 0, neg = 0, corners = 0, off_corner_on = 0;
  for (int x : t) {
    const int s = is_corner(x) ? 0 : geometry::orient3d(p[f[0]], p[f[1]], p[f[2]], p[x]);
    pos += s > 0;
    neg += s < 0;
    corners += is_corner(x);
    off_corner_on += s == 0 && !is_corner(x);
  }
  if (pos == 4 || neg == 4) return false;
  // Touching the plane only at one or two corners of the triangle misses
  // its interior.
  return !(interior && (pos == 0 || neg == 0) && off_corner_on == 0 && corners < 3);
}

} // namespace

// neighbours[t][k] = tet across the face opposite corner k (-1: none).
std::vector<std::array<int, 4>> face_neighbours(const std::vector<std::array<int, 4>>& tets) {
  std::unordered_map<std::uint64_t, std::pair<int, int>> open; // sorted face -> (tet, corner)
  std::vector<std::array<int, 4>> nb(tets.size(), {-1, -1, -1, -1});
  for (int t = 0; t < static_cast<int>(tets.size()); ++t)
    for (int k = 0; k < 4; ++k) {
      const std::uint64_t key = face_key(tets[t][(k + 1) % 4], tets[t][(k + 2) % 4], tets[t][(k + 3) % 4]);
      auto [it, fresh] = open.try_emplace(key, t, k);
      if (!fresh) {
        nb[t][k] = it->second.first;
        nb[it->second.first][it->second.second] = t;
      }
    }
  return nb;
}

Box padded_box(const std::vector<mesh::Vec3>& around, double margin) {
  Eigen::Vector3d lo = around[0], hi = around[0];
  for (const auto& p : around) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double pad = std::max(margin, 1e-3) * (hi - lo).norm();
  lo.array() -= pad;
  hi.array() += pad;
  return {lo, hi};
}

void append_new_points(std::vector<mesh::Vec3>& pts, const std::vector<mesh::Vec3>& extra) {
  std::set<std::array<double, 3>> taken;
  for (const auto& p : pts) taken.insert({p.x(), p.y(), p.z()});
  for (const auto& p : extra)
    if (taken.insert({p.x(), p.y(), p.z()}).second) pts.push_back(p);
}

void append_box_points(const Box& box, std::vector<mesh::Vec3>& pts) {
  const auto &lo = box.lo, &hi = box.hi;
  std::vector<mesh::Vec3> extra;
  for (int c = 0; c < 8; ++c)
    extra.emplace_back(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y(), c & 4 ? hi.z() : lo.z());
  constexpr int kGrid = 8;
  for (int i = 1; i < kGrid; ++i)
    for (int j = 1; j < kGrid; ++j)
      for (int k = 1; k < kGrid; ++k) extra.push_back(lo + (hi - lo).cwiseProduct(mesh::Vec3(i, j, k) / kGrid));
  append_new_points(pts, extra);
}

std::vector<std::array<int, 4>> triangle_faces(const BackgroundMesh& bg, const std::vector<mesh::Tri>& triangles,
                                              std::vector<int>* missing) {
  std::unordered_map<std::uint64_t, int> triangle_of;
  triangle_of.reserve(2 * triangles.size());
  for (int f = 0; f < static_cast<int>(triangles.size()); ++f) {
    const auto& t = triangles[f];
    triangle_of.emplace(face_key(t[0], t[1], t[2]), f);
  }
  std::vector<std::array<int, 4>> face_of(bg.tets.size(), {-1, -1, -1, -1});
  std::vector<char> found(triangles.size(), 0);
  for (std::size_t t = 0; t < bg.tets.size(); ++t)
    for (int k = 0; k < 4; ++k) {
      const auto& q = bg.tets[t];
      const auto it = triangle_of.find(face_key(q[(k + 1) % 4], q[(k + 2) % 4], q[(k + 3) % 4]));
      if (it == triangle_of.end()) continue;
      face_of[t][k] = it->second;
      found[it->second] = 1;
    }
  if (missing) {
    missing->clear();
    for (int f = 0; f < static_cast<int>(triangles.size()); ++f)
      if (!found[f]) missing->push_back(f);
  }
  return face_of;
}

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
  int id = 0;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    c->info() = id++;
    bg.tets.push_back({c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()});
  }
  bg.neighbours.reserve(bg.tets.size());
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    std::array<int, 4> nb;
    for (int k = 0; k < 4; ++k) nb[k] = dt.is_infinite(c->neighbor(k)) ? -1 : c->neighbor(k)->info();
    bg.neighbours.push_back(nb);
  }
  return bg;
}

std::vector<std::vector<int>> triangles_meeting_tets(const BackgroundMesh& bg, const std::vector<mesh::Tri>& triangles,
                                                     bool interior) {
  const auto& p = bg.points;
  const int nt = static_cast<int>(bg.tets.size());
  std::vector<std::array<int, 4>> computed;
  if (bg.neighbours.empty()) computed = face_neighbours(bg.tets);
  const auto& neighbours = bg.neighbours.empty() ? computed : bg.neighbours;
  // Tets around each point (CSR).
  std::vector<int> start(p.size() + 1, 0), star(4 * bg.tets.size());
  for (const auto& t : bg.tets)
    for (int x : t) ++start[x + 1];
  for (std::size_t i = 0; i < p.size(); ++i) start[i + 1] += start[i];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int t = 0; t < nt; ++t)
      for (int x : bg.tets[t]) star[fill[x]++] = t;
  }
  // Walk per triangle; pairs (tet, triangle) come out in triangle order.
  std::vector<int> seen(nt, -1), stack;
  std::vector<std::pair<int, int>> pairs;
  for (int j = 0; j < static_cast<int>(triangles.size()); ++j) {
    const auto& f = triangles[j];
    stack.clear();
    for (int x : f)
      for (int k = start[x]; k < start[x + 1]; ++k)
        if (seen[star[k]] != j) {
          seen[star[k]] = j; // contains a corner: meets the closed triangle
          if (!interior || may_meet(p, bg.tets[star[k]], f, true)) stack.push_back(star[k]);
        }
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      pairs.emplace_back(t, j);
      for (int o : neighbours[t])
        if (o >= 0 && seen[o] != j) {
          seen[o] = j;
          if (may_meet(p, bg.tets[o], f, interior)) stack.push_back(o);
        }
    }
  }
  std::vector<std::vector<int>> out(bg.tets.size());
  for (auto [t, j] : pairs) out[t].push_back(j);
  return out;
}

} // namespace curvetet::volume
