#include "curvetet/shell/slab_tet_nodes.hpp"

#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"

#include <algorithm>

namespace curvetet::shell {

namespace {

Vec3 slab_point(const SlabPatch& p, const std::array<double, 3>& uvw) {
  const double u = uvw[0], v = uvw[1], w = uvw[2];
  const Vec3 flat = (1 - u - v) * p.cap[0] + u * p.cap[1] + v * p.cap[2];
  const Vec3 middle = highorder::triangle_point(p.degree, p.middle_nodes, Eigen::Vector2d(u, v));
  return p.bottom ? Vec3((1 - w) * flat + w * middle) : Vec3((1 - w) * middle + w * flat);
}

// Node i of the patch lies on the flat triangle of its corners (relative
// 1e-12). Edge nodes are compared with the chord computed from the
// lexicographically smaller end, so the two prisms of an edge, which share
// its nodes bitwise, decide alike.
bool node_is_flat(const SlabPatch& p, int i) {
  const auto l = highorder::triangle_node(p.degree, i);
  const int L[3] = {p.degree - l[0] - l[1], l[0], l[1]};
  const Vec3* c = p.middle_nodes;
  Vec3 flat = Vec3::Zero();
  double scale = 0;
  int carrier[3], n = 0;
  for (int k = 0; k < 3; ++k)
    if (L[k] > 0) carrier[n++] = k;
  if (n == 2) {
    int a = carrier[0], b = carrier[1];
    if (std::lexicographical_compare(c[b].data(), c[b].data() + 3, c[a].data(), c[a].data() + 3)) std::swap(a, b);
    flat = c[a] + (double(L[b]) / p.degree) * (c[b] - c[a]);
    scale = (c[b] - c[a]).norm();
  } else {
    for (int k = 0; k < 3; ++k) flat += (double(L[k]) / p.degree) * c[k];
    scale = std::max({(c[1] - c[0]).norm(), (c[2] - c[1]).norm(), (c[0] - c[2]).norm()});
  }
  return (c[i] - flat).norm() <= 1e-12 * scale;
}

} // namespace

StraightParts straight_parts(const SlabPatch& p) {
  StraightParts out;
  out.edge = {true, true, true};
  bool interior = true;
  const int n = highorder::triangle_node_count(p.degree);
  for (int i = 3; i < n; ++i) {
    const auto l = highorder::triangle_node(p.degree, i);
    const int L[3] = {p.degree - l[0] - l[1], l[0], l[1]};
    const bool flat = node_is_flat(p, i);
    bool on_edge = false;
    for (int k = 0; k < 3; ++k)
      if (L[k] == 0) {
        out.edge[k] = out.edge[k] && flat;
        on_edge = true;
      }
    if (!on_edge) interior = interior && flat;
  }
  out.whole = interior && out.edge[0] && out.edge[1] && out.edge[2];
  return out;
}

std::vector<Vec3> slab_tet_nodes(const SlabPatch& patch, const SlabTet& tet, int order) {
  std::array<std::array<double, 3>, 4> ref;
  std::array<Vec3, 4> corner;
  std::array<bool, 4> pinched{}, on_middle{};
  std::array<int, 4> pillar{};
  for (int j = 0; j < 4; ++j) {
    const int c = tet.corners[j], k = c % 3;
    const bool upper = c >= 3;
    ref[j] = reference_corner(c);
    pillar[j] = k;
    pinched[j] = patch.pinched[k];
    on_middle[j] = upper == patch.bottom || pinched[j];
    // A pinched corner is on the middle too: evaluate it there so that
    // middle-surface nodes through it land on the curved patch.
    if (pinched[j]) ref[j][2] = patch.bottom ? 1.0 : 0.0;
    corner[j] = on_middle[j] ? patch.middle_nodes[k] : patch.cap[k];
  }
  const StraightParts straight = patch.degree == 1       ? StraightParts{{true, true, true}, true}
                                 : patch.straight_parts ? straight_parts(patch)
                                                        : StraightParts{};
  const int n = highorder::tet_node_count(order);
  std::vector<Vec3> out(n);
  for (int i = 0; i < n; ++i) {
    const auto lambda = highorder::tet_node_barycentric(order, i);
    bool near_pinch = false, middle = true;
    std::array<bool, 3> uses{}; // pillars of the carrier
    for (int j = 0; j < 4; ++j)
      if (lambda[j] > 0) {
        near_pinch |= pinched[j];
        middle &= on_middle[j];
        uses[pillar[j]] = true;
      }
    // Off the middle surface, the slab map is replaced by the straight tet
    // (a) beside a pinched pillar, where it degenerates; (b) over a straight
    // part of the middle (a lateral quad over a straight edge: the carrier
    // spans that edge's two pillars; or inside a prism whose patch is flat),
    // where the bilinear map of a non-planar quad can fold the thin tets
    // that invariant 1 proves positive. On one pillar the slab map is
    // already straight. Both rules read only the carrier and what the
    // prisms sharing it share, so tets sharing a node place it alike.
    const int spans = uses[0] + uses[1] + uses[2];
    bool linear = patch.degree == 1 || (!middle && near_pinch) || (!middle && spans == 3 && straight.whole);
    for (int k = 0; k < 3 && !linear; ++k)
      linear = !middle && spans == 2 && !uses[k] && straight.edge[k];
    if (linear) {
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
