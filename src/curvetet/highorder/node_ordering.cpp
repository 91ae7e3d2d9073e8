#include "curvetet/highorder/node_ordering.hpp"

#include <cstdlib>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

namespace curvetet::highorder {

namespace {

struct GmshNodeTable {
  int order;
  int type;
  int nodes;
  int coords[165 * 3];
};

#include "curvetet/highorder/gmsh_node_tables.inc"

void check_order(int order) {
  if (order < 1 || order > kMaxOrder)
    throw std::invalid_argument("element order must be 1.." + std::to_string(kMaxOrder) + ", got " +
                                std::to_string(order));
}

// Lattice point -> internal node index, for one element kind and order.
template <int D>
std::map<std::array<int, D>, int> node_lookup(int order) {
  std::map<std::array<int, D>, int> m;
  const int n = D == 2 ? triangle_node_count(order) : tet_node_count(order);
  for (int i = 0; i < n; ++i) {
    if constexpr (D == 2)
      m[triangle_node(order, i)] = i;
    else
      m[tet_node(order, i)] = i;
  }
  return m;
}

// VTK triangle points as barycentric triples (b0, b1, b2) where (b0, b1) / P
// are the reference coordinates: corners, edges 0-1, 1-2, 2-0, then the
// interior as a triangle of order P-3 shifted by one in every coordinate.
void vtk_triangle_points(int order, int shift, std::vector<std::array<int, 3>>& out) {
  if (order < 0) return;
  if (order == 0) {
    out.push_back({shift, shift, shift});
    return;
  }
  const int lo = shift, hi = shift + order;
  // Corners in VTK: (0,0), (P,0), (0,P) in (b0, b1); b2 is the remainder.
  const std::array<int, 3> corners[3] = {{lo, lo, hi}, {hi, lo, lo}, {lo, hi, lo}};
  for (const auto& c : corners) out.push_back(c);
  for (int e = 0; e < 3; ++e) {
    const auto& a = corners[e];
    const auto& b = corners[(e + 1) % 3];
    for (int s = 1; s < order; ++s) {
      std::array<int, 3> p;
      for (int k = 0; k < 3; ++k) p[k] = (a[k] * (order - s) + b[k] * s - shift * order) / order + shift;
      out.push_back(p);
    }
  }
  vtk_triangle_points(order - 3, shift + 1, out);
}

// VTK tet points as (x, y, z, w) lattice coordinates (times P), w = P-x-y-z.
void vtk_tet_points(int order, int shift, std::vector<std::array<int, 4>>& out) {
  if (order < 0) return;
  if (order == 0) {
    out.push_back({shift, shift, shift, shift});
    return;
  }
  const int lo = shift, hi = shift + order;
  const std::array<int, 4> corners[4] = {{lo, lo, lo, hi}, {hi, lo, lo, lo}, {lo, hi, lo, lo}, {lo, lo, hi, lo}};
  for (const auto& c : corners) out.push_back(c);
  static constexpr int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (const auto& e : edges)
    for (int s = 1; s < order; ++s) {
      std::array<int, 4> p;
      for (int k = 0; k < 4; ++k)
        p[k] = ((corners[e[0]][k] - shift) * (order - s) + (corners[e[1]][k] - shift) * s) / order + shift;
      out.push_back(p);
    }
  // Face f: the tet coordinate kHeld[f] stays at `shift`; the face's own
  // triangle coordinates (t0, t1, t2) go to tet coordinates kSpan[f].
  static constexpr int kSpan[4][3] = {{0, 2, 3}, {2, 0, 1}, {2, 1, 3}, {1, 0, 3}};
  static constexpr int kHeld[4] = {1, 3, 0, 2};
  if (order >= 3) {
    std::vector<std::array<int, 3>> face;
    vtk_triangle_points(order - 3, 0, face);
    for (int f = 0; f < 4; ++f)
      for (const auto& t : face) {
        std::array<int, 4> p;
        for (int k = 0; k < 3; ++k) p[kSpan[f][k]] = shift + 1 + t[k];
        p[kHeld[f]] = shift;
        out.push_back(p);
      }
  }
  vtk_tet_points(order - 4, shift + 1, out);
}

} // namespace

int triangle_node_count(int p) { return (p + 1) * (p + 2) / 2; }
int tet_node_count(int p) { return (p + 1) * (p + 2) * (p + 3) / 6; }

int triangle_order_from_nodes(int nodes) {
  for (int p = 1; p <= kMaxOrder; ++p)
    if (triangle_node_count(p) == nodes) return p;
  return 0;
}
int tet_order_from_nodes(int nodes) {
  for (int p = 1; p <= kMaxOrder; ++p)
    if (tet_node_count(p) == nodes) return p;
  return 0;
}

std::array<int, 2> triangle_node(int order, int i) {
  check_order(order);
  const auto& t = kGmshTriangleNodes[order - 1];
  return {t.coords[2 * i], t.coords[2 * i + 1]};
}

std::array<int, 3> tet_node(int order, int i) {
  check_order(order);
  const auto& t = kGmshTetrahedronNodes[order - 1];
  return {t.coords[3 * i], t.coords[3 * i + 1], t.coords[3 * i + 2]};
}

int gmsh_triangle_type(int order) { return order >= 1 && order <= kMaxOrder ? kGmshTriangleNodes[order - 1].type : 0; }
int gmsh_tet_type(int order) { return order >= 1 && order <= kMaxOrder ? kGmshTetrahedronNodes[order - 1].type : 0; }
int gmsh_triangle_order(int type) {
  for (const auto& t : kGmshTriangleNodes)
    if (t.type == type) return t.order;
  return 0;
}
int gmsh_tet_order(int type) {
  for (const auto& t : kGmshTetrahedronNodes)
    if (t.type == type) return t.order;
  return 0;
}

const std::vector<int>& vtk_triangle_permutation(int order) {
  check_order(order);
  static std::vector<int> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] {
    auto lookup = node_lookup<2>(order);
    std::vector<std::array<int, 3>> pts;
    vtk_triangle_points(order, 0, pts);
    for (const auto& p : pts) cache[order].push_back(lookup.at({p[0], p[1]}));
  });
  return cache[order];
}

const std::vector<int>& vtk_tet_permutation(int order) {
  check_order(order);
  static std::vector<int> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] {
    auto lookup = node_lookup<3>(order);
    std::vector<std::array<int, 4>> pts;
    vtk_tet_points(order, 0, pts);
    for (const auto& p : pts) cache[order].push_back(lookup.at({p[0], p[1], p[2]}));
  });
  return cache[order];
}

int tet_node_index(int order, const std::array<int, 3>& q) {
  check_order(order);
  static std::map<std::array<int, 3>, int> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] { cache[order] = node_lookup<3>(order); });
  auto it = cache[order].find(q);
  return it == cache[order].end() ? -1 : it->second;
}

int triangle_node_index(int order, const std::array<int, 2>& q) {
  check_order(order);
  static std::map<std::array<int, 2>, int> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] { cache[order] = node_lookup<2>(order); });
  auto it = cache[order].find(q);
  return it == cache[order].end() ? -1 : it->second;
}

const std::vector<int>& tet_face_nodes(int order, int face) {
  check_order(order);
  static std::vector<int> cache[kMaxOrder + 1][4];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] {
    auto lookup = node_lookup<3>(order);
    for (int f = 0; f < 4; ++f) {
      // Tet corner lattice points; a triangle node (a, b) maps to the point
      // c0 + a/P (c1 - c0) + b/P (c2 - c0) of the face's corners c0, c1, c2.
      const std::array<int, 3> corner[4] = {{0, 0, 0}, {order, 0, 0}, {0, order, 0}, {0, 0, order}};
      const auto& c0 = corner[kTetFaces[f][0]];
      const auto& c1 = corner[kTetFaces[f][1]];
      const auto& c2 = corner[kTetFaces[f][2]];
      for (int i = 0; i < triangle_node_count(order); ++i) {
        auto [a, b] = triangle_node(order, i);
        std::array<int, 3> p;
        for (int k = 0; k < 3; ++k) p[k] = c0[k] + (a * (c1[k] - c0[k]) + b * (c2[k] - c0[k])) / order;
        cache[order][f].push_back(lookup.at(p));
      }
    }
  });
  return cache[order][face];
}

const std::vector<std::pair<int, int>>& tet_lattice_edges(int order) {
  check_order(order);
  static std::vector<std::pair<int, int>> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] {
    const int n = tet_node_count(order);
    std::vector<std::array<int, 4>> q(n);
    for (int i = 0; i < n; ++i) {
      const auto c = tet_node(order, i);
      q[i] = {order - c[0] - c[1] - c[2], c[0], c[1], c[2]};
    }
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        int l1 = 0;
        for (int k = 0; k < 4; ++k) l1 += std::abs(q[i][k] - q[j][k]);
        if (l1 == 2) cache[order].emplace_back(i, j);
      }
  });
  return cache[order];
}

} // namespace curvetet::highorder
