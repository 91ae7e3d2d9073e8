#pragma once
// Whole-mesh verifier of the volume stage's output contract (exact):
//  - every tet positive by exact orient3d on its double coordinates;
//  - every face of a tet is either shared by exactly two tets, with opposite
//    orientations, or is a boundary face;
//  - the boundary faces, oriented outward, are exactly `expected_boundary`
//    (same corners, same cyclic order; vertex ids, so the coordinates are the
//    caller's bit for bit), plus, when box_lo/box_hi are given, faces lying
//    in a side of that box.
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/mesh/linear_tet_mesh.hpp"

#include <optional>
#include <string>
#include <vector>

namespace curvetet::volume {

struct TetMeshCheck {
  std::size_t non_positive = 0;      // tets with orient3d <= 0
  std::size_t overused_faces = 0;    // faces of 3+ tets or twice the same way
  std::size_t missing_boundary = 0;  // expected faces that are not boundary faces
  std::size_t extra_boundary = 0;    // boundary faces neither expected nor on the box
  double volume = 0;                 // sum of tet volumes (double, for reporting)
  bool ok() const { return non_positive + overused_faces + missing_boundary + extra_boundary == 0; }
  std::string text() const;
};

struct Box {
  mesh::Vec3 lo, hi;
};

TetMeshCheck verify_tet_mesh(const mesh::LinearTetMesh& m, const std::vector<mesh::Tri>& expected_boundary,
                             std::optional<Box> box = std::nullopt);

} // namespace curvetet::volume
