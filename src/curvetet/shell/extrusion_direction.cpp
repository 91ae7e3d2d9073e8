// Extrusion directions by the exact active-set enumeration of the QP
// "minimise |d|^2 subject to n_f . d >= 1" (DESIGN.md §3.1).
#include "curvetet/mesh/edge_topology.hpp"
#include "curvetet/shell/extrusion.hpp"

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include <limits>

namespace curvetet::shell {

namespace {

// Tolerance of the feasibility test of a KKT candidate. The direction is only
// a proposal: every guarantee is decided later by exact predicates.
constexpr double kFeasibilitySlack = 1e-9;

bool feasible(const std::vector<Vec3>& normals, const Vec3& d) {
  for (const auto& n : normals)
    if (n.dot(d) < 1 - kFeasibilitySlack) return false;
  return true;
}

// KKT point of the active set `ids`: d = N lambda with N^T N lambda = 1.
// Returns false when the set is degenerate or a multiplier is negative.
template <int K>
bool kkt_point(const std::vector<Vec3>& normals, const std::array<int, K>& ids, Vec3* d) {
  Eigen::Matrix<double, 3, K> N;
  for (int i = 0; i < K; ++i) N.col(i) = normals[ids[i]];
  const Eigen::Matrix<double, K, K> gram = N.transpose() * N;
  Eigen::FullPivLU<Eigen::Matrix<double, K, K>> lu(gram);
  if (!lu.isInvertible() || std::abs(lu.determinant()) < 1e-14) return false;
  const Eigen::Matrix<double, K, 1> lambda = lu.solve(Eigen::Matrix<double, K, 1>::Ones());
  if ((lambda.array() < 0).any()) return false;
  *d = N * lambda;
  return true;
}

} // namespace

DirectionResult extrusion_direction(const std::vector<Vec3>& normals, double singular_dot) {
  DirectionResult r;
  const int k = static_cast<int>(normals.size());
  Vec3 best;
  double best_norm = std::numeric_limits<double>::infinity();
  auto consider = [&](const Vec3& d) {
    if (d.squaredNorm() < best_norm && feasible(normals, d)) {
      best_norm = d.squaredNorm();
      best = d;
    }
  };
  // The QP is strictly convex: its optimum is the feasible KKT point, found
  // with the smallest active set that has one. Sizes are tried in order.
  for (int i = 0; i < k; ++i) consider(normals[i]);
  if (!std::isfinite(best_norm))
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j) {
        Vec3 d;
        if (kkt_point<2>(normals, {i, j}, &d)) consider(d);
      }
  if (!std::isfinite(best_norm))
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j)
        for (int l = j + 1; l < k; ++l) {
          Vec3 d;
          if (kkt_point<3>(normals, {i, j, l}, &d)) consider(d);
        }
  if (!std::isfinite(best_norm)) return r; // no direction sees every face
  const Vec3 unit = best.normalized();
  double min_dot = std::numeric_limits<double>::infinity();
  for (const auto& n : normals) min_dot = std::min(min_dot, n.dot(unit));
  r.min_dot = min_dot;
  if (min_dot < singular_dot) return r;
  r.direction = unit;
  r.singular = false;
  return r;
}

std::vector<DirectionResult> extrusion_directions(const mesh::SurfaceMesh& m, double singular_dot) {
  std::vector<Vec3> face_normal(m.num_faces());
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    const Vec3 n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    const double len = n.norm();
    face_normal[f] = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
  const auto vf = mesh::build_vertex_faces(m.num_vertices(), m.faces);
  std::vector<DirectionResult> out(m.num_vertices());
  tbb::parallel_for(0, m.num_vertices(), [&](int v) {
    std::vector<Vec3> normals;
    for (int i = vf.offsets[v]; i < vf.offsets[v + 1]; ++i) {
      // A face whose normal underflows to zero in double has no usable
      // direction: the vertex is treated as singular.
      if (face_normal[vf.faces[i]].isZero()) return;
      normals.push_back(face_normal[vf.faces[i]]);
    }
    if (!normals.empty()) out[v] = extrusion_direction(normals, singular_dot);
  });
  return out;
}

} // namespace curvetet::shell
