#pragma once
// Global numbering of the Lagrange nodes of an order-P tet mesh given by its
// corner vertices, so that tets sharing an edge or a face share the nodes on
// it (a conforming high-order mesh).
//
// A lattice node of a tet is identified by its barycentric integer weights on
// the tet's global corner vertices (weights > 0 only): the same physical
// lattice point seen from two tets has the same (vertex, weight) set, whatever
// the local vertex order. Corner nodes keep their vertex ids (0 ..
// num_vertices-1); the others are numbered from num_vertices in order of first
// appearance (tet by tet, internal node order), so the result is deterministic.
#include <array>
#include <vector>

namespace curvetet::highorder {

struct ConformingNodes {
  int order = 1;
  int num_nodes = 0;
  std::vector<int> tet_nodes; // per tet, tet_node_count(order) ids in internal (Gmsh) order
};

ConformingNodes number_tet_nodes(int num_vertices, const std::vector<std::array<int, 4>>& tets, int order);

// The same for order-P triangles (e.g. a curved surface patch); `tet_nodes`
// then holds triangle_node_count(order) ids per triangle.
ConformingNodes number_triangle_nodes(int num_vertices, const std::vector<std::array<int, 3>>& triangles, int order);

// The barycentric weights (summing to 1) of internal node i of an order-P tet
// on its four corners: what a caller maps through its element map to place
// the node.
std::array<double, 4> tet_node_barycentric(int order, int i);

} // namespace curvetet::highorder
