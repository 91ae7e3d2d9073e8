// Isolation of singular vertices: split edges joining two of them.
#include "curvetet/core/error.hpp"
#include "curvetet/mesh/edge_topology.hpp"
#include "curvetet/shell/build.hpp"

#include <fmt/format.h>

namespace curvetet::shell {

namespace {

constexpr int kMaxPasses = 4;

// Splits edge (a, b) of every face holding it; keeps orientation.
void split_edge(mesh::SurfaceMesh& m, std::vector<int>& origin, std::vector<std::vector<int>>& vf, int a, int b) {
  const int mid = m.num_vertices();
  m.vertices.push_back(0.5 * (m.vertices[a] + m.vertices[b]));
  vf.emplace_back();
  const std::vector<int> around = vf[a];
  for (int f : around) {
    auto t = m.faces[f];
    int ia = -1, ib = -1;
    for (int k = 0; k < 3; ++k) {
      if (t[k] == a) ia = k;
      if (t[k] == b) ib = k;
    }
    if (ib < 0) continue;
    // Corners in order: replace one endpoint by mid in each half.
    auto first = t, second = t;
    first[ib] = mid;  // keeps a
    second[ia] = mid; // keeps b
    const int g = m.num_faces();
    m.faces[f] = first;
    m.faces.push_back(second);
    origin.push_back(origin[f]);
    // Adjacency: f no longer touches b; g touches b, mid and the third corner.
    auto& vb = vf[b];
    vb.erase(std::find(vb.begin(), vb.end(), f));
    vb.push_back(g);
    vf[mid].push_back(f);
    vf[mid].push_back(g);
    vf[t[3 - ia - ib]].push_back(g);
  }
}

} // namespace

IsolatedMesh isolate_singularities(const mesh::SurfaceMesh& input, double singular_dot) {
  IsolatedMesh out;
  out.mesh = input;
  out.origin_face.resize(input.num_faces());
  for (int f = 0; f < input.num_faces(); ++f) out.origin_face[f] = f;
  for (int pass = 0;; ++pass) {
    out.directions = extrusion_directions(out.mesh, singular_dot);
    const auto topo = mesh::build_edge_topology(out.mesh.faces);
    std::vector<std::array<int, 2>> bad;
    for (const auto& e : topo.edges)
      if (out.directions[e[0]].singular && out.directions[e[1]].singular) bad.push_back(e);
    if (bad.empty()) return out;
    if (pass == kMaxPasses)
      throw Error(ExitCode::internal,
                  fmt::format("shell: singular vertices {} and {} stay adjacent after {} edge-split passes "
                              "({} such edges)",
                              bad[0][0], bad[0][1], kMaxPasses, bad.size()));
    std::vector<std::vector<int>> vf(out.mesh.num_vertices());
    for (int f = 0; f < out.mesh.num_faces(); ++f)
      for (int v : out.mesh.faces[f]) vf[v].push_back(f);
    for (const auto& e : bad) split_edge(out.mesh, out.origin_face, vf, e[0], e[1]);
    out.split_edges += static_cast<int>(bad.size());
  }
}

} // namespace curvetet::shell
