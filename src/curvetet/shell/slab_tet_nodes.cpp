#include "curvetet/shell/slab_tet_nodes.hpp"

#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"

namespace curvetet::shell {

namespace {

Vec3 slab_point(const SlabPatch& p, const std::array<double, 3>& uvw) {
  const double u = uvw[0], v = uvw[1], w = uvw[2];
  const Vec3 flat = (1 - u - v) * p.cap[0] + u * p.cap[1] + v * p.cap[2];
  const Vec3 middle = highorder::triangle_point(p.degree, p.middle_nodes, Eigen::Vector2d(u, v));
  return p.bottom ? Vec3((1 - w) * flat + w * middle) : Vec3((1 - w) * middle + w * flat);
}

} // namespace

std::vector<Vec3> slab_tet_nodes(const SlabPatch& patch, const SlabTet& tet, int order) {
  std::array<std::array<double, 3>, 4> ref;
  std::array<Vec3, 4> corner;
  std::array<bool, 4> pinched{}, on_middle{};
  for (int j = 0; j < 4; ++j) {
    const int c = tet.corners[j], k = c % 3;
    const bool upper = c >= 3;
    ref[j] = reference_corner(c);
    pinched[j] = patch.pinched[k];
    on_middle[j] = upper == patch.bottom || pinched[j];
    // A pinched corner is on the middle too: evaluate it there so that
    // middle-surface nodes through it land on the curved patch.
    if (pinched[j]) ref[j][2] = patch.bottom ? 1.0 : 0.0;
    corner[j] = on_middle[j] ? patch.middle_nodes[k] : patch.cap[k];
  }
  const int n = highorder::tet_node_count(order);
  std::vector<Vec3> out(n);
  for (int i = 0; i < n; ++i) {
    const auto lambda = highorder::tet_node_barycentric(order, i);
    bool near_pinch = false, middle = true;
    for (int j = 0; j < 4; ++j)
      if (lambda[j] > 0) {
        near_pinch |= pinched[j];
        middle &= on_middle[j];
      }
    // A flat middle needs no slab map: the straight canonical tets are the
    // ones invariant 1 proves positive, while the bilinear map of a
    // non-planar lateral quad can fold them.
    if (patch.degree == 1 || (near_pinch && !middle)) {
      Vec3 x = Vec3::Zero();
      for (int j = 0; j < 4; ++j) x += lambda[j] * corner[j];
      out[i] = x;
      continue;
    }
    std::array<double, 3> uvw{0, 0, 0};
    for (int j = 0; j < 4; ++j)
      for (int d = 0; d < 3; ++d) uvw[d] += lambda[j] * ref[j][d];
    out[i] = slab_point(patch, uvw);
  }
  return out;
}

} // namespace curvetet::shell
