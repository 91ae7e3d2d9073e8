#include "curvetet/shell/surface_distance.hpp"

#include "curvetet/core/wide_vectors.hpp"
#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/simplex_lattice.hpp"

#include <Eigen/Core>
#include <tbb/parallel_reduce.h>
#include <tbb/blocked_range.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>

namespace curvetet::shell {

namespace {

constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;
constexpr int kMaxLattice = 48;

Vec3 closest_on_segment(const Vec3& p, const Vec3& x, const Vec3& y) {
  const Vec3 d = y - x;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - x).dot(d) / len2, 0.0, 1.0) : 0.0;
  return x + t * d;
}

struct Faces {
  std::vector<std::array<Vec3, 3>> corners;
  std::array<std::vector<double>, 3> lo, hi; // bounding boxes, per coordinate (a loop over faces vectorizes)
  double max_norm = 0;
  int size() const { return static_cast<int>(corners.size()); }
};

Faces gather(const mesh::SurfaceMesh& input, std::span<const int> faces) {
  Faces out;
  for (int t : faces) {
    const auto& f = input.faces[t];
    const std::array<Vec3, 3> c{input.vertices[f[0]], input.vertices[f[1]], input.vertices[f[2]]};
    out.corners.push_back(c);
    for (int r = 0; r < 3; ++r) {
      out.lo[r].push_back(std::min({c[0][r], c[1][r], c[2][r]}));
      out.hi[r].push_back(std::max({c[0][r], c[1][r], c[2][r]}));
    }
    for (const auto& v : c) out.max_norm = std::max(out.max_norm, v.norm());
  }
  return out;
}

// Squared distance from p to every face's box (0 inside), into d2.
CURVETET_WIDE_VECTORS void box_distances(const Faces& f, const Vec3& p, double* d2) {
  const double* lo[3] = {f.lo[0].data(), f.lo[1].data(), f.lo[2].data()};
  const double* hi[3] = {f.hi[0].data(), f.hi[1].data(), f.hi[2].data()};
  const double x = p.x(), y = p.y(), z = p.z();
  const int n = f.size();
  // max(v, 0) without a branch (exact: v + |v| is 2v or 0), so that the loop vectorizes.
  const auto positive = [](double v) { return 0.5 * (v + std::abs(v)); };
  for (int t = 0; t < n; ++t) {
    const double bx = positive(lo[0][t] - x), by = positive(lo[1][t] - y), bz = positive(lo[2][t] - z);
    const double ax = positive(x - hi[0][t]), ay = positive(y - hi[1][t]), az = positive(z - hi[2][t]);
    d2[t] = (bx * bx + by * by + bz * bz) + (ax * ax + ay * ay + az * az);
  }
}

// The patch in Bernstein form and the constants of the bound.
struct BernsteinPatch {
  int degree = 1;
  std::vector<Vec3> control;  // canonical order
  double slope = 0;           // G: first derivatives along the three edge directions
  double curvature = 0;       // H: second derivatives d²/du², d²/du dv, d²/dv²
  double control_error = 0;   // bound on |computed b_α − exact b_α|
  double max_norm = 0;        // max |b_α|
};

BernsteinPatch to_bernstein(int k, std::span<const Vec3> nodes) {
  const auto& change = highorder::basis_change(2, k);
  const int n = static_cast<int>(nodes.size());
  BernsteinPatch p;
  p.degree = k;
  p.control.assign(n, Vec3::Zero());
  double node_norm = 0;
  for (const auto& x : nodes) node_norm = std::max(node_norm, x.norm());
  double row_sum = 0;
  for (int a = 0; a < n; ++a) {
    for (int i = 0; i < n; ++i) p.control[a] += change.lagrange_to_bernstein(a, i) * nodes[i];
    row_sum = std::max(row_sum, change.abs_lagrange_to_bernstein.row(a).sum());
    p.max_norm = std::max(p.max_norm, p.control[a].norm());
  }
  // A's entries are within one ulp of the exact rationals and the dot
  // products of n terms add n roundings: (n + 2) u |A| |f| per coordinate,
  // √3 ≤ 2 for the Euclidean norm. Degree 1: A is the identity, b = f.
  p.control_error = k == 1 ? 0 : 2 * (n + 2) * kUnitRoundoff * row_sum * node_norm;
  const auto& lat = highorder::lattice(2, k);
  // b_{a + e_i (+ e_j)}; index_of reads (α1, α2) only.
  auto at = [&](highorder::MultiIndex a, int i, int j = -1) {
    a[i] += 1;
    if (j >= 0) a[j] += 1;
    return p.control[lat.index_of(a)];
  };
  for (const auto& beta : highorder::lattice(2, k - 1).indices()) {
    const Vec3 b0 = at(beta, 0), b1 = at(beta, 1), b2 = at(beta, 2);
    p.slope = std::max({p.slope, (b1 - b0).norm(), (b2 - b0).norm(), (b1 - b2).norm()});
  }
  p.slope *= k;
  if (k >= 2) {
    for (const auto& g : highorder::lattice(2, k - 2).indices()) {
      const Vec3 b00 = at(g, 0, 0), b01 = at(g, 0, 1), b02 = at(g, 0, 2), b11 = at(g, 1, 1), b12 = at(g, 1, 2),
                 b22 = at(g, 2, 2);
      p.curvature = std::max({p.curvature, (b11 - 2 * b01 + b00).norm(), (b22 - 2 * b02 + b00).norm(),
                              (b12 - b01 - b02 + b00).norm()});
    }
    p.curvature *= k * (k - 1);
  }
  return p;
}

// Bernstein basis values of degree k at the points (i/n, j/n) of the
// lattice of order n, in lattice_bound's order (j outer, i inner), each
// point's values together; computed once per (k, n).
constexpr int kMaxDegree = 7;
int lattice_index(int n, int i, int j) { return j * (n + 1) - j * (j - 1) / 2 + i; }

const std::vector<double>& lattice_basis(int k, int n) {
  if (k < 1 || k > kMaxDegree || n < 1 || n > kMaxLattice)
    throw std::invalid_argument("surface distance: lattice basis out of range");
  static std::vector<double> cache[kMaxDegree + 1][kMaxLattice + 1];
  static std::once_flag once[kMaxDegree + 1][kMaxLattice + 1];
  std::call_once(once[k][n], [k, n] {
    auto& out = cache[k][n];
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i + j <= n; ++i) {
        const double u = double(i) / n, v = double(j) / n;
        const double lambda[3] = {1 - u - v, u, v};
        const auto basis = highorder::bernstein_basis(2, k, lambda);
        out.insert(out.end(), basis.begin(), basis.end());
      }
  });
  return cache[k][n];
}

Vec3 combine(const BernsteinPatch& p, const double* basis) {
  Vec3 x = Vec3::Zero();
  for (std::size_t a = 0; a < p.control.size(); ++a) x += basis[a] * p.control[a];
  return x;
}

double distance_to_face(const Vec3& x, const Faces& f, int t) {
  const auto& c = f.corners[t];
  return (x - closest_point_on_triangle(x, c[0], c[1], c[2])).norm();
}

// Distance from x to the nearest face (into `face`), starting from face
// `face` (lattice neighbours share faces, which prunes the others by box).
double nearest_face(const Vec3& x, const Faces& f, int& face) {
  thread_local std::vector<double> box_d2;
  box_d2.resize(f.size());
  box_distances(f, x, box_d2.data());
  double best = std::numeric_limits<double>::infinity();
  int best_face = -1;
  auto visit = [&](int t) {
    if (box_d2[t] >= best * best) return;
    const double d = distance_to_face(x, f, t);
    if (d < best) {
      best = d;
      best_face = t;
    }
  };
  if (face >= 0) visit(face);
  for (int t = 0; t < f.size(); ++t) visit(t);
  face = best_face;
  return best;
}

// The samples of a lattice of order n: positions, distances, nearest faces.
// Point (i, j) (i + j <= n) is number lattice_index(n, i, j), j outer.
struct Samples {
  int n = 0;
  std::vector<Vec3> x;
  std::vector<double> d;
  std::vector<int> face;
  int index(int i, int j) const { return lattice_index(n, i, j); }
};

// Bound on the distance over one lattice cell (corners a, b, c), given
// `worst` so far (a cell that cannot exceed it is not refined further).
//  first order: some corner is within 2/(3n) (steps along the edge
//    directions) of every point: max d_i + 2G/(3n);
//  second order: q differs from its linear interpolant ℓ on the cell by at
//    most H/(2n²) (Taylor at x: q − ℓ = −½ Σ w_i D²q[s_i − x] and
//    Σ w_i |s_i − x|₁² ≤ h² on a lattice cell), and ℓ(x) is a convex
//    combination of the corners, so for any one input face t (a convex
//    set, whose distance function is convex) dist(ℓ(x), t) ≤ max_i
//    dist(q(s_i), t); t ranges over the corners' nearest faces.
double cell_bound(const BernsteinPatch& p, const Faces& f, const Samples& s, std::array<int, 3> corner, double worst) {
  const double h = 1.0 / s.n;
  double dmax = 0;
  for (int i : corner) dmax = std::max(dmax, s.d[i]);
  double bound = dmax + 2 * p.slope * h / 3;
  if (bound <= worst) return bound;
  const double interpolation = 0.5 * p.curvature * h * h;
  if (dmax + interpolation >= bound) return bound;
  // The caller keeps max(worst, bound): a face that cannot lower the bound
  // is left as soon as that shows, and the cell as soon as it is below worst.
  for (int a = 0; a < 3; ++a) {
    const int t = s.face[corner[a]];
    if ((a > 0 && t == s.face[corner[0]]) || (a > 1 && t == s.face[corner[1]])) continue; // same figure
    double dt = 0;
    for (int i : corner) {
      dt = std::max(dt, s.face[i] == t ? s.d[i] : distance_to_face(s.x[i], f, t));
      if (dt + interpolation >= bound) break;
    }
    bound = std::min(bound, dt + interpolation);
    if (bound <= worst) return bound;
  }
  return bound;
}

// Samples the lattice of order n and bounds the patch's distance. Stops at
// the first sample farther than `give_up` (then bound > give_up).
PatchDistance lattice_bound(const BernsteinPatch& p, const Faces& f, int n, double give_up) {
  PatchDistance out;
  out.lattice = n;
  Samples s;
  s.n = n;
  int hint = -1;
  const double* basis = lattice_basis(p.degree, n).data();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i + j <= n; ++i, basis += p.control.size()) {
      s.x.push_back(combine(p, basis));
      s.d.push_back(nearest_face(s.x.back(), f, hint));
      s.face.push_back(hint);
      out.sampled = std::max(out.sampled, s.d.back());
      if (out.sampled > give_up) return out;
    }
  double worst = out.sampled;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i) {
      worst = std::max(worst, cell_bound(p, f, s, {s.index(i, j), s.index(i + 1, j), s.index(i, j + 1)}, worst));
      if (i + j + 1 < n)
        worst = std::max(worst, cell_bound(p, f, s, {s.index(i + 1, j), s.index(i, j + 1), s.index(i + 1, j + 1)}, worst));
    }
  out.between = worst - out.sampled;
  return out;
}

} // namespace

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d00 = ab.dot(ab), d01 = ab.dot(ac), d11 = ac.dot(ac), d20 = ap.dot(ab), d21 = ap.dot(ac);
  const double den = d00 * d11 - d01 * d01;
  if (den > 0) {
    const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    if (v >= 0 && w >= 0 && v + w <= 1) return a + v * ab + w * ac;
  }
  Vec3 best = closest_on_segment(p, a, b);
  for (const Vec3& q : {closest_on_segment(p, b, c), closest_on_segment(p, c, a)})
    if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
  return best;
}

struct PatchDistanceCheck::Data {
  BernsteinPatch patch;
  Faces faces;
  double epsilon = 0, rounding = 0;
  int first = 0; // order of the first lattice
};

PatchDistanceCheck::PatchDistanceCheck(int degree, std::span<const Vec3> nodes, const mesh::SurfaceMesh& input,
                                       std::span<const int> faces, double epsilon)
    : d_(std::make_unique<Data>()) {
  Data& d = *d_;
  d.patch = to_bernstein(degree, nodes);
  d.faces = gather(input, faces);
  d.epsilon = epsilon;
  const BernsteinPatch& p = d.patch;
  // Rounding ρ (u = unit roundoff, N control points, R = max |b_α|, V = max
  // |input vertex|): the control points err by e_b each; the Bernstein sum
  // at a lattice point adds (N + 2k + 6) u √3 R (basis values, sum, the
  // rounded lattice coordinate); the closest point, a convex combination of
  // corners formed in double, lies within 16 √3 u V of the triangle, and the
  // final norm adds 8 u (R + V); G and H computed from rounded b_α err by at
  // most 2k e_b + 4 u G and 4k(k - 1) e_b + 8 u H, and 2/(3n), h²/2 ≤ 1.
  const int N = static_cast<int>(nodes.size()), k = degree;
  d.rounding = (2 * k + 1 + 4 * k * (k - 1)) * p.control_error +
               4 * kUnitRoundoff * (N + 2 * k + 16) * (p.max_norm + d.faces.max_norm) +
               8 * kUnitRoundoff * (p.slope + p.curvature);
  // First lattice: the first-order term at most epsilon/4 and the
  // interpolation term at most epsilon/8, at least 2k and at most 48
  // segments per edge.
  const double wanted = std::max({2.0 * k, std::ceil(8 * p.slope / (3 * epsilon)), std::ceil(std::sqrt(4 * p.curvature / epsilon))});
  d.first = static_cast<int>(std::min(wanted, double(kMaxLattice)));
}

PatchDistanceCheck::~PatchDistanceCheck() = default;
PatchDistanceCheck::PatchDistanceCheck(PatchDistanceCheck&&) noexcept = default;

bool PatchDistanceCheck::fails_early() const {
  const Data& d = *d_;
  if (d.faces.corners.empty()) return true;
  const int n = d.first;
  const std::size_t N = d.patch.control.size();
  const double* basis = lattice_basis(d.patch.degree, n).data();
  const int probes[7][2] = {{n / 3, n / 3}, {n / 2, 0}, {0, n / 2}, {n / 2, n - n / 2},
                            {n / 6, n / 6}, {n - n / 3, n / 6}, {n / 6, n - n / 3}};
  for (const auto& [i, j] : probes) {
    int hint = -1;
    if (nearest_face(combine(d.patch, basis + lattice_index(n, i, j) * N), d.faces, hint) > d.epsilon - d.rounding)
      return true;
  }
  return false;
}

PatchDistance PatchDistanceCheck::bound() const {
  const Data& d = *d_;
  if (d.faces.corners.empty()) return {std::numeric_limits<double>::infinity(), 0, d.rounding, 0};
  auto out = lattice_bound(d.patch, d.faces, d.first, d.epsilon - d.rounding);
  out.rounding = d.rounding;
  if (out.bound() <= d.epsilon || out.sampled + d.rounding >= d.epsilon || d.first >= kMaxLattice) return out;
  // Missed only between samples: twice as fine, once.
  out = lattice_bound(d.patch, d.faces, std::min(kMaxLattice, 2 * d.first), d.epsilon - d.rounding);
  out.rounding = d.rounding;
  return out;
}

PatchDistance patch_distance_bound(int degree, std::span<const Vec3> nodes, const mesh::SurfaceMesh& input,
                                   std::span<const int> faces, double epsilon) {
  return PatchDistanceCheck(degree, nodes, input, faces, epsilon).bound();
}

double middle_distance_bound(const Shell& s, double epsilon) {
  const int k = s.middle_nodes.empty() ? 1 : s.middle_degree;
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, s.num_prisms()), 0.0,
      [&](const tbb::blocked_range<int>& r, double worst) {
        for (int f = r.begin(); f < r.end(); ++f) {
          const Tri& t = s.faces[f];
          const std::vector<Vec3> flat = {s.middle[t[0]], s.middle[t[1]], s.middle[t[2]]};
          const auto& nodes = k == 1 ? flat : s.middle_nodes[f];
          worst = std::max(worst, patch_distance_bound(k, nodes, s.input, s.tracked[f], epsilon).bound());
        }
        return worst;
      },
      [](double a, double b) { return std::max(a, b); });
}

} // namespace curvetet::shell
