#pragma once
// The prismatic shell S = (B, V, T, F) (DESIGN.md §2-3, Jiang et al. 2020).
//
// bottom[v], middle[v], top[v] are the three positions of shell vertex v; all
// three surfaces share the triangle list `faces` (counter-clockwise seen from
// outside, i.e. from the top side). Prism f is (bottom, middle, top) of
// faces[f] and splits into two slabs: the bottom slab (lower = B, upper = V)
// and the top slab (lower = V, upper = T). The "pillar" of vertex v in a slab
// is upper[v] - lower[v] (oriented bottom -> top). A pillar is zero exactly
// when its two end positions are bitwise equal (singular vertices: B = V = T).
//
// tracked[f] lists the input faces (ids into `input.faces`) whose part inside
// prism f is parametrised by it. Initially (middle = input) prism f tracks its
// own input face; after isolation splits a face, both halves track it.
//
// Feature straightening (paper §5.1): Π acts on M̄, a copy of the input with
// the same faces whose feature chain vertices are moved onto the straight
// coarse middle edges, so Π maps each chain onto its edge; φ = ψ∘Π∘β with β:
// M -> M̄ affine per face. Distances are always measured from M. `straight`
// holds M̄'s vertices; empty means M̄ = M (no feature was straightened).
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/shell/features.hpp"

#include <array>
#include <vector>

namespace curvetet::shell {

using Vec3 = mesh::Vec3;
using Tri = mesh::Tri;

// A point of the middle surface: barycentric coordinates in prism `prism`'s
// middle triangle: position = (1-u-v)*c0 + u*c1 + v*c2 with c_k =
// middle[faces[prism][k]].
struct MapPoint {
  int prism = -1;
  double u = 0, v = 0;
};

// A point of the input followed through every shell edit: its position on
// M, an input face holding it, and its image Π(β(position)). Points
// 0..n-1 are the input vertices; later ones are constraint points
// (add_constraint_points), placed by `barycentric` on their input face.
struct TrackedPoint {
  Vec3 position;
  int input_face = -1;
  MapPoint image;
  std::array<double, 3> barycentric{}; // constraint points only
};

struct Shell {
  std::vector<Vec3> bottom, middle, top; // one entry per shell vertex
  std::vector<Tri> faces;                // shared F
  std::vector<std::vector<int>> tracked; // per prism: input face ids, sorted
  std::vector<char> singular;            // per shell vertex: pinched pillar
  mesh::SurfaceMesh input;               // the input surface M
  std::vector<Vec3> straight;            // M̄'s vertices (empty: M̄ = M)
  std::vector<TrackedPoint> points;      // input vertices, then constraint points
  // The curved middle surface (paper §4.1): per prism, the Lagrange nodes of
  // a degree-`middle_degree` triangle in internal (Gmsh) order, corners
  // first and bitwise equal to middle[faces[f][k]]; edge nodes agree between
  // the two prisms of an edge. Empty = the flat middle triangles. The middle
  // point of MapPoint (prism, u, v) is that triangle's map at (u, v).
  int middle_degree = 1;
  std::vector<std::vector<Vec3>> middle_nodes;
  // Slab tets off the middle are placed straight over straight middle parts
  // (slab_tet_nodes.hpp), set when the slab map folds somewhere on the
  // shell the curving starts from; else they follow the slab map.
  bool straight_slab_parts = false;
  ShellFeatures features;                // feature chains and corners (empty: none)

  int num_vertices() const { return static_cast<int>(middle.size()); }
  int num_prisms() const { return static_cast<int>(faces.size()); }
};

// Vertex i and face t of M̄ (the surface Π acts on).
inline const Vec3& straight_vertex(const Shell& s, int i) {
  return s.straight.empty() ? s.input.vertices[i] : s.straight[i];
}
inline std::array<Vec3, 3> straight_triangle(const Shell& s, int t) {
  const Tri& f = s.input.faces[t];
  return {straight_vertex(s, f[0]), straight_vertex(s, f[1]), straight_vertex(s, f[2])};
}
// Tracked point p on M̄: input vertex p, or a constraint point at its
// barycentric coordinates on its (straightened) face.
inline Vec3 straight_point(const Shell& s, int p) {
  if (p < s.input.num_vertices()) return straight_vertex(s, p);
  const auto t = straight_triangle(s, s.points[p].input_face);
  const auto& b = s.points[p].barycentric;
  return b[0] * t[0] + b[1] * t[1] + b[2] * t[2];
}

// The point of the (curved or flat) middle surface at p.
Vec3 middle_point(const Shell& s, const MapPoint& p);

// Sets the curved middle to the flat triangles as degree-`degree` nodes
// (degree 1: clears middle_nodes).
void set_flat_middle(Shell& s, int degree);
// Degree-`degree` Lagrange nodes (internal order) of a flat triangle.
std::vector<Vec3> flat_triangle_nodes(const std::array<Vec3, 3>& corners, int degree);

// The three surfaces as meshes (same faces; the middle one flat).
mesh::SurfaceMesh bottom_surface(const Shell& s);
mesh::SurfaceMesh middle_surface(const Shell& s);
mesh::SurfaceMesh top_surface(const Shell& s);

} // namespace curvetet::shell
