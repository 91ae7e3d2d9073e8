#pragma once
// Lagrange node orderings of triangles and tetrahedra, orders 1..8.
//
// curvetet's internal node order IS Gmsh's (STYLE.md 8): node i of an order-P
// element sits at the lattice point gmsh_*_node(P, i) (integer reference
// coordinates times P on the unit simplex: tet (0,0,0),(1,0,0),(0,1,0),(0,0,1),
// triangle (0,0),(1,0),(0,1)). The table comes from Gmsh's own
// getElementProperties (tools/gen_gmsh_node_tables.py regenerates and checks
// it); Gmsh walks the tet edges 0-1, 1-2, 2-0, 3-0, 3-2, 3-1, then faces,
// then the interior recursively.
//
// VTK Lagrange cells (VTK_LAGRANGE_TRIANGLE = 69, VTK_LAGRANGE_TETRAHEDRON =
// 71) use another order: tet edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3, faces
// (0,1,3), (1,2,3), (2,0,3), (0,2,1) each with its own triangle order, then the
// interior recursively (VTK's vtkHigherOrderTetra). vtk_*_permutation(P)[k] is
// the internal node written as the k-th VTK point.
#include <array>
#include <utility>
#include <vector>

namespace curvetet::highorder {

constexpr int kMaxOrder = 8;

int triangle_node_count(int order); // (P+1)(P+2)/2
int tet_node_count(int order);      // (P+1)(P+2)(P+3)/6
// Order of an element with that many nodes, or 0 if no complete element has it.
int triangle_order_from_nodes(int nodes);
int tet_order_from_nodes(int nodes);

// Integer lattice coordinates (times P) of internal node i.
std::array<int, 2> triangle_node(int order, int i);
std::array<int, 3> tet_node(int order, int i);

// Inverse lookup: internal index of the node at lattice point q (times P),
// -1 if q is not a lattice point of the element.
int tet_node_index(int order, const std::array<int, 3>& q);
int triangle_node_index(int order, const std::array<int, 2>& q);

// Gmsh element type numbers (MSH); 0 if the order has none.
int gmsh_triangle_type(int order);
int gmsh_tet_type(int order);
// Inverse: order of a Gmsh triangle/tet type, 0 if not one.
int gmsh_triangle_order(int type);
int gmsh_tet_order(int type);

// VTK point k = internal node perm[k].
const std::vector<int>& vtk_triangle_permutation(int order);
const std::vector<int>& vtk_tet_permutation(int order);

// Internal nodes of local face f of an order-P tet, in the internal order of
// an order-P triangle whose corners are tet vertices kTetFaces[f] (so a
// boundary triangle's nodes are a plain lookup). Face f is opposite vertex f;
// its corners are ordered so the triangle's normal points out of the tet.
inline constexpr int kTetFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
const std::vector<int>& tet_face_nodes(int order, int face);

// Pairs (i, j), i < j, of internal nodes of an order-P tet that are
// neighbours on its lattice (integer barycentric coordinates differing by
// e_a - e_b): the edges of the P^3 small tets and octahedra of the lattice.
const std::vector<std::pair<int, int>>& tet_lattice_edges(int order);

} // namespace curvetet::highorder
