#include "curvetet/pipeline/features_stage.hpp"

#include "curvetet/features/refine.hpp"

#include "curvetet/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

namespace curvetet::pipeline {

mesh::SurfaceMesh refine_for_features(const mesh::SurfaceMesh& input, const features::FeatureGraph& g) {
  std::vector<std::array<int, 2>> edges;
  for (const auto& c : g.chains)
    for (int i = 0; i < c.num_edges(); ++i) {
      const int a = c.vertices[i], b = c.vertices[(i + 1) % c.vertices.size()];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  return features::refine_multi_feature_faces(input, edges).mesh;
}

int add_feature_lines(mesh::TetMesh& m, const shell::Shell& s) {
  const auto& f = s.features;
  if (f.edges.empty()) return 0;
  // Shell vertex of each feature edge end, by exact middle position.
  std::map<std::array<double, 3>, int> vertex_at;
  for (const auto& [key, e] : f.edges)
    for (int v : {static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu)})
      vertex_at[{s.middle[v].x(), s.middle[v].y(), s.middle[v].z()}] = v;
  auto shell_vertex = [&](int node) {
    const auto& p = m.nodes[node];
    auto it = vertex_at.find({p.x(), p.y(), p.z()});
    return it == vertex_at.end() ? -1 : it->second;
  };
  const int P = m.order;
  std::set<std::uint64_t> done;
  const int before = m.num_lines();
  for (int b = 0; b < m.num_boundary(); ++b) {
    const int* t = m.boundary_triangle(b);
    for (int e = 0; e < 3; ++e) {
      const int a = shell_vertex(t[e]), c = shell_vertex(t[(e + 1) % 3]);
      if (a < 0 || c < 0 || !f.edge(a, c)) continue;
      if (!done.insert(shell::ShellFeatures::edge_key(a, c)).second) continue;
      // Triangle edge e runs from corner e to corner e+1 with its P-1
      // interior nodes in that direction (internal = Gmsh order).
      m.lines.push_back(t[e]);
      m.lines.push_back(t[(e + 1) % 3]);
      for (int j = 0; j < P - 1; ++j) m.lines.push_back(t[3 + e * (P - 1) + j]);
      m.line_tags.push_back(mesh::kFeatureTag);
    }
  }
  if (done.size() != f.edges.size())
    throw Error(ExitCode::internal, fmt::format("feature lines: {} of {} feature edges are not boundary edges",
                                                f.edges.size() - done.size(), f.edges.size()));
  bool named = false;
  for (const auto& g : m.groups) named = named || (g.dim == 1 && g.tag == mesh::kFeatureTag);
  if (!named) m.groups.push_back({1, mesh::kFeatureTag, "features"});
  return m.num_lines() - before;
}

} // namespace curvetet::pipeline
