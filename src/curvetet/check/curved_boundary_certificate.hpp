#pragma once
// Certificate that the curved boundary of a tet mesh is embedded: no patch
// folds onto itself, and two patches meet only at the corner or edge they
// share (issue 27; the flat linearization of check/boundary_linearization.hpp
// stays as the verifier's fast pre-filter).
//
// Each boundary triangle is a Bézier patch (check/bezier_patch.hpp). Pairs
// whose boxes overlap are examined piece by piece, splitting both at edge
// midpoints until every pair of pieces is settled by one of three proofs:
//  - no shared point (by the pieces' exact parameters): their boxes, or
//    their extents along one of their normals or edges' in-plane normals,
//    are disjoint;
//  - one shared corner: a plane through it separates the two control nets
//    (patch_separation.hpp);
//  - one shared edge: the union of the two pieces is embedded;
// and each patch alone is embedded, or its four pieces are and pairwise meet
// only where they share. A pair still unsettled at the depth limit is a
// failure: the certificate never guesses.
#include "curvetet/mesh/tet_mesh.hpp"

#include <cstddef>
#include <utility>
#include <vector>

namespace curvetet::check {

struct CurvedBoundaryOptions {
  int max_depth = 16;                       // midpoint splits per patch
  std::size_t max_tests_per_pair = 1 << 16; // proofs tried before giving up on a pair, or on a patch alone
};

struct CurvedBoundaryCertificate {
  std::size_t patches = 0;
  std::size_t pairs = 0;        // patch pairs whose boxes overlap (adjacent ones included)
  std::size_t piece_tests = 0;  // proofs tried on pieces, all pairs and patches
  int deepest = 0;              // most splits any proof needed
  // Boundary triangles not shown to meet only where they share, sorted;
  // (i, i): triangle i not shown to be embedded.
  std::vector<std::pair<int, int>> unsettled;
  bool ok() const { return unsettled.empty(); }
};

// The mesh's boundary triangles (mesh.boundary) with its nodes; the tets are
// not read. Two triangles that share two corners must share that edge's
// nodes (else the pair is unsettled); three shared corners is unsettled.
CurvedBoundaryCertificate certify_curved_boundary(const mesh::TetMesh& mesh, const CurvedBoundaryOptions& options = {});

} // namespace curvetet::check
