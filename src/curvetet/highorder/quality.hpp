#pragma once
// Element quality of curved tets and triangles (plain double, for ranking
// and reporting; validity is the certificate's job).
//
// THE QUALITY CONVENTION (DESIGN.md §8; the same as
// ../shared/tools/validate.py, which must agree with every figure curvetet
// reports):
//  - AMIPS of a tet at a point: with F = J W^-1, J = dx/dxi and W the map
//    from the reference tet to the regular tet of unit edge,
//    AMIPS = tr(F^T F) / det(F)^(2/3): 3 for the regular tet (at any scale),
//    +inf where det J <= 0.
//  - Scaled Jacobian at a point, for each of the 4 corner frames v of the
//    reference tet: sJ_v = sqrt(2) det J / (|a| |b| |c|), a, b, c = J e for
//    the three reference edges e leaving corner v; the min over the frames.
//    For a straight tet this is Verdict's scaled Jacobian (1 for the regular
//    tet, <= 0 when inverted).
//  - A tet of order P is sampled at the points of quality_samples(P), the
//    points validate.py samples: the order-2P lattice of the reference tet
//    INCLUDING its corners (all (i, j, l) / 2P with i + j + l <= 2P: it
//    contains the Lagrange nodes), united with the degree-3(P-1) lattice
//    (where det J's Bernstein coefficients live; the same lattice for P = 3).
//    Max AMIPS and min scaled Jacobian are over those points, the tet's mean
//    AMIPS is their plain mean, and a mesh's mean AMIPS is the plain mean of
//    its tets' means (validate.py's amips_curved_max, amips_curved_mean,
//    scaled_jacobian_curved_min; its mean counts the 4 corners, on both
//    lattices, twice). Order 1 (and any straight tet): J is constant, one
//    evaluation stands for every point.
// (volume/tet_amips.hpp's linear-fill energy is a third of this AMIPS; what
// the fill reports is converted to this convention.)
//
// MIPS (triangles in 3D): J_r = J W2^-1 (W2: reference -> unit equilateral),
// MIPS = tr(J_r^T J_r) / (2 sqrt(det(J_r^T J_r))); 1 for equilateral (the
// shell's ranking rule; not reported as an element quality).
#include <Eigen/Core>

#include <vector>

namespace curvetet::highorder {

struct TetQuality {
  double min_scaled_jacobian = 0;
  double max_amips = 0;  // regular tet: 3
  double mean_amips = 0; // plain mean over quality_samples(order)
};

// Nodes in internal (Gmsh) order, order 1..8. Straight tets (nodes where
// the affine map of the corners puts them, to 1e-12 of the tet's size) take
// one evaluation.
TetQuality tet_quality(int order, const Eigen::Vector3d* nodes);
// (The curved optimization's inner loop uses highorder/amips_frames.hpp.)

// The sample points of the convention, in reference coordinates: the
// order-2P lattice (canonical order, simplex_lattice.hpp), then the
// degree-3(P-1) lattice's points not on it; order 1: the centroid alone (its
// Jacobian is constant).
const std::vector<Eigen::Vector3d>& quality_samples(int order);
// How many of them, from the first, make the order-2P lattice (order 1: 1).
int quality_lattice_points(int order);

// Pointwise measures (J = dx/dxi, columns u, v, w).
double scaled_jacobian(const Eigen::Matrix3d& j);
double amips(const Eigen::Matrix3d& j); // regular tet: 3
double triangle_mips(const Eigen::Matrix<double, 3, 2>& j);

// Max MIPS of a curved triangle over the order-2k lattice with its corners
// (as tets are sampled; +inf where the map degenerates). A tet on this
// triangle has at least the AMIPS its distortion forces at each point, so a
// distorted curved face makes a bad tet however its other nodes are placed.
double triangle_max_mips(int order, const Eigen::Vector3d* nodes);

} // namespace curvetet::highorder
