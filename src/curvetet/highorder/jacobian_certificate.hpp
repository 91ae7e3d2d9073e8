#pragma once
// Certified sign of the Jacobian determinant of curved elements
// (Johnen, Remacle, Geuzaine 2013; DESIGN.md §4, STYLE.md 7).
//
// det J of a polynomial map is itself a polynomial; we get its Bernstein
// coefficients c_alpha. Since the Bernstein basis is non-negative and sums to
// one, min c <= det J <= max c on the element, and corner coefficients ARE
// values of det J. Decision:
//   all c > 0                      -> positive (det J > 0 everywhere)
//   a corner c <= 0                -> invalid (a point with det J <= 0 exists)
//   otherwise bisect (de Casteljau) and decide each piece, most negative
//   piece first (a heap), up to a depth / piece budget    -> else undecided.
// Callers must treat `undecided` as invalid.
//
// How the coefficients are computed: the element's Lagrange nodes go to
// Bernstein control points (exact rational matrix rounded to double), the
// three columns dx/dxi_k get their Bernstein coefficients by differences, and
// det J = J1 . (J2 x J3) is formed by exact Bernstein product rules
// (convolutions of the scaled coefficients c_alpha * n!/alpha!). This yields
// exactly the coefficients that sampling det J on the degree-3(P-1) lattice and
// converting to Bernstein would give (tests/highorder checks both), with no
// large dense conversion matrix and with a simple rounding analysis.
//
// Why floating point cannot fool it: every double quantity carries a radius
// that bounds its distance to the exact value for the given (double) nodes.
// Radii follow Higham's a-priori bounds (|fl(sum) - sum| <= gamma_K sum|terms|,
// gamma_K = K u / (1 - K u)) plus the propagated input radii, and are
// inflated by 1e-9 relative to cover rounding in the radius arithmetic
// itself. A coefficient counts as positive only if c - r > 0, and a corner
// proves invalidity only if c + r <= 0. When the top-level float decision is
// blocked only by radii, the coefficients are recomputed EXACTLY with GMP
// rationals (exact_fallback) and the signs decided exactly. Subdivision runs
// in floating point with radii (undecided when they are too large).
//
// Subdivision scheme: bisection of the longest edge of the piece in reference
// coordinates (ties: lowest local edge index), children by de Casteljau at
// the edge midpoint. For slabs, the t interval is halved instead when it is
// at least as long as the longest triangle edge. max_depth counts bisections.
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace curvetet::highorder {

enum class Validity { positive, invalid, undecided };
std::string to_string(Validity v);

struct CertificateOptions {
  int max_depth = 18;        // bisection levels below the element
  int max_pieces = 2000;     // pieces examined in total (budget)
  bool exact_fallback = true;
};

struct Certificate {
  Validity validity = Validity::undecided;
  // Certified bounds on the minimum of det J over the element (for slabs: of
  // the oriented determinant): min_det_lower <= min det J <= min_det_upper.
  double min_det_lower = 0;
  double min_det_upper = 0;
  int pieces = 1;        // pieces examined (1 = decided without subdivision)
  int depth = 0;         // deepest bisection level reached
  bool exact = false;    // the exact rational path decided it
  // Reference-space barycentric corners of the piece that proved invalidity
  // or stayed undecided (tets: 4 points in (u,v,w); slabs: 3 points (u,v) and
  // t in [t0,t1]); empty when positive.
  std::vector<Eigen::Vector3d> region;
  double region_t0 = 0, region_t1 = 1;
};

// Order-P tet, P in 1..8, nodes in internal (Gmsh) order (tet_node_count(P)
// points). det J is taken w.r.t. the unit reference tet, so a straight tet has
// det J = 6 * volume and the convention matches geometry::orient3d.
Certificate certify_tet(int order, const Eigen::Vector3d* nodes, const CertificateOptions& options = {});

// Curved prism slab (DESIGN.md §4, paper §4.1): middle triangle of degree k
// (k in 1..8) given by its Lagrange nodes in internal triangle order
// (basis = lagrange) or by its Bezier control points in canonical order
// (basis = bezier, simplex_lattice.hpp), and a linear cap triangle (top or
// bottom: cap[i] is above/below middle corner i).
//   x(u, v, t) = (1 - t) M(u, v) + t C(u, v),  (u, v) in the reference
//   triangle (0,0),(1,0),(0,1), t in [0, 1] from the middle (t=0) to the cap.
// The triangle (u, v) is counter-clockwise seen from outside (from the top),
// so for a top slab det[x_u, x_v, x_t] > 0 and for a bottom slab < 0; the
// certificate decides s * det J > 0 with s = +1 (top) / -1 (bottom).
// det J has degree 3k-2 in (u, v) and 2 in t.
// collapsed[i] = true marks a singular vertex (cap[i] == middle corner i,
// checked bitwise): det J vanishes on that pillar, and the certificate then
// means "s det J > 0 everywhere except on the collapsed pillar(s)".
enum class SlabSide { top, bottom };
enum class MiddleBasis { lagrange, bezier };
Certificate certify_slab(int k, const Eigen::Vector3d* middle_nodes, const std::array<Eigen::Vector3d, 3>& cap,
                         SlabSide side, const std::array<bool, 3>& collapsed = {false, false, false},
                         const CertificateOptions& options = {}, MiddleBasis basis = MiddleBasis::lagrange);

// The Bernstein coefficients behind the certificate, for tests and reports:
// det J on the simplex (dim 3 for tets, 2 for slabs) x [0,1] (degree t_degree,
// 0 for tets), index = simplex canonical index * (t_degree + 1) + j.
struct JacobianCoefficients {
  int simplex_dim = 3, degree = 0, t_degree = 0;
  std::vector<double> value;  // unscaled Bernstein coefficients
  std::vector<double> radius; // |value - exact| <= radius
};
JacobianCoefficients tet_jacobian_coefficients(int order, const Eigen::Vector3d* nodes);
JacobianCoefficients slab_jacobian_coefficients(int k, const Eigen::Vector3d* middle_nodes,
                                                const std::array<Eigen::Vector3d, 3>& cap, SlabSide side,
                                                MiddleBasis basis = MiddleBasis::lagrange);
// The same coefficients computed exactly (GMP rationals), rounded to double
// at the very end (each within one ulp; exact zero stays zero).
std::vector<double> exact_tet_jacobian_coefficients(int order, const Eigen::Vector3d* nodes);

} // namespace curvetet::highorder
