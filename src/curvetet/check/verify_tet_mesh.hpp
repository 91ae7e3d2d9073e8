#pragma once
// Whole-mesh verifier of a curved tet mesh (STYLE.md 13): what `curvetet
// check` prints and what the pipeline's report re-verifies.
//
// 1. Positivity: every tet's Jacobian certificate (highorder/
//    jacobian_certificate.hpp); counts of positive / invalid / undecided
//    (undecided fails), certified bounds of min det J, quality (min scaled
//    Jacobian, AMIPS).
// 2. Conformity: every tet face is shared by at most two tets; the listed
//    boundary triangles are exactly the tet faces used once, outward, and
//    carry the same high-order nodes as the tet face. (No listed boundary:
//    the tet faces used once are taken as the boundary.)
//    Two regions (pipeline `--fill all`): tets tagged mesh::kExteriorTag form
//    the exterior, every other tet the domain. The domain's boundary (faces
//    with exactly one domain tet: the interface with the exterior, plus any
//    face used once) must be listed, oriented outward from the domain; the
//    exterior's outer faces (the box) must be listed too, outward. Items 3
//    and 4 concern the domain's boundary only; the outer faces get item 3's
//    surface test on their own (`outer_surface`).
// 3. Boundary surface: a conforming linearization of the curved boundary
//    (check/boundary_linearization.hpp, s segments per edge) must pass the
//    input preconditions exactly: closed, edge- and vertex-manifold,
//    consistently oriented, outward, no zero-area triangle, no
//    self-intersection (exact predicates on the linearization). That is a
//    fast pre-filter; the curved patches themselves are then certified to
//    meet only where they share a corner or an edge
//    (check/curved_boundary_certificate.hpp: Bézier hulls, subdivision).
// 4. With an input surface: distance from every input vertex to the curved
//    boundary (check/curved_distance.hpp: to an actual point of it, so an
//    upper bound of the true distance) and from every linearization vertex
//    (points of the curved boundary) to the input, max and mean relative to
//    the input's bbox diagonal; both maxima must be <= epsilon (ε both ways:
//    DESIGN.md invariant 4), and the report names the direction that fails.
//    The boundary->input figure is measured at the linearization vertices
//    (samples of the curved boundary, s per edge): a lower bound of the true
//    maximum that the shell's sampled bound (shell/surface_distance.hpp)
//    guarantees from above.
#include "curvetet/check/curved_boundary_certificate.hpp"
#include "curvetet/check/preconditions.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace curvetet::check {

struct TetMeshVerifyOptions {
  int segments_per_edge = 0;           // boundary linearization; 0 = 2 * order
  highorder::CertificateOptions certificate;
  const mesh::SurfaceMesh* input = nullptr; // optional input surface
  double epsilon = 1e-2;                // relative to the input bbox diagonal
};

struct TetMeshVerification {
  int order = 0;
  std::size_t num_nodes = 0, num_tets = 0, num_boundary = 0;

  // Positivity, per tet and totals.
  std::vector<highorder::Validity> validity;
  std::vector<double> min_det_lower, min_scaled_jacobian, max_amips;
  std::size_t positive = 0, invalid = 0, undecided = 0;
  std::vector<int> invalid_examples, undecided_examples;
  double min_det_lower_bound = 0, min_det_upper_bound = 0;
  double worst_scaled_jacobian = 0, worst_amips = 0, mean_amips = 0;

  // Conformity.
  std::size_t overshared_faces = 0;      // faces of > 2 tets
  std::size_t boundary_missing = 0;      // tet faces used once but not listed
  std::size_t boundary_extra = 0;        // listed triangles that are not such faces
  std::size_t boundary_flipped = 0;      // listed with inward orientation
  std::size_t boundary_node_mismatch = 0; // high-order nodes differ from the tet face
  bool boundary_listed = true;
  std::size_t exterior_tets = 0;          // tets of the exterior region (0: one region)
  std::size_t interface_triangles = 0;    // domain faces shared with an exterior tet
  std::size_t outer_triangles = 0;        // exterior faces used once (the box)

  // Boundary surface.
  int segments_per_edge = 0;
  std::size_t linearized_faces = 0;
  PreconditionReport surface;
  PreconditionReport outer_surface; // exterior's outer faces (empty and ok with one region)
  // The curved domain boundary, certified when its linearization passed.
  bool curved_boundary_checked = false;
  CurvedBoundaryCertificate curved_boundary;
  bool surface_ok() const { return surface.ok() && curved_boundary_checked && curved_boundary.ok(); }

  // Distances (with input).
  bool has_input = false;
  double epsilon = 0, bbox_diagonal = 0;
  double input_to_boundary_max = 0, input_to_boundary_mean = 0; // relative
  double boundary_to_input_max = 0, boundary_to_input_mean = 0; // relative

  bool positivity_ok() const { return invalid == 0 && undecided == 0; }
  bool conformity_ok() const {
    return overshared_faces == 0 && boundary_missing == 0 && boundary_extra == 0 && boundary_flipped == 0 &&
           boundary_node_mismatch == 0;
  }
  bool input_to_boundary_ok() const { return !has_input || input_to_boundary_max <= epsilon; }
  bool boundary_to_input_ok() const { return !has_input || boundary_to_input_max <= epsilon; }
  bool distance_ok() const { return input_to_boundary_ok() && boundary_to_input_ok(); }
  bool ok() const {
    return positivity_ok() && conformity_ok() && surface_ok() && outer_surface.ok() && distance_ok();
  }
  std::string text() const;
  nlohmann::json json() const;
};

TetMeshVerification verify_tet_mesh(const mesh::TetMesh& mesh, const TetMeshVerifyOptions& options = {});

} // namespace curvetet::check
