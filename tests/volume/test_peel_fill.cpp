// The peeling fill (volume/peel_fill.hpp) on closed surfaces built here:
// convex prisms, prisms over non-convex polygons whose insides have no
// kernel point (no cone can fill them), and Schönhardt's twisted prism,
// which has no tetrahedralization without a new point at all. Every result
// is checked exactly: positive tets that, with the front left where peeling
// stopped, form a proper complex: each surface triangle is either still on
// the front or the face of one tet on its inner side, each front face is
// the face of one tet (or a surface triangle), every other face is shared
// by two tets in opposite orientations, and the tets' volumes plus what the
// front encloses sum to the enclosed volume.
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/volume/mesh_keys.hpp"
#include "curvetet/volume/peel_fill.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace curvetet {
namespace {

using mesh::Tri;
using mesh::Vec3;

struct Closed {
  std::vector<Vec3> points;
  std::vector<Tri> inward; // the region on each face's positive side
};

// The prism of height 1 over a counter-clockwise polygon whose cap
// triangulation is given (counter-clockwise triangles). Each side quad is
// split along the diagonal from its least id: then no cap triangle's prism
// has three sides turning the same way (a Schönhardt prism), so the prism
// has a tetrahedralization with no new point.
Closed prism(const std::vector<Vec3>& polygon, const std::vector<Tri>& cap) {
  Closed c;
  const int n = static_cast<int>(polygon.size());
  for (const auto& q : polygon) c.points.push_back(q);
  for (const auto& q : polygon) c.points.push_back(q + Vec3(0, 0, 1));
  std::vector<Tri> outward;
  for (const auto& t : cap) {
    outward.push_back({t[0], t[2], t[1]});
    outward.push_back({t[0] + n, t[1] + n, t[2] + n});
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    if (i < j) {
      outward.push_back({i, j, j + n});
      outward.push_back({i, j + n, i + n});
    } else {
      outward.push_back({i, j, i + n});
      outward.push_back({j, j + n, i + n});
    }
  }
  for (const auto& f : outward) c.inward.push_back({f[0], f[2], f[1]});
  return c;
}

double signed_volume(const std::vector<Vec3>& p, const std::array<int, 4>& t) {
  return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]) / 6.0;
}

// The volume on the positive side of closed faces.
double volume_inside(const std::vector<Vec3>& p, const std::vector<Tri>& inward) {
  double v = 0;
  for (const auto& f : inward) v -= p[f[0]].dot(p[f[1]].cross(p[f[2]])) / 6.0;
  return v;
}

// A face's ids rotated to start at the least: equal for the same directed face.
Tri directed(Tri f) {
  std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
  return f;
}
Tri reversed(const Tri& f) { return directed({f[0], f[2], f[1]}); }

void expect_proper(const Closed& c, const volume::Peeled& peeled) {
  const auto& p = c.points;
  std::map<Tri, int> count; // each tet face, seen from outside the tet
  double volume = 0;
  for (const auto& t : peeled.tets) {
    EXPECT_GT(geometry::orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]), 0);
    volume += signed_volume(p, t);
    for (const Tri& f : {Tri{t[0], t[2], t[1]}, Tri{t[0], t[1], t[3]}, Tri{t[0], t[3], t[2]}, Tri{t[1], t[2], t[3]}})
      ++count[directed(f)];
  }
  std::map<Tri, int> rest;
  for (const auto& f : peeled.rest) ++rest[directed(f)];
  for (const auto& f : c.inward) {
    if (rest.count(directed(f))) { // never peeled
      rest.erase(directed(f));
      continue;
    }
    EXPECT_EQ(count[reversed(f)], 1) << f[0] << " " << f[1] << " " << f[2];
    count.erase(reversed(f));
  }
  // A front face sees the unpeeled part on its positive side: seen from the
  // tet behind it, it is that tet's outward face.
  for (const auto& [f, k] : rest) {
    EXPECT_EQ(k, 1);
    EXPECT_EQ(count[f], 1) << "front face " << f[0] << " " << f[1] << " " << f[2];
    count.erase(f);
  }
  for (const auto& [f, k] : count) {
    EXPECT_EQ(k, 1) << "face " << f[0] << " " << f[1] << " " << f[2];
    EXPECT_EQ(count.count(reversed(f)), 1u) << "unpaired face " << f[0] << " " << f[1] << " " << f[2];
  }
  const double expected = volume_inside(p, c.inward);
  EXPECT_NEAR(volume + volume_inside(p, peeled.rest), expected, 1e-12 * expected);
}

// Convex prisms (a triangle's, a square's) peel completely.
TEST(PeelFill, ConvexPrismsPeelCompletely) {
  const Closed triangle = prism({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  const Closed square = prism({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  for (const auto* c : {&triangle, &square}) {
    const auto peeled = volume::peel_tetrahedralize(c->points, c->inward, 100, 1);
    ASSERT_EQ(peeled.size(), 1u);
    EXPECT_TRUE(peeled[0].rest.empty());
    expect_proper(*c, peeled[0]);
  }
  EXPECT_EQ(volume::peel_tetrahedralize(triangle.points, triangle.inward, 100, 1)[0].tets.size(), 3u);
}

// A U: the inner walls of its two arms face each other, so no point sees
// both from inside. Peeling goes as far as it can; what it did and what is
// left must fit together exactly, and what is left must be smaller.
TEST(PeelFill, UShapedPrismWithoutKernel) {
  const std::vector<Vec3> u{{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {2, 3, 0}, {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};
  const std::vector<Tri> cap{{0, 1, 4}, {0, 4, 5}, {1, 2, 3}, {1, 3, 4}, {0, 5, 6}, {0, 6, 7}};
  const auto c = prism(u, cap);
  const auto peeled = volume::peel_tetrahedralize(c.points, c.inward, 200, 4);
  ASSERT_FALSE(peeled.empty());
  for (const auto& attempt : peeled) expect_proper(c, attempt);
  EXPECT_LT(peeled[0].rest.size(), c.inward.size() / 2);
  for (std::size_t i = 1; i < peeled.size(); ++i) EXPECT_LE(peeled[i - 1].rest.size(), peeled[i].rest.size());
}

// Schönhardt's polyhedron (a triangular prism, its top turned by 30
// degrees, each side split along the diagonal that bends inward) has no
// tetrahedralization of its own six vertices: every attempt must stop with
// part of it left rather than claim it done.
TEST(PeelFill, SchoenhardtPolyhedronIsRefused) {
  Closed c;
  const double pi = std::acos(-1.0);
  for (int k = 0; k < 3; ++k) c.points.push_back({std::cos(2 * pi * k / 3), std::sin(2 * pi * k / 3), 0});
  for (int k = 0; k < 3; ++k) {
    const double a = 2 * pi * k / 3 + pi / 6;
    c.points.push_back({std::cos(a), std::sin(a), 1});
  }
  // Outward faces: bottom, top, and each side (i, j) split along i -> j+3,
  // the reflex diagonal for a counter-clockwise twist of the top.
  std::vector<Tri> outward{{0, 2, 1}, {3, 4, 5}};
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    outward.push_back({i, j, j + 3});
    outward.push_back({i, j + 3, i + 3});
  }
  for (const auto& f : outward) c.inward.push_back({f[0], f[2], f[1]});
  // The surface is the one described: each side pair bends inward (the far
  // corner of one triangle lies outside the other's plane).
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    ASSERT_GT(geometry::orient3d(c.points[i], c.points[j], c.points[j + 3], c.points[i + 3]), 0);
  }
  const auto peeled = volume::peel_tetrahedralize(c.points, c.inward, 1000, 4);
  ASSERT_EQ(peeled.size(), 4u);
  for (const auto& attempt : peeled) {
    EXPECT_FALSE(attempt.rest.empty());
    expect_proper(c, attempt);
  }
}

} // namespace
} // namespace curvetet
