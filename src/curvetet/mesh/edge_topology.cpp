#include "curvetet/mesh/edge_topology.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace curvetet::mesh {

EdgeTopology build_edge_topology(const std::vector<Tri>& faces) {
  // Sort (min, max, face, corner) records; equal keys form one edge.
  struct Rec {
    std::uint64_t key;
    int face;
    int corner;
  };
  std::vector<Rec> recs;
  recs.reserve(faces.size() * 3);
  for (int f = 0; f < static_cast<int>(faces.size()); ++f)
    for (int k = 0; k < 3; ++k) {
      auto a = static_cast<std::uint32_t>(faces[f][(k + 1) % 3]);
      auto b = static_cast<std::uint32_t>(faces[f][(k + 2) % 3]);
      if (a > b) std::swap(a, b);
      recs.push_back({(std::uint64_t(a) << 32) | b, f, k});
    }
  std::sort(recs.begin(), recs.end(), [](const Rec& x, const Rec& y) {
    return x.key != y.key ? x.key < y.key : (x.face != y.face ? x.face < y.face : x.corner < y.corner);
  });

  EdgeTopology t;
  t.face_edges.resize(faces.size());
  t.edge_face_offsets.push_back(0);
  for (std::size_t i = 0; i < recs.size();) {
    std::size_t j = i;
    int e = static_cast<int>(t.edges.size());
    t.edges.push_back({static_cast<int>(recs[i].key >> 32), static_cast<int>(recs[i].key & 0xffffffffu)});
    for (; j < recs.size() && recs[j].key == recs[i].key; ++j) {
      t.face_edges[recs[j].face][recs[j].corner] = e;
      t.edge_faces.push_back(recs[j].face);
    }
    t.edge_face_offsets.push_back(static_cast<int>(t.edge_faces.size()));
    i = j;
  }
  return t;
}

VertexFaces build_vertex_faces(int num_vertices, const std::vector<Tri>& faces) {
  VertexFaces vf;
  vf.offsets.assign(num_vertices + 1, 0);
  for (const auto& f : faces)
    for (int v : f) ++vf.offsets[v + 1];
  std::partial_sum(vf.offsets.begin(), vf.offsets.end(), vf.offsets.begin());
  vf.faces.resize(vf.offsets.back());
  std::vector<int> fill(vf.offsets.begin(), vf.offsets.end() - 1);
  for (int f = 0; f < static_cast<int>(faces.size()); ++f)
    for (int v : faces[f]) vf.faces[fill[v]++] = f;
  return vf;
}

std::vector<int> face_components(const std::vector<Tri>& faces, const EdgeTopology& topo, int* count) {
  std::vector<int> comp(faces.size(), -1);
  std::vector<int> stack;
  int next = 0;
  for (int seed = 0; seed < static_cast<int>(faces.size()); ++seed) {
    if (comp[seed] >= 0) continue;
    comp[seed] = next;
    stack.push_back(seed);
    while (!stack.empty()) {
      int f = stack.back();
      stack.pop_back();
      for (int e : topo.face_edges[f])
        for (int i = 0; i < topo.num_faces_of(e); ++i) {
          int g = topo.faces_of(e)[i];
          if (comp[g] < 0) {
            comp[g] = next;
            stack.push_back(g);
          }
        }
    }
    ++next;
  }
  if (count) *count = next;
  return comp;
}

} // namespace curvetet::mesh
