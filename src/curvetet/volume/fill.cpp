#include "curvetet/volume/fill.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/volume/background.hpp"
#include "curvetet/volume/bsp_insert.hpp"
#include "curvetet/volume/face_recovery.hpp"
#include "curvetet/volume/mesh_keys.hpp"
#include "curvetet/volume/optimize.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <unordered_map>

namespace curvetet::volume {

const char* to_string(FillReject r) {
  switch (r) {
    case FillReject::frozen: return "frozen";
    case FillReject::topology: return "topology";
    case FillReject::duplicate_entity: return "duplicate_entity";
    case FillReject::link_condition: return "link_condition";
    case FillReject::energy: return "energy";
    case FillReject::frozen_tet_energy: return "frozen_tet_energy";
    case FillReject::sizing: return "sizing";
    case FillReject::no_gain: return "no_gain";
    case FillReject::positivity: return "positivity";
  }
  return "?";
}

nlohmann::json FillStats::rejected_json() const {
  nlohmann::json out = nlohmann::json::object();
  for (int r = 0; r < kFillRejectReasons; ++r) out[to_string(static_cast<FillReject>(r))] = rejected[r];
  return out;
}
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Vertices of `tris` strictly inside segment xy, ordered from x to y.
std::vector<int> chain_on_segment(const exact::Vertices& v, int x, int y,
                                  const std::vector<std::array<int, 3>>& tris) {
  if (tris.size() == 1) return {x, y}; // the triangle itself (most of them)
  std::vector<int> cand;
  for (const auto& t : tris)
    for (int i : t)
      if (i != x && i != y) cand.push_back(i);
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  mpq_class d[3];
  for (int k = 0; k < 3; ++k) d[k] = v.q[y].c[k] - v.q[x].c[k];
  const mpq_class dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  std::vector<std::pair<mpq_class, int>> on;
  for (int i : cand) {
    mpq_class r[3];
    for (int k = 0; k < 3; ++k) r[k] = v.q[i].c[k] - v.q[x].c[k];
    if (d[1] * r[2] != d[2] * r[1] || d[2] * r[0] != d[0] * r[2] || d[0] * r[1] != d[1] * r[0]) continue;
    mpq_class t = d[0] * r[0] + d[1] * r[1] + d[2] * r[2];
    if (sgn(t) > 0 && t < dd) on.emplace_back(t, i);
  }
  std::sort(on.begin(), on.end());
  std::vector<int> out{x};
  for (auto& p : on) out.push_back(p.second);
  out.push_back(y);
  return out;
}

} // namespace

mesh::LinearTetMesh fill_layered(const LayeredSurface& s, const FillOptions& options, FillStats* stats_out) {
  FillStats stats;
  const int n = s.surface.num_vertices();
  const auto& faces = s.surface.faces;
  auto t0 = std::chrono::steady_clock::now();

  std::vector<int> layer_face;
  const auto layer = layer_tets(s, &layer_face);

  // Background: offset vertices (id v = offset of v) + box corners.
  BackgroundMesh bg;
  std::vector<mesh::Vec3> pts = s.offset;
  std::vector<mesh::Vec3> around = s.offset;
  around.insert(around.end(), s.surface.vertices.begin(), s.surface.vertices.end());
  const Box box = padded_box(around, options.box_margin);
  const Eigen::Vector3d lo = box.lo, hi = box.hi;
  // The inside needs no box: the offset surface lies in its vertices' hull.
  const bool inward = s.side == OffsetSide::inward;
  if (!inward) append_box_points(box, pts);
  bg = delaunay(pts);
  logger().debug("volume: background Delaunay of {} points in {:.3f} s", pts.size(), seconds_since(t0));
  stats.background_tets = bg.tets.size();
  // Flips recover most offset triangles that are not Delaunay faces (on
  // cheese_genus133, 5647 of 6954): each one recovered is one triangle less
  // to cut in, and the cuts' rational vertices are what the optimizer then
  // spends its time collapsing (260k exact tets to 105k there).
  if (pts.size() < static_cast<std::size_t>(kMaxFaceKeyId)) { // see face_key
    std::vector<int> missing;
    triangle_faces(bg, faces, &missing);
    const auto flips_start = std::chrono::steady_clock::now();
    if (!missing.empty()) bg = recover_triangles(bg, faces, missing);
    logger().debug("volume: {} offset triangles not in the background Delaunay, flips tried in {:.3f} s",
                   missing.size(), seconds_since(flips_start));
  }

  auto ins = exact::insert_surface(bg, faces, inward ? 1 : 0);
  stats.bsp_cuts = ins.num_cuts;
  stats.bsp_cells = ins.num_cells;
  stats.seconds_insert = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();

  // Output ids: surface vertices first; complex vertices on demand.
  exact::ExactTetMesh m;
  for (const auto& p : s.surface.vertices) m.v.add(p);
  std::vector<int> id_of(ins.vertices.size(), -1);
  for (int v = 0; v < n; ++v)
    if (s.pinched(v)) id_of[v] = v;
  auto id = [&](int c) {
    if (id_of[c] < 0) {
      id_of[c] = ins.vertices.exact[c] ? m.v.add(ins.vertices.d[c]) : m.v.add(ins.vertices.q[c]);
    }
    return id_of[c];
  };
  auto add_tet = [&](std::array<int, 4> t) {
    const int o = m.v.orient(t[0], t[1], t[2], t[3]);
    if (o == 0) throw Error(ExitCode::internal, "volume: flat tet while filling the layer");
    if (o < 0) std::swap(t[0], t[1]);
    m.tets.push_back(t);
  };
  for (const auto& t : ins.tets) m.tets.push_back({id(t[0]), id(t[1]), id(t[2]), id(t[3])});

  // Layer: layer ids (v < n surface, n + v offset of v) -> complex ids.
  auto complex_of_layer = [&](int l) { return l < n ? l : l - n; }; // only for offset ends
  std::unordered_map<std::uint64_t, std::vector<int>> chains; // complex edge -> chain (complex ids)
  auto chain = [&](int f, int cx, int cy) -> const std::vector<int>& {
    const std::uint64_t key =
        (static_cast<std::uint64_t>(std::min(cx, cy)) << 32) | static_cast<std::uint32_t>(std::max(cx, cy));
    auto it = chains.find(key);
    if (it == chains.end())
      it = chains.emplace(key, chain_on_segment(ins.vertices, std::min(cx, cy), std::max(cx, cy), ins.refined[f])).first;
    return it->second;
  };
  for (std::size_t k = 0; k < layer.size(); ++k) {
    const auto& t = layer[k];
    const int f = layer_face[k];
    std::array<int, 3> E;
    for (int i = 0; i < 3; ++i) E[i] = offset_id(s, faces[f][i]);
    std::vector<int> on, off;
    for (int x : t) (std::find(E.begin(), E.end(), x) != E.end() ? on : off).push_back(x);
    auto out_id = [&](int l) { return l < n ? l : id(l - n); };
    if (on.size() == 3) {
      const int apex = out_id(off[0]);
      for (const auto& tri : ins.refined[f]) add_tet({id(tri[0]), id(tri[1]), id(tri[2]), apex});
    } else if (on.size() == 2) {
      const auto& c = chain(f, complex_of_layer(on[0]), complex_of_layer(on[1]));
      for (std::size_t i = 0; i + 1 < c.size(); ++i) add_tet({out_id(off[0]), out_id(off[1]), id(c[i]), id(c[i + 1])});
    } else {
      std::array<int, 4> o;
      for (int i = 0; i < 4; ++i) o[i] = out_id(t[i]);
      add_tet(o);
    }
  }
  // Steiner points on pinched surface edges and faces (the offset coincides
  // with the surface there): they must be collapsed away (optimize.cpp).
  {
    std::map<int, std::vector<int>> targets_of; // ordered: deterministic
    auto pinched_face = [&](int f) { return s.pinched(faces[f][0]) && s.pinched(faces[f][1]) && s.pinched(faces[f][2]); };
    // A vertex on a pinched edge may only slide along it (the faces on both
    // sides stay flat); a vertex inside a pinched face may go to any vertex
    // of that face.
    for (int f = 0; f < s.surface.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = faces[f][k], b = faces[f][(k + 1) % 3];
        if (!s.pinched(a) || !s.pinched(b)) continue;
        const auto& c = chain(f, a, b); // complex ids a, b are the pinched vertices themselves
        if (c.size() == 2) continue;
        std::vector<int> ids;
        for (int x : c) ids.push_back(id(x));
        for (int x : ids)
          if (x >= n) targets_of[x].insert(targets_of[x].end(), ids.begin(), ids.end());
      }
    std::set<int> on_edge;
    for (const auto& kv : targets_of) on_edge.insert(kv.first);
    for (int f = 0; f < s.surface.num_faces(); ++f) {
      if (!pinched_face(f)) continue;
      std::vector<int> all;
      for (const auto& tri : ins.refined[f])
        for (int x : tri) all.push_back(id(x));
      std::sort(all.begin(), all.end());
      all.erase(std::unique(all.begin(), all.end()), all.end());
      for (int x : all)
        if (x >= n && !on_edge.count(x)) targets_of[x].insert(targets_of[x].end(), all.begin(), all.end());
    }
    for (auto& [x, t] : targets_of) {
      std::sort(t.begin(), t.end());
      t.erase(std::unique(t.begin(), t.end()), t.end());
      t.erase(std::remove(t.begin(), t.end(), x), t.end());
      m.on_surface.push_back({x, std::move(t)});
    }
  }
  stats.seconds_layer = seconds_since(t0);

  // Frozen: the surface, and vertices on the box boundary.
  m.frozen.assign(m.v.size(), 0);
  for (int v = 0; v < n; ++v) m.frozen[v] = 1;
  for (int v = n; v < m.v.size() && !inward; ++v)
    for (int k = 0; k < 3; ++k)
      if (m.v.q[v].c[k] == lo[k] || m.v.q[v].c[k] == hi[k]) m.frozen[v] = 1;
  stats.exact_tets = m.tets.size();
  stats.exact_vertices = m.v.size();
  for (char e : m.v.exact) stats.rational_vertices += !e;
  logger().debug("volume: {} background tets, {} cuts, {} cells, {} exact tets ({} rational of {} vertices)",
                 stats.background_tets, stats.bsp_cuts, stats.bsp_cells, stats.exact_tets, stats.rational_vertices,
                 stats.exact_vertices);

  t0 = std::chrono::steady_clock::now();
  auto out = exact::round_and_optimize(std::move(m), n, options, stats);
  stats.seconds_optimize = seconds_since(t0);
  const int tag = inward ? 1 : 2;
  out.tags.assign(out.tets.size(), tag);
  if (stats_out) *stats_out = stats;
  return out;
}

} // namespace curvetet::volume
