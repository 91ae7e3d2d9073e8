#pragma once
// A curved (high-order) tetrahedral mesh as plain data, the output of the
// pipeline and the input of `curvetet check`.
//
// All elements share one order P (1..8). Node ids are 0-based into `nodes`.
// Tet t has nodes tets[t * tet_nodes() + i], i in curvetet's internal
// element order, which is Gmsh's (highorder/node_ordering.hpp: corners, then
// edges 0-1, 1-2, 2-0, 3-0, 3-2, 3-1, faces, interior). Positive tets have
// orient3d(corner0..3) > 0 (geometry/predicates.hpp) and det J > 0.
// Boundary triangle b has nodes boundary[b * triangle_nodes() + i] in the
// internal triangle order (corners, edges 0-1, 1-2, 2-0, interior),
// counter-clockwise seen from outside the domain.
// Line l (feature curves, optional) has nodes lines[l * line_nodes() + i]:
// its two ends, then its interior nodes from end 0 to end 1 (Gmsh's order).
// Tags are physical group tags (0 = none); `groups` names them.
#include <Eigen/Core>

#include <string>
#include <vector>

namespace curvetet::mesh {

struct PhysicalGroup {
  int dim = 0; // 1, 2 or 3
  int tag = 0;
  std::string name;
};

struct TetMesh {
  int order = 1;
  std::vector<Eigen::Vector3d> nodes;
  std::vector<int> tets;     // num_tets() x tet_nodes()
  std::vector<int> boundary; // num_boundary() x triangle_nodes()
  std::vector<int> tet_tags;      // one per tet (may be empty = all 0)
  std::vector<int> boundary_tags; // one per boundary triangle (may be empty)
  std::vector<int> lines;         // num_lines() x line_nodes() (may be empty)
  std::vector<int> line_tags;     // one per line (may be empty)
  std::vector<PhysicalGroup> groups;

  int tet_nodes() const { return (order + 1) * (order + 2) * (order + 3) / 6; }
  int triangle_nodes() const { return (order + 1) * (order + 2) / 2; }
  int line_nodes() const { return order + 1; }
  int num_lines() const { return static_cast<int>(lines.size()) / line_nodes(); }
  const int* line(int l) const { return lines.data() + static_cast<std::size_t>(l) * line_nodes(); }
  int num_tets() const { return static_cast<int>(tets.size()) / tet_nodes(); }
  int num_boundary() const { return static_cast<int>(boundary.size()) / triangle_nodes(); }
  const int* tet(int t) const { return tets.data() + static_cast<std::size_t>(t) * tet_nodes(); }
  // Positions of tet t's nodes into out[0, tet_nodes()).
  void tet_positions(int t, Eigen::Vector3d* out) const {
    const int* ids = tet(t);
    for (int i = 0, n = tet_nodes(); i < n; ++i) out[i] = nodes[ids[i]];
  }
  const int* boundary_triangle(int b) const { return boundary.data() + static_cast<std::size_t>(b) * triangle_nodes(); }
};

// Default physical groups written by curvetet: boundary triangles in
// "boundary" (dim 2, tag 1), tets in "domain" (dim 3, tag 2).
constexpr int kBoundaryTag = 1;
constexpr int kDomainTag = 2;
// Feature curves written by curvetet: lines in "features" (dim 1, tag 3).
constexpr int kFeatureTag = 3;
void set_default_groups(TetMesh& mesh);

// With an exterior region (`--fill all`, flows around an obstacle): its tets
// in "exterior" (dim 3, tag 3), the outer box faces in "box" (dim 2, tag 4).
// The "boundary" triangles are then the interface between "domain" and
// "exterior", still oriented outward from the domain.
constexpr int kExteriorTag = 3;
constexpr int kBoxTag = 4;
void add_exterior_groups(TetMesh& mesh); // adds the two groups (tags are set by the caller)

} // namespace curvetet::mesh
