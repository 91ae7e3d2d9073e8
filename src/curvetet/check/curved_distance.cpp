#include "curvetet/check/curved_distance.hpp"

#include "curvetet/check/closest_points.hpp"
#include "curvetet/highorder/element_map.hpp"

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

namespace curvetet::check {

namespace {

using Vec2 = Eigen::Vector2d;

// Nearest point of the reference triangle {u, v >= 0, u + v <= 1} to uv.
Vec2 clamp_to_triangle(Vec2 uv) {
  uv = uv.cwiseMax(0.0);
  if (uv.sum() > 1) {
    uv.array() -= 0.5 * (uv.sum() - 1);
    uv = uv.cwiseMax(0.0);
    uv /= std::max(1.0, uv.sum());
  }
  return uv;
}

// Barycentric coordinates of p (on the plane of a, b, c) in that triangle.
Eigen::Vector3d barycentric(const mesh::Vec3& p, const mesh::Vec3& a, const mesh::Vec3& b, const mesh::Vec3& c) {
  Eigen::Matrix<double, 3, 2> e;
  e << b - a, c - a;
  const Vec2 w = (e.transpose() * e).ldlt().solve(e.transpose() * (p - a));
  return {1 - w.sum(), w[0], w[1]};
}

} // namespace

std::vector<double> distances_to_curved_boundary(const mesh::TetMesh& m, const BoundaryLinearization& lin,
                                                 const std::vector<mesh::Vec3>& queries) {
  const auto closest = closest_points(lin.surface, queries);
  std::vector<double> out(queries.size(), std::numeric_limits<double>::infinity());
  const int tn = m.triangle_nodes();
  tbb::parallel_for(std::size_t(0), queries.size(), [&](std::size_t i) {
    const int f = closest[i].face;
    if (f < 0) return;
    std::vector<mesh::Vec3> nodes(tn);
    const int* tri = m.boundary_triangle(lin.source_face[f]);
    for (int k = 0; k < tn; ++k) nodes[k] = m.nodes[tri[k]];
    const auto& corner = lin.surface.faces[f];
    const Eigen::Vector3d w = barycentric(closest[i].point, lin.surface.vertices[corner[0]],
                                          lin.surface.vertices[corner[1]], lin.surface.vertices[corner[2]]);
    const auto& uvs = lin.source_uv[f];
    Vec2 uv = clamp_to_triangle(w[0] * uvs[0] + w[1] * uvs[1] + w[2] * uvs[2]);
    const mesh::Vec3& q = queries[i];
    mesh::Vec3 r = highorder::triangle_point(m.order, nodes.data(), uv) - q; // residual at uv
    for (int it = 0; it < 16; ++it) {
      const Eigen::Matrix<double, 3, 2> j = highorder::triangle_jacobian(m.order, nodes.data(), uv);
      const Vec2 step = -(j.transpose() * j).ldlt().solve(j.transpose() * r);
      if (!step.allFinite()) break;
      const Vec2 next = clamp_to_triangle(uv + step);
      const mesh::Vec3 r_next = highorder::triangle_point(m.order, nodes.data(), next) - q;
      if (!(r_next.norm() < r.norm())) break;
      r = r_next;
      uv = next;
    }
    out[i] = r.norm();
  });
  return out;
}

} // namespace curvetet::check
