#pragma once
// The curved middle surface (paper §4.1; DESIGN.md §3.2): the MiddleFit that
// coarsening runs inside every operation when the output order P > 2.
//
// For a candidate star, the middle triangles become degree-k Lagrange
// triangles (k = P - 1; top and bottom stay flat):
//  1. fit: least squares (highorder::fit_patch_star) of the free nodes to
//     samples of the input paired with their Π: the constraint points of the
//     removed prisms (c.images) and, for every tracked input face, its
//     centroid and edge midpoints with their Π in the new prism holding them.
//     Corners are the middle vertices; every node of the star's boundary
//     edges keeps its current position (so neighbours stay conforming).
//  2. check: both slabs of every new prism (bottom -> curved middle, curved
//     middle -> top) are certified positive by the Bézier certificate
//     (highorder::certify_slab); `undecided` counts as a failure. If that
//     fails or the fit misses epsilon at a constraint point, the same star
//     with its free nodes left flat (boundary-edge nodes still fixed) is
//     tried and checked the same way.
// The Distance invariant then measures ε on the curved surface through
// evaluate(). The fitted nodes travel in c.middle_nodes to the commit.
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/mesh/tet_mesh.hpp"
#include "curvetet/shell/middle_fit.hpp"

#include <nlohmann/json.hpp>

#include <atomic>

namespace curvetet::shell {

// Work done by a CurvedMiddleFit (summed over threads; CPU seconds).
struct CurvedFitStats {
  int degree = 0;
  long long fits = 0, rejected = 0;
  double fit_seconds = 0, certificate_seconds = 0;
  nlohmann::json json() const;
};

class CurvedMiddleFit final : public MiddleFit {
 public:
  // degree k in 2..7.
  explicit CurvedMiddleFit(int degree);
  int degree() const override { return degree_; }
  bool fit_and_check(const ShellEditor& editor, StarCandidate& c, double epsilon) const override;
  Vec3 evaluate(const StarCandidate& c, int k, double u, double v) const override;
  std::vector<Vec3> patch_nodes(const StarCandidate& c, int k) const override { return c.middle_nodes[k]; }
  CurvedFitStats stats() const;

 private:
  int degree_;
  highorder::CertificateOptions certificate_;
  mutable std::atomic<long long> fits_{0}, rejected_{0}, fit_ns_{0}, certificate_ns_{0};
};

// Both slabs of prism f of a curved shell, certified (a flat shell passes
// trivially: invariant 1 covers it). Returns the first failing prism, or -1.
int first_uncertified_prism(const Shell& s);

// The middle surface as a conforming mesh of degree-k triangles (a TetMesh of
// order k with no tets; boundary = one triangle per prism, tag kBoundaryTag,
// group "middle"), for MSH/VTU output. Flat shells give order 1.
mesh::TetMesh middle_surface_mesh(const Shell& s);

} // namespace curvetet::shell
