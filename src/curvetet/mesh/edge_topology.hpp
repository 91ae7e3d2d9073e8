#pragma once
// Undirected edges of a triangle mesh and their incident faces. Works on any
// triangle list (non-manifold too): an edge may have 1, 2 or more faces.
//
// Edge e joins vertices edges[e][0] < edges[e][1]. face_edges[f][k] is the
// edge opposite corner k of face f, i.e. between corners (k+1)%3 and (k+2)%3.
#include "curvetet/mesh/surface_mesh.hpp"

#include <array>
#include <vector>

namespace curvetet::mesh {

struct EdgeTopology {
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 3>> face_edges;
  // CSR: faces of edge e are edge_faces[edge_face_offsets[e] .. [e+1]).
  std::vector<int> edge_face_offsets;
  std::vector<int> edge_faces;

  int num_edges() const { return static_cast<int>(edges.size()); }
  int num_faces_of(int e) const { return edge_face_offsets[e + 1] - edge_face_offsets[e]; }
  const int* faces_of(int e) const { return edge_faces.data() + edge_face_offsets[e]; }
};

EdgeTopology build_edge_topology(const std::vector<Tri>& faces);

// Faces around each vertex, CSR layout (vertex_faces[offsets[v] .. [v+1])).
struct VertexFaces {
  std::vector<int> offsets;
  std::vector<int> faces;
};
VertexFaces build_vertex_faces(int num_vertices, const std::vector<Tri>& faces);

// Connected components of faces through shared edges. Returns the component
// id of every face; ids are 0..count-1 in order of first face.
std::vector<int> face_components(const std::vector<Tri>& faces, const EdgeTopology& topo, int* count);

} // namespace curvetet::mesh
