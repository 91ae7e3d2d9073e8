// Coarsening across 90° creases (convex and concave): the Section rule lets
// an input face across a crease touch a prism along the crease (its lateral
// fibres are checked by the tets holding the crease's pillars), so flat
// sides coarsen up to their edges. Checked by the global invariants after
// every pass and by the map check, whose image areas would exceed 1 where Π
// were not injective.
#include "curvetet/shell/build.hpp"
#include "curvetet/shell/coarsen.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/star_invariants.hpp"

#include <gtest/gtest.h>

#include <array>
#include <map>
#include <set>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

// Boundary of a union of unit voxels, two triangles per unit square,
// oriented outward.
mesh::SurfaceMesh voxel_surface(const std::set<std::array<int, 3>>& cells) {
  mesh::SurfaceMesh m;
  std::map<std::array<int, 3>, int> id;
  auto vertex = [&](const std::array<int, 3>& q) {
    auto [it, fresh] = id.try_emplace(q, m.num_vertices());
    if (fresh) m.vertices.emplace_back(q[0], q[1], q[2]);
    return it->second;
  };
  for (const auto& c : cells)
    for (int d = 0; d < 3; ++d)
      for (int s : {1, -1}) {
        auto nb = c;
        nb[d] += s;
        if (cells.count(nb)) continue;
        const int du = (d + 1) % 3, dv = (d + 2) % 3;
        auto at = [&](int i, int j) {
          auto q = c;
          q[d] += s > 0;
          q[du] += i;
          q[dv] += j;
          return vertex(q);
        };
        const int p00 = at(0, 0), p10 = at(1, 0), p11 = at(1, 1), p01 = at(0, 1);
        if (s > 0) {
          m.faces.push_back({p00, p10, p11});
          m.faces.push_back({p00, p11, p01});
        } else {
          m.faces.push_back({p00, p11, p10});
          m.faces.push_back({p00, p01, p11});
        }
      }
  return m;
}

CoarsenStats coarsen_checked(Shell& s) {
  CoarsenOptions o;
  o.debug_invariants = true; // global checker after every pass (throws)
  const auto st = coarsen_shell(s, o);
  EXPECT_TRUE(check_shell(s).empty());
  const auto m = check_map(s);
  EXPECT_LT(m.max_distance, st.epsilon);
  EXPECT_EQ(m.points_outside, 0);
  EXPECT_EQ(m.prisms_not_tiled, 0) << "prism " << m.worst_prism << ", area error " << m.max_area_error;
  EXPECT_EQ(m.prisms_folded, 0) << "min piece " << m.min_piece_area;
  return st;
}

} // namespace

TEST(CoarsenCreases, SubdividedCubeCoarsensToItsFaces) {
  std::set<std::array<int, 3>> cells;
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 4; ++z) cells.insert({x, y, z});
  auto built = build_shell(voxel_surface(cells));
  const auto st = coarsen_checked(built.shell);
  EXPECT_EQ(st.faces_before, 192);
  // 84 when contact along the creases is rejected.
  EXPECT_LE(st.faces_after, 24);
}

TEST(CoarsenCreases, LShapeWithAConcaveCreaseCoarsens) {
  std::set<std::array<int, 3>> cells;
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 2; ++z)
        if (x < 2 || y < 2) cells.insert({x, y, z});
  auto built = build_shell(voxel_surface(cells));
  const auto st = coarsen_checked(built.shell);
  EXPECT_EQ(st.faces_before, 112);
  EXPECT_LE(st.faces_after, 36); // 72 with contact along creases rejected
}
