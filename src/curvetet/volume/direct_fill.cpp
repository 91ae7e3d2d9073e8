#include "curvetet/volume/direct_fill.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/volume/background.hpp"
#include "curvetet/volume/exact_mesh.hpp"
#include "curvetet/volume/face_recovery.hpp"
#include "curvetet/volume/mesh_keys.hpp"
#include "curvetet/volume/optimize.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <limits>
#include <unordered_map>

namespace curvetet::volume {
namespace {

// At most this many missing triangles are worth an attempt at recovery.
constexpr std::size_t kMaxRecoveries = 1000;

// Winding number of every tet by crossing surface faces from the outside
// (0): +1 when going against the face's outward normal. Throws if two paths
// disagree (the surface would not be closed and oriented).
std::vector<int> windings(const BackgroundMesh& bg, const std::vector<mesh::Tri>& faces,
                          const std::vector<std::array<int, 4>>& face_of) {
  const int nt = static_cast<int>(bg.tets.size());
  constexpr int kUnset = std::numeric_limits<int>::min();
  std::vector<int> w(nt, kUnset);
  std::deque<int> queue;
  // Winding change when entering tet t through its face opposite corner k.
  auto entering = [&](int t, int k) {
    const int f = face_of[t][k];
    if (f < 0) return 0;
    const auto& tri = faces[f];
    const auto& p = bg.points;
    // t lies behind the face (inside) iff its corner k is on the negative side.
    return geometry::orient3d(p[tri[0]], p[tri[1]], p[tri[2]], p[bg.tets[t][k]]) < 0 ? 1 : -1;
  };
  auto assign = [&](int t, int value) {
    if (w[t] == kUnset) {
      w[t] = value;
      queue.push_back(t);
    } else if (w[t] != value) {
      throw Error(ExitCode::internal, fmt::format("volume: inconsistent winding numbers at tet {}", t));
    }
  };
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 4; ++k)
      if (bg.neighbours[t][k] < 0) assign(t, entering(t, k));
  while (!queue.empty()) {
    const int t = queue.front();
    queue.pop_front();
    for (int k = 0; k < 4; ++k) {
      const int n = bg.neighbours[t][k];
      if (n < 0) continue;
      int j = 0;
      while (bg.neighbours[n][j] != t) ++j;
      assign(n, w[t] + entering(n, j));
    }
  }
  return w;
}

} // namespace

std::optional<mesh::LinearTetMesh> fill_direct(const mesh::SurfaceMesh& surface, OffsetSide side,
                                               const FillOptions& options, FillStats* stats_out) {
  auto t0 = std::chrono::steady_clock::now();
  const bool inward = side == OffsetSide::inward;
  const int n = surface.num_vertices();
  std::vector<mesh::Vec3> pts = surface.vertices;
  Box box{mesh::Vec3::Zero(), mesh::Vec3::Zero()};
  if (!inward) {
    box = padded_box(surface.vertices, options.box_margin);
    append_box_points(box, pts);
  }
  if (pts.size() >= static_cast<std::size_t>(kMaxFaceKeyId)) return std::nullopt; // see face_key
  BackgroundMesh bg = delaunay(pts);

  // Which tet faces are surface triangles; every triangle must be one.
  std::unordered_map<std::uint64_t, int> triangle_of;
  triangle_of.reserve(2 * surface.faces.size());
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto& t = surface.faces[f];
    triangle_of.emplace(face_key(t[0], t[1], t[2]), f);
  }
  std::vector<std::array<int, 4>> face_of;
  auto missing_triangles = [&] {
    face_of.assign(bg.tets.size(), {-1, -1, -1, -1});
    std::vector<char> found(surface.faces.size(), 0);
    for (std::size_t t = 0; t < bg.tets.size(); ++t)
      for (int k = 0; k < 4; ++k) {
        const auto& q = bg.tets[t];
        const auto it = triangle_of.find(face_key(q[(k + 1) % 4], q[(k + 2) % 4], q[(k + 3) % 4]));
        if (it == triangle_of.end()) continue;
        face_of[t][k] = it->second;
        found[it->second] = 1;
      }
    std::vector<int> out;
    for (int f = 0; f < surface.num_faces(); ++f)
      if (!found[f]) out.push_back(f);
    return out;
  };
  auto missing = missing_triangles();
  // A few missing triangles (flat CAD faces: co-circular points) are
  // recovered by flips; more mean a surface the layered fill suits.
  if (!missing.empty() && missing.size() <= kMaxRecoveries) {
    bg = recover_triangles(bg, surface.faces, missing);
    const auto before = missing.size();
    missing = missing_triangles();
    logger().debug("volume: {} of {} missing surface triangles recovered by flips", before - missing.size(), before);
  }
  if (!missing.empty()) {
    logger().debug("volume: {} of {} surface triangles are not Delaunay faces: layered fill", missing.size(),
                   surface.num_faces());
    return std::nullopt;
  }
  const int nt = static_cast<int>(bg.tets.size());

  const auto w = windings(bg, surface.faces, face_of);
  const int keep = inward ? 1 : 0;
  exact::ExactTetMesh m;
  for (const auto& p : surface.vertices) m.v.add(p);
  std::vector<int> id(pts.size(), -1);
  for (int v = 0; v < n; ++v) id[v] = v;
  for (int t = 0; t < nt; ++t) {
    if (w[t] != keep) continue;
    std::array<int, 4> q;
    for (int k = 0; k < 4; ++k) {
      int& x = id[bg.tets[t][k]];
      if (x < 0) x = m.v.add(pts[bg.tets[t][k]]);
      q[k] = x;
    }
    m.tets.push_back(q);
  }
  // Frozen: the surface, and the box boundary (its grid points are free).
  m.frozen.assign(m.v.size(), 0);
  for (int v = 0; v < m.v.size(); ++v)
    for (int k = 0; k < 3; ++k)
      if (v < n || m.v.d[v][k] == box.lo[k] || m.v.d[v][k] == box.hi[k]) m.frozen[v] = 1;

  FillStats stats;
  stats.background_tets = bg.tets.size();
  stats.exact_tets = m.tets.size();
  stats.exact_vertices = m.v.size();
  stats.direct = true;
  stats.seconds_insert = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  logger().debug("volume: every surface triangle is a face: {} of {} tets kept, no Steiner point",
                 m.tets.size(), bg.tets.size());
  t0 = std::chrono::steady_clock::now();
  auto out = exact::round_and_optimize(std::move(m), n, options, stats);
  stats.seconds_optimize = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.tags.assign(out.tets.size(), inward ? 1 : 2);
  if (stats_out) *stats_out = stats;
  return out;
}

} // namespace curvetet::volume
