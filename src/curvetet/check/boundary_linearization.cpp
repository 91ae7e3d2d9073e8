#include "curvetet/check/boundary_linearization.hpp"

#include "curvetet/highorder/element_map.hpp"

#include <array>
#include <map>
#include <stdexcept>

namespace curvetet::check {

BoundaryLinearization linearize_boundary(const mesh::TetMesh& m, int s) {
  if (s < 1) throw std::invalid_argument("linearize_boundary: segments_per_edge must be >= 1");
  BoundaryLinearization out;
  auto& verts = out.surface.vertices;
  std::map<int, int> corner_vertex;                      // mesh node -> vertex
  std::map<std::array<int, 3>, int> edge_vertex;         // (lo, hi, step from lo) -> vertex
  const int nt = m.triangle_nodes();
  std::vector<Eigen::Vector3d> nodes(nt);
  std::vector<int> grid((s + 1) * (s + 1));
  auto at = [&](int i, int j) -> int& { return grid[i * (s + 1) + j]; };
  for (int b = 0; b < m.num_boundary(); ++b) {
    const int* tri = m.boundary_triangle(b);
    for (int k = 0; k < nt; ++k) nodes[k] = m.nodes[tri[k]];
    const int corner[3] = {tri[0], tri[1], tri[2]};
    for (int i = 0; i <= s; ++i)
      for (int j = 0; i + j <= s; ++j) {
        // Lattice point (u, v) = (i, j) / s; barycentric (s-i-j, i, j).
        const int l[3] = {s - i - j, i, j};
        int zeros = (l[0] == 0) + (l[1] == 0) + (l[2] == 0);
        auto eval = [&] {
          verts.push_back(highorder::triangle_point(m.order, nodes.data(), Eigen::Vector2d(double(i) / s, double(j) / s)));
          return static_cast<int>(verts.size()) - 1;
        };
        if (zeros == 2) { // a corner
          int c = l[0] ? 0 : (l[1] ? 1 : 2);
          auto [it, ins] = corner_vertex.emplace(corner[c], -1);
          if (ins) {
            verts.push_back(m.nodes[corner[c]]);
            it->second = static_cast<int>(verts.size()) - 1;
          }
          at(i, j) = it->second;
        } else if (zeros == 1) { // on the edge between the two non-zero corners
          int a = -1, c = -1;
          for (int k = 0; k < 3; ++k)
            if (l[k]) (a < 0 ? a : c) = k;
          int lo = a, hi = c;
          if (corner[lo] > corner[hi]) std::swap(lo, hi);
          // l[hi] steps from corner lo toward hi.
          std::array<int, 3> key{corner[lo], corner[hi], l[hi]};
          auto it = edge_vertex.find(key);
          at(i, j) = it != edge_vertex.end() ? it->second : (edge_vertex[key] = eval());
        } else {
          at(i, j) = eval();
        }
      }
    const auto uv = [s](int i, int j) { return Eigen::Vector2d(double(i) / s, double(j) / s); };
    for (int i = 0; i < s; ++i)
      for (int j = 0; i + j < s; ++j) {
        out.surface.faces.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        out.source_face.push_back(b);
        out.source_uv.push_back({uv(i, j), uv(i + 1, j), uv(i, j + 1)});
        if (i + j + 1 < s) {
          out.surface.faces.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
          out.source_face.push_back(b);
          out.source_uv.push_back({uv(i + 1, j), uv(i + 1, j + 1), uv(i, j + 1)});
        }
      }
  }
  return out;
}

} // namespace curvetet::check
