#include "curvetet/map/build_map.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/shell/prism_geometry.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>

namespace curvetet::map {
namespace {

using Key = std::array<double, 3>;
Key key(const mesh::Vec3& p) { return {p.x(), p.y(), p.z()}; }

// Where boundary triangle b sits on the shell: face f, and the rotation r
// with triangle corner j = faces[f][(j + r) % 3].
struct Placement {
  int face = -1, rotation = 0;
};

std::vector<Placement> place_triangles(const shell::Shell& s, const mesh::TetMesh& m) {
  std::map<Key, int> vertex_at;
  for (int v = 0; v < s.num_vertices(); ++v) vertex_at.emplace(key(s.middle[v]), v);
  std::map<std::array<int, 3>, int> face_of;
  for (int f = 0; f < s.num_prisms(); ++f) {
    auto sorted = s.faces[f];
    std::sort(sorted.begin(), sorted.end());
    face_of.emplace(sorted, f);
  }
  std::vector<Placement> out(m.num_boundary());
  std::vector<int> seen(s.num_prisms(), -1);
  for (int b = 0; b < m.num_boundary(); ++b) {
    std::array<int, 3> corner;
    for (int j = 0; j < 3; ++j) {
      const auto it = vertex_at.find(key(m.nodes[m.boundary_triangle(b)[j]]));
      if (it == vertex_at.end()) throw Error(ExitCode::internal, fmt::format("map: boundary triangle {} has a corner on no shell vertex", b));
      corner[j] = it->second;
    }
    auto sorted = corner;
    std::sort(sorted.begin(), sorted.end());
    const auto it = face_of.find(sorted);
    if (it == face_of.end()) throw Error(ExitCode::internal, fmt::format("map: boundary triangle {} matches no shell face", b));
    const int f = it->second;
    int r = 0;
    while (r < 3 && s.faces[f][r] != corner[0]) ++r;
    if (s.faces[f][(1 + r) % 3] != corner[1]) throw Error(ExitCode::internal, fmt::format("map: boundary triangle {} is reversed against shell face {}", b, f));
    if (seen[f] >= 0) throw Error(ExitCode::internal, fmt::format("map: shell face {} is boundary triangles {} and {}", f, seen[f], b));
    seen[f] = b;
    out[b] = {f, r};
  }
  for (int f = 0; f < s.num_prisms(); ++f)
    if (seen[f] < 0) throw Error(ExitCode::internal, fmt::format("map: shell face {} has no boundary triangle", f));
  return out;
}

// Barycentric (1-u-v, u, v) between the face frame and the triangle frame.
std::array<double, 3> face_to_triangle(const std::array<double, 3>& l, int r) {
  return {l[r % 3], l[(1 + r) % 3], l[(2 + r) % 3]};
}
std::array<double, 3> triangle_to_face(const std::array<double, 3>& t, int r) {
  std::array<double, 3> l;
  for (int j = 0; j < 3; ++j) l[(j + r) % 3] = t[j];
  return l;
}

// Barycentric (u, v) of x on triangle (a, b, c), projected into the closed
// triangle (Π⁻¹ hits lie inside up to fiber_hit's 1e-9 slack).
mesh::SurfacePoint barycentric_on(int face, const mesh::Vec3& x, const mesh::Vec3& a, const mesh::Vec3& b, const mesh::Vec3& c) {
  const mesh::Vec3 n = (b - a).cross(c - a);
  const double area = n.squaredNorm();
  double lb = n.dot((x - a).cross(c - a)) / area, lc = n.dot((b - a).cross(x - a)) / area;
  double la = 1 - lb - lc;
  la = std::max(la, 0.0), lb = std::max(lb, 0.0), lc = std::max(lc, 0.0);
  const double sum = la + lb + lc;
  return {face, lb / sum, lc / sum};
}

} // namespace

mesh::BoundaryMap build_boundary_map(const shell::Shell& s, const mesh::TetMesh& m, MapBuildStats* stats_out) {
  const auto placement = place_triangles(s, m);
  mesh::BoundaryMap out;
  out.order = m.order;
  out.input = s.input;
  const int per = m.triangle_nodes(), P = m.order;

  // Distinct boundary nodes in order of first use; every use remembered so a
  // fiber that grazes one face's edge can be retried from the neighbour.
  std::vector<int> local(m.nodes.size(), -1);
  std::vector<std::vector<std::pair<int, int>>> uses; // (triangle, local node)
  for (int b = 0; b < m.num_boundary(); ++b)
    for (int i = 0; i < per; ++i) {
      const int g = m.boundary_triangle(b)[i];
      if (local[g] < 0) {
        local[g] = static_cast<int>(out.nodes.size());
        out.nodes.push_back(m.nodes[g]);
        out.node_ids.push_back(g);
        uses.emplace_back();
      }
      out.triangles.push_back(local[g]);
      uses[local[g]].emplace_back(b, i);
    }

  // φ: input vertices.
  const int nv = static_cast<int>(s.input.vertices.size());
  std::vector<int> triangle_of(s.num_prisms());
  for (int b = 0; b < m.num_boundary(); ++b) triangle_of[placement[b].face] = b;
  out.vertex_to_boundary.resize(nv);
  for (int i = 0; i < nv; ++i) {
    const auto& img = s.points[i].image;
    if (img.prism < 0 || img.prism >= s.num_prisms()) throw Error(ExitCode::internal, fmt::format("map: input vertex {} has no image", i));
    const int b = triangle_of[img.prism];
    const auto t = face_to_triangle({1 - img.u - img.v, img.u, img.v}, placement[b].rotation);
    out.vertex_to_boundary[i] = {b, t[1], t[2]};
  }

  // φ⁻¹: boundary nodes, independent of each other (parallel; the result
  // does not depend on the thread count).
  MapBuildStats stats;
  stats.nodes = static_cast<int>(out.nodes.size());
  stats.triangles = m.num_boundary();
  std::vector<shell::PrismGeom> geom(s.num_prisms());
  for (int f = 0; f < s.num_prisms(); ++f) geom[f] = shell::prism_geom(s, f);
  out.node_to_input.resize(out.nodes.size());
  std::vector<double> depth_of(out.nodes.size(), std::numeric_limits<double>::infinity());
  std::vector<char> fallback(out.nodes.size(), 0);
  tbb::parallel_for(std::size_t(0), out.nodes.size(), [&](std::size_t j) {
    bool found = false;
    for (std::size_t k = 0; k < uses[j].size() && !found; ++k) {
      const auto [b, i] = uses[j][k];
      const auto q = highorder::triangle_node(P, i);
      const double tu = double(q[0]) / P, tv = double(q[1]) / P;
      const auto l = triangle_to_face({1 - tu - tv, tu, tv}, placement[b].rotation);
      const int f = placement[b].face;
      double best = -std::numeric_limits<double>::infinity();
      for (int t : s.tracked[f]) {
        // Π⁻¹ lands on M̄; the same barycentric point of M is φ⁻¹ (β⁻¹).
        const auto [A, B, C] = shell::straight_triangle(s, t);
        double depth = 0;
        const auto hit = shell::fiber_hit(geom[f], l[1], l[2], A, B, C, &depth);
        if (hit && depth > best) {
          best = depth;
          out.node_to_input[j] = barycentric_on(t, *hit, A, B, C);
          found = true;
        }
      }
      if (found) {
        depth_of[j] = best;
        fallback[j] = k > 0;
      }
    }
  });
  for (std::size_t j = 0; j < out.nodes.size(); ++j) {
    if (out.node_to_input[j].face < 0)
      throw Error(ExitCode::internal, fmt::format("map: the fiber of boundary node {} (mesh node {}) meets no tracked input face", j, out.node_ids[j]));
    stats.node_fallbacks += fallback[j];
  }
  stats.min_hit_depth = depth_of.empty() ? 0 : *std::min_element(depth_of.begin(), depth_of.end());
  if (stats_out) *stats_out = stats;
  return out;
}

} // namespace curvetet::map
