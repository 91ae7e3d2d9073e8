#include "curvetet/volume/direct_fill.hpp"

#include "curvetet/check/closest_points.hpp"
#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/volume/background.hpp"
#include "curvetet/volume/cavity_fill.hpp"
#include "curvetet/volume/exact_mesh.hpp"
#include "curvetet/volume/face_recovery.hpp"
#include "curvetet/volume/mesh_keys.hpp"
#include "curvetet/volume/optimize.hpp"

#include <algorithm>
#include <chrono>

namespace curvetet::volume {
namespace {

// A point one mean edge length h inside each vertex (outside, for the
// exterior), along its area-weighted normal, if it keeps at least
// kOffsetClearance × h from the whole surface. On scans the worst Delaunay
// tets are flat ones between four surface vertices; these points give the
// tets at the surface an apex off it. One that would crowd another part of
// the surface is left out (it would make triangles there non-Delaunay), and
// outward, one not strictly inside the box (whose sides must stay the hull).
constexpr double kOffsetClearance = 0.5;
// Up to this fraction of missing triangles, flips are tried before offset
// points are added (above it, on scans, offset points are needed anyway).
constexpr double kFewMissing = 0.01;
void append_offset_points(const mesh::SurfaceMesh& surface, bool inward, const Box& box, std::vector<mesh::Vec3>& pts) {
  const int n = surface.num_vertices();
  std::vector<mesh::Vec3> normal(n, mesh::Vec3::Zero());
  std::vector<double> length(n, 0);
  std::vector<int> count(n, 0);
  for (const auto& f : surface.faces) {
    const auto &a = surface.vertices[f[0]], &b = surface.vertices[f[1]], &c = surface.vertices[f[2]];
    const mesh::Vec3 area = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) {
      normal[f[k]] += area;
      length[f[k]] += (surface.vertices[f[(k + 1) % 3]] - surface.vertices[f[k]]).norm();
      ++count[f[k]];
    }
  }
  std::vector<mesh::Vec3> candidates;
  std::vector<double> depth;
  for (int v = 0; v < n; ++v) {
    const double h = length[v] / std::max(count[v], 1);
    const mesh::Vec3 p = surface.vertices[v] + (inward ? -h : h) * normal[v].normalized();
    const bool in_box = (p.array() > box.lo.array()).all() && (p.array() < box.hi.array()).all();
    if (!p.allFinite() || (!inward && !in_box)) continue;
    candidates.push_back(p);
    depth.push_back(h);
  }
  const auto clearance = check::distances_to_surface(surface, candidates);
  std::vector<mesh::Vec3> clear;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (clearance[i] >= kOffsetClearance * depth[i]) clear.push_back(candidates[i]);
  append_new_points(pts, clear);
}

// Grid points of the surface's bbox, `spacing` apart, at least half of it
// from the surface (those outside end in discarded tets).
void append_interior_points(const mesh::SurfaceMesh& surface, double spacing, std::vector<mesh::Vec3>& pts) {
  mesh::Vec3 lo = surface.vertices.front(), hi = lo;
  for (const auto& p : surface.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3i n = ((hi - lo) / spacing).array().floor().cast<int>();
  const mesh::Vec3 start = 0.5 * (lo + hi) - 0.5 * spacing * n.cast<double>();
  std::vector<mesh::Vec3> grid;
  for (int i = 0; i <= n.x(); ++i)
    for (int j = 0; j <= n.y(); ++j)
      for (int k = 0; k <= n.z(); ++k) grid.push_back(start + spacing * mesh::Vec3(i, j, k));
  const auto clearance = check::distances_to_surface(surface, grid);
  std::vector<mesh::Vec3> clear;
  for (std::size_t i = 0; i < grid.size(); ++i)
    if (clearance[i] >= 0.5 * spacing) clear.push_back(grid[i]);
  append_new_points(pts, clear);
}

} // namespace

std::optional<mesh::LinearTetMesh> fill_direct(const mesh::SurfaceMesh& surface, OffsetSide side,
                                               const FillOptions& options, FillStats* stats_out,
                                               const std::function<void()>& on_scan_like) {
  auto t0 = std::chrono::steady_clock::now();
  const bool inward = side == OffsetSide::inward;
  const int n = surface.num_vertices();
  std::vector<mesh::Vec3> pts = surface.vertices;
  Box box{mesh::Vec3::Zero(), mesh::Vec3::Zero()};
  if (!inward) {
    box = padded_box(surface.vertices, options.box_margin);
    append_box_points(box, pts);
  }
  if (inward && options.interior_spacing > 0) append_interior_points(surface, options.interior_spacing, pts);
  BackgroundMesh bg;
  std::vector<std::array<int, 4>> face_of;
  FillStats stats;
  std::vector<int> missing;
  auto tetrahedralize_points = [&] {
    if (pts.size() >= static_cast<std::size_t>(kMaxFaceKeyId)) return false; // see face_key
    bg = delaunay(pts);
    face_of = triangle_faces(bg, surface.faces, &missing);
    stats.missing_triangles = missing.size();
    stats.recovered_by_flips = 0;
    return true;
  };
  auto recover_by_flips = [&] {
    if (missing.empty()) return;
    bg = recover_triangles(bg, surface.faces, missing);
    face_of = triangle_faces(bg, surface.faces, &missing);
    stats.recovered_by_flips = stats.missing_triangles - missing.size();
    logger().debug("volume: {} of {} missing surface triangles recovered by flips", stats.recovered_by_flips,
                   stats.missing_triangles);
  };
  // The surface's own vertices first: on CAD surfaces every triangle, or all
  // but a few that flips recover, is a Delaunay face. Elsewhere (scans), the
  // offset points join them (they also keep the tets at the surface off it),
  // and interior points stand in for the triangles flips cannot recover,
  // each the apex of a cone that fills part of a cavity.
  if (!tetrahedralize_points()) return std::nullopt;
  if (missing.size() <= kFewMissing * surface.faces.size()) recover_by_flips();
  if (!missing.empty()) {
    if (on_scan_like) on_scan_like();
    const auto before = pts.size();
    append_offset_points(surface, inward, box, pts);
    stats.offset_points = pts.size() - before;
    if (!tetrahedralize_points()) return std::nullopt;
    recover_by_flips();
  }
  const auto side_tets = volume::side_tets(bg, surface.faces, face_of, missing, inward);
  if (!side_tets) {
    logger().info("volume: {} surface triangles are not Delaunay faces and no cone closes around them: "
                  "taking the layered fill (slower)",
                  missing.size());
    return std::nullopt;
  }
  stats.cones = side_tets->steiner.size();
  pts.insert(pts.end(), side_tets->steiner.begin(), side_tets->steiner.end());

  exact::ExactTetMesh m;
  for (const auto& p : surface.vertices) m.v.add(p);
  std::vector<int> id(pts.size(), -1);
  for (int v = 0; v < n; ++v) id[v] = v;
  for (const auto& t : side_tets->tets) {
    std::array<int, 4> q;
    for (int k = 0; k < 4; ++k) {
      int& x = id[t[k]];
      if (x < 0) x = m.v.add(pts[t[k]]);
      q[k] = x;
    }
    m.tets.push_back(q);
  }
  // Frozen: the surface, and the box boundary (its grid points are free).
  m.frozen.assign(m.v.size(), 0);
  for (int v = 0; v < m.v.size(); ++v)
    for (int k = 0; k < 3; ++k)
      if (v < n || (!inward && (m.v.d[v][k] == box.lo[k] || m.v.d[v][k] == box.hi[k]))) m.frozen[v] = 1;

  stats.background_tets = bg.tets.size();
  stats.exact_tets = m.tets.size();
  stats.exact_vertices = m.v.size();
  stats.direct = true;
  stats.seconds_insert = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  logger().debug("volume: {} tets to optimize ({} Delaunay tets, {} cones)", m.tets.size(), bg.tets.size(),
                 stats.cones);
  t0 = std::chrono::steady_clock::now();
  auto out = exact::round_and_optimize(std::move(m), n, options, stats);
  stats.seconds_optimize = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.tags.assign(out.tets.size(), inward ? 1 : 2);
  if (stats_out) *stats_out = stats;
  return out;
}

} // namespace curvetet::volume
